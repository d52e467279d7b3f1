#include "shellfrac/meshio/exodus_piece_reader.hpp"

#include <netcdf.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/meshio/exodus_outline.hpp"

namespace shellfrac::meshio {

namespace {

/// Rank r's share of n things numbered 0..n-1 on P ranks: [r w, min(n, (r + 1) w)), w = ceil(n / P).
struct Share {
  GlobalId first = 0, end = 0;
  GlobalId size() const { return end - first; }
};

GlobalId share_width(GlobalId n, int P) { return std::max<GlobalId>(1, n / P + (n % P != 0)); }  // no overflow

Share share_of(GlobalId n, int P, int r) {
  const GlobalId w = share_width(n, P);
  return {std::min(n, r * w), std::min(n, (r + 1) * w)};
}

int share_owner(GlobalId i, GlobalId n, int P) { return static_cast<int>(i / share_width(n, P)); }

/// Index of `value` in the sorted vector v (which holds it).
std::size_t position_in(const std::vector<GlobalId>& v, GlobalId value) {
  return static_cast<std::size_t>(std::lower_bound(v.begin(), v.end(), value) - v.begin());
}

class PieceReader {
 public:
  PieceReader(const std::string& path, MPI_Comm comm)
      : path_(path), comm_(comm), rank_(parallel::rank(comm)), size_(parallel::size(comm)) {}

  mesh::MeshPiece read() {
    parallel::on_all_then_agree([&] { read_own_ranges(); }, comm_);
    check_element_id_map();
    deliver_set_entries();
    deliver_node_data();
    parallel::on_all_then_agree([&] { mesh::check_piece_elements(out_.piece, o_.num_nodes); }, comm_);
    return std::move(out_);
  }

 private:
  /// Everything this rank reads of the file: the outline, its elements, its nodes, its slices of the sets.
  void read_own_ranges() {
    detail::read_exodus_file(path_, [&](int exo_id, detail::ExodusOutline& outline) {
      id_ = exo_id;
      o_ = std::move(outline);
      make_outline();
      read_elements();
      read_element_id_map();
      read_node_share();
      read_side_set_slices();
      read_node_set_slices();
      read_element_set_slices();
    });
  }

  void make_outline() {
    out_.outline = detail::mesh_outline_of(o_, path_);
    out_.piece.nodes_per_element = o_.nodes_per_element;
    out_.piece.source = path_;
  }

  /// The connectivity of this rank's element share, block by block.
  void read_elements() {
    const int npe = o_.nodes_per_element;
    const Share mine = share_of(o_.num_elements, size_, rank_);
    mesh::ElementPiece& p = out_.piece;
    std::vector<std::int64_t> conn;
    for (std::size_t b = 0; b < o_.blocks.size(); ++b) {
      const detail::ExodusBlock& blk = o_.blocks[b];
      const GlobalId first = std::max(mine.first, blk.first), end = std::min(mine.end, blk.first + blk.count);
      if (first >= end) continue;
      conn.assign(static_cast<std::size_t>((end - first) * npe), 0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_partial_conn(id_, EX_ELEM_BLOCK, blk.id, first - blk.first + 1, end - first,
                                                    conn.data(), nullptr, nullptr),
                                path_ << ": cannot read the connectivity of " << blk.what);
      const std::int64_t offset = (first - blk.first) * npe;  // of conn[0] in the block's connectivity
      for (std::size_t k = 0; k < conn.size(); ++k)
        p.nodes.push_back(
            detail::checked_node(conn[k], offset + static_cast<std::int64_t>(k), npe, blk, o_.num_nodes, path_));
      for (GlobalId e = first; e < end; ++e) {
        p.elements.push_back(e);
        p.blocks.push_back(static_cast<int>(b));
      }
    }
  }

  /// The ids the file's element id map gives this rank's elements (FileIds; read_exodus_mesh's checks and
  /// messages). Dropped when the map is the identity on every rank: check_element_id_map.
  void read_element_id_map() {
    const Share mine = share_of(o_.num_elements, size_, rank_);
    std::vector<std::int64_t>& ids = out_.piece.element_file_ids;
    ids.assign(static_cast<std::size_t>(mine.size()), 0);
    if (!ids.empty())
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_partial_id_map(id_, EX_ELEM_MAP, mine.first + 1, mine.size(), ids.data()),
                                path_ << ": cannot read the element id map");
    for (std::size_t i = 0; i < ids.size(); ++i)
      SHELLFRAC_INPUT_REQUIRE(ids[i] > 0, path_ << ": element " << mine.first + GlobalId(i) + 1 << " has the id "
                                                << ids[i] << " in the file's element id map; ids must be positive");
  }

