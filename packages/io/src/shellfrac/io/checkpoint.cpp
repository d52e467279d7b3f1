#include "shellfrac/io/checkpoint.hpp"

#include <climits>
#include <cstdint>
#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <utility>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/io/checkpoint_file.hpp"

namespace shellfrac::io {

namespace {

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

/// x * num / den without overflow (all non-negative, the result below 2^63).
__extension__ using Wide = unsigned __int128;
std::uint64_t scaled(std::uint64_t x, std::uint64_t num, std::uint64_t den) {
  return std::uint64_t(Wide(x) * num / den);
}

/// Who writes which rows of a table: rank r the ids in [bound(r, 0), bound(r, rounds)) (a P-th of the table's
/// id range), in round k those in [bound(r, k), bound(r, k + 1)). The ids of a round are spread over the whole
/// range (a piece of every rank's share), so that a rank sends about a block of rows a round however the ids are
/// distributed over the ranks; balanced when the ids are dense, as the element and interface ids are.
struct WriteSlices {
  GlobalId lo = 0;
  std::uint64_t span = 0;  ///< hi - lo + 1, 0 for a table without rows
  int np = 1;
  std::size_t rounds = 1;

  WriteSlices(const std::vector<GlobalId>& ids, MPI_Comm comm) : np(parallel::size(comm)) {
    std::int64_t range[2] = {ids.empty() ? INT64_MAX : ids.front(), ids.empty() ? INT64_MIN : -ids.back()};
    MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_INT64_T, MPI_MIN, comm);
    if (range[0] > -range[1]) return;
    lo = range[0], span = std::uint64_t(-range[1] - range[0]) + 1;
    const std::uint64_t share = (span + std::uint64_t(np) - 1) / std::uint64_t(np);
    rounds = std::max<std::size_t>(1, (share + checkpoint_rows_per_block - 1) / checkpoint_rows_per_block);
  }
  GlobalId bound(int r, std::size_t k) const {
    const std::uint64_t a = scaled(span, std::uint64_t(r), std::uint64_t(np));
    const std::uint64_t b = scaled(span, std::uint64_t(r) + 1, std::uint64_t(np));
    return lo + GlobalId(a + scaled(b - a, k, rounds));
  }
};

/// Round k of writing a table: every rank sends the rows it gives of the ids each rank writes this round; returns
/// the rows this rank writes, sorted, each id once (of an id given by several ranks, or twice by one, the row of the
/// lowest rank, first given). Only the ids when `with_values` is false. Collective.
void gather_round(const LocalRows& mine, const WriteSlices& slices, std::size_t k, bool with_values, int width,
                  std::vector<GlobalId>& ids, std::vector<double>& values, MPI_Comm comm) {
  const int np = slices.np;
  std::vector<std::vector<GlobalId>> send_ids(static_cast<std::size_t>(np));
  std::vector<std::vector<double>> send_values(static_cast<std::size_t>(np));
  for (int q = 0; q < np; ++q) {
    const auto first = std::lower_bound(mine.ids.begin(), mine.ids.end(), slices.bound(q, k));
    const auto end = std::lower_bound(first, mine.ids.end(), slices.bound(q, k + 1));
    send_ids[std::size_t(q)].assign(first, end);
    if (!with_values || first == end) continue;
    send_values[std::size_t(q)].resize(std::size_t(end - first) * std::size_t(width));
    mine.rows(std::size_t(first - mine.ids.begin()), std::size_t(end - first), send_values[std::size_t(q)].data());
  }
  std::vector<int> counts;
  const std::vector<GlobalId> in_ids = parallel::exchange(std::move(send_ids), counts, comm);
  const std::vector<double> in_values =
      with_values ? parallel::exchange(std::move(send_values), counts, comm) : std::vector<double>();
  std::vector<std::size_t> order(in_ids.size());
  std::iota(order.begin(), order.end(), std::size_t(0));  // in rank order: a stable sort keeps the lowest first
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return in_ids[a] < in_ids[b]; });
  ids.clear(), values.clear();
  for (const std::size_t i : order) {
    if (!ids.empty() && ids.back() == in_ids[i]) continue;
    ids.push_back(in_ids[i]);
    if (with_values)
      values.insert(values.end(), in_values.begin() + std::ptrdiff_t(i * std::size_t(width)),
                    in_values.begin() + std::ptrdiff_t((i + 1) * std::size_t(width)));
  }
}

