#include "shellfrac/solver/step/central_difference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/solver/fracture/fracture.hpp"
#include "shellfrac/solver/model/kernel_views.hpp"
#include "shellfrac/solver/model/shell_model.hpp"
#include "shellfrac/solver/contact/rigid_bodies.hpp"
#include "shellfrac/solver/contact/rigid_walls.hpp"
#include "shellfrac/solver/contact/shell_contact.hpp"
#include "shellfrac/solver/step/constraints.hpp"
#include "shellfrac/solver/step/force_assembly.hpp"
#include "shellfrac/solver/step/loads.hpp"

namespace shellfrac::solver {

namespace {

using Motion = Constraints::Motion;

/// The constraints of the owned nodes as views of Constraints' arrays, with the velocity programs of the
/// conditions evaluated at one time: program(bc * 3 + c) (a displacement, velocity or acceleration).
struct ConstraintViews {
  KernelView<const Motion> motion;
  KernelView<const unsigned char> components;
  KernelView<const int> prescribing, plane_offset, director_holder, director_offset;
  KernelView<const Plane> planes;
  KernelView<const DirectorConstraint> director_constraints;
  KernelView<const double> program;
  ConstraintViews() = default;
  ConstraintViews(const Constraints& c, const std::vector<double>& programs)
      : motion(kernel_view(c.motions())),
        components(kernel_view(c.prescribed_components())),
        prescribing(kernel_view(c.prescribings())),
        plane_offset(kernel_view(c.position_planes().offsets())),
        director_holder(kernel_view(c.director_holders())),
        director_offset(kernel_view(c.director_constraints().offsets())),
        planes(kernel_view(c.position_planes().planes())),
        director_constraints(kernel_view(c.director_constraints().constraints())),
        program(kernel_view(programs)) {}
  /// Whether component c of position node i follows its velocity program.
  KOKKOS_INLINE_FUNCTION bool prescribed(LocalId i, int c) const { return (components(i) >> c) & 1; }
  /// Component c of the program of the condition that prescribes node i.
  KOKKOS_INLINE_FUNCTION double program_of(LocalId i, int c) const { return program(prescribing(i) * 3 + c); }
  KOKKOS_INLINE_FUNCTION void remove_plane_normals(LocalId i, double w[3]) const {
    solver::remove_plane_normals(planes.data() + plane_offset(i), planes.data() + plane_offset(i + 1), w);
  }
  KOKKOS_INLINE_FUNCTION bool director_held(LocalId j) const { return director_holder(j) >= 0; }
  KOKKOS_INLINE_FUNCTION void remove_forbidden(LocalId j, const double L[3][3], const double t[3], double w[2]) const {
    if (director_offset(j) == director_offset(j + 1)) return;
    remove_forbidden_director_components(director_constraints.data() + director_offset(j),
                                         director_constraints.data() + director_offset(j + 1), L, t, w);
  }
};

/// Accelerations of owned element le at time t from the current forces (paper eq. 49): a = (f_ext - f - alpha m v)/m
/// on free components, the program's acceleration on prescribed ones, 0 on held nodes, without the components
/// normal to symmetry planes; T-ddot = -(Lambda-bar^T g + alpha I T-dot)/I on free directors. `rate` is the
/// director rate in the damping force (the predicted one in a step). Also the reactions R = m a - f_ext + f on held
/// and prescribed components, and the damping dissipated over dt.
struct Accelerate {
  ConstraintViews con;  // programs: the accelerations at t
  ConstPositionView v, f, fe;                    // velocities, internal and external forces
  ConstViewOf<PositionNodeScalars> m;            // lumped masses
  ConstDirectorView g, ge, director;             // internal and external director forces, directors
  ConstViewOf<RotationRows> rotation;
  ConstViewOf<DirectorNodeScalars> inertia;
  ConstViewOf<RateRows> rate;                    // the director rate in the damping force
  PositionView a, reaction;
  ViewOf<RateRows> director_acceleration;
  ViewOf<Scalars> damping;                       // the damping dissipation of each element
  double alpha = 0, dt = 0;
  bool director_loads = false;

