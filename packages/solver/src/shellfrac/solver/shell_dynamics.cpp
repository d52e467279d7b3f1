#include "shellfrac/solver/shell_dynamics.hpp"

#include <Kokkos_Core.hpp>
#include <chrono>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/disc/lumped_mass.hpp"
#include "shellfrac/disc/stable_time_step.hpp"
#include "shellfrac/dist/distributed_mesh.hpp"
#include "shellfrac/dist/element_maps.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"
#include "shellfrac/solver/cohesive_interface.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"

namespace shellfrac::solver {

namespace {
constexpr int nx = 18;            // position values per element (6 nodes x 3)
constexpr int nt = 9;             // director values per element (3 vertices x 3)
constexpr int nstate = nx + nt;   // columns of the ghost-exchanged state
constexpr int nflux_edge = 15;    // lifting flux per edge: 3 position nodes x 3 + 2 director nodes x 3
constexpr int nflux = 3 * nflux_edge;
constexpr int nedge_nm = 3 * disc::num_edge_points * 6;  // projected edge force + couple per edge point (fracture)
enum InterfaceState : int { intact = 0, cohesive = 1, separated = 2 };
using exec = dist::execution_space;
constexpr int nq = disc::num_area_points;

/// The inputs of the element kernel for owned element le (dg_element_forces / dg_kinematics): its nodes, its
/// lifted edges and, across each lifted edge, the neighbour's edge nodes in the neighbour's edge-local order.
KOKKOS_INLINE_FUNCTION void element_inputs(const dist::DistributedMesh& d, const double* xp, const double* tp,
                                           const std::array<bool, 3>& lift, LocalId le, double xe[6][3],
                                           double te[3][3], bool lf[3], double xn[3][3][3], double tn[3][2][3]) {
  for (int i = 0; i < nx; ++i) xe[i / 3][i % 3] = xp[le * nx + i];
  for (int i = 0; i < nt; ++i) te[i / 3][i % 3] = tp[le * nt + i];
  for (int k = 0; k < 3; ++k) {
    lf[k] = lift[k];
    if (!lf[k]) continue;
    const LocalId nb = d.neighbor(le, k);
    const int kk = d.neighbor_edge(le, k);
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) xn[k][j][c] = xp[nb * nx + disc::edge_node(kk, j) * 3 + c];
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) tn[k][j][c] = tp[nb * nt + disc::edge_node(kk, j) * 3 + c];
  }
}

/// von Mises norm of a resultant triple [X11, X22, X12]: sqrt(X11^2 - X11 X22 + X22^2 + 3 X12^2).
double vm_norm(const double X[3]) {
  return std::sqrt(std::max(0.0, X[0] * X[0] - X[0] * X[1] + X[1] * X[1] + 3 * X[2] * X[2]));
}
/// Sum of values contributed by all ranks, in increasing id order (bitwise independent of the rank count).
double ordered_sum(const std::vector<GlobalId>& ids, const std::vector<double>& vals, MPI_Comm comm) {
  const auto all_ids = parallel::all_gather(ids, comm);
  const auto all_vals = parallel::all_gather(vals, comm);
  std::vector<std::size_t> order(all_ids.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return all_ids[p] < all_ids[q]; });
  double sum = 0;
  for (std::size_t i : order) sum += all_vals[i];
  return sum;
}
}  // namespace

struct ShellDynamics::Impl {
  const dist::DistributedMesh& dm;
  DynamicsSetup setup;
  LocalId no = 0, nov = 0;
  std::vector<disc::DgElementRef> refs;        // owned
  std::vector<std::array<bool, 3>> lift;        // owned: lifted edges
  std::vector<materials::ElasticSection> sect;  // overlap
  // Resultant plasticity (math.md §4), owned elements: section, flag, state at t_n (committed) and t_{n+1}
  // (written by the element kernel) per area point, plastic work of the last kernel call and accumulated.
  bool any_plastic = false;
  std::vector<materials::PlasticSection> psect;
  std::vector<char> plastic_el;
  std::vector<materials::PlasticState> pstate, pstate_new;
  std::vector<double> pwork_step, plastic_work;
  std::vector<int> return_failed;
  // Fracture (math.md §9), per local interface: may it break, its cohesive parameters, its state, delta_max and
  // the last co-normal at its edge points, its stored and dissipated cohesive energy, the DG energy released
  // when it was activated (penalty part); per owned element: the strain energy released by switching off the
  // lifting of its edges. edge_nm (overlap): the elements' projected edge tractions for the nucleation check.
  bool fracture = false;  // some interface of the mesh may break (the same on every rank)
  int nflux_cols = nflux;
  std::vector<char> breakable;
  std::vector<materials::CohesiveParams> cparams;
  std::vector<int> istate;
  std::vector<double> dmax, conormal, ucoh, dcoh, act_i, act_e;
  std::vector<double> edge_nm;
  std::vector<double> crack_log;  // activations of owned interfaces not yet reported, crack_log_width each
  std::vector<std::array<GlobalId, 3>> all_interfaces;  // fracture: (gid, minus gid, plus gid) of every interface
  mutable GlobalId fragments_at = -1;                   // number of separated interfaces the cache belongs to
  mutable GlobalId fragments = 0;
  mutable std::vector<GlobalId> fragment_root;           // per global element: smallest element gid of its fragment
  std::vector<double> beta_x, beta_t;           // overlap
  std::vector<double> mass, inertia;            // owned: [no*6], [no*3]
  std::vector<double> X;                        // overlap reference positions [nov*18]
  std::vector<double> x, t;                     // overlap current positions, directors
  std::vector<double> v, a, Lam, Tdot, Tddot;   // owned
  std::vector<char> fixed_x, fixed_t;           // owned: per DG position node / director node: clamped/supported
  std::vector<int> presc;                       // owned position node: index of its Prescribed Velocity BC, or -1
  std::vector<std::vector<Vec3>> sym_x, sym_t;  // owned position / director node: symmetry-plane normals
  std::vector<std::uint32_t> bc_mask;           // owned position node: bit b set if BC b acts on it
  /// A director node whose rotation is prescribed (Prescribed Rotation): t = R(theta(t)) t0, Lambda = R Lambda0.
  struct RotNode {
    LocalId le;
    int b, bc;
    double t0[3], L0[3][3];
    double t_prev[3], g_prev[3], kin_prev;  // previous step, for the reaction work
  };
  std::vector<RotNode> rot_nodes;
  std::vector<double> fext, fext_old, react, react_old, x_old;  // owned: loads, reactions, previous positions
  std::vector<double> gravity_force;            // owned: constant lumped gravity loads
  std::vector<std::vector<LocalId>> pressure_elements;  // per load: owned elements carrying it
  std::vector<double> work_ext, work_react, dissipated;  // owned element accounts
  std::vector<double> f, g, energy_e;           // owned: forces, spatial director moments, strain energy
  std::vector<double> flux;                     // overlap: lifting fluxes written by each element for its neighbours
  // interfaces (all local ones)
  std::vector<disc::DgInterfaceRef> iref;
  std::vector<double> ibeta_x, ibeta_t, fi, gi, energy_i;
  std::vector<std::vector<std::pair<int, int>>> incident;  // owned element -> (local interface, side 0 = minus)
  // Tpetra transfer buffers: owned rows (only the send rows are filled) and ghost rows
  Teuchos::RCP<dist::multivector_type> state_own, state_ghost, flux_own, flux_ghost;
  double dt_stable = 0, dt = 0, time = 0;
  long step = 0;
  PhaseTimes times;

  Impl(const mesh::SerialMesh& mesh, const dist::DistributedMesh& d, const DynamicsSetup& s);
  void sync_state();
  void compute_forces();
  void check_finite() const;
  void commit_plasticity();
  void nucleate(double t1);
  void log_activation(std::size_t i, double t1, double fbar, const double xm[3][3], const double n[3][3],
                      const double m[3][3], const double nu[3][3]);
  double element_energy(LocalId le) const;
  template <class F>
  void area_points(LocalId le, F&& f) const;
  void update_fragments() const;
  void external_forces(double t);
  Vec3 prescribed_displacement(int bc, double t) const;
  Vec3 prescribed_velocity(int bc, double t) const;
  /// Whether component c of owned position node i follows a Prescribed Velocity condition.
  bool prescribed(LocalId i, int c) const {
    return presc[i] >= 0 && setup.boundary_conditions[presc[i]].components[c];
  }
  Vec3 prescribed_acceleration(int bc, double t) const;
  void apply_rotations(double t);
  double rotary_kinetic(LocalId le, int b) const {
    const double* T = &Tdot[le * 6 + b * 2];
    return 0.5 * inertia[le * 3 + b] * (T[0] * T[0] + T[1] * T[1]);
  }
};

// Prescribed director rotations (math.md §10.2): t = R(a, theta(t)) t0, Lambda = R Lambda0 and the material
// director rate Tdot = Lambda-bar^T (theta-dot a x t).
void ShellDynamics::Impl::apply_rotations(double time) {
  for (const auto& rn : rot_nodes) {
    const auto& bc = setup.boundary_conditions[rn.bc];
    double R[3][3], L[3][3], w[3], td[3], T[2];
    disc::axis_angle_rotation(bc.axis.data(), bc.rotation_angle(time), R);
    disc::mat_vec(R, rn.t0, &t[rn.le * nt + rn.b * 3]);
    disc::mat_mat(R, rn.L0, L);
    for (int i = 0; i < 9; ++i) Lam[rn.le * 27 + rn.b * 9 + i] = L[i / 3][i % 3];
    for (int c = 0; c < 3; ++c) w[c] = bc.rotation_rate(time) * bc.axis[c];
    disc::cross3(w, &t[rn.le * nt + rn.b * 3], td);
    disc::lambda_bar_transpose_times(L, td, T);
    Tdot[rn.le * 6 + rn.b * 2] = T[0], Tdot[rn.le * 6 + rn.b * 2 + 1] = T[1];
  }
}

