// Checkpoint files (io/checkpoint.hpp), on 1, 2 and 3 ranks. References are exact: every value written is a
// function of its id, so a row read back must carry exactly those values.
//  * WritesSortedRowsOnceAndReadsThemBack: each rank writes an interleaved share of the ids (rank r the ids
//    r, r + np, ...; id 0 also from every rank, as an interface two ranks hold); the file holds every id once,
//    sorted; read whole on every rank, the table equals the generator bitwise.
//  * EachRankReceivesOnlyTheRowsItAsksFor: read with a per-rank list of ids (some absent from the file, some on
//    both sides of the boundaries of the ranks' and rounds' pieces), a rank gets exactly the rows of the listed ids
//    the file has, sorted, and nothing else (docs/parallel.md).
//  * TheFileIsTheSameWhateverTheRanksThatWroteIt: the same rows written by every rank (interleaved, as above) and
//    by rank 0 alone give the same file contents: ids, values and the checksum attribute, bitwise.
//  * TheChecksumCoversEveryTable: a value changed in the file (through HDF5, so the chunk checksums stay
//    valid) is refused by the file checksum.
//  * TableSizesAreCheckedAgainstTheFileBeforeAllocating: a table declaring 2^40 rows it does not hold is refused
//    before anything is allocated.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint.hpp"

using namespace shellfrac;

