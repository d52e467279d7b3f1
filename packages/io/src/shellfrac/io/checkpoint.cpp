#include "shellfrac/io/checkpoint.hpp"


#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <queue>
#include <utility>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint_file.hpp"

namespace shellfrac::io {

namespace {

// Point-to-point transfers of long vectors (MPI counts are int: sent in pieces of 2^27 values).
template <class T>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}
template <>
MPI_Datatype mpi_type<std::int64_t>() {
  return MPI_INT64_T;
}
constexpr std::size_t piece = std::size_t(1) << 27;

template <class T>
void send_vector(const std::vector<T>& v, int to, MPI_Comm comm) {
  std::uint64_t n = v.size();
  MPI_Send(&n, 1, MPI_UINT64_T, to, 0, comm);
  for (std::size_t off = 0; off < v.size(); off += piece)
    MPI_Send(v.data() + off, static_cast<int>(std::min(piece, v.size() - off)), mpi_type<T>(), to, 0, comm);
}

template <class T>
std::vector<T> receive_vector(int from, MPI_Comm comm) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 0, comm, MPI_STATUS_IGNORE);
  std::vector<T> v(n);
  for (std::size_t off = 0; off < v.size(); off += piece)
    MPI_Recv(v.data() + off, static_cast<int>(std::min(piece, v.size() - off)), mpi_type<T>(), from, 0, comm,
             MPI_STATUS_IGNORE);
  return v;
}

/// One table as a rank gives it: its ids, sorted, and a way to read a range of its rows in that order.
struct LocalRows {
  int width = 0;
  std::vector<GlobalId> ids;
  std::function<void(std::size_t first, std::size_t count, double* out)> rows;
};

/// Table `name` of `d`: a source as it is, a given table (ids in any order) through its sorting permutation.
LocalRows local_rows(const CheckpointData& d, const std::string& name) {
  const auto source = d.table_sources.find(name);
  if (source != d.table_sources.end()) return {source->second.width, source->second.ids(), source->second.rows};
  const CheckpointTable& t = d.tables.at(name);
  std::vector<std::size_t> order(t.ids.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t.ids[a] < t.ids[b]; });
  LocalRows r;
  r.width = t.width;
  for (const std::size_t i : order) r.ids.push_back(t.ids[i]);
  r.rows = [&t, order](std::size_t first, std::size_t count, double* out) {
    for (std::size_t i = 0; i < count; ++i)
      std::copy_n(t.values.data() + order[first + i] * std::size_t(t.width), t.width, out + i * std::size_t(t.width));
  };
  return r;
}

// The row requests of a table from rank 0 to rank r: (first, count) of r's rows, answered with their values; a
// request with count 0 ends the table.
std::vector<double> request_rows(int r, std::size_t first, std::size_t count, MPI_Comm comm) {
  const std::uint64_t request[2] = {first, count};
  MPI_Send(request, 2, MPI_UINT64_T, r, 0, comm);
  return receive_vector<double>(r, comm);
}
void end_row_requests(int r, MPI_Comm comm) {
  const std::uint64_t request[2] = {0, 0};
  MPI_Send(request, 2, MPI_UINT64_T, r, 0, comm);
}
void serve_row_requests(const LocalRows& t, MPI_Comm comm) {
  std::vector<double> values;
  for (;;) {
    std::uint64_t request[2] = {0, 0};
    MPI_Recv(request, 2, MPI_UINT64_T, 0, 0, comm, MPI_STATUS_IGNORE);
    if (request[1] == 0) return;
    const bool valid = request[0] + request[1] <= t.ids.size();
    values.assign(valid ? request[1] * std::size_t(t.width) : 0, 0.0);  // rank 0 reports a short answer
    if (valid) t.rows(request[0], request[1], values.data());
    send_vector(values, 0, comm);
  }
}