// Cosine velocity ramp with its exact displacement integral (math.md §10.2):
// r(t) = (1 - cos(pi t/t_r))/2 for t < t_r, 1 afterwards.
Vec3 ShellDynamics::Impl::prescribed_velocity(int bc, double t) const {
  const auto& b = setup.boundary_conditions[bc];
  const double tr = b.ramp_time, r = (tr > 0 && t < tr) ? 0.5 * (1 - std::cos(M_PI * t / tr)) : 1.0;
  return {r * b.velocity[0], r * b.velocity[1], r * b.velocity[2]};
}
Vec3 ShellDynamics::Impl::prescribed_displacement(int bc, double t) const {
  const auto& b = setup.boundary_conditions[bc];
  const double tr = b.ramp_time;
  const double u = (tr > 0 && t < tr) ? 0.5 * t - tr / (2 * M_PI) * std::sin(M_PI * t / tr) : t - 0.5 * tr;
  return {u * b.velocity[0], u * b.velocity[1], u * b.velocity[2]};
}
Vec3 ShellDynamics::Impl::prescribed_acceleration(int bc, double t) const {
  const auto& b = setup.boundary_conditions[bc];
  const double tr = b.ramp_time, r = (tr > 0 && t < tr) ? M_PI / (2 * tr) * std::sin(M_PI * t / tr) : 0.0;
  return {r * b.velocity[0], r * b.velocity[1], r * b.velocity[2]};
}