namespace {

constexpr int width = 5;
constexpr GlobalId num_ids = 40000;  // more than two blocks of 4 HDF5 chunks of 4096 rows (what a rank writes at a time)

double value(GlobalId id, int c) { return std::sin(double(id) * 0.37 + c) * 1e3 + double(id); }

std::string file_name(const char* stem) {
  const std::string dir = "checkpoint_test_np" + std::to_string(parallel::size());
  if (parallel::rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir + "/" + stem + ".h5";
}

/// This rank's share: ids r, r + np, ... in decreasing order (the writer sorts), plus id 0 from every rank.
io::CheckpointData share() {
  const int r = parallel::rank(), np = parallel::size();
  io::CheckpointData d;
  d.scalars["time"] = 1.25, d.strings["deck"] = "run.xml";
  auto& t = d.tables["elements"];
  t.width = width;
  std::vector<GlobalId> ids;
  for (GlobalId id = r; id < num_ids; id += np) ids.push_back(id);
  if (r != 0) ids.push_back(0);
  for (auto it = ids.rbegin(); it != ids.rend(); ++it) {
    t.ids.push_back(*it);
    for (int c = 0; c < width; ++c) t.values.push_back(value(*it, c));
  }
  d.tables["empty"].width = 3;
  return d;
}

/// The InputError of reading `path`, or "read without complaint". Collective.
std::string read_error(const std::string& path) {
  try {
    io::read_checkpoint(path, MPI_COMM_WORLD);
  } catch (const InputError& e) {
    return e.what();
  }
  return "read without complaint";
}

void expect_rows(const io::CheckpointTable& t, const std::vector<GlobalId>& ids) {
  ASSERT_EQ(t.width, width);
  ASSERT_EQ(t.ids, ids);
  ASSERT_EQ(t.values.size(), ids.size() * width);
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (int c = 0; c < width; ++c) ASSERT_EQ(t.values[i * width + c], value(ids[i], c)) << "id " << ids[i];
}

TEST(Checkpoint, WritesSortedRowsOnceAndReadsThemBack) {
  const std::string path = file_name("whole");
  io::write_checkpoint(path, share(), MPI_COMM_WORLD);
  const auto d = io::read_checkpoint(path, MPI_COMM_WORLD);
  EXPECT_EQ(d.scalars.at("time"), 1.25);
  EXPECT_EQ(d.strings.at("deck"), "run.xml");
  std::vector<GlobalId> all(num_ids);
  for (GlobalId id = 0; id < num_ids; ++id) all[std::size_t(id)] = id;
  expect_rows(d.tables.at("elements"), all);
  EXPECT_EQ(d.tables.at("empty").width, 3);
  EXPECT_TRUE(d.tables.at("empty").ids.empty());
}

TEST(Checkpoint, EachRankReceivesOnlyTheRowsItAsksFor) {
  const std::string path = file_name("rows");
  io::write_checkpoint(path, share(), MPI_COMM_WORLD);
  const int r = parallel::rank();
  // Rank r asks for ids 7r .. 7r + 20 in decreasing order, for the ids on both sides of the first two block
  // boundaries (16 384 rows a block) and of thirds of the file (the ranks' slices on 3 ranks, the rounds' pieces
  // on 1), and for two ids the file does not have.
  std::vector<GlobalId> ask{num_ids + 5, -3, 32768 + r, 32767 - r, 16384 + r, 16383 - r, 13333 + r, 13332 - r};
  for (GlobalId id = 7 * r + 20; id >= 7 * r; --id) ask.push_back(id);
  const auto d = io::read_checkpoint(path, MPI_COMM_WORLD, {{"elements", ask}});
  std::vector<GlobalId> expected;
  for (GlobalId id = 7 * r; id <= 7 * r + 20; ++id) expected.push_back(id);
  for (const GlobalId id : {13332 - r, 13333 + r, 16383 - r, 16384 + r, 32767 - r, 32768 + r}) expected.push_back(id);
  expect_rows(d.tables.at("elements"), expected);
  EXPECT_EQ(d.tables.at("empty").width, 3);  // not asked for: whole (empty)
}

/// The ids, values and checksum attribute of a file's table "elements", read on one rank.
struct FileContents {
  std::vector<GlobalId> ids;
  std::vector<double> values;
  std::string checksum;
};
FileContents contents(const std::string& path) {
  FileContents c;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << path;
  const hid_t ids = H5Dopen2(file, "/tables/elements/ids", H5P_DEFAULT);
  const hid_t values = H5Dopen2(file, "/tables/elements/values", H5P_DEFAULT);
  c.ids.resize(num_ids), c.values.resize(num_ids * width);
  EXPECT_GE(H5Dread(ids, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.ids.data()), 0);
  EXPECT_GE(H5Dread(values, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.values.data()), 0);
  const hid_t attr = H5Aopen(file, "checksum", H5P_DEFAULT), type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  char* s = nullptr;
  EXPECT_GE(H5Aread(attr, type, &s), 0);
  c.checksum = s ? s : "";
  H5free_memory(s);
  H5Tclose(type), H5Aclose(attr), H5Dclose(values), H5Dclose(ids), H5Fclose(file);
  return c;
}

TEST(Checkpoint, TheFileIsTheSameWhateverTheRanksThatWroteIt) {
  const std::string all = file_name("by_every_rank"), one = file_name("by_rank_0");
  io::write_checkpoint(all, share(), MPI_COMM_WORLD);
  MPI_Comm self;
  MPI_Comm_split(MPI_COMM_WORLD, parallel::rank() == 0 ? 0 : MPI_UNDEFINED, 0, &self);
  if (parallel::rank() == 0) {
    io::CheckpointData whole = share();  // rank 0's share plus every other id: the same rows as all ranks give
    auto& t = whole.tables["elements"];
    t.ids.clear(), t.values.clear();
    for (GlobalId id = num_ids - 1; id >= 0; --id) {
      t.ids.push_back(id);
      for (int c = 0; c < width; ++c) t.values.push_back(value(id, c));
    }
    io::write_checkpoint(one, whole, self);
    MPI_Comm_free(&self);
    const FileContents a = contents(all), b = contents(one);
    EXPECT_EQ(a.ids, b.ids);
    EXPECT_EQ(a.values, b.values);
    EXPECT_EQ(a.checksum, b.checksum);
    EXPECT_EQ(a.checksum.size(), 32u);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

TEST(Checkpoint, TheChecksumCoversEveryTable) {
  const std::string path = file_name("changed");
  io::write_checkpoint(path, share(), MPI_COMM_WORLD);
  if (parallel::rank() == 0) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t ds = H5Dopen2(file, "/tables/elements/values", H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    std::vector<double> v(num_ids * width);
    ASSERT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    v[5000 * width + 2] += 1.0;  // a row of the second chunk
    ASSERT_GE(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    H5Dclose(ds), H5Fclose(file);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string error = read_error(path);
  EXPECT_NE(error.find("do not match its checksum"), std::string::npos) << error;
}

TEST(Checkpoint, TableSizesAreCheckedAgainstTheFileBeforeAllocating) {
  // A 59 kB file declaring 16 x 2^24 rows took 4.4 GB and a minute before it was refused; larger ones ended in
  // bad_alloc. A table of 2^40 rows of 16 values, declared (chunked, never written) in a valid file, is refused at
  // once, before anything of its size is allocated.
  const std::string path = file_name("forged");
  io::write_checkpoint(path, share(), MPI_COMM_WORLD);
  if (parallel::rank() == 0) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t g = H5Gcreate2(file, "/tables/huge", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t rows = hsize_t(1) << 40, dims[2] = {rows, 16}, chunk[2] = {4096, 16};
    for (const char* name : {"ids", "values"}) {
      const bool ids = std::string(name) == "ids";
      const hid_t space = H5Screate_simple(ids ? 1 : 2, dims, nullptr), dcpl = H5Pcreate(H5P_DATASET_CREATE);
      H5Pset_chunk(dcpl, ids ? 1 : 2, chunk);
      const hid_t ds = H5Dcreate2(g, name, ids ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl,
                                  H5P_DEFAULT);
      ASSERT_GE(ds, 0);
      H5Dclose(ds), H5Pclose(dcpl), H5Sclose(space);
    }
    H5Gclose(g), H5Fclose(file);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_EQ(read_error(path), path + ": table huge declares 1099511627776 rows of 16 values, more than the file "
                                     "holds: the file is corrupt");
}

}  // namespace
