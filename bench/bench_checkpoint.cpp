// shellfrac_checkpoint_bench: write and read a checkpoint of the state's tables for a synthetic mesh of E elements
// and print, per rank, the memory each takes beyond what the rank held before it and its wall time. Not a test.
//   mpiexec -np P shellfrac_checkpoint_bench [--elements E] [--dir D]
// The tables are those of a run's checkpoint, with their widths (19 element tables, 8 interface tables, the
// plastic state: 288 values per element with 1.5 interfaces per element), each row a function of its id (no state is
// stored: a table is read from its generator as a run reads it from the state). Rank r owns the ids of the blocks
// of 1 000 consecutive ids that a fixed hash sends to it (a partition with locality, not contiguous in id). The
// restart asks for the rows of the ids it owns. Memory: the peak resident size during the write (and the read) minus
// the resident size before it, from /proc/self (VmHWM reset through clear_refs); time: the wall time of the slowest
// rank. Output: one line per rank, then key=value lines: write_peak_extra_bytes_max, ..._rank0, per global element.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <iostream>
#include <string>
#include <vector>

#include "process_memory.hpp"
#include "shellfrac/core/memory_release.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint.hpp"

using namespace shellfrac;
using bench::reset_peak;
using bench::status_bytes;

namespace {

double value(GlobalId id, int c) { return std::sin(double(id) * 0.37 + c) * 1e3 + double(id); }

std::uint64_t owner_hash(std::uint64_t block) {
  block ^= block >> 33, block *= 0xff51afd7ed558ccdULL, block ^= block >> 33;
  return block;
}

/// This rank's ids of a table of n rows.
std::vector<GlobalId> owned_ids(GlobalId n, MPI_Comm comm) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  std::vector<GlobalId> ids;
  for (GlobalId id = 0; id < n; ++id)
    if (owner_hash(std::uint64_t(id / 1000)) % std::uint64_t(np) == std::uint64_t(me)) ids.push_back(id);
  return ids;
}

}  // namespace

int main(int argc, char** argv) {
  shellfrac::release_freed_memory_promptly();  // as the shellfrac executable does
  MPI_Init(&argc, &argv);
  const MPI_Comm comm = MPI_COMM_WORLD;
  GlobalId elements = 500000;
  std::string dir = ".";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--elements") elements = std::stoll(argv[i + 1]);
    else if (a == "--dir") dir = argv[i + 1];
  }
  const GlobalId interfaces = elements * 3 / 2;
  const auto element_ids = std::make_shared<std::vector<GlobalId>>(owned_ids(elements, comm));
  const auto interface_ids = std::make_shared<std::vector<GlobalId>>(owned_ids(interfaces, comm));
  io::CheckpointData data;
  data.scalars["time"] = 1.0;
  const int element_widths[] = {18, 1, 1, 6, 6, 1, 18, 18, 1, 9, 9, 1, 18, 1, 27, 1, 9, 18, 18, 54};
  const int interface_widths[] = {1, 18, 1, 1, 9, 3, 1, 1};
  std::map<std::string, std::vector<GlobalId>> asked;
  const auto add = [&](const std::string& name, int width, std::shared_ptr<std::vector<GlobalId>> ids) {
    data.table_sources[name] = {width, [ids] { return *ids; },
                                [ids, width](std::size_t first, std::size_t count, double* out) {
                                  for (std::size_t i = first; i < first + count; ++i)
                                    for (int c = 0; c < width; ++c) *out++ = value((*ids)[i], c);
                                }};
    asked[name] = *ids;
  };
  int k = 0;
  for (const int w : element_widths) add("element " + std::to_string(k++), w, element_ids);
  for (const int w : interface_widths) add("interface " + std::to_string(k++), w, interface_ids);
  const std::string path = dir + "/bench_checkpoint.h5";
  MPI_Barrier(comm);
  double before = reset_peak();
  auto t0 = std::chrono::steady_clock::now();
  io::write_checkpoint(path, data, comm);
  MPI_Barrier(comm);
  const double write_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double write_extra = status_bytes("VmHWM:") - before;
  before = reset_peak();
  t0 = std::chrono::steady_clock::now();
  std::size_t rows = 0, wrong = 0;
  io::read_checkpoint(
      path, comm, [&](const std::string& name) { return &asked.at(name); }, [](const io::CheckpointData&) {},
      [&](const std::string&, const io::CheckpointTable& t) {
        rows += t.ids.size();
        for (std::size_t i = 0; i < t.ids.size(); ++i)
          wrong += t.values[i * std::size_t(t.width)] != value(t.ids[i], 0);
      });
  MPI_Barrier(comm);
  const double read_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double read_extra = status_bytes("VmHWM:") - before;
  const auto writes = parallel::all_gather(std::vector<double>{write_extra}, comm);
  const auto reads = parallel::all_gather(std::vector<double>{read_extra}, comm);
  const std::int64_t all_rows = parallel::sum(std::int64_t(rows), comm), all_wrong = parallel::sum(std::int64_t(wrong), comm);
  if (parallel::rank(comm) == 0) {
    const double per = 1.0 / double(elements);
    for (std::size_t r = 0; r < writes.size(); ++r)
      std::printf("rank %zu: write +%.1f MiB, read +%.1f MiB\n", r, writes[r] / 1048576.0, reads[r] / 1048576.0);
    std::printf("ranks=%zu\nelements=%lld\nwrite_s=%.3f\nread_s=%.3f\n", writes.size(), (long long)elements, write_s,
                read_s);
    std::printf("write_peak_extra_bytes_rank0=%.0f\nwrite_peak_extra_bytes_max_other=%.0f\n", writes[0],
                writes.size() > 1 ? *std::max_element(writes.begin() + 1, writes.end()) : 0.0);
    std::printf("write_peak_extra_bytes_max_per_global_element=%.2f\n",
                *std::max_element(writes.begin(), writes.end()) * per);
    std::printf("read_peak_extra_bytes_max_per_global_element=%.2f\n", *std::max_element(reads.begin(), reads.end()) * per);
    std::printf("rows_read=%lld wrong_rows=%lld\n", (long long)all_rows, (long long)all_wrong);
  }
  MPI_Finalize();
  return all_wrong == 0 ? 0 : 3;
}