ShellDynamics::Impl::Impl(const mesh::SerialMesh& mesh, const dist::DistributedMesh& d, const DynamicsSetup& s)
    : dm(d), setup(s), no(d.num_owned()), nov(d.num_overlap()) {
  SHELLFRAC_REQUIRE(dm.nodes_per_element() == 6, "the DG shell needs TRI6 elements");
  const auto& file = setup.deck_file;
  // Sections and DG penalty constants per overlap element (paper eq. 42).
  sect.resize(nov), beta_x.resize(nov), beta_t.resize(nov);
  for (LocalId le = 0; le < nov; ++le) {
    const Section& sc = setup.block_sections.at(dm.element_block(le));
    sect[le] = materials::make_elastic_section(sc.E, sc.nu, sc.h);
    beta_x[le] = setup.discretization.cx * sc.E * sc.h;
    beta_t[le] = setup.discretization.cT * sc.E * sc.h * sc.h * sc.h / 12;
  }
  psect.resize(no), plastic_el.assign(no, 0);
  for (LocalId le = 0; le < no; ++le) {
    const Section& sc = setup.block_sections.at(dm.element_block(le));
    if (!sc.plastic) continue;
    plastic_el[le] = 1, any_plastic = true;
    psect[le] = materials::make_plastic_section(sc.E, sc.nu, sc.h, sc.Y0, sc.H, sc.shear_yield);
  }
  pstate.assign(any_plastic ? no * nq : 0, materials::PlasticState{});
  pstate_new = pstate;
  pwork_step.assign(no, 0.0), plastic_work.assign(no, 0.0), return_failed.assign(no, 0);
  // Reference positions and directors (overlap).
  X.resize(nov * nx), t.resize(nov * nt);
  for (LocalId le = 0; le < nov; ++le) {
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) X[le * nx + A * 3 + c] = dm.node_coords(le, A)[c];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) t[le * nt + a * 3 + c] = dm.reference_director(le, a)[c];
  }
  x = X;
  // Non-manifold interfaces are penalized but not lifted (a kink has no single neighbour).
  std::set<std::pair<LocalId, int>> not_lifted;
  for (const auto& fc : dm.interfaces())
    if (fc.non_manifold) not_lifted.insert({fc.minus, fc.minus_edge}), not_lifted.insert({fc.plus, fc.plus_edge});
  // Element reference data, lifted edges, masses.
  refs.resize(no), lift.resize(no), mass.resize(no * 6), inertia.resize(no * 3);
  dt_stable = std::numeric_limits<double>::max();
  for (LocalId le = 0; le < no; ++le) {
    double Xe[6][3], Te[3][3];
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) Xe[A][c] = X[le * nx + A * 3 + c];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) Te[a][c] = t[le * nt + a * 3 + c];
    bool same[3];
    for (int k = 0; k < 3; ++k) {
      const LocalId nb = dm.neighbor(le, k);
      lift[le][k] = nb >= 0 && !not_lifted.count({le, k});
      same[k] = nb >= 0 && dm.mesh_node(le, disc::edge_node(k, 0)) ==
                               dm.mesh_node(nb, disc::edge_node(dm.neighbor_edge(le, k), 0));
    }
    disc::build_dg_element_ref(Xe, Te, same, refs[le]);
    const Section& sc = setup.block_sections.at(dm.element_block(le));
    double m[6], I[3];
    disc::hrz_lumped_mass(Xe, sc.rho * sc.h, m);
    disc::hrz_rotary_inertia(Xe, setup.time.rotary_inertia_scale * sc.rho * sc.h * sc.h * sc.h / 12, I);
    for (int A = 0; A < 6; ++A) mass[le * 6 + A] = m[A];
    for (int a = 0; a < 3; ++a) inertia[le * 3 + a] = I[a];
    disc::StableStepParams sp{sc.E, sc.nu, sc.rho, sc.h};
    sp.cx = setup.discretization.cx, sp.cT = setup.discretization.cT, sp.rotary_scale = setup.time.rotary_inertia_scale;
    dt_stable = std::min(dt_stable, disc::element_stable_dt(sp, disc::characteristic_length(Xe)));
  }
  dt_stable = -parallel::max(-dt_stable, dm.comm());  // global minimum (exact, rank-count independent)
  const auto& tp = setup.time;
  if (tp.time_step > 0) {
    SHELLFRAC_INPUT_REQUIRE(tp.force_time_step || tp.time_step <= dt_stable,
                            file << ": 'Time Integration->Time Step' = " << tp.time_step
                                 << " exceeds the stable estimate " << dt_stable
                                 << " (math.md §8); lower it, or set 'Force Time Step' to true to run anyway");
    dt = tp.time_step;
  } else {
    dt = tp.safety_factor * dt_stable;
  }
  // Interfaces.
  const auto& ifs = dm.interfaces();
  const int ni = static_cast<int>(ifs.size());
  iref.resize(ni), ibeta_x.resize(ni), ibeta_t.resize(ni), fi.resize(ni * 2 * nflux_edge), energy_i.resize(ni);
  incident.resize(no);
  for (int i = 0; i < ni; ++i) {
    const auto& fc = ifs[i];
    // Reference edge data of the minus side, built with the same routine as the elements' own data.
    double Xe[6][3], Te[3][3];
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) Xe[A][c] = X[fc.minus * nx + A * 3 + c];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) Te[a][c] = t[fc.minus * nt + a * 3 + c];
    bool same[3] = {false, false, false};
    same[fc.minus_edge] = dm.mesh_node(fc.minus, disc::edge_node(fc.minus_edge, 0)) ==
                          dm.mesh_node(fc.plus, disc::edge_node(fc.plus_edge, 0));
    disc::DgElementRef r;
    disc::build_dg_element_ref(Xe, Te, same, r);
    disc::build_dg_interface_ref(r.edge[fc.minus_edge], iref[i]);
    // CHOICE: sides of different blocks use the mean of their penalty constants.
    ibeta_x[i] = 0.5 * (beta_x[fc.minus] + beta_x[fc.plus]);
    ibeta_t[i] = 0.5 * (beta_t[fc.minus] + beta_t[fc.plus]);
    if (fc.minus < no) incident[fc.minus].push_back({i, 0});
    if (fc.plus < no) incident[fc.plus].push_back({i, 1});
  }
  // Fracture: an interior, manifold interface between two breakable sections, in the Fracture->Edges set.
  {
    const auto& fr = setup.fracture;
    std::set<std::pair<GlobalId, int>> allowed;
    if (fr.edges != "all") {
      const auto it = std::find_if(mesh.side_sets.begin(), mesh.side_sets.end(),
                                   [&](const auto& ss) { return ss.name == fr.edges; });
      std::string names;
      for (const auto& ss : mesh.side_sets) names += " '" + ss.name + "'";
      SHELLFRAC_INPUT_REQUIRE(it != mesh.side_sets.end(), file << ": 'Fracture->Edges' names side set '" << fr.edges
                                                              << "', which the mesh (" << mesh.source
                                                              << ") does not have; its side sets:" << names);
      for (std::size_t k = 0; k < it->elements.size(); ++k) allowed.insert({it->elements[k], it->local_edges[k]});
    }
    breakable.assign(ni, 0), cparams.resize(ni), istate.assign(ni, intact);
    dmax.assign(ni * 3, 0.0), conormal.assign(ni * 9, 0.0), ucoh.assign(ni, 0.0), dcoh.assign(ni, 0.0);
    act_i.assign(ni, 0.0), act_e.assign(no, 0.0);
    bool any = false;
    for (int i = 0; i < ni; ++i) {
      const auto& fc = ifs[i];
      const Section& a = setup.block_sections.at(dm.element_block(fc.minus));
      const Section& b = setup.block_sections.at(dm.element_block(fc.plus));
      if (fc.non_manifold || a.sigma_c <= 0 || b.sigma_c <= 0) continue;
      if (fr.edges != "all" && !allowed.count({dm.element_gid(fc.minus), fc.minus_edge}) &&
          !allowed.count({dm.element_gid(fc.plus), fc.plus_edge}))
        continue;
      // CHOICE: sides of different sections use the mean thickness, strength and work of separation.
      breakable[i] = 1, any = true;
      cparams[i] = materials::make_cohesive_params(0.5 * (a.h + b.h), 0.5 * (a.sigma_c + b.sigma_c),
                                                   0.5 * (a.Gamma + b.Gamma), fr.alpha1, fr.alpha2, fr.alpha3);
    }
    fracture = parallel::any(any, dm.comm());
    nflux_cols = nflux + (fracture ? nedge_nm : 0);
    if (fracture) {
      std::vector<GlobalId> mine;
      for (const auto& fc : ifs)
        if (fc.owned) mine.insert(mine.end(), {fc.gid, dm.element_gid(fc.minus), dm.element_gid(fc.plus)});
      const auto all = parallel::all_gather(mine, dm.comm());
      for (std::size_t k = 0; k + 2 < all.size(); k += 3) all_interfaces.push_back({all[k], all[k + 1], all[k + 2]});
      std::sort(all_interfaces.begin(), all_interfaces.end());
    }
  }
  // Elements named by a condition or load: 'all', an element set or a block (flag per mesh element).
  const auto element_members = [&](const std::string& what, const std::string& name) {
    std::vector<char> member(mesh.num_elements(), 0);
    bool found = name == "all";
    if (found) std::fill(member.begin(), member.end(), 1);
    for (const auto& es : mesh.element_sets)
      if (es.name == name) {
        found = true;
        for (GlobalId e : es.elements) member[e] = 1;
      }
    for (std::size_t bl = 0; bl < mesh.blocks.size(); ++bl)
      if (mesh.blocks[bl].name == name) {
        found = true;
        for (GlobalId e = 0; e < mesh.num_elements(); ++e)
          if (mesh.element_block[e] == static_cast<int>(bl)) member[e] = 1;
      }
    SHELLFRAC_INPUT_REQUIRE(found, file << ": " << what << " names '" << name
                                        << "', which is neither 'all' nor an element set or block of the mesh");
    return member;
  };
  // Boundary conditions on every DG copy of the nodes of a node set (math.md §10.1-10.2), or only on the copies
  // that belong to the condition's Elements.
  fixed_x.assign(no * 6, 0), fixed_t.assign(no * 3, 0), presc.assign(no * 6, -1);
  std::vector<int> rot_bc(no * 3, -1);
  sym_x.assign(no * 6, {}), sym_t.assign(no * 3, {}), bc_mask.assign(no * 6, 0);
  SHELLFRAC_INPUT_REQUIRE(setup.boundary_conditions.size() <= 32, file << ": at most 32 boundary conditions");
  for (std::size_t ib = 0; ib < setup.boundary_conditions.size(); ++ib) {
    const auto& bc = setup.boundary_conditions[ib];
    const auto it = std::find_if(mesh.node_sets.begin(), mesh.node_sets.end(),
                                 [&](const auto& ns) { return ns.name == bc.node_set; });
    std::string names;
    for (const auto& ns : mesh.node_sets) names += " '" + ns.name + "'";
    const bool every_node = bc.node_set == "all";
    SHELLFRAC_INPUT_REQUIRE(every_node || it != mesh.node_sets.end(),
                            file << ": boundary condition '" << bc.name << "' names node set '" << bc.node_set
                                 << "', which the mesh (" << mesh.source << ") does not have; its node sets:" << names
                                 << " (or 'all')");
    std::vector<char> member(mesh.num_nodes(), every_node ? 1 : 0);
    if (!every_node)
      for (GlobalId n : it->nodes) member[n] = 1;
    const auto in_elements = element_members("boundary condition '" + bc.name + "' (Elements)", bc.elements);
    for (LocalId le = 0; le < no; ++le)
      for (int A = 0; A < 6; ++A) {
        if (!member[dm.mesh_node(le, A)] || !in_elements[dm.element_gid(le)]) continue;
        const int i = le * 6 + A;
        bc_mask[i] |= 1u << ib;
        using T = BoundaryCondition::Type;
        switch (bc.type) {
          case T::Clamped:
            fixed_x[i] = 1;
            if (A < 3) fixed_t[le * 3 + A] = 1;
            break;
          case T::SimplySupported: fixed_x[i] = 1; break;
          case T::Symmetry:
            sym_x[i].push_back(bc.normal);
            if (A < 3) sym_t[le * 3 + A].push_back(bc.normal);
            break;
          case T::PrescribedVelocity:
            presc[i] = static_cast<int>(ib);
            if (A < 3) fixed_t[le * 3 + A] = 1;
            break;
          case T::PrescribedRotation:
            if (A < 3) rot_bc[le * 3 + A] = static_cast<int>(ib);
            break;
        }
      }
  }
  // A clamped/supported node is fixed whatever else acts on it; a director clamped by another condition is not
  // rotated.
  for (LocalId i = 0; i < no * 6; ++i)
    if (fixed_x[i]) presc[i] = -1, sym_x[i].clear();
  for (LocalId le = 0; le < no; ++le)
    for (int b = 0; b < 3; ++b)
      if (rot_bc[le * 3 + b] >= 0 && !fixed_t[le * 3 + b]) {
        fixed_t[le * 3 + b] = 1, sym_t[le * 3 + b].clear();
        RotNode rn{};
        rn.le = le, rn.b = b, rn.bc = rot_bc[le * 3 + b];
        disc::copy3(&t[le * nt + b * 3], rn.t0);
        rot_nodes.push_back(rn);
      }
  // Loads: element lists of pressure loads, lumped gravity forces (constant).
  gravity_force.assign(no * nx, 0.0);
  for (const auto& load : setup.loads) {
    const auto member = element_members("load '" + load.name + "'", load.elements);
    pressure_elements.emplace_back();
    for (LocalId le = 0; le < no; ++le) {
      if (!member[dm.element_gid(le)]) continue;
      if (load.type == Load::Type::Pressure) {
        pressure_elements.back().push_back(le);
      } else {
        for (int A = 0; A < 6; ++A)
          for (int c = 0; c < 3; ++c) gravity_force[le * nx + A * 3 + c] += mass[le * 6 + A] * load.acceleration[c];
      }
    }
  }
  fext.assign(no * nx, 0.0), react.assign(no * nx, 0.0), x_old.assign(no * nx, 0.0);
  work_ext.assign(no, 0.0), work_react.assign(no, 0.0), dissipated.assign(no, 0.0);
  // Initial velocities on every DG copy of the nodes of the listed elements (no spurious initial jumps).
  v.assign(no * nx, 0.0);
  for (const auto& iv : setup.initial_velocities) {
    std::vector<char> member(mesh.num_nodes(), 0);
    const auto mark = [&](GlobalId e) {
      for (int A = 0; A < mesh.nodes_per_element; ++A) member[mesh.node(e, A)] = 1;
    };
    bool found = iv.elements == "all";
    if (found)
      for (GlobalId e = 0; e < mesh.num_elements(); ++e) mark(e);
    for (const auto& es : mesh.element_sets)
      if (es.name == iv.elements) {
        found = true;
        for (GlobalId e : es.elements) mark(e);
      }
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
      if (mesh.blocks[b].name == iv.elements) {
        found = true;
        for (GlobalId e = 0; e < mesh.num_elements(); ++e)
          if (mesh.element_block[e] == static_cast<int>(b)) mark(e);
      }
    SHELLFRAC_INPUT_REQUIRE(found, file << ": initial condition '" << iv.name << "' names '" << iv.elements
                                        << "', which is neither 'all' nor an element set or block of the mesh");
    for (LocalId le = 0; le < no; ++le)
      for (int A = 0; A < 6; ++A)
        if (member[dm.mesh_node(le, A)] && !fixed_x[le * 6 + A] && presc[le * 6 + A] < 0) {
          Vec3 vel = iv.velocity;
          const double r[3] = {X[le * nx + A * 3] - iv.center[0], X[le * nx + A * 3 + 1] - iv.center[1],
                               X[le * nx + A * 3 + 2] - iv.center[2]};
          double spin[3];
          disc::cross3(iv.angular_velocity.data(), r, spin);
          for (int c = 0; c < 3; ++c) vel[c] += spin[c];
          if (iv.normal_velocity != 0) {
            // Reference director at the node: exact at vertices; at a mid-side node the normalized mean of its
            // edge's vertex directors (the same in every DG copy, so no initial jumps).
            double n[3];
            if (A < 3) {
              disc::copy3(&t[le * nt + A * 3], n);
            } else {
              disc::add3(&t[le * nt + disc::edge_node(A - 3, 0) * 3], &t[le * nt + disc::edge_node(A - 3, 1) * 3], n);
              disc::normalize3(n);
            }
            for (int c = 0; c < 3; ++c) vel[c] += iv.normal_velocity * n[c];
          }
          for (const auto& n : sym_x[le * 6 + A]) {  // no velocity across a symmetry plane
            const double vn = vel[0] * n[0] + vel[1] * n[1] + vel[2] * n[2];
            for (int c = 0; c < 3; ++c) vel[c] -= vn * n[c];
          }
          for (int c = 0; c < 3; ++c) v[le * nx + A * 3 + c] = vel[c];
        }
  }
  // Director state: rotations from Rodrigues (paper A.1), at rest.
  Lam.resize(no * 27), Tdot.assign(no * 6, 0.0), Tddot.assign(no * 6, 0.0), a.assign(no * nx, 0.0);
  for (LocalId le = 0; le < no; ++le)
    for (int b = 0; b < 3; ++b) {
      double L[3][3];
      disc::initial_rotation(&t[le * nt + b * 3], L);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Lam[le * 27 + b * 9 + i * 3 + j] = L[i][j];
    }
  for (auto& rn : rot_nodes)
    for (int i = 0; i < 9; ++i) rn.L0[i / 3][i % 3] = Lam[rn.le * 27 + rn.b * 9 + i];
  // Director rates of a rigid spin: tdot = omega x t, material components Tdot = Lambda-bar^T tdot.
  for (const auto& iv : setup.initial_velocities) {
    if (iv.angular_velocity == Vec3{0, 0, 0}) continue;
    std::vector<char> member(mesh.num_nodes(), 0);
    for (GlobalId e = 0; e < mesh.num_elements(); ++e) {
      bool in = iv.elements == "all";
      for (const auto& es : mesh.element_sets)
        if (es.name == iv.elements) in = in || std::binary_search(es.elements.begin(), es.elements.end(), e);
      for (std::size_t bl = 0; bl < mesh.blocks.size(); ++bl)
        if (mesh.blocks[bl].name == iv.elements) in = in || mesh.element_block[e] == static_cast<int>(bl);
      if (in)
        for (int A = 0; A < mesh.nodes_per_element; ++A) member[mesh.node(e, A)] = 1;
    }
    for (LocalId le = 0; le < no; ++le)
      for (int b = 0; b < 3; ++b) {
        if (!member[dm.mesh_node(le, b)] || fixed_t[le * 3 + b]) continue;
        double td[3], L[3][3], T[2];
        disc::cross3(iv.angular_velocity.data(), &t[le * nt + b * 3], td);
        for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = Lam[le * 27 + b * 9 + i];
        disc::lambda_bar_transpose_times(L, td, T);
        Tdot[le * 6 + b * 2] += T[0], Tdot[le * 6 + b * 2 + 1] += T[1];
      }
  }
  f.resize(no * nx), g.resize(no * nt), energy_e.resize(no), flux.assign(nov * nflux_cols, 0.0);
  const auto& maps = dm.maps();
  state_own = Teuchos::rcp(new dist::multivector_type(maps.owned, nstate));
  state_ghost = Teuchos::rcp(new dist::multivector_type(maps.ghosts, nstate));
  flux_own = Teuchos::rcp(new dist::multivector_type(maps.owned, nflux_cols));
  flux_ghost = Teuchos::rcp(new dist::multivector_type(maps.ghosts, nflux_cols));
  // Prescribed velocities at t = 0.
  for (LocalId i = 0; i < no * 6; ++i)
    if (presc[i] >= 0) {
      const Vec3 pv = prescribed_velocity(presc[i], 0.0);
      for (int c = 0; c < 3; ++c)
        if (prescribed(i, c)) v[i * 3 + c] = pv[c];
    }
  apply_rotations(0.0);
  // Start-up: forces and accelerations at t = 0 (math.md §7.4).
  sync_state();
  compute_forces();
  commit_plasticity();
  external_forces(0.0);
  for (LocalId le = 0; le < no; ++le) {
    for (int A = 0; A < 6; ++A) {
      const int i = le * 6 + A;
      Vec3 acc{0, 0, 0};
      if (!fixed_x[i]) {
        const Vec3 pa = presc[i] >= 0 ? prescribed_acceleration(presc[i], 0.0) : Vec3{0, 0, 0};
        for (int c = 0; c < 3; ++c) acc[c] = prescribed(i, c) ? pa[c] : (fext[i * 3 + c] - f[i * 3 + c]) / mass[i];
        if (presc[i] < 0)
          for (const auto& n : sym_x[i]) {
            const double an = acc[0] * n[0] + acc[1] * n[1] + acc[2] * n[2];
            for (int c = 0; c < 3; ++c) acc[c] -= an * n[c];
          }
      }
      for (int c = 0; c < 3; ++c) {
        a[i * 3 + c] = acc[c];
        react[i * 3 + c] =
            (fixed_x[i] || prescribed(i, c)) ? mass[i] * acc[c] - fext[i * 3 + c] + f[i * 3 + c] : 0.0;
      }
    }
    for (int b = 0; b < 3; ++b) {
      double L[3][3], fT[2];
      for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = Lam[le * 27 + b * 9 + i];
      disc::lambda_bar_transpose_times(L, &g[le * nt + b * 3], fT);
      for (const auto& n : sym_t[le * 3 + b]) {
        double d[2];
        disc::lambda_bar_transpose_times(L, n.data(), d);
        disc::project_out(fT, d);
      }
      for (int c = 0; c < 2; ++c) Tddot[le * 6 + b * 2 + c] = fixed_t[le * 3 + b] ? 0.0 : -fT[c] / inertia[le * 3 + b];
    }
  }
}