/// Writes table `name`: every rank writes its share of the id range, a round at a time, at the rows the ids before
/// it take (counted in a first pass over the ids only). Collective.
void write_table(const std::string& name, const CheckpointData& local, CheckpointFileWriter& writer, MPI_Comm comm) {
  const LocalRows mine = local_rows(local, name);
  const int width = static_cast<int>(parallel::max(double(mine.width), comm));
  parallel::on_all_then_agree(
      [&] {
        SHELLFRAC_REQUIRE(mine.ids.empty() || mine.width == width,
                          "checkpoint table " << name << ": rows of width " << mine.width << " here, " << width
                                              << " on another rank");
        SHELLFRAC_REQUIRE(std::is_sorted(mine.ids.begin(), mine.ids.end()),
                          "checkpoint table " << name << ": the ids are not sorted");
      },
      comm);
  const WriteSlices slices(mine.ids, comm);
  std::vector<GlobalId> ids;
  std::vector<double> values;
  std::vector<std::int64_t> round_rows(slices.rounds, 0);  // rows this rank writes in each round
  std::int64_t my_rows = 0;
  for (std::size_t k = 0; k < slices.rounds; ++k) {
    gather_round(mine, slices, k, false, width, ids, values, comm);
    round_rows[k] = std::int64_t(ids.size()), my_rows += round_rows[k];
  }
  std::int64_t first = 0;
  MPI_Exscan(&my_rows, &first, 1, MPI_INT64_T, MPI_SUM, comm);
  if (parallel::rank(comm) == 0) first = 0;
  writer.begin_table(name, width, std::size_t(parallel::sum(my_rows, comm)));
  for (std::size_t k = 0; k < slices.rounds; ++k) {
    gather_round(mine, slices, k, true, width, ids, values, comm);
    parallel::on_all_then_agree(
        [&] { SHELLFRAC_REQUIRE(std::int64_t(ids.size()) == round_rows[k], "checkpoint table " << name << " changed"); },
        comm);
    writer.write_rows(std::size_t(first), ids.data(), values.data(), ids.size());
    first += round_rows[k];
  }
}

/// Which rows of a table each rank reads in each round. A table asked for by rows: rank r reads its P-th of the
/// file, rows [N r / P, N (r + 1) / P), a block at a time. A table every rank gets whole: round k is block k of
/// the file, shared among the ranks (the rounds then come in file order).
struct ReadPieces {
  std::size_t num_rows = 0;
  int np = 1;
  bool whole = false;
  std::size_t rounds = 1;

  ReadPieces(std::size_t n, int ranks, bool whole_table) : num_rows(n), np(ranks), whole(whole_table) {
    const std::size_t block = checkpoint_rows_per_block, share = (n + std::size_t(np) - 1) / std::size_t(np);
    rounds = std::max<std::size_t>(1, ((whole ? n : share) + block - 1) / block);
  }
  /// Rows [first, end) that rank r reads in round k.
  std::pair<std::size_t, std::size_t> piece(int r, std::size_t k) const {
    std::size_t a = 0, b = num_rows;
    if (whole)
      a = std::min(num_rows, k * checkpoint_rows_per_block), b = std::min(num_rows, a + checkpoint_rows_per_block);
    const auto at = [&](std::size_t lo, std::size_t hi, std::uint64_t i, std::uint64_t of) {
      return lo + std::size_t(scaled(hi - lo, i, of));
    };
    if (whole) return {at(a, b, std::uint64_t(r), std::uint64_t(np)), at(a, b, std::uint64_t(r) + 1, std::uint64_t(np))};
    const std::size_t s = at(a, b, std::uint64_t(r), std::uint64_t(np)), e = at(a, b, std::uint64_t(r) + 1, std::uint64_t(np));
    return {at(s, e, k, rounds), at(s, e, k + 1, rounds)};
  }
};

/// The rows of a round read by the ranks that another rank asks for: `asked` (sorted, unique) split by the id
/// range of each rank's piece, sent there, answered with the rows it has. Returns this rank's rows, sorted (the
/// pieces of a round are in rank order in the file). Collective.
CheckpointTable share_asked_rows(const std::vector<GlobalId>& piece_ids, const std::vector<double>& piece_values,
                                 int width, const std::vector<GlobalId>& asked, MPI_Comm comm) {
  const int np = parallel::size(comm);
  std::int64_t mine[3] = {piece_ids.empty() ? 0 : piece_ids.front(), piece_ids.empty() ? 0 : piece_ids.back(),
                          std::int64_t(piece_ids.size())};
  std::vector<std::int64_t> ranges(std::size_t(3 * np));
  MPI_Allgather(mine, 3, MPI_INT64_T, ranges.data(), 3, MPI_INT64_T, comm);
  std::vector<std::vector<GlobalId>> requests(static_cast<std::size_t>(np));
  for (int q = 0; q < np; ++q) {
    const std::int64_t* range = ranges.data() + 3 * q;
    if (range[2] == 0) continue;
    const auto first = std::lower_bound(asked.begin(), asked.end(), range[0]);
    requests[std::size_t(q)].assign(first, std::upper_bound(first, asked.end(), range[1]));
  }
  std::vector<int> counts;
  const std::vector<GlobalId> wanted_here = parallel::exchange(std::move(requests), counts, comm);
  std::vector<std::vector<GlobalId>> found_ids(static_cast<std::size_t>(np));
  std::vector<std::vector<double>> found_values(static_cast<std::size_t>(np));
  std::size_t at = 0;
  for (int q = 0; q < np; ++q)
    for (int i = 0; i < counts[std::size_t(q)]; ++i, ++at) {
      const auto it = std::lower_bound(piece_ids.begin(), piece_ids.end(), wanted_here[at]);
      if (it == piece_ids.end() || *it != wanted_here[at]) continue;  // not in the file
      const std::size_t row = std::size_t(it - piece_ids.begin());
      found_ids[std::size_t(q)].push_back(*it);
      found_values[std::size_t(q)].insert(found_values[std::size_t(q)].end(),
                                          piece_values.begin() + std::ptrdiff_t(row * std::size_t(width)),
                                          piece_values.begin() + std::ptrdiff_t((row + 1) * std::size_t(width)));
    }
  CheckpointTable own;
  own.width = width;
  own.ids = parallel::exchange(std::move(found_ids), counts, comm);
  own.values = parallel::exchange(std::move(found_values), counts, comm);
  return own;
}