/// The ranks' sorted ids of a table merged in id order (an id several ranks give is taken from the lowest of them),
/// walked a block of rows at a time.
class RowMerge {
 public:
  /// ids[r]: rank r's ids, sorted (an id repeated within a rank is taken once).
  explicit RowMerge(const std::vector<std::vector<GlobalId>>& ids) : ids_(ids) {
    restart();
    std::vector<std::size_t> first, count;
    for (;;) {
      const auto& block = next_block(checkpoint_rows_per_block, first, count);
      if (block.empty()) break;
      for (const auto& [r, row] : block) sorted_.push_back(ids_[std::size_t(r)][row]);
    }
    size_ = sorted_.size();
    restart();
  }
  std::size_t size() const { return size_; }
  /// The merged ids (once: they are handed over).
  std::vector<GlobalId> take_sorted_ids() { return std::move(sorted_); }
  /// The next n rows: (rank, row) of each; first[r] and count[r] the range of rank r's rows the block passes
  /// (including repeats of a lower rank's ids, not taken).
  const std::vector<std::pair<int, std::size_t>>& next_block(std::size_t n, std::vector<std::size_t>& first,
                                                             std::vector<std::size_t>& count) {
    first = cursor_;
    block_.clear();
    while (block_.size() < n && !heads_.empty()) {
      const auto [id, r] = heads_.top();
      block_.emplace_back(r, cursor_[std::size_t(r)]);
      while (!heads_.empty() && heads_.top().first == id) {
        const int rr = heads_.top().second;
        heads_.pop();
        pass(rr, id);
      }
    }
    count.resize(cursor_.size());
    for (std::size_t r = 0; r < cursor_.size(); ++r) count[r] = cursor_[r] - first[r];
    return block_;
  }

 private:
  void restart() {
    cursor_.assign(ids_.size(), 0);
    heads_ = {};
    for (std::size_t r = 0; r < ids_.size(); ++r)
      if (!ids_[r].empty()) heads_.emplace(ids_[r][0], int(r));
  }
  /// Moves rank r past `id` and queues its next id.
  void pass(int r, GlobalId id) {
    const auto& mine = ids_[std::size_t(r)];
    std::size_t& c = cursor_[std::size_t(r)];
    while (c < mine.size() && mine[c] == id) ++c;
    if (c < mine.size()) heads_.emplace(mine[c], r);
  }

  const std::vector<std::vector<GlobalId>>& ids_;
  std::vector<std::size_t> cursor_;
  std::priority_queue<std::pair<GlobalId, int>, std::vector<std::pair<GlobalId, int>>, std::greater<>> heads_;
  std::vector<std::pair<int, std::size_t>> block_;
  std::vector<GlobalId> sorted_;
  std::size_t size_ = 0;
};

/// The names of the tables and table sources, sorted, the same on every rank (an internal error otherwise).
/// Collective.
std::vector<std::string> agreed_table_names(const CheckpointData& local, MPI_Comm comm) {
  std::vector<std::string> names;
  for (const auto& [name, t] : local.tables) names.push_back(name);
  for (const auto& [name, source] : local.table_sources) {
    SHELLFRAC_REQUIRE(!local.tables.count(name), "checkpoint: table " << name << " given twice");
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  std::string mine;
  for (const auto& name : names) mine += name + '\n';
  std::string roots = mine;
  parallel::broadcast(roots, 0, comm);
  SHELLFRAC_REQUIRE(!parallel::any(roots != mine, comm), "checkpoint: the ranks hold different tables");
  return names;
}

}  // namespace

CheckpointData built(CheckpointData data) {
  for (const auto& [name, source] : data.table_sources) {
    CheckpointTable& t = data.tables[name];
    t.width = source.width, t.ids = source.ids();
    t.values.resize(t.ids.size() * std::size_t(source.width));
    source.rows(0, t.ids.size(), t.values.data());
  }
  data.table_sources.clear();
  return data;
}

const double* CheckpointTable::row(GlobalId id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  if (it == ids.end() || *it != id) return nullptr;
  return values.data() + (it - ids.begin()) * width;
}

namespace {

/// The first error met on rank 0 while writing, raised on every rank at the end (the other ranks go on serving
/// rows so that nobody hangs).
struct RootError {
  int me = 0;
  int kind = 0;  ///< 0 none, 1 InputError, 2 Error, 3 OutputError
  std::string message;