void ShellDynamics::Impl::external_forces(double t) {
  // Constant gravity plus follower pressures on the current mid-surface (math.md §10.3):
  // f_ext^A = p(t) sum_q w_q N^A(xi_q) (dphi/dxi1 x dphi/dxi2)(xi_q), ordinary element derivatives.
  fext = gravity_force;
  for (std::size_t l = 0; l < setup.loads.size(); ++l) {
    const auto& load = setup.loads[l];
    if (load.type != Load::Type::Pressure) continue;
    const double p = load.pressure_at(t);
    for (LocalId le : pressure_elements[l])
      for (int q = 0; q < disc::tri6_rule.num_points; ++q) {
        double N[6], dN[6][2], g1[3] = {0, 0, 0}, g2[3] = {0, 0, 0}, n[3];
        disc::p2_shape(disc::tri6_rule.xi[q][0], disc::tri6_rule.xi[q][1], N, dN);
        for (int A = 0; A < 6; ++A)
          for (int c = 0; c < 3; ++c) g1[c] += dN[A][0] * x[le * nx + A * 3 + c], g2[c] += dN[A][1] * x[le * nx + A * 3 + c];
        disc::cross3(g1, g2, n);
        for (int A = 0; A < 6; ++A)
          for (int c = 0; c < 3; ++c) fext[le * nx + A * 3 + c] += p * disc::tri6_rule.w[q] * N[A] * n[c];
      }
  }
}

namespace {
/// Adds the wall time of its scope to a counter.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// Owned rows -> ghost rows (Import, INSERT: no arithmetic, deterministic). pack(view, le) writes the owned row le
/// of `own`; it is called only for the rows another rank holds as a ghost (maps.send_rows). unpack(view, r, le)
/// reads row r of `ghost` into the ghost element le = num_owned + r. The owned rows themselves never move.
template <class Pack, class Unpack>
void import_ghost_rows(const dist::ElementMaps& maps, LocalId num_owned, dist::multivector_type& own,
                       dist::multivector_type& ghost, Pack&& pack, Unpack&& unpack) {
  {
    auto s = own.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (const LocalId le : maps.send_rows) pack(s, le);
  }
  ghost.doImport(own, *maps.ghost_importer, Tpetra::INSERT);
  auto s = ghost.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto ng = static_cast<LocalId>(ghost.getLocalLength());
  for (LocalId r = 0; r < ng; ++r) unpack(s, r, num_owned + r);
}
}  // namespace

void ShellDynamics::Impl::sync_state() {
  ScopedTimer timer(times.exchange);
  import_ghost_rows(
      dm.maps(), no, *state_own, *state_ghost,
      [this](auto& s, LocalId le) {
        for (int i = 0; i < nx; ++i) s(le, i) = x[le * nx + i];
        for (int i = 0; i < nt; ++i) s(le, nx + i) = t[le * nt + i];
      },
      [this](const auto& s, LocalId r, LocalId le) {
        for (int i = 0; i < nx; ++i) x[le * nx + i] = s(r, i);
        for (int i = 0; i < nt; ++i) t[le * nt + i] = s(r, nx + i);
      });
}

void ShellDynamics::Impl::compute_forces() {
  // 1. Element kernel over owned elements: writes only its own slots of f, g, energy_e and flux.
  {
    ScopedTimer timer(times.element);
    const double* xp = x.data();
    const double* tp = t.data();
    double* fp = f.data();
    double* gp = g.data();
    double* ep = energy_e.data();
    double* flp = flux.data();
    const auto* rp = refs.data();
    const auto* lp = lift.data();
    const auto* sp = sect.data();
    const auto* psp = psect.data();
    const char* plp = plastic_el.data();
    const materials::PlasticState* pold = pstate.data();
    materials::PlasticState* pnew = pstate_new.data();
    double* pwp = pwork_step.data();
    int* failp = return_failed.data();
    const dist::DistributedMesh* d = &dm;
    const int ncols = nflux_cols;
    const bool with_edge_nm = fracture;
    Kokkos::parallel_for(
        "shellfrac::ShellElementForces", Kokkos::RangePolicy<exec>(0, no), [=](const int le) {
          double xe[6][3], te[3][3], xn[3][3][3] = {}, tn[3][2][3] = {}, fe[6][3], ge[3][3], fk[3][3][3], gk[3][2][3];
          bool lf[3];
          element_inputs(*d, xp, tp, lp[le], le, xe, te, lf, xn, tn);
          // Projected edge tractions (nucleation check) go to the tail of the element's flux row.
          auto* enm = with_edge_nm ? reinterpret_cast<double(*)[disc::num_edge_points][6]>(flp + le * ncols + nflux)
                                   : nullptr;
          if (plp[le]) {
            // Resultant plasticity: the return map at each area point q (the law is called once per point, in
            // order q = 0..nq-1) from the committed state to this element's slots of the new state.
            const materials::PlasticSection ps = psp[le];
            const disc::DgElementRef& R = rp[le];
            int q = 0, failed = 0;
            double work = 0;
            auto law = [&](const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                           double M[3]) {
              const int k = q++;
              materials::PlasticState& st = pnew[le * nq + k];
              const auto r = materials::resultant_return_map(ps, eps, gam, rho, pold[le * nq + k], st, N, Q, M);
              work += R.wj0[k] * r.plastic_work;
              failed |= r.converged ? 0 : 1;
              return materials::elastic_energy(ps.elastic, eps, gam, rho, st.eps_p, st.gam_p, st.rho_p);
            };
            ep[le] = disc::dg_element_forces(R, xe, te, lf, xn, tn, law, fe, ge, fk, gk, enm);
            pwp[le] = work, failp[le] = failed;
          } else {
            const materials::ElasticSection sc = sp[le];
            auto law = [&sc](const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                             double M[3]) {
              materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
              return materials::elastic_energy(sc, eps, gam, rho);
            };
            ep[le] = disc::dg_element_forces(rp[le], xe, te, lf, xn, tn, law, fe, ge, fk, gk, enm);
          }
          for (int i = 0; i < nx; ++i) fp[le * nx + i] = fe[i / 3][i % 3];
          for (int i = 0; i < nt; ++i) gp[le * nt + i] = ge[i / 3][i % 3];
          for (int k = 0; k < 3; ++k) {
            double* out = flp + le * ncols + k * nflux_edge;
            for (int j = 0; j < 3; ++j)
              for (int c = 0; c < 3; ++c) out[j * 3 + c] = fk[k][j][c];
            for (int j = 0; j < 2; ++j)
              for (int c = 0; c < 3; ++c) out[9 + j * 3 + c] = gk[k][j][c];
          }
        });
  }
  // 2. The ghosts' fluxes come from their owners (Import, INSERT).
  {
    ScopedTimer timer(times.exchange);
    import_ghost_rows(
        dm.maps(), no, *flux_own, *flux_ghost,
        [this](auto& s, LocalId le) {
          for (int i = 0; i < nflux_cols; ++i) s(le, i) = flux[le * nflux_cols + i];
        },
        [this](const auto& s, LocalId r, LocalId le) {
          for (int i = 0; i < nflux_cols; ++i) flux[le * nflux_cols + i] = s(r, i);
        });
  }
  // 3. Interface kernel (penalty on intact interfaces), every local interface: writes its own slots.
  {
    ScopedTimer timer(times.interface);
    const auto& ifs = dm.interfaces();
    const auto* ip = ifs.data();
    const auto* irp = iref.data();
    const double *xp = x.data(), *tp = t.data(), *bx = ibeta_x.data(), *bt = ibeta_t.data();
    double* fip = fi.data();
    double* eip = energy_i.data();
    int* stp = istate.data();
    const auto* cpp = cparams.data();
    double *dmp = dmax.data(), *cnp = conormal.data(), *ucp = ucoh.data(), *dcp = dcoh.data();
    Kokkos::parallel_for(
        "shellfrac::InterfaceForces", Kokkos::RangePolicy<exec>(0, static_cast<int>(ifs.size())),
        [=](const int i) {
          const auto& fc = ip[i];
          double xm[3][3], tm[2][3], xq[3][3], tq[2][3], fm[3][3], gm[2][3], fq[3][3], gq[2][3];
          for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) {
              xm[j][c] = xp[fc.minus * nx + disc::edge_node(fc.minus_edge, j) * 3 + c];
              xq[j][c] = xp[fc.plus * nx + disc::edge_node(fc.plus_edge, j) * 3 + c];
            }
          for (int j = 0; j < 2; ++j)
            for (int c = 0; c < 3; ++c) {
              tm[j][c] = tp[fc.minus * nt + disc::edge_node(fc.minus_edge, j) * 3 + c];
              tq[j][c] = tp[fc.plus * nt + disc::edge_node(fc.plus_edge, j) * 3 + c];
            }
          if (stp[i] == intact) {
            eip[i] = disc::dg_penalty_forces(irp[i], bx[i], bt[i], xm, tm, xq, tq, fm, gm, fq, gq);
          } else {
            // Activated: the cohesive law replaces the penalty (paper eqs. 53-54); a separated interface still
            // evaluates it (zero tractions) so that its energies stay current.
            eip[i] = 0;
            const auto r = cohesive_interface_forces(irp[i], cpp[i], xm, tm, xq, tq, dmp + i * 3,
                                                     reinterpret_cast<double(*)[3]>(cnp + i * 9), fm, gm, fq, gq);
            ucp[i] = r.stored, dcp[i] = r.dissipated;
            if (r.separated) stp[i] = separated;
          }
          double* out = fip + i * 2 * nflux_edge;
          for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) out[j * 3 + c] = fm[j][c], out[nflux_edge + j * 3 + c] = fq[j][c];
          for (int j = 0; j < 2; ++j)
            for (int c = 0; c < 3; ++c) out[9 + j * 3 + c] = gm[j][c], out[nflux_edge + 9 + j * 3 + c] = gq[j][c];
        });
  }
  // 4. Gather, per owned element in a fixed order: own, then neighbours' fluxes by local edge, then
  //    interfaces by global id.
  {
    ScopedTimer timer(times.gather);
    double* fp = f.data();
    double* gp = g.data();
    const double* flp = flux.data();
    const double* fip = fi.data();
    const auto* lp = lift.data();
    const auto* inc = incident.data();
    const auto& ifs = dm.interfaces();
    const auto* ip = ifs.data();
    const dist::DistributedMesh* d = &dm;
    const int ncols = nflux_cols;
    Kokkos::parallel_for("shellfrac::GatherForces", Kokkos::RangePolicy<exec>(0, no), [=](const int le) {
      for (int k = 0; k < 3; ++k) {
        if (!lp[le][k]) continue;
        const double* in = flp + d->neighbor(le, k) * ncols + d->neighbor_edge(le, k) * nflux_edge;
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) fp[le * nx + disc::edge_node(k, j) * 3 + c] += in[j * 3 + c];
        for (int j = 0; j < 2; ++j)
          for (int c = 0; c < 3; ++c) gp[le * nt + disc::edge_node(k, j) * 3 + c] += in[9 + j * 3 + c];
      }
      for (const auto& [i, side] : inc[le]) {
        const int edge = side == 0 ? ip[i].minus_edge : ip[i].plus_edge;
        const double* in = fip + i * 2 * nflux_edge + side * nflux_edge;
        for (int j = 0; j < 3; ++j)
          for (int c = 0; c < 3; ++c) fp[le * nx + disc::edge_node(edge, j) * 3 + c] += in[j * 3 + c];
        for (int j = 0; j < 2; ++j)
          for (int c = 0; c < 3; ++c) gp[le * nt + disc::edge_node(edge, j) * 3 + c] += in[9 + j * 3 + c];
      }
    });
  }
}