  /// No element id given to two elements: each id goes to the rank of its share of the ids' range, which finds
  /// the smallest repeated one, as the serial reader does. Collective.
  void check_element_id_map() {
    std::vector<std::int64_t>& ids = out_.piece.element_file_ids;
    const GlobalId first = share_of(o_.num_elements, size_, rank_).first;
    bool positions = true;
    for (std::size_t i = 0; i < ids.size() && positions; ++i) positions = ids[i] == first + GlobalId(i) + 1;
    if (!parallel::any(!positions, comm_)) {
      std::vector<std::int64_t>().swap(ids);
      return;
    }
    std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = 0;
    for (auto id : ids) lo = std::min(lo, id), hi = std::max(hi, id);
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_INT64_T, MPI_MIN, comm_);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_INT64_T, MPI_MAX, comm_);
    struct IdAt {
      std::int64_t id;
      GlobalId position;
    };
    std::vector<std::vector<IdAt>> send(static_cast<std::size_t>(size_));
    for (std::size_t i = 0; i < ids.size(); ++i)
      send[static_cast<std::size_t>(share_owner(ids[i] - lo, hi - lo + 1, size_))].push_back(
          {ids[i], first + GlobalId(i)});
    std::vector<int> counts;
    std::vector<IdAt> mine = parallel::exchange(std::move(send), counts, comm_);
    std::sort(mine.begin(), mine.end(),
              [](const IdAt& x, const IdAt& y) { return std::tie(x.id, x.position) < std::tie(y.id, y.position); });
    parallel::on_all_then_agree(
        [&] {
          for (std::size_t k = 1; k < mine.size(); ++k)
            SHELLFRAC_INPUT_REQUIRE(mine[k].id != mine[k - 1].id,
                                    path_ << ": the element id " << mine[k].id << " is given to elements "
                                          << mine[k - 1].position + 1 << " and " << mine[k].position + 1
                                          << " (positions in the file) by its element id map; ids must be unique");
        },
        comm_);
  }

  /// The coordinates of this rank's node share.
  void read_node_share() {
    const Share mine = share_of(o_.num_nodes, size_, rank_);
    const auto n = static_cast<std::size_t>(mine.size());
    std::vector<double> x(n), y(n), z(n, 0.0);
    if (n > 0)
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_partial_coord(id_, mine.first + 1, mine.size(), x.data(), y.data(),
                                                     o_.num_dim == 3 ? z.data() : nullptr),
                                path_ << ": cannot read the node coordinates");
    share_coords_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      share_coords_[i] = {x[i], y[i], z[i]};
      SHELLFRAC_INPUT_REQUIRE(std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i]),
                              path_ << ": a node has a non-finite coordinate");
    }
  }

  void read_side_set_slices() {
    side_sends_.assign(static_cast<std::size_t>(size_), {});
    std::vector<std::int64_t> elems, sides;
    for (std::size_t s = 0; s < o_.side_sets.size(); ++s) {
      const detail::ExodusSet& set = o_.side_sets[s];
      const Share slice = share_of(set.count, size_, rank_);
      if (slice.size() == 0) continue;
      elems.assign(static_cast<std::size_t>(slice.size()), 0);
      sides.assign(elems.size(), 0);
      SHELLFRAC_EXO_INPUT_CHECK(
          ex_get_partial_side_set(id_, set.id, slice.first + 1, slice.size(), elems.data(), sides.data()),
          path_ << ": cannot read the entries of " << set.what);
      for (std::size_t k = 0; k < elems.size(); ++k) {
        const int edge = detail::local_edge_of_side(o_, elems[k], sides[k], path_, set.what);
        const GlobalId e = elems[k] - 1;
        side_sends_[static_cast<std::size_t>(share_owner(e, o_.num_elements, size_))].push_back(
            {e, edge, static_cast<int>(s)});
      }
    }
  }

  void read_node_set_slices() {
    node_set_sends_.assign(static_cast<std::size_t>(size_), {});
    std::vector<std::int64_t> entries;
    for (std::size_t s = 0; s < o_.node_sets.size(); ++s) {
      const detail::ExodusSet& set = o_.node_sets[s];
      const Share slice = share_of(set.count, size_, rank_);
      if (slice.size() == 0) continue;
      entries.assign(static_cast<std::size_t>(slice.size()), 0);
      SHELLFRAC_EXO_INPUT_CHECK(ex_get_partial_node_set(id_, set.id, slice.first + 1, slice.size(), entries.data()),
                                path_ << ": cannot read the entries of " << set.what);
      route_set_entries(entries, static_cast<int>(s), o_.num_nodes, set.what, "node", node_set_sends_);
    }
  }

  /// Exodus 6.02 has no partial read of an element set: its entries are read from the netCDF variable that
  /// holds them (elem_els<k>, k the set's position in the file; its size was checked by check_exodus_structure).
  void read_element_set_slices() {
    element_set_sends_.assign(static_cast<std::size_t>(size_), {});
    std::vector<long long> entries;
    for (std::size_t s = 0; s < o_.element_sets.size(); ++s) {
      const detail::ExodusSet& set = o_.element_sets[s];
      const Share slice = share_of(set.count, size_, rank_);
      if (slice.size() == 0) continue;
      entries.assign(static_cast<std::size_t>(slice.size()), 0);
      const std::string var = "elem_els" + std::to_string(s + 1);
      int varid = -1;
      const std::size_t start = static_cast<std::size_t>(slice.first), count = entries.size();
      SHELLFRAC_INPUT_REQUIRE(nc_inq_varid(id_, var.c_str(), &varid) == NC_NOERR &&
                                  nc_get_vara_longlong(id_, varid, &start, &count, entries.data()) == NC_NOERR,
                              path_ << ": cannot read the entries of " << set.what);
      const std::vector<std::int64_t> values(entries.begin(), entries.end());
      route_set_entries(values, static_cast<int>(s), o_.num_elements, set.what, "element", element_set_sends_);
    }
  }

  /// 1-based entries of set `s` (of `n` nodes or elements) to the ranks of their shares.
  void route_set_entries(const std::vector<std::int64_t>& entries, int s, GlobalId n, const std::string& what,
                         const char* entity, std::vector<std::vector<mesh::SetEntry>>& sends) const {
    for (auto value : entries) {
      const GlobalId member = detail::checked_index(value, n, path_, what, entity);
      sends[static_cast<std::size_t>(share_owner(member, n, size_))].push_back({member, s});
    }
  }

  /// Side and element set entries to the ranks of their elements; node set entries to the ranks of their nodes.
  void deliver_set_entries() {
    std::vector<int> counts;
    mesh::ElementPiece& p = out_.piece;
    p.side_entries = parallel::exchange(std::move(side_sends_), counts, comm_);
    mesh::sort_side_entries(p.side_entries);
    p.element_set_entries = parallel::exchange(std::move(element_set_sends_), counts, comm_);
    mesh::sort_set_entries(p.element_set_entries);
    share_node_set_entries_ = parallel::exchange(std::move(node_set_sends_), counts, comm_);
    mesh::sort_set_entries(share_node_set_entries_);
  }

  /// The coordinates and the node set entries of the nodes of this rank's elements, from their shares' ranks.
  void deliver_node_data() {
    mesh::ElementPiece& p = out_.piece;
    std::vector<GlobalId> wanted = p.nodes;
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    std::vector<std::vector<GlobalId>> requests(static_cast<std::size_t>(size_));
    for (GlobalId n : wanted) requests[static_cast<std::size_t>(share_owner(n, o_.num_nodes, size_))].push_back(n);
    std::vector<int> counts;
    std::vector<GlobalId> asked = parallel::exchange(std::move(requests), counts, comm_);

    // Answers in the order asked: requests from each rank are ascending, so are the node set entries.
    const GlobalId first = share_of(o_.num_nodes, size_, rank_).first;
    std::vector<std::vector<Vec3>> coords(static_cast<std::size_t>(size_));
    std::vector<std::vector<mesh::SetEntry>> entries(static_cast<std::size_t>(size_));
    std::size_t k = 0;
    for (int q = 0; q < size_; ++q)
      for (int i = 0; i < counts[static_cast<std::size_t>(q)]; ++i, ++k) {
        const GlobalId n = asked[k];
        coords[static_cast<std::size_t>(q)].push_back(share_coords_[static_cast<std::size_t>(n - first)]);
        auto it = std::lower_bound(share_node_set_entries_.begin(), share_node_set_entries_.end(), n,
                                   [](const mesh::SetEntry& x, GlobalId v) { return x.member < v; });
        for (; it != share_node_set_entries_.end() && it->member == n; ++it)
          entries[static_cast<std::size_t>(q)].push_back(*it);
      }
    std::vector<Vec3>().swap(share_coords_);
    std::vector<mesh::SetEntry>().swap(share_node_set_entries_);
    std::vector<GlobalId>().swap(asked);
    const std::vector<Vec3> wanted_coords = parallel::exchange(std::move(coords), counts, comm_);
    p.node_set_entries = parallel::exchange(std::move(entries), counts, comm_);
    p.coords.resize(p.nodes.size());
    for (std::size_t i = 0; i < p.nodes.size(); ++i) p.coords[i] = wanted_coords[position_in(wanted, p.nodes[i])];
  }

  const std::string& path_;
  MPI_Comm comm_;
  int rank_, size_;
  int id_ = -1;
  detail::ExodusOutline o_;
  std::vector<Vec3> share_coords_;                      ///< of this rank's node share
  std::vector<mesh::SetEntry> share_node_set_entries_;  ///< the node set entries of this rank's node share
  std::vector<std::vector<mesh::SideEntry>> side_sends_;
  std::vector<std::vector<mesh::SetEntry>> node_set_sends_, element_set_sends_;
  mesh::MeshPiece out_;
};

}  // namespace

mesh::MeshPiece read_exodus_piece(const std::string& path, MPI_Comm comm) { return PieceReader(path, comm).read(); }

}  // namespace shellfrac::meshio