  /// Runs fn on rank 0 while no error has been met, keeping the first error.
  template <class Fn>
  void attempt(const Fn& fn) {
    if (me != 0 || kind != 0) return;
    try {
      fn();
    } catch (const OutputError& e) {
      kind = 3, message = e.what();
    } catch (const InputError& e) {
      kind = 1, message = e.what();
    } catch (const std::exception& e) {
      kind = 2, message = e.what();
    }
  }
  /// Collective: throws rank 0's error, of its kind, on every rank.
  void raise_everywhere(MPI_Comm comm) {
    MPI_Bcast(&kind, 1, MPI_INT, 0, comm);
    if (kind == 0) return;
    parallel::broadcast(message, 0, comm);
    if (kind == 1) throw InputError(message);
    if (kind == 3) throw OutputError(message);
    throw Error(message);
  }
};

/// Rank 0's part of writing table `name`: gathers every rank's ids, merges them, then writes block by block with
/// the rows asked of each rank.
void write_table_on_root(const std::string& name, const LocalRows& mine, int width, CheckpointFileWriter* writer,
                         RootError& failure, MPI_Comm comm) {
  const int np = parallel::size(comm);
  std::vector<std::vector<GlobalId>> ids(static_cast<std::size_t>(np));
  std::vector<int> widths(static_cast<std::size_t>(np), mine.width);
  ids[0] = mine.ids;
  for (int r = 1; r < np; ++r) {
    widths[std::size_t(r)] = static_cast<int>(receive_vector<std::int64_t>(r, comm).at(0));
    ids[std::size_t(r)] = receive_vector<std::int64_t>(r, comm);
  }
  std::optional<RowMerge> merge;
  failure.attempt([&] {
    for (int r = 0; r < np; ++r) {
      const auto& theirs = ids[std::size_t(r)];
      SHELLFRAC_REQUIRE(theirs.empty() || widths[std::size_t(r)] == width,
                        "checkpoint table " << name << ": rows of width " << widths[std::size_t(r)] << " from rank "
                                            << r << ", " << width << " from another");
      SHELLFRAC_REQUIRE(std::is_sorted(theirs.begin(), theirs.end()),
                        "checkpoint table " << name << ": the ids of rank " << r << " are not sorted");
    }
    merge.emplace(ids);
    writer->begin_table(name, width, merge->take_sorted_ids());
  });
  std::vector<double> block;
  std::vector<std::size_t> first(static_cast<std::size_t>(np)), count(static_cast<std::size_t>(np));
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(np));
  for (std::size_t done = 0; failure.kind == 0 && merge && done < merge->size(); done += checkpoint_rows_per_block) {
    const std::size_t n = std::min(checkpoint_rows_per_block, merge->size() - done);
    const auto& sources = merge->next_block(n, first, count);  // (rank, row) of each row of the block
    for (int r = 0; r < np; ++r) {
      auto& buffer = rows[std::size_t(r)];
      buffer.resize(count[std::size_t(r)] * std::size_t(width));
      if (count[std::size_t(r)] == 0) continue;
      if (r == 0)
        mine.rows(first[0], count[0], buffer.data());
      else
        buffer = request_rows(r, first[std::size_t(r)], count[std::size_t(r)], comm);
    }
    failure.attempt([&] {
      block.resize(n * std::size_t(width));
      for (std::size_t i = 0; i < n; ++i) {
        const auto [r, row] = sources[i];
        const auto& buffer = rows[std::size_t(r)];
        SHELLFRAC_REQUIRE(buffer.size() == count[std::size_t(r)] * std::size_t(width),
                          "checkpoint table " << name << ": rank " << r << " sent " << buffer.size() << " values");
        std::copy_n(buffer.data() + (row - first[std::size_t(r)]) * std::size_t(width), width,
                    block.data() + i * std::size_t(width));
      }
      writer->write_rows(block.data(), n);
    });
  }
  for (int r = 1; r < np; ++r) end_row_requests(r, comm);
}

/// Collective: rank 0 opens the file; every rank gets its scalars, strings and table names.
std::unique_ptr<CheckpointFileReader> open_and_share_header(const std::string& path, CheckpointData& d,
                                                            std::vector<std::string>& names, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  std::unique_ptr<CheckpointFileReader> reader;
  parallel::on_root_then_agree(
      [&] {
        reader = std::make_unique<CheckpointFileReader>(path);
        d.scalars = reader->header().scalars, d.strings = reader->header().strings;
        names = reader->table_names();
      },
      0, comm);
  parallel::ByteWriter w;
  if (me == 0) {
    w = serialize_header(d, names.size());
    for (const auto& n : names) w.put_string(n);
  }
  parallel::broadcast(w.buffer(), 0, comm);
  if (me != 0) {
    parallel::ByteReader r(w.buffer());
    for (auto n = deserialize_header(r, d); n > 0; --n) names.push_back(r.get_string());
  }
  return reader;
}