void ShellDynamics::Impl::check_finite() const {
  GlobalId bad = -1;
  for (LocalId le = 0; le < no && bad < 0; ++le)
    for (int i = 0; i < nx; ++i)
      if (!std::isfinite(x[le * nx + i]) || !std::isfinite(f[le * nx + i])) {
        bad = dm.element_gid(le);
        break;
      }
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, dm.comm());
  if (worst >= 0) {
    std::ostringstream os;
    os << "numerical blow-up at step " << step << ", time " << time << ": non-finite position or force in element "
       << GlobalId(worst) + 1 << " (time step too large or unstable input?)";
    throw NumericalError(os.str());  // on every rank (the reduction above)
  }
}

// Accepts the plastic state computed by the last element kernel as the state at the new time and adds its
// plastic work. A return map that hit its iteration limit stops the run on every rank, naming the element.
void ShellDynamics::Impl::commit_plasticity() {
  if (!any_plastic) return;
  GlobalId bad = -1;
  for (LocalId le = 0; le < no; ++le) {
    if (!plastic_el[le]) continue;
    if (return_failed[le] && bad < 0) bad = dm.element_gid(le);
    plastic_work[le] += pwork_step[le];
  }
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, dm.comm());
  SHELLFRAC_REQUIRE(worst < 0, "the plastic return map did not converge in element " << GlobalId(worst) + 1
                                   << " at step " << step << ", time " << time
                                   << " (math.md §4.3; a non-finite or extreme strain?)");
  pstate.swap(pstate_new);
}

ShellDynamics::ShellDynamics(const mesh::SerialMesh& mesh, const dist::DistributedMesh& dm, const DynamicsSetup& setup)
    : impl_(std::make_unique<Impl>(mesh, dm, setup)) {}
ShellDynamics::~ShellDynamics() = default;
double ShellDynamics::stable_time_step() const { return impl_->dt_stable; }
double ShellDynamics::time_step() const { return impl_->dt; }
double ShellDynamics::time() const { return impl_->time; }
long ShellDynamics::step_count() const { return impl_->step; }