  KOKKOS_INLINE_FUNCTION void operator()(LocalId le) const {
    double diss = 0;
    for (int A = 0; A < position_nodes; ++A) {
      const LocalId i = le * position_nodes + A;
      double* acc = a.point(i);
      double* R = reaction.point(i);
      const double *vi = v.point(i), *fi = f.point(i), *fei = fe.point(i);
      const double mi = m(i);
      const Motion motion = con.motion(i);
      if (motion == Motion::held) {
        for (int c = 0; c < 3; ++c) acc[c] = 0, R[c] = mi * acc[c] - fei[c] + fi[c];
        continue;
      }
      if (motion == Motion::prescribed) {
        for (int c = 0; c < 3; ++c) {
          if (con.prescribed(i, c)) {
            acc[c] = con.program_of(i, c), R[c] = mi * acc[c] - fei[c] + fi[c];
          } else {
            diss += dt * alpha * mi * vi[c] * vi[c];
            acc[c] = (fei[c] - fi[c] - alpha * mi * vi[c]) / mi, R[c] = 0.0;
          }
        }
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        diss += dt * alpha * mi * vi[c] * vi[c];
        acc[c] = (fei[c] - fi[c] - alpha * mi * vi[c]) / mi, R[c] = 0.0;
      }
      if (motion == Motion::on_planes) con.remove_plane_normals(i, acc);
    }
    for (int b = 0; b < director_nodes; ++b) {
      const LocalId j = le * director_nodes + b;
      double L[3][3], fT[2];
      load_matrix(rotation.point(j), L);
      if (director_loads) {  // f_T = Lambda-bar^T (g - g_ext)
        double gj[3];
        for (int c = 0; c < 3; ++c) gj[c] = g.point(j)[c] - ge.point(j)[c];
        disc::lambda_bar_transpose_times(L, gj, fT);
      } else {
        disc::lambda_bar_transpose_times(L, g.point(j), fT);
      }
      const double I = inertia(j);
      const double* Tp = rate.point(j);
      for (int c = 0; c < 2; ++c) {
        diss += dt * alpha * I * Tp[c] * Tp[c];
        fT[c] += alpha * I * Tp[c];
      }
      con.remove_forbidden(j, L, director.point(j), fT);
      const bool held = con.director_held(j);
      for (int c = 0; c < 2; ++c) director_acceleration.point(j)[c] = held ? 0.0 : -fT[c] / I;
    }
    damping(le) += diss;
  }
};

/// One velocity program of every condition at time t: out[bc * 3 + c].
void evaluate_programs(const Constraints& constraints, double t, Vec3 (Constraints::*program)(int, double) const,
                       std::vector<double>& out) {
  out.assign(3 * constraints.size(), 0.0);
  for (std::size_t bc = 0; bc < constraints.size(); ++bc) {
    const Vec3 p = (constraints.*program)(int(bc), t);
    for (int c = 0; c < 3; ++c) out[bc * 3 + c] = p[c];
  }
}

/// The Accelerate kernel of state s at time t (`programs`: filled with the programs' accelerations at t), with
/// `director_rate` in the damping force.
Accelerate accelerations(const ShellModel& model, const Constraints& constraints, bool director_loads, double alpha,
                         ShellState& s, double t, double dt, const RateRows& director_rate,
                         std::vector<double>& programs) {
  evaluate_programs(constraints, t, &Constraints::prescribed_acceleration, programs);
  Accelerate k;
  k.con = ConstraintViews(constraints, programs);
  k.v = kernel_view(std::as_const(s.v)), k.f = kernel_view(std::as_const(s.internal_force));
  k.fe = kernel_view(std::as_const(s.external_force)), k.m = kernel_view(model.mass);
  k.g = kernel_view(std::as_const(s.director_force)), k.ge = kernel_view(std::as_const(s.external_director_force));
  k.director = kernel_view(std::as_const(s.t)), k.rotation = kernel_view(std::as_const(s.rotation));
  k.inertia = kernel_view(model.inertia), k.rate = kernel_view(director_rate);
  k.a = kernel_view(s.a), k.reaction = kernel_view(s.reaction);
  k.director_acceleration = kernel_view(s.director_acceleration), k.damping = kernel_view(s.damping_dissipation);
  k.alpha = alpha, k.dt = dt, k.director_loads = director_loads;
  return k;
}

}  // namespace

CentralDifference::CentralDifference(ShellModel& model, Constraints& constraints, const Loads& loads,
                                     const RigidWalls& walls, const RigidBodies& bodies, ShellContact& shells,
                                     ForceAssembly& assembly,
                                     Fracture& fracture,
                                     PhaseTimes& times, double mass_damping, Relaxation relaxation)
    : model_(model),
      constraints_(constraints),
      loads_(loads),
      walls_(walls),
      bodies_(bodies),
      shells_(shells),
      assembly_(assembly),
      fracture_(fracture),
      times_(times),
      alpha_(mass_damping),
      relaxation_(relaxation),
      residual_(std::numeric_limits<double>::quiet_NaN()) {
  director_rate_predicted_.assign(model.owned);
  x_start_.assign(model.owned);
  finite_.assign(std::size_t(model.owned), 1);
}

void CentralDifference::start(ShellState& s) {
  assembly_.exchange_state(s);
  assembly_.compute_forces(s, fracture_.cohesive_params());
  book_plastic_work(s);
  external_forces(s.time, s);
  const Accelerate accelerate = accelerations(model_, constraints_, loads_.has_director_loads(), alpha_, s, s.time,
                                              0.0, s.director_rate, programs_a_);
  static const std::string label_start_accelerations("shellfrac::StartAccelerations");
  Kokkos::parallel_for(label_start_accelerations, KernelRange(0, model_.owned), accelerate);
}

void CentralDifference::step(ShellState& s, double dt, double t1) {
  {
    ScopedTimer timer(times_.update);
    remember_step_start(s);
    predict(s, dt, t1);  // paper eqs. 47-48, Algorithm 1
    bodies_.predict(s, dt, t1);
    constraints_.apply_rotations(t1, s);
  }
  assembly_.exchange_state(s);
  assembly_.compute_forces(s, fracture_.cohesive_params());
  ScopedTimer timer(times_.update);
  book_plastic_work(s);
  if (fracture_.enabled()) {
    ScopedTimer nucleation(times_.nucleation);
    fracture_.nucleate(s.step, t1, s, model_, assembly_.edge_tractions());
  }
  external_forces(t1, s);
  correct(s, dt, t1);
  bodies_.correct(s, dt);
  constraints_.apply_rotations(t1, s);
  constraints_.add_rotation_work(s, model_);
  s.time = t1;
  ++s.step;
  check_finite(s);
  if (relaxation_.enabled) relax(s);
}

void CentralDifference::external_forces(double t, ShellState& s) {
  loads_.external_forces(t, s, s.external_force, s.external_director_force);
  // The friction's dissipation is booked over the step that ends at t: none at the start (t = s.time).
  const double step = t - s.time;
  if (!walls_.empty()) walls_.add_forces(t, step, s);
  if (!bodies_.empty()) bodies_.add_forces(step, s);
  if (shells_.enabled()) {
    ScopedTimer timer(times_.contact);
    shells_.add_forces(step, s);
  }
}

// Static relaxation (docs/theory.md §7.5): when the global kinetic energy has passed a peak, the free velocities are
// set to zero (the removed energy is booked as damping), so the motion settles into the static state; once the
// programs have reached their final values, the run is relaxed when the out-of-balance force is small. The global
// sums are exact (ExactSum), so the decisions are the same on any rank count.
void CentralDifference::relax(ShellState& s) {
  ExactSum kinetic;
  for (LocalId le = 0; le < model_.owned; ++le) kinetic.add(model_.element_kinetic(s, le));
  kinetic.allreduce(model_.dm.comm());
  const double k = kinetic.value();
  RelaxationProgress& p = s.relaxation;
  const bool peak = k < p.kinetic_before;
  if (peak) {
    reset_free_velocities(s);
    p.kinetic_before = 0;
  } else {
    p.kinetic_before = k;
  }
  if (s.time < relaxation_.start) return;
  residual_ = relative_residual(s);
  relaxed_ = residual_ <= relaxation_.tolerance;
  if (peak && !relaxed_) watch_for_stall(s);
}

// At a kinetic-energy peak (theory.md §7.5): the residual has stopped falling when it has not fallen below
// stall_drop of its smallest value for stall_peaks peaks. Then either the displacement has settled too (its norm
// changed, relative, by at most the tolerance or settled_factor x the smallest residual over those peaks: steady to
// the level of the round-off in the forces): the equilibrium at the residual's round-off floor,
// which a small load against a stiff shell puts above the tolerance; or it has not: the relaxation has stalled (no
// equilibrium: a mechanism, an instability). Exact sums, so the same decision on the same step on every rank count.
void CentralDifference::watch_for_stall(ShellState& s) {
  const double u = displacement_norm(s);
  RelaxationProgress& p = s.relaxation;
  if (residual_ < relaxation_.stall_drop * p.best_residual) {
    p.best_residual = residual_;
    p.peaks_since_best = 0;
    p.u_low = p.u_high = u;
    return;
  }
  p.best_residual = std::min(p.best_residual, residual_);
  p.u_low = std::min(p.u_low, u), p.u_high = std::max(p.u_high, u);
  if (++p.peaks_since_best < relaxation_.stall_peaks) return;
  displacement_change_ = (p.u_high - p.u_low) / p.u_high;
  at_floor_ = displacement_change_ <= std::max(relaxation_.tolerance, relaxation_.settled_factor * p.best_residual);
  relaxed_ = at_floor_;
  stalled_ = !at_floor_;
}

// |x - X| over the owned position nodes.
double CentralDifference::displacement_norm(const ShellState& s) const {
  ExactSum u2;
  for (LocalId le = 0; le < model_.owned; ++le)
    for (int A = 0; A < position_nodes; ++A) {
      const double *x = s.x.at(le, A), *X = model_.X.at(le, A);
      for (int c = 0; c < 3; ++c) u2.add((x[c] - X[c]) * (x[c] - X[c]));
    }
  u2.allreduce(model_.dm.comm());
  return std::sqrt(u2.value());
}

void CentralDifference::reset_free_velocities(ShellState& s) const {
  using Motion = Constraints::Motion;
  for (LocalId le = 0; le < model_.owned; ++le) {
    double removed = 0;
    for (int A = 0; A < position_nodes; ++A) {
      const LocalId i = le * position_nodes + A;
      if (constraints_.motion(i) == Motion::held) continue;
      double* v = s.v.point(i);
      for (int c = 0; c < 3; ++c)
        if (!constraints_.prescribed(i, c)) removed += 0.5 * *model_.mass.point(i) * v[c] * v[c], v[c] = 0;
    }
    for (int b = 0; b < director_nodes; ++b) {
      const LocalId j = le * director_nodes + b;
      if (constraints_.director_held(j)) continue;
      removed += model_.rotary_kinetic(s, le, b);
      s.director_rate.point(j)[0] = s.director_rate.point(j)[1] = 0;
    }
    *s.damping_dissipation.at(le) += removed;
  }
}

// |f_ext - f_int| over the free components (projected on the constraints) relative to the norm of the forces that
// hold the state: loads, reactions and the couples of held directors.
double CentralDifference::relative_residual(const ShellState& s) const {
  using Motion = Constraints::Motion;
  ExactSum r2, f2;
  for (LocalId i = 0; i < model_.owned * position_nodes; ++i) {
    const double *f = s.internal_force.point(i), *fe = s.external_force.point(i), *R = s.reaction.point(i);
    double r[3];
    for (int c = 0; c < 3; ++c) r[c] = constraints_.free(i, c) ? fe[c] - f[c] : 0.0, f2.add(fe[c] * fe[c] + R[c] * R[c]);
    if (constraints_.motion(i) == Motion::on_planes) constraints_.position_planes().remove_normal_components(i, r);
    for (int c = 0; c < 3; ++c) r2.add(r[c] * r[c]);
  }
  for (LocalId j = 0; j < model_.owned * director_nodes; ++j) {
    const double *g = s.director_force.point(j), *ge = s.external_director_force.point(j);
    double w[3], L[3][3], rT[2];
    for (int c = 0; c < 3; ++c) w[c] = ge[c] - g[c], f2.add(ge[c] * ge[c]);
    if (constraints_.director_held(j)) {
      for (int c = 0; c < 3; ++c) f2.add(g[c] * g[c]);
      continue;
    }
    load_matrix(s.rotation.point(j), L);
    disc::lambda_bar_transpose_times(L, w, rT);
    constraints_.director_constraints().remove_forbidden_components(j, L, s.t.point(j), rT);
    r2.add(rT[0] * rT[0] + rT[1] * rT[1]);
  }
  r2.allreduce(model_.dm.comm()), f2.allreduce(model_.dm.comm());
  const double ref = std::sqrt(f2.value());
  return ref > 0 ? std::sqrt(r2.value()) / ref : std::sqrt(r2.value());
}

void CentralDifference::remember_step_start(const ShellState& s) {
  // (The positions at t_n are copied by the predictor, in its pass over them.)
  // The loaded elements' rows only: an element without external forces at t_n adds 0 * dx to its work, and leaving
  // out a term that is +0 or -0 does not change a sum that starts at +0 (the work stays bitwise the same).
  fext_start_slot_.assign(std::size_t(model_.owned), -1);
  std::vector<double>& rows = fext_start_.vector();
  rows.clear();
  for (LocalId le = 0; le < model_.owned; ++le) {
    const double* f = s.external_force.at(le);
    if (std::all_of(f, f + position_values, [](double v) { return v == 0.0; })) continue;
    fext_start_slot_[std::size_t(le)] = int(rows.size() / position_values);
    rows.insert(rows.end(), f, f + position_values);
  }
  if (loads_.has_director_loads()) {
    t_start_.vector().assign(s.t.vector().begin(), s.t.vector().begin() + std::size_t(model_.owned) * director_values);
    gext_start_ = s.external_director_force;
  }
  constraints_.begin_step(s, model_);
}

// Predictor (docs/theory.md §7.4 steps 1-2): x^{n+1} = x^n + dt v^n + dt^2/2 a^n, v_pre = v^n + dt/2 a^n; held nodes
// stay at X, prescribed components follow the exact integral of their velocity program, and no increment crosses
// a symmetry plane. Directors: Delta T = dt T-dot + dt^2/2 T-ddot, then the exponential map. The positions at t_n
// are kept for the work accounts (x_start_) in the same pass.
void CentralDifference::predict(ShellState& s, double dt, double t1) {
  evaluate_programs(constraints_, t1, &Constraints::prescribed_displacement, programs_u_);
  const ConstraintViews con(constraints_, programs_u_);
  const PositionView x = kernel_view(s.x), v = kernel_view(s.v), x0 = kernel_view(x_start_);
  const ConstPositionView a = kernel_view(std::as_const(s.a)), X = kernel_view(model_.X);
  static const std::string label_predict_positions("shellfrac::PredictPositions");
  Kokkos::parallel_for(label_predict_positions, KernelRange(0, model_.owned * position_nodes), [=](const LocalId i) {
    double* xi = x.point(i);
    double* vi = v.point(i);
    for (int c = 0; c < 3; ++c) x0.point(i)[c] = xi[c];
    const double* ai = a.point(i);
    const double* Xi = X.point(i);
    const Motion motion = con.motion(i);
    if (motion == Motion::held) {
      for (int c = 0; c < 3; ++c) xi[c] = Xi[c], vi[c] = 0;
      return;
    }
    double dx[3];
    for (int c = 0; c < 3; ++c) dx[c] = dt * vi[c] + 0.5 * dt * dt * ai[c];
    if (motion == Motion::prescribed) {  // the exact integral of the program: no drift
      for (int c = 0; c < 3; ++c) {
        const bool p = con.prescribed(i, c);
        xi[c] = p ? Xi[c] + con.program_of(i, c) : xi[c] + dx[c];
        if (!p) vi[c] += 0.5 * dt * ai[c];
      }
      return;
    }
    for (int c = 0; c < 3; ++c) vi[c] += 0.5 * dt * ai[c];
    if (motion == Motion::on_planes) {
      con.remove_plane_normals(i, dx);
      con.remove_plane_normals(i, vi);
    }
    for (int c = 0; c < 3; ++c) xi[c] += dx[c];
  });
  const DirectorView t = kernel_view(s.t);
  const ViewOf<RotationRows> rotation = kernel_view(s.rotation);
  const ConstViewOf<RateRows> Td = kernel_view(std::as_const(s.director_rate));
  const ConstViewOf<RateRows> Tdd = kernel_view(std::as_const(s.director_acceleration));
  const ViewOf<RateRows> Tp = kernel_view(director_rate_predicted_);
  static const std::string label_predict_directors("shellfrac::PredictDirectors");
  Kokkos::parallel_for(label_predict_directors, KernelRange(0, model_.owned * director_nodes), [=](const LocalId j) {
    double L[3][3], dT[2];
    load_matrix(rotation.point(j), L);
    const bool held = con.director_held(j);
    double* Tpj = Tp.point(j);
    const double *Tdj = Td.point(j), *Tddj = Tdd.point(j);
    for (int c = 0; c < 2; ++c) {
      dT[c] = held ? 0.0 : dt * Tdj[c] + 0.5 * dt * dt * Tddj[c];  // paper eq. 47
      Tpj[c] = held ? 0.0 : Tdj[c] + 0.5 * dt * Tddj[c];           // paper eq. 48, gamma = 1/2
    }
    double* tj = t.point(j);
    con.remove_forbidden(j, L, tj, dT);
    con.remove_forbidden(j, L, tj, Tpj);
    disc::update_director(tj, L, dT, tj, L);  // Algorithm 1
    store_matrix(L, rotation.point(j));
  });
}

// Adds the plastic work of the last element kernel (which updated the plastic state to the new time in place).
// A return map that hit its iteration limit stops the run on every rank, naming the element.
void CentralDifference::book_plastic_work(ShellState& s) const {
  if (!model_.any_plastic) return;
  GlobalId bad = -1;
  const auto& failed = assembly_.return_failed();
  const auto& work = assembly_.plastic_work_increment();
  for (LocalId le = 0; le < model_.owned; ++le) {
    if (!model_.is_plastic(le)) continue;
    if (failed[le] && bad < 0) bad = model_.dm.element_gid(le);
    *s.plastic_work.at(le) += work[le];
  }
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, model_.dm.comm());
  SHELLFRAC_REQUIRE(worst < 0, "the plastic return map did not converge in "
                                   << model_.element_name(GlobalId(worst))
                                   << " at step " << s.step << ", time " << s.time
                                   << " (docs/theory.md §4.3; a non-finite or extreme strain?)");
}