/// Collective: the ids of table `name` each rank asks for (sorted, unique; gathered on rank 0, empty elsewhere);
/// `whole` when nobody names the table (it then goes whole to every rank).
std::vector<std::vector<GlobalId>> gather_asked_ids(const std::string& path, const std::string& name,
                                                    const WantedRows& wanted, bool& whole, MPI_Comm comm) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  const std::vector<GlobalId>* ask = wanted(name);
  whole = ask == nullptr;
  std::vector<GlobalId> mine_asked;
  if (!whole) {
    mine_asked = *ask;
    std::sort(mine_asked.begin(), mine_asked.end());
    mine_asked.erase(std::unique(mine_asked.begin(), mine_asked.end()), mine_asked.end());
  }
  SHELLFRAC_REQUIRE(!(parallel::any(whole, comm) && parallel::any(!whole, comm)),
                    "checkpoint " << path << ": table " << name << " is asked for by some ranks only");
  std::vector<std::vector<GlobalId>> asked(static_cast<std::size_t>(np));
  if (whole) return asked;
  if (me == 0) {
    asked[0] = std::move(mine_asked);
    for (int r = 1; r < np; ++r) asked[std::size_t(r)] = receive_vector<std::int64_t>(r, comm);
  } else {
    send_vector(mine_asked, 0, comm);
  }
  return asked;
}

/// Rank 0: sends each rank its asked rows of one block (ids [begin, end) with values `block`) and returns its own.
/// `cursor` is each rank's position in its asked ids (both sorted: one pass over each).
CheckpointTable share_asked_rows(std::vector<GlobalId>::const_iterator begin, std::vector<GlobalId>::const_iterator end,
                                 const std::vector<double>& block, std::size_t width,
                                 const std::vector<std::vector<GlobalId>>& asked, std::vector<std::size_t>& cursor,
                                 MPI_Comm comm) {
  CheckpointTable own;
  own.width = static_cast<int>(width);
  for (int r = 0; r < static_cast<int>(asked.size()); ++r) {
    const auto& want = asked[std::size_t(r)];
    std::size_t& c = cursor[std::size_t(r)];
    std::vector<GlobalId> out_ids;
    std::vector<double> out_values;
    auto at = begin;
    for (; c < want.size() && want[c] <= *(end - 1); ++c) {
      at = std::lower_bound(at, end, want[c]);
      if (at == end || *at != want[c]) continue;  // not in the file
      const std::size_t row = std::size_t(at - begin);
      out_ids.push_back(want[c]);
      out_values.insert(out_values.end(), block.begin() + std::ptrdiff_t(row * width),
                        block.begin() + std::ptrdiff_t((row + 1) * width));
    }
    if (r == 0)
      own.ids = std::move(out_ids), own.values = std::move(out_values);
    else
      send_vector(out_ids, r, comm), send_vector(out_values, r, comm);
  }
  return own;
}

}  // namespace

// Rank 0 writes, one table at a time and a block of checkpoint_rows_per_block rows at a time: it gathers every rank's ids of the
// table, merges them (sorted, a row given by two ranks taken from the lower), writes them, then asks each rank for
// the rows of each block and writes the block. No rank ever holds a table: rank 0 holds the ids and one block,
// the others build the rows of a block when asked. An error on rank 0 is raised on every rank after the last table.
void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm) {
  const int me = parallel::rank(comm);
  const auto names = agreed_table_names(local, comm);
  RootError failure;
  failure.me = me;
  std::unique_ptr<CheckpointFileWriter> writer;
  failure.attempt([&] { writer = std::make_unique<CheckpointFileWriter>(path, local, names.size()); });
  for (const auto& name : names) {
    const LocalRows mine = local_rows(local, name);
    const int width = static_cast<int>(parallel::max(double(mine.width), comm));
    if (me == 0) {
      write_table_on_root(name, mine, width, writer.get(), failure, comm);
      continue;
    }
    send_vector(std::vector<std::int64_t>{mine.width}, 0, comm), send_vector(mine.ids, 0, comm);
    serve_row_requests(mine, comm);
  }
  failure.attempt([&] { writer->finish(); });
  writer.reset();
  failure.raise_everywhere(comm);
}