void ShellDynamics::step() {
  Impl& s = *impl_;
  const double dt = s.dt, t1 = s.time + dt, alpha = s.setup.time.mass_damping;
  std::vector<double> Tdot_pre(s.no * 6);
  auto t0 = std::chrono::steady_clock::now();
  s.x_old.assign(s.x.begin(), s.x.begin() + s.no * nx);
  s.fext_old = s.fext, s.react_old = s.react;
  for (auto& rn : s.rot_nodes) {
    disc::copy3(&s.t[rn.le * nt + rn.b * 3], rn.t_prev);
    disc::copy3(&s.g[rn.le * nt + rn.b * 3], rn.g_prev);
    rn.kin_prev = s.rotary_kinetic(rn.le, rn.b);
  }
  const auto remove_normal = [](double* w, const std::vector<Vec3>& normals) {
    for (const auto& n : normals) {
      const double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
      for (int c = 0; c < 3; ++c) w[c] -= wn * n[c];
    }
  };
  // Predictor (math.md §7.4 steps 1-2): positions, then directors by the exponential map.
  for (LocalId le = 0; le < s.no; ++le) {
    for (int A = 0; A < 6; ++A) {
      const int i = le * 6 + A;
      double* x = &s.x[i * 3];
      double* v = &s.v[i * 3];
      if (s.fixed_x[i]) {
        for (int c = 0; c < 3; ++c) x[c] = s.X[i * 3 + c], v[c] = 0;
      } else if (s.presc[i] >= 0) {  // exact integral of the velocity program: no drift
        const Vec3 u = s.prescribed_displacement(s.presc[i], t1);
        for (int c = 0; c < 3; ++c) {
          if (s.prescribed(i, c)) {
            x[c] = s.X[i * 3 + c] + u[c];
          } else {  // a free component of a partly prescribed node
            x[c] += dt * v[c] + 0.5 * dt * dt * s.a[i * 3 + c];
            v[c] += 0.5 * dt * s.a[i * 3 + c];
          }
        }
      } else {
        double dx[3];
        for (int c = 0; c < 3; ++c) {
          dx[c] = dt * v[c] + 0.5 * dt * dt * s.a[i * 3 + c];  // x^{n+1} = x^n + dt v^n + dt^2/2 a^n
          v[c] += 0.5 * dt * s.a[i * 3 + c];                    // v_pre = v^n + dt/2 a^n
        }
        remove_normal(dx, s.sym_x[i]);
        remove_normal(v, s.sym_x[i]);
        for (int c = 0; c < 3; ++c) x[c] += dx[c];
      }
    }
    for (int b = 0; b < 3; ++b) {
      double dT[2], L[3][3];
      for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = s.Lam[le * 27 + b * 9 + i];
      for (int c = 0; c < 2; ++c) {
        const int i = le * 6 + b * 2 + c;
        const bool fixed = s.fixed_t[le * 3 + b];
        dT[c] = fixed ? 0.0 : dt * s.Tdot[i] + 0.5 * dt * dt * s.Tddot[i];  // SEED eq. 47
        Tdot_pre[i] = fixed ? 0.0 : s.Tdot[i] + 0.5 * dt * s.Tddot[i];     // SEED eq. 48, gamma = 1/2
      }
      for (const auto& n : s.sym_t[le * 3 + b]) {  // keep the director in the symmetry plane (math.md §10.1)
        double d[2];
        disc::lambda_bar_transpose_times(L, n.data(), d);
        disc::project_out(dT, d);
        disc::project_out(&Tdot_pre[le * 6 + b * 2], d);
      }
      disc::update_director(&s.t[le * nt + b * 3], L, dT, &s.t[le * nt + b * 3], L);  // Algorithm 1
      for (int i = 0; i < 9; ++i) s.Lam[le * 27 + b * 9 + i] = L[i / 3][i % 3];
    }
  }
  s.apply_rotations(t1);
  s.times.update += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Forces at t_{n+1}.
  s.sync_state();
  s.compute_forces();
  t0 = std::chrono::steady_clock::now();
  s.commit_plasticity();
  if (s.fracture) {
    ScopedTimer timer(s.times.nucleation);
    s.nucleate(t1);
  }
  s.external_forces(t1);
  // Accelerations and corrector (steps 4-5); damping force alpha m v_pre.
  for (LocalId le = 0; le < s.no; ++le) {
    double wext = 0, wreact = 0, diss = 0;
    for (int A = 0; A < 6; ++A) {
      const int i = le * 6 + A;
      double* v = &s.v[i * 3];
      double* acc = &s.a[i * 3];
      if (s.fixed_x[i]) {
        acc[0] = acc[1] = acc[2] = 0;
      } else if (s.presc[i] >= 0) {
        const Vec3 pa = s.prescribed_acceleration(s.presc[i], t1), pv = s.prescribed_velocity(s.presc[i], t1);
        for (int c = 0; c < 3; ++c) {
          if (s.prescribed(i, c)) {
            acc[c] = pa[c], v[c] = pv[c];
          } else {  // a free component of a partly prescribed node
            diss += dt * alpha * s.mass[i] * v[c] * v[c];
            acc[c] = (s.fext[i * 3 + c] - s.f[i * 3 + c] - alpha * s.mass[i] * v[c]) / s.mass[i];
            v[c] += 0.5 * dt * acc[c];
          }
        }
      } else {
        for (int c = 0; c < 3; ++c) {
          diss += dt * alpha * s.mass[i] * v[c] * v[c];
          acc[c] = (s.fext[i * 3 + c] - s.f[i * 3 + c] - alpha * s.mass[i] * v[c]) / s.mass[i];
        }
        remove_normal(acc, s.sym_x[i]);
        for (int c = 0; c < 3; ++c) v[c] += 0.5 * dt * acc[c];  // v^{n+1} = v_pre + dt/2 a^{n+1}
      }
      for (int c = 0; c < 3; ++c) {
        const int j = i * 3 + c;
        // Reaction R = m a - f_ext + f on constrained nodes and components (math.md §9.7).
        s.react[j] = (s.fixed_x[i] || s.prescribed(i, c)) ? s.mass[i] * acc[c] - s.fext[j] + s.f[j] : 0.0;
        const double dx = s.x[j] - s.x_old[j];
        wext += 0.5 * (s.fext_old[j] + s.fext[j]) * dx;
        wreact += 0.5 * (s.react_old[j] + s.react[j]) * dx;
      }
    }
    for (int b = 0; b < 3; ++b) {
      double L[3][3], fT[2];
      for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = s.Lam[le * 27 + b * 9 + i];
      disc::lambda_bar_transpose_times(L, &s.g[le * nt + b * 3], fT);  // f_T = Lambda-bar^T g
      for (int c = 0; c < 2; ++c) {
        const int i = le * 6 + b * 2 + c;
        diss += dt * alpha * s.inertia[le * 3 + b] * Tdot_pre[i] * Tdot_pre[i];
        fT[c] += alpha * s.inertia[le * 3 + b] * Tdot_pre[i];
      }
      for (const auto& n : s.sym_t[le * 3 + b]) {
        double d[2];
        disc::lambda_bar_transpose_times(L, n.data(), d);
        disc::project_out(fT, d);
      }
      for (int c = 0; c < 2; ++c) {
        const int i = le * 6 + b * 2 + c;
        s.Tddot[i] = s.fixed_t[le * 3 + b] ? 0.0 : -fT[c] / s.inertia[le * 3 + b];  // SEED eq. 49
        s.Tdot[i] = Tdot_pre[i] + 0.5 * dt * s.Tddot[i];                            // SEED eq. 50, gamma = 1/2
      }
    }
    s.work_ext[le] += wext, s.work_react[le] += wreact, s.dissipated[le] += diss;
  }
  // Prescribed rotations: director rates at t_{n+1}, and the work of the support couple, which supplies the
  // director's internal force work (trapezoidal) and its rotary kinetic energy change.
  s.apply_rotations(t1);
  for (const auto& rn : s.rot_nodes) {
    const double* g1 = &s.g[rn.le * nt + rn.b * 3];
    const double* t1n = &s.t[rn.le * nt + rn.b * 3];
    double w = s.rotary_kinetic(rn.le, rn.b) - rn.kin_prev;
    for (int c = 0; c < 3; ++c) w += 0.5 * (rn.g_prev[c] + g1[c]) * (t1n[c] - rn.t_prev[c]);
    s.work_react[rn.le] += w;
  }
  s.time = t1;
  ++s.step;
  s.check_finite();
  s.times.update += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> ShellDynamics::reactions() const {
  const Impl& s = *impl_;
  std::vector<double> out;
  for (std::size_t ib = 0; ib < s.setup.boundary_conditions.size(); ++ib) {
    std::vector<GlobalId> ids;
    std::vector<std::vector<double>> vals(3);
    for (LocalId le = 0; le < s.no; ++le)
      for (int A = 0; A < 6; ++A) {
        const int i = le * 6 + A;
        if (!(s.bc_mask[i] & (1u << ib))) continue;
        ids.push_back(s.dm.dg_node_gid(le, A));
        // Symmetry nodes: the reaction is the normal force that keeps them on the plane.
        for (int c = 0; c < 3; ++c) {
          double r = s.react[i * 3 + c];
          if (!s.fixed_x[i] && s.presc[i] < 0)
            for (const auto& n : s.sym_x[i])
              r += n[c] * ((s.f[i * 3] - s.fext[i * 3]) * n[0] + (s.f[i * 3 + 1] - s.fext[i * 3 + 1]) * n[1] +
                           (s.f[i * 3 + 2] - s.fext[i * 3 + 2]) * n[2]);
          vals[c].push_back(r);
        }
      }
    for (int c = 0; c < 3; ++c) out.push_back(ordered_sum(ids, vals[c], s.dm.comm()));
    // Support couple on the condition's constrained directors: t x g per director node (g = dU/dt is balanced
    // by the support; the virtual work g . (dtheta x t) = dtheta . (t x g)).
    std::vector<GlobalId> dids;
    std::vector<std::vector<double>> mom(3);
    for (LocalId le = 0; le < s.no; ++le)
      for (int b = 0; b < 3; ++b) {
        if (!(s.bc_mask[le * 6 + b] & (1u << ib)) || !s.fixed_t[le * 3 + b]) continue;
        dids.push_back(s.dm.dg_node_gid(le, b));
        double m[3];
        disc::cross3(&s.t[le * nt + b * 3], &s.g[le * nt + b * 3], m);
        for (int c = 0; c < 3; ++c) mom[c].push_back(m[c]);
      }
    for (int c = 0; c < 3; ++c) out.push_back(ordered_sum(dids, mom[c], s.dm.comm()));
  }
  return out;
}

const PhaseTimes& ShellDynamics::phase_times() const { return impl_->times; }

double ShellDynamics::bytes_per_element() const {
  const Impl& s = *impl_;
  const double bytes = sizeof(disc::DgElementRef) * double(s.refs.size()) +
                       sizeof(double) * double(s.X.size() + s.x.size() + s.t.size() + s.v.size() + s.a.size() +
                                           s.Lam.size() + s.Tdot.size() + s.Tddot.size() + s.mass.size() +
                                           s.inertia.size() + s.f.size() + s.g.size() + s.flux.size() +
                                           s.energy_e.size() + s.fi.size() + s.energy_i.size()) +
                       sizeof(disc::DgInterfaceRef) * double(s.iref.size()) +
                       sizeof(materials::PlasticState) * double(s.pstate.size() + s.pstate_new.size()) +
                       sizeof(materials::PlasticSection) * double(s.psect.size()) +
                       // Tpetra transfer buffers: owned rows (no) plus ghost rows (nov - no), state and flux
                       sizeof(double) * double(nstate + s.nflux_cols) * double(s.nov);
  return s.no > 0 ? bytes / s.no : 0.0;
}


std::vector<double> ShellDynamics::probes(const std::vector<std::vector<char>>& members) const {
  const Impl& s = *impl_;
  std::vector<double> out;
  for (const auto& member : members) {
    std::vector<GlobalId> ids;
    std::vector<std::vector<double>> vals(6);
    for (LocalId le = 0; le < s.no; ++le)
      for (int A = 0; A < 6; ++A) {
        if (!member[s.dm.mesh_node(le, A)]) continue;
        ids.push_back(s.dm.dg_node_gid(le, A));
        for (int c = 0; c < 3; ++c) {
          vals[c].push_back(s.x[le * nx + A * 3 + c] - s.X[le * nx + A * 3 + c]);
          vals[3 + c].push_back(s.v[le * nx + A * 3 + c]);
        }
      }
    const double count = double(parallel::sum(static_cast<std::int64_t>(ids.size()), s.dm.comm()));
    for (int c = 0; c < 6; ++c) out.push_back(count > 0 ? ordered_sum(ids, vals[c], s.dm.comm()) / count : 0.0);
  }
  return out;
}

StepRecord ShellDynamics::record() const {
  const Impl& s = *impl_;
  // Per-element kinetic + strain energy and per-owned-interface penalty energy, summed in global-id order
  // on every rank (bitwise independent of the rank count).
  std::vector<GlobalId> egid(s.no);
  std::vector<double> ek(s.no), es(s.no);
  for (LocalId le = 0; le < s.no; ++le) {
    egid[le] = s.dm.element_gid(le);
    double k = 0;
    for (int A = 0; A < 6; ++A)
      for (int c = 0; c < 3; ++c) k += 0.5 * s.mass[le * 6 + A] * s.v[le * nx + A * 3 + c] * s.v[le * nx + A * 3 + c];
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 2; ++c) k += 0.5 * s.inertia[le * 3 + b] * s.Tdot[le * 6 + b * 2 + c] * s.Tdot[le * 6 + b * 2 + c];
    ek[le] = k, es[le] = s.energy_e[le];
  }
  std::vector<GlobalId> igid;
  std::vector<double> ep;
  const auto& ifs = s.dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned) igid.push_back(ifs[i].gid), ep.push_back(s.energy_i[i]);
  StepRecord r;
  r.step = s.step, r.time = s.time, r.dt = s.dt;
  r.kinetic = ordered_sum(egid, ek, s.dm.comm());
  r.strain = ordered_sum(egid, es, s.dm.comm());
  r.penalty = ordered_sum(igid, ep, s.dm.comm());
  r.external_work = ordered_sum(egid, std::vector<double>(s.work_ext.begin(), s.work_ext.begin() + s.no), s.dm.comm());
  r.reaction_work = ordered_sum(egid, std::vector<double>(s.work_react.begin(), s.work_react.begin() + s.no), s.dm.comm());
  r.damping = ordered_sum(egid, std::vector<double>(s.dissipated.begin(), s.dissipated.begin() + s.no), s.dm.comm());
  r.plastic_work = ordered_sum(egid, s.plastic_work, s.dm.comm());
  if (s.fracture) {
    std::vector<double> uc, dc, ai;
    std::int64_t ncoh = 0, nsep = 0;
    for (std::size_t i = 0; i < ifs.size(); ++i)
      if (ifs[i].owned) {
        uc.push_back(s.ucoh[i]), dc.push_back(s.dcoh[i]), ai.push_back(s.act_i[i]);
        ncoh += s.istate[i] != intact, nsep += s.istate[i] == separated;
      }
    r.cohesive_energy = ordered_sum(igid, uc, s.dm.comm());
    r.cohesive_dissipation = ordered_sum(igid, dc, s.dm.comm());
    r.activation_loss = ordered_sum(igid, ai, s.dm.comm()) + ordered_sum(egid, s.act_e, s.dm.comm());
    r.cohesive_edges = parallel::sum(ncoh, s.dm.comm());
    r.separated_edges = parallel::sum(nsep, s.dm.comm());
    s.update_fragments();
    r.fragments = s.fragments;
  }
  std::vector<std::vector<double>> lm(3, std::vector<double>(s.no, 0.0));
  for (LocalId le = 0; le < s.no; ++le) {
    for (int A = 0; A < 6; ++A) {
      double h[3];
      disc::cross3(&s.x[le * nx + A * 3], &s.v[le * nx + A * 3], h);
      for (int c = 0; c < 3; ++c) lm[c][le] += s.mass[le * 6 + A] * h[c];
    }
    for (int b = 0; b < 3; ++b) {  // director spin: I t x tdot, tdot = Lambda-bar Tdot
      double L[3][3], td[3], h[3];
      for (int i = 0; i < 9; ++i) L[i / 3][i % 3] = s.Lam[le * 27 + b * 9 + i];
      disc::lambda_bar_times(L, &s.Tdot[le * 6 + b * 2], td);
      disc::cross3(&s.t[le * nt + b * 3], td, h);
      for (int c = 0; c < 3; ++c) lm[c][le] += s.inertia[le * 3 + b] * h[c];
    }
  }
  for (int c = 0; c < 3; ++c) r.angular_momentum[c] = ordered_sum(egid, lm[c], s.dm.comm());
  return r;
}