// The corrector, element by element (one pass over the element's rows): accelerations and reactions at t1
// (paper eq. 49, with the damping force alpha m v_pre), velocities at t1 (paper eq. 50, gamma = 1/2:
// v^{n+1} = v_pre + dt/2 a^{n+1} on free components, the program's velocity on prescribed ones;
// T-dot^{n+1} = T-dot_pre + dt/2 T-ddot^{n+1}), and the work of the loads and of the reactions over the step by the
// trapezoidal rule (docs/theory.md §9.7).
void CentralDifference::correct(ShellState& s, double dt, double t1) {
  const Accelerate accelerate = accelerations(model_, constraints_, loads_.has_director_loads(), alpha_, s, t1, dt,
                                              director_rate_predicted_, programs_a_);
  evaluate_programs(constraints_, t1, &Constraints::prescribed_velocity, programs_v_);
  const ConstraintViews con(constraints_, programs_v_);
  const PositionView v = kernel_view(s.v);
  const ViewOf<RateRows> rate = kernel_view(s.director_rate);
  const ConstPositionView a = kernel_view(std::as_const(s.a));
  const ConstViewOf<RateRows> Tdd = kernel_view(std::as_const(s.director_acceleration));
  const ConstViewOf<RateRows> Tp = kernel_view(std::as_const(director_rate_predicted_));
  const ConstPositionView x = kernel_view(std::as_const(s.x)), x0 = kernel_view(std::as_const(x_start_));
  // fe0: the external forces at t_n of the loaded elements only, row fe0_slot(le) (-1: none)
  const ConstPositionView fe = kernel_view(std::as_const(s.external_force)), fe0 = kernel_view(std::as_const(fext_start_));
  const KernelView<const int> fe0_slot = kernel_view(std::as_const(fext_start_slot_));
  const ConstPositionView R = kernel_view(std::as_const(s.reaction));
  const ConstDirectorView t = kernel_view(std::as_const(s.t)), t0 = kernel_view(std::as_const(t_start_));
  const ConstDirectorView ge = kernel_view(std::as_const(s.external_director_force));
  const ConstDirectorView ge0 = kernel_view(std::as_const(gext_start_));
  const ViewOf<Scalars> external_work = kernel_view(s.external_work), reaction_work = kernel_view(s.reaction_work);
  const bool director_loads = loads_.has_director_loads();
  const ConstPositionView f = kernel_view(std::as_const(s.internal_force));
  const KernelView<char> finite = kernel_view(finite_);
  static const std::string label_correct("shellfrac::Correct");
  Kokkos::parallel_for(label_correct, KernelRange(0, model_.owned), [=](const LocalId le) {
    double R0[position_values];  // the reactions at t_n, before accelerate overwrites them
    for (int k = 0; k < position_values; ++k) R0[k] = R.at(le)[k];
    accelerate(le);
    for (LocalId i = le * position_nodes; i < (le + 1) * position_nodes; ++i) {
      double* vi = v.point(i);
      const double* ai = a.point(i);
      const Motion motion = con.motion(i);
      if (motion == Motion::held) continue;
      if (motion == Motion::prescribed) {
        for (int c = 0; c < 3; ++c) vi[c] = con.prescribed(i, c) ? con.program_of(i, c) : vi[c] + 0.5 * dt * ai[c];
        continue;
      }
      for (int c = 0; c < 3; ++c) vi[c] += 0.5 * dt * ai[c];
    }
    for (LocalId j = le * director_nodes; j < (le + 1) * director_nodes; ++j)
      for (int c = 0; c < 2; ++c) rate.point(j)[c] = Tp.point(j)[c] + 0.5 * dt * Tdd.point(j)[c];
    double wext = 0, wreact = 0;
    const double* f0 = fe0_slot(le) >= 0 ? fe0.at(fe0_slot(le)) : nullptr;
    const double *xe = x.at(le), *x0e = x0.at(le), *fee = fe.at(le), *Re = R.at(le), *fie = f.at(le);
    bool all_finite = true;
    for (int j = 0; j < position_values; ++j) {
      const double dx = xe[j] - x0e[j];
      wext += 0.5 * ((f0 ? f0[j] : 0.0) + fee[j]) * dx;
      wreact += 0.5 * (R0[j] + Re[j]) * dx;
      all_finite = all_finite && std::isfinite(xe[j]) && std::isfinite(fie[j]);
    }
    finite(le) = all_finite ? 1 : 0;
    if (director_loads) {  // the work of the edge couples on the directors
      const double *te = t.at(le), *t0e = t0.at(le), *gee = ge.at(le), *ge0e = ge0.at(le);
      for (int j = 0; j < director_values; ++j) wext += 0.5 * (ge0e[j] + gee[j]) * (te[j] - t0e[j]);
    }
    external_work(le) += wext, reaction_work(le) += wreact;
  });
}

// Whether the corrector found a non-finite position or internal force (nothing after it in the step moves a shell
// node: the rotations after it set directors), in the first such element on any rank.
void CentralDifference::check_finite(const ShellState& s) const {
  GlobalId bad = -1;
  for (LocalId le = 0; le < model_.owned && bad < 0; ++le)
    if (!finite_[std::size_t(le)]) bad = model_.dm.element_gid(le);
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, model_.dm.comm());
  if (worst >= 0) {
    std::ostringstream os;
    os << "numerical blow-up at step " << s.step << ", time " << s.time
       << ": non-finite position or force in " << model_.element_name(GlobalId(worst))
       << " (time step too large or unstable input?)";
    throw NumericalError(os.str());  // on every rank (the reduction above)
  }
}

}  // namespace shellfrac::solver