// Rank 0 reads one table at a time, a block of checkpoint_rows_per_block rows at a time, and sends every rank the rows of each
// block that it asks for (`wanted`; a table not asked for goes whole to every rank): no rank but rank 0 ever sees a
// row it did not ask for, and each rank holds one table of its rows at a time.
void read_checkpoint(const std::string& path, MPI_Comm comm, const WantedRows& wanted,
                     const std::function<void(const CheckpointData& header)>& header,
                     const std::function<void(const std::string& name, const CheckpointTable& rows)>& table) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  CheckpointData d;
  std::vector<std::string> names;
  const std::unique_ptr<CheckpointFileReader> reader = open_and_share_header(path, d, names, comm);
  header(d);
  for (const auto& name : names) {
    bool whole = false;
    const std::vector<std::vector<GlobalId>> asked = gather_asked_ids(path, name, wanted, whole, comm);
    CheckpointTable ids;  // rank 0: the file's ids and width
    parallel::on_root_then_agree([&] { ids = reader->begin_table(name); }, 0, comm);
    std::int64_t shape[2] = {ids.width, std::int64_t(ids.ids.size())};
    MPI_Bcast(shape, 2, MPI_INT64_T, 0, comm);
    CheckpointTable rows;  // this rank's rows of a block
    rows.width = static_cast<int>(shape[0]);
    const std::size_t num_rows = std::size_t(shape[1]), width = std::size_t(shape[0]);
    std::vector<std::size_t> cursor(static_cast<std::size_t>(np), 0);
    std::vector<double> block;
    std::vector<GlobalId> block_ids;
    for (std::size_t first = 0; first < num_rows; first += checkpoint_rows_per_block) {
      const std::size_t n = std::min(checkpoint_rows_per_block, num_rows - first);
      if (me == 0 || whole) block.resize(n * width);  // the other ranks get only their rows of a wanted table
      parallel::on_root_then_agree([&] { reader->read_rows(n, block.data()); }, 0, comm);
      rows.ids.clear(), rows.values.clear();
      if (whole) {  // every rank gets the block
        block_ids.assign(n, 0);
        if (me == 0) std::copy_n(ids.ids.begin() + std::ptrdiff_t(first), n, block_ids.begin());
        SHELLFRAC_REQUIRE(MPI_Bcast(block_ids.data(), int(n), MPI_INT64_T, 0, comm) == MPI_SUCCESS &&
                              MPI_Bcast(block.data(), int(n * width), MPI_DOUBLE, 0, comm) == MPI_SUCCESS,
                          "checkpoint: broadcast of table " << name << " failed");
        rows.ids = block_ids, rows.values = block;
      } else if (me != 0) {  // this rank's rows of the block
        rows.ids = receive_vector<std::int64_t>(0, comm);
        rows.values = receive_vector<double>(0, comm);
      } else {
        const auto begin = ids.ids.cbegin() + std::ptrdiff_t(first);
        rows = share_asked_rows(begin, begin + std::ptrdiff_t(n), block, width, asked, cursor, comm);
      }
      table(name, rows);
    }
    if (num_rows == 0) table(name, rows);  // an empty table is still one
  }
  parallel::on_root_then_agree([&] { reader->verify(); }, 0, comm);
}

CheckpointData read_checkpoint(const std::string& path, MPI_Comm comm,
                               const std::map<std::string, std::vector<GlobalId>>& wanted) {
  CheckpointData d;
  const auto ask = [&](const std::string& name) -> const std::vector<GlobalId>* {
    const auto it = wanted.find(name);
    return it == wanted.end() ? nullptr : &it->second;
  };
  read_checkpoint(
      path, comm, ask, [&](const CheckpointData& header) { d = header; },
      [&](const std::string& name, const CheckpointTable& rows) {
        CheckpointTable& t = d.tables[name];
        t.width = rows.width;
        t.ids.insert(t.ids.end(), rows.ids.begin(), rows.ids.end());
        t.values.insert(t.values.end(), rows.values.begin(), rows.values.end());
      });
  return d;
}

}  // namespace shellfrac::io