std::vector<std::string> ShellDynamics::element_field_names() {
  return {"eq_plastic_strain", "membrane_force", "bending_moment", "shear_force", "damage", "fragment_id"};
}

// Calls f(q, w, eps, gam, rho, state) at each area point of owned element le for the current state: DG
// kinematics with the element's current lift flags (ghosts are current after a step), strains, and the committed
// plastic state (nullptr in elastic blocks); w = w_q j0_q. The resultants of the committed state are those the
// last element kernel produced.
template <class F>
void ShellDynamics::Impl::area_points(LocalId le, F&& f) const {
  double xe[6][3], te[3][3], xn[3][3][3] = {}, tn[3][2][3] = {};
  bool lf[3];
  element_inputs(dm, x.data(), t.data(), lift[le], le, xe, te, lf, xn, tn);
  disc::ShellKinematics kin[nq];
  const disc::DgElementRef& R = refs[le];
  disc::dg_kinematics(R, xe, te, lf, xn, tn, kin);
  for (int q = 0; q < nq; ++q) {
    double eps[3], gam[2], rho[3];
    disc::compute_strains(kin[q], R.ref[q], eps, gam, rho);
    f(q, R.wj0[q], eps, gam, rho, plastic_el[le] ? &pstate[le * nq + q] : nullptr);
  }
}

// Stored elastic energy of owned element le in the current state (frozen plastic strains).
double ShellDynamics::Impl::element_energy(LocalId le) const {
  double energy = 0;
  const double zero[3] = {0, 0, 0};
  area_points(le, [&](int, double w, const double* eps, const double* gam, const double* rho,
                      const materials::PlasticState* st) {
    energy += w * materials::elastic_energy(sect[le], eps, gam, rho, st ? st->eps_p : zero, st ? st->gam_p : zero,
                                            st ? st->rho_p : zero);
  });
  return energy;
}

// Nucleation and activation (math.md §9.5-9.6; paper §5.1), after the forces at t_{n+1}: every local intact
// breakable interface is checked with both sides' projected edge tractions (the ghosts' come with the flux
// Import), so the two ranks that hold an interface take the same decision from the same numbers: the flag
// needs no message of its own. An activated interface leaves the lifting of both sides and its penalty is
// replaced by the cohesive law (delta_max = 0: no force until the faces move). The DG energy this releases
// (its penalty energy, and the change of the neighbours' strain energy without the lifting, same
// configuration, frozen plastic state) is booked as activation_loss.
void ShellDynamics::Impl::nucleate(double t1) {
  const auto& ifs = dm.interfaces();
  std::vector<LocalId> changed;
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (!breakable[i] || istate[i] != intact) continue;
    const auto& fc = ifs[i];
    const auto* em = reinterpret_cast<const double(*)[6]>(&flux[fc.minus * nflux_cols + nflux + fc.minus_edge * 18]);
    const auto* ep = reinterpret_cast<const double(*)[6]>(&flux[fc.plus * nflux_cols + nflux + fc.plus_edge * 18]);
    double n[3][3], m[3][3];
    if (interface_edge_tractions(iref[i], cparams[i], em, ep, n, m) < 0) continue;  // cannot activate: cheap
    double xm[3][3], tm[2][3], tq[2][3];
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) xm[j][c] = x[fc.minus * nx + disc::edge_node(fc.minus_edge, j) * 3 + c];
    for (int j = 0; j < 2; ++j)
      for (int c = 0; c < 3; ++c) {
        tm[j][c] = t[fc.minus * nt + disc::edge_node(fc.minus_edge, j) * 3 + c];
        tq[j][c] = t[fc.plus * nt + disc::edge_node(fc.plus_edge, j) * 3 + c];
      }
    double nu[3][3];
    const double fbar = interface_nucleation(iref[i], cparams[i], xm, tm, tq, n, m, nu);
    if (fbar < 0) continue;
    if (fc.owned) log_activation(i, t1, fbar, xm, n, m, nu);
    istate[i] = cparams[i].Gamma > 0 ? cohesive : separated;
    for (int g = 0; g < 3; ++g) {
      dmax[i * 3 + g] = 0;
      for (int c = 0; c < 3; ++c) conormal[i * 9 + g * 3 + c] = nu[g][c];
    }
    act_i[i] += energy_i[i];
    energy_i[i] = 0;
    for (const auto& [le, k] : {std::pair{fc.minus, fc.minus_edge}, std::pair{fc.plus, fc.plus_edge}})
      if (le < no) lift[le][k] = false, changed.push_back(le);
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (LocalId le : changed) {
    const double after = element_energy(le);
    act_e[le] += energy_e[le] - after;
    energy_e[le] = after;
  }
}

// One row of the crack log for interface i activated at t1: where it is and which terms of the equivalent
// traction made it break (ShellDynamics::crack_events). The in-plane tangent at each edge point is the
// edge chord of the minus side made orthogonal to nu (a diagnostic: exact for straight edges).
void ShellDynamics::Impl::log_activation(std::size_t i, double t1, double fbar, const double xm[3][3],
                                         const double n[3][3], const double m[3][3], const double nu[3][3]) {
  const auto& fc = dm.interfaces()[i];
  double parts[5] = {0, 0, 0, 0, 0}, total = 0;
  for (int g = 0; g < 3; ++g) {
    double tau[3], tn = 0, tt = 0;
    for (int c = 0; c < 3; ++c) tau[c] = xm[1][c] - xm[0][c], tn += tau[c] * nu[g][c];
    for (int c = 0; c < 3; ++c) tau[c] -= tn * nu[g][c], tt += tau[c] * tau[c];
    for (double& c : tau) c /= std::sqrt(tt);
    double pg[5];
    materials::equivalent_traction_parts(cparams[i], n[g], m[g], nu[g], tau, pg);
    for (int k = 0; k < 5; ++k) parts[k] += iref[i].omega[g] * pg[k], total += iref[i].omega[g] * pg[k];
  }
  crack_log.insert(crack_log.end(), {double(step + 1), t1, double(fc.gid + 1), double(dm.element_gid(fc.minus) + 1),
                                     double(dm.element_gid(fc.plus) + 1), xm[2][0], xm[2][1], xm[2][2], fbar});
  for (double p : parts) crack_log.push_back(total > 0 ? p / total : 0.0);
}

// Fragments: connected components of the elements through interfaces that are not fully separated, by
// union-find over the global interface list (the same on every rank); recomputed only when the global number
// of separated interfaces has changed. Collective.
void ShellDynamics::Impl::update_fragments() const {
  std::vector<GlobalId> mine;
  const auto& ifs = dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i)
    if (ifs[i].owned && istate[i] == separated) mine.push_back(ifs[i].gid);
  const GlobalId count = parallel::sum(static_cast<std::int64_t>(mine.size()), dm.comm());
  if (count == fragments_at) return;
  auto cut = parallel::all_gather(mine, dm.comm());
  std::sort(cut.begin(), cut.end());
  const GlobalId ne = dm.num_global_elements();
  fragment_root.resize(ne);
  for (GlobalId e = 0; e < ne; ++e) fragment_root[e] = e;
  const auto find = [&](GlobalId e) {
    while (fragment_root[e] != e) e = fragment_root[e] = fragment_root[fragment_root[e]];
    return e;
  };
  for (const auto& [gid, a, b] : all_interfaces) {
    if (std::binary_search(cut.begin(), cut.end(), gid)) continue;
    const GlobalId ra = find(a), rb = find(b);
    if (ra != rb) fragment_root[std::max(ra, rb)] = std::min(ra, rb);  // the root is the smallest id
  }
  fragments = 0;
  for (GlobalId e = 0; e < ne; ++e) {
    fragment_root[e] = find(e);
    fragments += fragment_root[e] == e;
  }
  fragments_at = count;
}

bool ShellDynamics::fracture() const { return impl_->fracture; }

namespace {
// Per-element state columns of a checkpoint, in order: x, v, a, f, fext, react (nx each), t, g (nt each),
// Lambda (27), Tdot, Tddot (6 each), energy_e, work_ext, work_react, dissipated, plastic_work, act_e.
constexpr int ckpt_element_width = 6 * nx + 2 * nt + 27 + 12 + 6;
// Per-interface columns: state, delta_max (3), co-normal (9), U_coh, D_coh, act_i, penalty energy.
constexpr int ckpt_interface_width = 17;
// Per-area-point plastic columns: eps_p (3), rho_p (3), alpha, gam_p (2).
constexpr int ckpt_plastic_point_width = 9;
constexpr int ckpt_plastic_width = nq * ckpt_plastic_point_width;
}  // namespace