/// The ids of table `name` this rank asks for (sorted, unique); `whole` when no rank names the table (it then goes
/// whole to every rank). Collective.
std::vector<GlobalId> asked_ids(const std::string& path, const std::string& name, const WantedRows& wanted,
                                bool& whole, MPI_Comm comm) {
  const std::vector<GlobalId>* ask = wanted(name);
  whole = ask == nullptr;
  SHELLFRAC_REQUIRE(!(parallel::any(whole, comm) && parallel::any(!whole, comm)),
                    "checkpoint " << path << ": table " << name << " is asked for by some ranks only");
  std::vector<GlobalId> ids;
  if (whole) return ids;
  ids = *ask;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
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

// Every rank writes, one table at a time and about a block of checkpoint_rows_per_block rows a round: the rows
// with ids in its share of the table's id range, sent to it by the ranks that give them (merged, sorted, a row
// given by two ranks taken from the lower), at the file rows the ids before its share take. No rank ever holds
// more than its own rows and a round's; rank 0 does what the others do, plus the header's attributes.
void write_checkpoint(const std::string& path, const CheckpointData& local, MPI_Comm comm) {
  const auto names = agreed_table_names(local, comm);
  CheckpointData header;  // rank 0's scalars and strings, on every rank
  parallel::ByteWriter w;
  if (parallel::rank(comm) == 0) w = serialize_header(local, names.size());
  parallel::broadcast(w.buffer(), 0, comm);
  parallel::ByteReader r(w.buffer());
  deserialize_header(r, header);
  CheckpointFileWriter writer(path, header, names.size(), comm);
  for (const auto& name : names) write_table(name, local, writer, comm);
  writer.finish();
}

// Every rank reads its P-th of each table, a block at a time, and sends the ranks the rows they ask for
// (`wanted`; a table not asked for goes whole to every rank, a block at a time in file order): each rank holds its
// asked rows of one round at a time, and the rows it reads.
void read_checkpoint(const std::string& path, MPI_Comm comm, const WantedRows& wanted,
                     const std::function<void(const CheckpointData& header)>& header,
                     const std::function<void(const std::string& name, const CheckpointTable& rows)>& table) {
  const int me = parallel::rank(comm), np = parallel::size(comm);
  CheckpointFileReader reader(path, comm);
  header(reader.header());
  std::vector<GlobalId> piece_ids;
  std::vector<double> piece_values;
  for (const auto& name : reader.table_names()) {
    bool whole = false;
    const std::vector<GlobalId> asked = asked_ids(path, name, wanted, whole, comm);
    int width = 0;
    std::size_t num_rows = 0;
    reader.begin_table(name, width, num_rows);
    const ReadPieces pieces(num_rows, np, whole);
    for (std::size_t k = 0; k < pieces.rounds; ++k) {
      const auto [first, end] = pieces.piece(me, k);
      reader.read_rows(first, end - first, piece_ids, piece_values);
      CheckpointTable rows;
      rows.width = width;
      if (whole) {
        rows.ids = parallel::all_gather(piece_ids, comm);
        rows.values = parallel::all_gather(piece_values, comm);
      } else {
        rows = share_asked_rows(piece_ids, piece_values, width, asked, comm);
      }
      table(name, rows);
    }
  }
  reader.verify();
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
  for (auto& [name, t] : d.tables) {  // the rounds of a table asked for by rows interleave in id: sorted here
    std::vector<std::size_t> order(t.ids.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t.ids[a] < t.ids[b]; });
    CheckpointTable sorted;
    sorted.width = t.width;
    for (const std::size_t i : order) {
      sorted.ids.push_back(t.ids[i]);
      sorted.values.insert(sorted.values.end(), t.values.begin() + std::ptrdiff_t(i * std::size_t(t.width)),
                           t.values.begin() + std::ptrdiff_t((i + 1) * std::size_t(t.width)));
    }
    t = std::move(sorted);
  }
  return d;
}

}  // namespace shellfrac::io
