#include "shellfrac/decomposition/distributed_mesh.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <algorithm>
#include <cstdint>
#include <memory>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/element_maps.hpp"
#include "shellfrac/decomposition/element_migration.hpp"
#include "shellfrac/mesh/generators.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::decomposition {

namespace {

/// FNV-1a hash of the partition, to check that every rank was given the same one.
std::uint64_t hash_partition(const std::vector<int>& part) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](std::uint64_t v) {
    for (int b = 0; b < 8; ++b) {
      h ^= (v >> (8 * b)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  mix(part.size());
  for (int p : part) mix(static_cast<std::uint64_t>(static_cast<std::int64_t>(p)));
  return h;
}

/// The n entries of v from `first` on (an empty view when n = 0: no pointer into an empty vector).
Teuchos::ArrayView<const tpetra_go> view_of(const std::vector<tpetra_go>& v, std::size_t first, std::size_t n) {
  if (n == 0) return Teuchos::ArrayView<const tpetra_go>();
  return Teuchos::ArrayView<const tpetra_go>(v.data() + first,
                                             static_cast<Teuchos::ArrayView<const tpetra_go>::size_type>(n));
}

/// 1. Checks the inputs on every rank, then agrees (a rank given different data must not hang the others); then
/// checks that every rank was given the same mesh size and partition.
void check_inputs(const mesh::EdgeTopology& topo, const std::vector<int>& part, int npe, GlobalId ne, int num_ranks,
                  MPI_Comm comm) {
  parallel::on_all_then_agree(
      [&] {
        SHELLFRAC_REQUIRE(npe == num_nodes_tri3 || npe == num_nodes_tri6,
                          "DistributedMesh: nodes_per_element must be 3 or 6, got " << npe);
        SHELLFRAC_REQUIRE(static_cast<GlobalId>(part.size()) == ne,
                          "DistributedMesh: the partition has " << part.size() << " entries for " << ne << " elements");
        SHELLFRAC_REQUIRE(static_cast<GlobalId>(topo.element_edges.size()) == ne &&
                              static_cast<GlobalId>(topo.neighbor.size()) == ne &&
                              static_cast<GlobalId>(topo.element_interface.size()) == ne,
                          "DistributedMesh: the edge topology does not match the mesh (" << ne << " elements)");
        for (GlobalId e = 0; e < ne; ++e)
          SHELLFRAC_REQUIRE(part[e] >= 0 && part[e] < num_ranks, "DistributedMesh: element " << e << " has part "
                                                                      << part[e] << ", not a rank in [0, "
                                                                      << num_ranks << ")");
      },
      comm);
  unsigned long long h[2] = {hash_partition(part), 0}, lo[2] = {0, 0}, hi[2] = {0, 0};
  h[1] = static_cast<unsigned long long>(ne);
  MPI_Allreduce(h, lo, 2, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
  MPI_Allreduce(h, hi, 2, MPI_UNSIGNED_LONG_LONG, MPI_MAX, comm);
  SHELLFRAC_REQUIRE(lo[0] == hi[0] && lo[1] == hi[1],
                    "DistributedMesh: the mesh or the partition differs between ranks (they must be identical)");
}

/// 2. Owned elements (ascending gid), then the ghost layer: elements across an interface from an owned
///    element and owned elsewhere (ascending gid, unique). Sets num_owned.
std::vector<GlobalId> overlap_elements(const mesh::EdgeTopology& topo, const std::vector<int>& part, int rank,
                                       LocalId& num_owned) {
  std::vector<GlobalId> element_gid;
  const GlobalId ne = static_cast<GlobalId>(part.size());
  for (GlobalId e = 0; e < ne; ++e)
    if (part[e] == rank) element_gid.push_back(e);
  num_owned = static_cast<LocalId>(element_gid.size());
  std::vector<GlobalId> ghosts;
  for (const auto& f : topo.interfaces) {
    const GlobalId a = f.minus.element, b = f.plus.element;
    if (part[a] == rank && part[b] != rank) ghosts.push_back(b);
    if (part[b] == rank && part[a] != rank) ghosts.push_back(a);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  element_gid.insert(element_gid.end(), ghosts.begin(), ghosts.end());
  return element_gid;
}

/// 6. Tpetra maps and transfers over the overlap elements `element_gid` (collective, also on a rank without
///    elements).
std::unique_ptr<ElementMaps> make_maps(const std::vector<GlobalId>& element_gid, LocalId num_owned, GlobalId ne,
                                       MPI_Comm comm) {
  auto tcomm = Teuchos::rcp(new Teuchos::MpiComm<int>(comm));
  const std::vector<tpetra_go> gids(element_gid.begin(), element_gid.end());
  auto maps = std::make_unique<ElementMaps>();
  maps->owned = Teuchos::rcp(new map_type(static_cast<Tpetra::global_size_t>(ne),
                                           view_of(gids, 0, static_cast<std::size_t>(num_owned)), tpetra_go(0), tcomm));
  maps->overlap = Teuchos::rcp(new map_type(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                             view_of(gids, 0, gids.size()), tpetra_go(0), tcomm));
  maps->importer = Teuchos::rcp(new import_type(maps->owned, maps->overlap));
  const std::size_t nghost = gids.size() - static_cast<std::size_t>(num_owned);
  maps->ghosts = Teuchos::rcp(new map_type(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                            view_of(gids, static_cast<std::size_t>(num_owned), nghost), tpetra_go(0),
                                            tcomm));
  maps->ghost_importer = Teuchos::rcp(new import_type(maps->owned, maps->ghosts));
  const auto sent = maps->ghost_importer->getExportLIDs();
  maps->send_rows.assign(sent.begin(), sent.end());
  std::sort(maps->send_rows.begin(), maps->send_rows.end());
  maps->send_rows.erase(std::unique(maps->send_rows.begin(), maps->send_rows.end()), maps->send_rows.end());
  std::vector<tpetra_go> send_gids;
  send_gids.reserve(maps->send_rows.size());
  for (const LocalId le : maps->send_rows) send_gids.push_back(gids[std::size_t(le)]);
  maps->senders = Teuchos::rcp(new map_type(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                             view_of(send_gids, 0, send_gids.size()), tpetra_go(0), tcomm));
  maps->send_importer = Teuchos::rcp(new import_type(maps->senders, maps->ghosts));
  return maps;
}

}  // namespace

DistributedMesh::DistributedMesh(const mesh::SerialMesh& mesh, const mesh::EdgeTopology& topo,
                                 const std::vector<int>& part, MPI_Comm comm)
    : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &num_ranks_);
  npe_ = mesh.nodes_per_element;
  num_global_elements_ = mesh.num_elements();
  const GlobalId ne = num_global_elements_;
  check_inputs(topo, part, npe_, ne, num_ranks_, comm_);
  element_gid_ = overlap_elements(topo, part, rank_, num_owned_);
  const LocalId nov = num_overlap();

  // 3. Per-element data of the overlap: owner, block, DG nodes (coordinates, mesh node), directors.
  const std::vector<Vec3> normals = mesh::reference_vertex_normals(mesh);
  SHELLFRAC_REQUIRE(static_cast<GlobalId>(normals.size()) == mesh.num_nodes(),
                    "DistributedMesh: reference_vertex_normals returned " << normals.size() << " normals for "
                                                                           << mesh.num_nodes() << " nodes");
  element_owner_.resize(nov);
  element_block_.resize(nov);
  coords_.resize(static_cast<std::size_t>(nov) * npe_);
  mesh_node_.resize(static_cast<std::size_t>(nov) * npe_);
  directors_.resize(static_cast<std::size_t>(nov) * num_vertices_tri);
  neighbor_.assign(static_cast<std::size_t>(nov) * 3, -1);
  neighbor_edge_.assign(static_cast<std::size_t>(nov) * 3, -1);
  for (LocalId le = 0; le < nov; ++le) {
    const GlobalId e = element_gid_[le];
    element_owner_[le] = part[e];
    element_block_[le] = mesh.element_block[e];
    for (int a = 0; a < npe_; ++a) {
      const GlobalId n = mesh.node(e, a);
      mesh_node_[static_cast<std::size_t>(le) * npe_ + a] = n;
      coords_[static_cast<std::size_t>(le) * npe_ + a] = mesh.coords[n];
    }
    for (int a = 0; a < num_vertices_tri; ++a) directors_[static_cast<std::size_t>(le) * 3 + a] = normals[mesh.node(e, a)];
    for (int k = 0; k < 3; ++k) {
      const auto& nb = topo.neighbor[e][k];
      if (nb.element < 0) continue;
      const LocalId ln = local_id(nb.element);
      if (ln < 0) continue;
      neighbor_[static_cast<std::size_t>(le) * 3 + k] = ln;
      neighbor_edge_[static_cast<std::size_t>(le) * 3 + k] = nb.local_edge;
    }
  }

  // 4. Interfaces with at least one owned side; owned by the lower of the two owners' ranks.
  for (std::size_t i = 0; i < topo.interfaces.size(); ++i) {
    const auto& f = topo.interfaces[i];
    const int pm = part[f.minus.element], pp = part[f.plus.element];
    if (pm != rank_ && pp != rank_) continue;
    LocalInterface li;
    li.gid = static_cast<GlobalId>(i);
    li.minus = local_id(f.minus.element);
    li.plus = local_id(f.plus.element);
    li.minus_edge = f.minus.local_edge;
    li.plus_edge = f.plus.local_edge;
    li.owned = std::min(pm, pp) == rank_;
    li.non_manifold = f.non_manifold;
    SHELLFRAC_REQUIRE(li.minus >= 0 && li.plus >= 0, "DistributedMesh: interface " << i << " side not in the overlap");
    interfaces_.push_back(li);
  }

  // 5. Boundary edges of owned elements, with their side sets.
  for (std::size_t i = 0; i < topo.boundary.size(); ++i) {
    const auto& b = topo.boundary[i];
    if (part[b.element] != rank_) continue;
    LocalBoundaryEdge lb;
    lb.element = local_id(b.element);
    lb.local_edge = b.local_edge;
    if (i < topo.boundary_side_sets.size()) lb.side_sets = topo.boundary_side_sets[i];
    boundary_.push_back(std::move(lb));
  }
  overlap_sets_ = mesh::set_entries_of(mesh, element_gid_);
  if (!mesh.element_ids.empty())
    for (GlobalId g : element_gid_) element_file_ids_.push_back(mesh.element_ids.ids[std::size_t(g)]);

  maps_ = make_maps(element_gid_, num_owned_, ne, comm_);
}

DistributedMesh::DistributedMesh(const ElementPiece& piece, const LocalTopology& topo, const std::vector<int>& part,
                                 MPI_Comm comm)
    : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &num_ranks_);
  MigratedPart m = migrate_elements(piece, topo, part, comm_);
  npe_ = m.nodes_per_element;
  num_global_elements_ = m.num_global_elements;
  num_owned_ = m.num_owned;
  const std::size_t nov = m.elements.size(), npe = std::size_t(npe_);
  for (const MigratedElement& r : m.elements) element_gid_.push_back(r.gid);
  if (parallel::any(!piece.element_file_ids.empty(), comm_))  // the same on every rank
    for (const MigratedElement& r : m.elements) element_file_ids_.push_back(r.file_id);
  element_owner_.resize(nov);
  element_block_.resize(nov);
  coords_.resize(nov * npe);
  mesh_node_.resize(nov * npe);
  directors_.resize(nov * num_vertices_tri);
  neighbor_.assign(nov * 3, -1);
  neighbor_edge_.assign(nov * 3, -1);
  for (std::size_t le = 0; le < nov; ++le) {
    const MigratedElement& r = m.elements[le];
    element_owner_[le] = r.owner;
    element_block_[le] = r.block;
    for (std::size_t a = 0; a < npe; ++a) mesh_node_[le * npe + a] = r.nodes[a], coords_[le * npe + a] = r.coords[a];
    for (std::size_t k = 0; k < 3; ++k) {
      directors_[le * 3 + k] = r.directors[k];
      const LocalId ln = r.neighbor[k].element < 0 ? -1 : local_id(r.neighbor[k].element);
      if (ln < 0) continue;
      neighbor_[le * 3 + k] = ln;
      neighbor_edge_[le * 3 + k] = r.neighbor[k].local_edge;
    }
  }
  std::vector<MigratedElement>().swap(m.elements);  // the largest of the set-up's buffers: gone before the maps
  for (const MigratedInterface& r : m.interfaces) {
    const auto& f = r.interface;
    LocalInterface li;
    li.gid = r.id;
    li.minus = local_id(f.minus.element);
    li.plus = local_id(f.plus.element);
    li.minus_edge = f.minus.local_edge;
    li.plus_edge = f.plus.local_edge;
    li.owned = std::min(r.minus_owner, r.plus_owner) == rank_;
    li.non_manifold = f.non_manifold;
    SHELLFRAC_REQUIRE(li.minus >= 0 && li.plus >= 0,
                      "DistributedMesh: interface " << r.id << " side not in the overlap");
    interfaces_.push_back(li);
  }
  std::vector<MigratedInterface>().swap(m.interfaces);
  for (MigratedBoundary& b : m.boundary)
    boundary_.push_back({local_id(b.side.element), b.side.local_edge, std::move(b.side_sets)});
  std::vector<MigratedBoundary>().swap(m.boundary);
  overlap_sets_ = std::move(m.sets);
  maps_ = make_maps(element_gid_, num_owned_, num_global_elements_, comm_);
}

DistributedMesh::~DistributedMesh() = default;

LocalId DistributedMesh::local_id(GlobalId gid) const {
  // Owned gids [0, num_owned) and ghost gids [num_owned, num_overlap) are each sorted.
  const auto owned_end = element_gid_.begin() + num_owned_;
  auto it = std::lower_bound(element_gid_.begin(), owned_end, gid);
  if (it != owned_end && *it == gid) return static_cast<LocalId>(it - element_gid_.begin());
  it = std::lower_bound(owned_end, element_gid_.end(), gid);
  if (it != element_gid_.end() && *it == gid) return static_cast<LocalId>(it - element_gid_.begin());
  return -1;
}

}  // namespace shellfrac::decomposition