io::CheckpointData ShellDynamics::checkpoint() const {
  const Impl& s = *impl_;
  io::CheckpointData d;
  d.scalars["time"] = s.time, d.scalars["step"] = double(s.step), d.scalars["dt"] = s.dt;
  d.scalars["num_elements"] = double(s.dm.num_global_elements());
  auto& el = d.tables["elements"];
  el.width = ckpt_element_width;
  for (LocalId le = 0; le < s.no; ++le) {
    el.ids.push_back(s.dm.element_gid(le));
    for (const auto* a : {&s.x, &s.v, &s.a, &s.f, &s.fext, &s.react})
      el.values.insert(el.values.end(), a->begin() + le * nx, a->begin() + (le + 1) * nx);
    for (const auto* a : {&s.t, &s.g}) el.values.insert(el.values.end(), a->begin() + le * nt, a->begin() + (le + 1) * nt);
    el.values.insert(el.values.end(), s.Lam.begin() + le * 27, s.Lam.begin() + (le + 1) * 27);
    for (const auto* a : {&s.Tdot, &s.Tddot}) el.values.insert(el.values.end(), a->begin() + le * 6, a->begin() + (le + 1) * 6);
    for (const auto* a : {&s.energy_e, &s.work_ext, &s.work_react, &s.dissipated, &s.plastic_work, &s.act_e})
      el.values.push_back((*a)[le]);
  }
  if (s.any_plastic) {
    auto& pl = d.tables["plastic"];
    pl.width = ckpt_plastic_width;
    for (LocalId le = 0; le < s.no; ++le) {
      pl.ids.push_back(s.dm.element_gid(le));
      for (int q = 0; q < nq; ++q) {
        const auto& st = s.pstate[le * nq + q];
        pl.values.insert(pl.values.end(), {st.eps_p[0], st.eps_p[1], st.eps_p[2], st.rho_p[0], st.rho_p[1], st.rho_p[2],
                                           st.alpha, st.gam_p[0], st.gam_p[1]});
      }
    }
  }
  auto& it = d.tables["interfaces"];
  it.width = ckpt_interface_width;
  const auto& ifs = s.dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (!ifs[i].owned) continue;
    it.ids.push_back(ifs[i].gid);
    it.values.push_back(double(s.istate[i]));
    it.values.insert(it.values.end(), s.dmax.begin() + i * 3, s.dmax.begin() + i * 3 + 3);
    it.values.insert(it.values.end(), s.conormal.begin() + i * 9, s.conormal.begin() + i * 9 + 9);
    it.values.insert(it.values.end(), {s.ucoh[i], s.dcoh[i], s.act_i[i], s.energy_i[i]});
  }
  return d;
}

void ShellDynamics::restore(const io::CheckpointData& d) {
  Impl& s = *impl_;
  const auto& file = s.setup.deck_file;
  const auto scalar = [&](const char* name) {
    const auto it = d.scalars.find(name);
    SHELLFRAC_INPUT_REQUIRE(it != d.scalars.end(), file << ": the checkpoint has no '" << name << "'");
    return it->second;
  };
  const auto table = [&](const char* name, int width) -> const io::CheckpointTable& {
    const auto it = d.tables.find(name);
    SHELLFRAC_INPUT_REQUIRE(it != d.tables.end() && it->second.width == width,
                            file << ": the checkpoint's table '" << name << "' is missing or has another width "
                                 << "(written by another version or for another model?)");
    return it->second;
  };
  SHELLFRAC_INPUT_REQUIRE(GlobalId(scalar("num_elements")) == s.dm.num_global_elements(),
                          file << ": the checkpoint has " << GlobalId(scalar("num_elements")) << " elements, the mesh "
                               << s.dm.num_global_elements());
  // The time step is the deck's (the same deck gives the same step, hence a bitwise continuation; a deck with a
  // smaller Time Step or Safety Factor continues a blown-up run from its last good state).
  s.time = scalar("time"), s.step = long(scalar("step"));
  s.crack_log.clear();
  const auto& el = table("elements", ckpt_element_width);
  const io::CheckpointTable* pl = s.any_plastic ? &table("plastic", ckpt_plastic_width) : nullptr;
  for (LocalId le = 0; le < s.no; ++le) {
    const GlobalId gid = s.dm.element_gid(le);
    const double* r = el.row(gid);
    SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no state for element " << gid + 1);
    for (auto* a : {&s.x, &s.v, &s.a, &s.f, &s.fext, &s.react}) std::copy(r, r + nx, a->begin() + le * nx), r += nx;
    for (auto* a : {&s.t, &s.g}) std::copy(r, r + nt, a->begin() + le * nt), r += nt;
    std::copy(r, r + 27, s.Lam.begin() + le * 27), r += 27;
    for (auto* a : {&s.Tdot, &s.Tddot}) std::copy(r, r + 6, a->begin() + le * 6), r += 6;
    for (auto* a : {&s.energy_e, &s.work_ext, &s.work_react, &s.dissipated, &s.plastic_work, &s.act_e}) (*a)[le] = *r++;
    if (pl) {
      const double* p = pl->row(gid);
      SHELLFRAC_INPUT_REQUIRE(p, file << ": the checkpoint has no plastic state for element " << gid + 1);
      for (int q = 0; q < nq; ++q, p += ckpt_plastic_point_width) {
        auto& st = s.pstate[le * nq + q];
        std::copy(p, p + 3, st.eps_p), std::copy(p + 3, p + 6, st.rho_p), st.alpha = p[6];
        std::copy(p + 7, p + 9, st.gam_p);
      }
    }
  }
  const auto& it = table("interfaces", ckpt_interface_width);
  const auto& ifs = s.dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    const double* r = it.row(ifs[i].gid);
    SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no state for interface " << ifs[i].gid + 1);
    s.istate[i] = int(r[0]);
    std::copy(r + 1, r + 4, s.dmax.begin() + i * 3);
    std::copy(r + 4, r + 13, s.conormal.begin() + i * 9);
    s.ucoh[i] = r[13], s.dcoh[i] = r[14], s.act_i[i] = r[15], s.energy_i[i] = r[16];
    if (s.istate[i] != intact) {  // an activated edge is lifted by neither side
      if (ifs[i].minus < s.no) s.lift[ifs[i].minus][ifs[i].minus_edge] = false;
      if (ifs[i].plus < s.no) s.lift[ifs[i].plus][ifs[i].plus_edge] = false;
    }
  }
  s.fragments_at = -1;
  s.sync_state();
}

std::vector<std::string> ShellDynamics::crack_event_columns() {
  return {"step",        "time",          "interface",         "element_minus",         "element_plus",
          "x",           "y",             "z",                 "fbar",                  "share_normal",
          "share_inplane_shear", "share_transverse_shear", "share_couple_normal", "share_couple_shear"};
}

std::vector<std::vector<double>> ShellDynamics::crack_events() {
  Impl& s = *impl_;
  const std::size_t width = crack_event_columns().size();
  const auto all = parallel::all_gather(s.crack_log, s.dm.comm());
  s.crack_log.clear();
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k + width <= all.size(); k += width) rows.emplace_back(all.begin() + k, all.begin() + k + width);
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return a[0] != b[0] ? a[0] < b[0] : a[2] < b[2];  // by step, then interface id
  });
  return rows;
}

std::vector<std::vector<double>> ShellDynamics::fragment_table() const {
  const Impl& s = *impl_;
  if (s.fracture) s.update_fragments();
  constexpr int nv = 9;  // element gid, fragment root, m, m x (3), m v (3)
  std::vector<double> mine(s.no * nv, 0.0);
  for (LocalId le = 0; le < s.no; ++le) {
    double* r = &mine[le * nv];
    const GlobalId gid = s.dm.element_gid(le);
    r[0] = double(gid), r[1] = s.fracture ? double(s.fragment_root[gid]) : 0.0;
    for (int A = 0; A < 6; ++A) {
      const double m = s.mass[le * 6 + A];
      r[2] += m;
      for (int c = 0; c < 3; ++c) r[3 + c] += m * s.x[le * nx + A * 3 + c], r[6 + c] += m * s.v[le * nx + A * 3 + c];
    }
  }
  const auto all = parallel::all_gather(mine, s.dm.comm());
  std::vector<std::size_t> order(all.size() / nv);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a * nv] < all[b * nv]; });
  std::map<GlobalId, std::vector<double>> frag;  // root -> {elements, m, m x, m v}
  for (std::size_t i : order) {
    auto& f = frag[GlobalId(all[i * nv + 1])];
    f.resize(8, 0.0);
    f[0] += 1;
    for (int k = 0; k < 7; ++k) f[1 + k] += all[i * nv + 2 + k];
  }
  std::vector<std::vector<double>> rows;
  for (const auto& [root, f] : frag)
    rows.push_back({double(root + 1), f[0], f[1], f[2] / f[1], f[3] / f[1], f[4] / f[1], f[5], f[6], f[7]});
  return rows;
}

void ShellDynamics::element_fields(std::vector<std::vector<double>>& fields) const {
  const Impl& s = *impl_;
  fields.assign(6, std::vector<double>(s.no, 0.0));
  const double zero[3] = {0, 0, 0};
  for (LocalId le = 0; le < s.no; ++le) {
    const double area = s.refs[le].area;
    s.area_points(le, [&](int, double w, const double* eps, const double* gam, const double* rho,
                          const materials::PlasticState* st) {
      double N[3], Q[2], M[3];
      materials::elastic_resultants(s.sect[le], eps, gam, rho, st ? st->eps_p : zero, st ? st->gam_p : zero,
                                    st ? st->rho_p : zero, N, Q, M);
      fields[0][le] += w / area * (st ? st->alpha : 0.0);
      fields[1][le] += w / area * vm_norm(N);
      fields[2][le] += w / area * vm_norm(M);
      fields[3][le] += w / area * std::sqrt(Q[0] * Q[0] + Q[1] * Q[1]);
    });
    for (const auto& [i, side] : s.incident[le]) {
      double dmg = s.istate[i] == separated ? 1.0 : 0.0;
      if (s.istate[i] == cohesive)
        for (int g = 0; g < 3; ++g) dmg = std::max(dmg, std::min(1.0, s.dmax[i * 3 + g] / s.cparams[i].delta_f));
      fields[4][le] = std::max(fields[4][le], dmg);
    }
  }
  if (s.fracture) s.update_fragments();
  for (LocalId le = 0; le < s.no; ++le)
    fields[5][le] = s.fracture ? double(s.fragment_root[s.dm.element_gid(le)] + 1) : 1.0;
}

void ShellDynamics::nodal_fields(std::vector<Vec3>& displacement, std::vector<Vec3>& velocity,
                                 std::vector<Vec3>& director) const {
  const Impl& s = *impl_;
  displacement.resize(s.no * 6), velocity.resize(s.no * 6), director.resize(s.no * 6);
  for (LocalId le = 0; le < s.no; ++le)
    for (int A = 0; A < 6; ++A) {
      for (int c = 0; c < 3; ++c) {
        displacement[le * 6 + A][c] = s.x[le * nx + A * 3 + c] - s.X[le * nx + A * 3 + c];
        velocity[le * 6 + A][c] = s.v[le * nx + A * 3 + c];
        // P1 directors: a mid-side node shows the mean of its edge's vertex directors (t_h is linear).
        director[le * 6 + A][c] = A < 3 ? s.t[le * nt + A * 3 + c]
                                        : 0.5 * (s.t[le * nt + disc::edge_node(A - 3, 0) * 3 + c] +
                                                 s.t[le * nt + disc::edge_node(A - 3, 1) * 3 + c]);
      }
    }
}

}  // namespace shellfrac::solver
