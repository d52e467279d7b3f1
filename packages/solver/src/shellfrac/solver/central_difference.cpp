#include "shellfrac/solver/central_difference.hpp"

#include <Kokkos_Core.hpp>
#include <cmath>
#include <limits>
#include <sstream>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/exact_sum.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/disc/director.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/solver/constraints.hpp"
#include "shellfrac/solver/force_assembly.hpp"
#include "shellfrac/solver/fracture.hpp"
#include "shellfrac/solver/loads.hpp"
#include "shellfrac/solver/shell_model.hpp"

namespace shellfrac::solver {

namespace {
/// for_each(n, body): body(i) for i in [0, n) on the host execution space (threads with Kokkos OpenMP). The bodies
/// below write only the rows of their own node or element, so the result does not depend on the thread count.
template <class Body>
void for_each(LocalId n, const char* name, const Body& body) {
  Kokkos::parallel_for(name, Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, n),
                       [&](const LocalId i) { body(i); });
}
}  // namespace

CentralDifference::CentralDifference(ShellModel& model, Constraints& constraints, const Loads& loads,
                                     ForceAssembly& assembly, Fracture& fracture, PhaseTimes& times,
                                     double mass_damping, Relaxation relaxation)
    : model_(model),
      constraints_(constraints),
      loads_(loads),
      assembly_(assembly),
      fracture_(fracture),
      times_(times),
      alpha_(mass_damping),
      relaxation_(relaxation),
      residual_(std::numeric_limits<double>::quiet_NaN()) {
  director_rate_predicted_.assign(model.owned);
}

void CentralDifference::start(ShellState& s) {
  assembly_.exchange_state(s);
  assembly_.compute_forces(s, fracture_.cohesive_params());
  commit_plasticity(s);
  loads_.external_forces(s.time, s, s.external_force, s.external_director_force);
  for (LocalId le = 0; le < model_.owned; ++le) accelerate(s, le, s.time, 0.0, s.director_rate);
}

void CentralDifference::step(ShellState& s, double dt) {
  const double t1 = s.time + dt;
  {
    ScopedTimer timer(times_.update);
    remember_step_start(s);
    predict(s, dt, t1);  // paper eqs. 47-48, Algorithm 1
    constraints_.apply_rotations(t1, s);
  }
  assembly_.exchange_state(s);
  assembly_.compute_forces(s, fracture_.cohesive_params());
  ScopedTimer timer(times_.update);
  commit_plasticity(s);
  if (fracture_.enabled()) {
    ScopedTimer nucleation(times_.nucleation);
    fracture_.nucleate(s.step, t1, s, model_, assembly_);
  }
  loads_.external_forces(t1, s, s.external_force, s.external_director_force);
  correct(s, dt, t1);
  constraints_.apply_rotations(t1, s);
  constraints_.add_rotation_work(s, model_);
  s.time = t1;
  ++s.step;
  check_finite(s);
  if (relaxation_.enabled) relax(s);
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
  if (k < kinetic_before_) {
    reset_free_velocities(s);
    kinetic_before_ = 0;
  } else {
    kinetic_before_ = k;
  }
  if (s.time < relaxation_.start) return;
  residual_ = relative_residual(s);
  relaxed_ = residual_ <= relaxation_.tolerance;
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
  x_start_.vector().assign(s.x.vector().begin(), s.x.vector().begin() + std::size_t(model_.owned) * position_values);
  fext_start_ = s.external_force, reaction_start_ = s.reaction;
  if (loads_.has_director_loads()) {
    t_start_.vector().assign(s.t.vector().begin(), s.t.vector().begin() + std::size_t(model_.owned) * director_values);
    gext_start_ = s.external_director_force;
  }
  constraints_.begin_step(s, model_);
}

// Predictor (docs/theory.md §7.4 steps 1-2): x^{n+1} = x^n + dt v^n + dt^2/2 a^n, v_pre = v^n + dt/2 a^n; held nodes
// stay at X, prescribed components follow the exact integral of their velocity program, and no increment crosses
// a symmetry plane. Directors: Delta T = dt T-dot + dt^2/2 T-ddot, then the exponential map.
void CentralDifference::predict(ShellState& s, double dt, double t1) {
  using Motion = Constraints::Motion;
  for_each(model_.owned * position_nodes, "shellfrac::PredictPositions", [&](const LocalId i) {
    double* x = s.x.point(i);
    double* v = s.v.point(i);
    const double* a = s.a.point(i);
    const double* X = model_.X.point(i);
    const Motion motion = constraints_.motion(i);
    if (motion == Motion::held) {
      for (int c = 0; c < 3; ++c) x[c] = X[c], v[c] = 0;
      return;
    }
    double dx[3];
    for (int c = 0; c < 3; ++c) dx[c] = dt * v[c] + 0.5 * dt * dt * a[c];
    if (motion == Motion::prescribed) {  // the exact integral of the program: no drift
      const Vec3 u = constraints_.prescribed_displacement(constraints_.prescribing(i), t1);
      for (int c = 0; c < 3; ++c) {
        const bool p = constraints_.prescribed(i, c);
        x[c] = p ? X[c] + u[c] : x[c] + dx[c];
        if (!p) v[c] += 0.5 * dt * a[c];
      }
      return;
    }
    for (int c = 0; c < 3; ++c) v[c] += 0.5 * dt * a[c];
    if (motion == Motion::on_planes) {
      constraints_.position_planes().remove_normal_components(i, dx);
      constraints_.position_planes().remove_normal_components(i, v);
    }
    for (int c = 0; c < 3; ++c) x[c] += dx[c];
  });
  const auto& director_constraints = constraints_.director_constraints();
  for_each(model_.owned * director_nodes, "shellfrac::PredictDirectors", [&](const LocalId j) {
    double L[3][3], dT[2];
    load_matrix(s.rotation.point(j), L);
    const double* Td = s.director_rate.point(j);
    const double* Tdd = s.director_acceleration.point(j);
    double* Tp = director_rate_predicted_.point(j);
    const bool held = constraints_.director_held(j);
    for (int c = 0; c < 2; ++c) {
      dT[c] = held ? 0.0 : dt * Td[c] + 0.5 * dt * dt * Tdd[c];  // paper eq. 47
      Tp[c] = held ? 0.0 : Td[c] + 0.5 * dt * Tdd[c];            // paper eq. 48, gamma = 1/2
    }
    director_constraints.remove_forbidden_components(j, L, s.t.point(j), dT);
    director_constraints.remove_forbidden_components(j, L, s.t.point(j), Tp);
    double* t = s.t.point(j);
    disc::update_director(t, L, dT, t, L);  // Algorithm 1
    store_matrix(L, s.rotation.point(j));
  });
}

// Accepts the plastic state of the last element kernel as the state at the new time and adds its plastic work.
// A return map that hit its iteration limit stops the run on every rank, naming the element.
void CentralDifference::commit_plasticity(ShellState& s) const {
  if (!model_.any_plastic) return;
  GlobalId bad = -1;
  const auto& failed = assembly_.return_failed();
  const auto& work = assembly_.plastic_work_increment();
  for (LocalId le = 0; le < model_.owned; ++le) {
    if (!model_.is_plastic[le]) continue;
    if (failed[le] && bad < 0) bad = model_.dm.element_gid(le);
    *s.plastic_work.at(le) += work[le];
  }
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, model_.dm.comm());
  SHELLFRAC_REQUIRE(worst < 0, "the plastic return map did not converge in element " << GlobalId(worst) + 1
                                   << " at step " << s.step << ", time " << s.time
                                   << " (docs/theory.md §4.3; a non-finite or extreme strain?)");
  s.plastic.swap(assembly_.plastic_trial());
}

// The corrector, element by element (one pass over the element's rows): accelerations and reactions at t1,
// velocities at t1, and the work of the step.
void CentralDifference::correct(ShellState& s, double dt, double t1) {
  for_each(model_.owned, "shellfrac::Correct", [&](const LocalId le) {
    accelerate(s, le, t1, dt, director_rate_predicted_);  // paper eq. 49, with the damping force alpha m v_pre
    correct_velocities(s, le, dt, t1);                     // paper eq. 50
    book_work(s, le);
  });
}

// Accelerations of owned element le at time t from the current forces (paper eq. 49): a = (f_ext - f - alpha m v)/m
// on free components, the program's acceleration on prescribed ones, 0 on held nodes, without the components
// normal to symmetry planes; T-ddot = -(Lambda-bar^T g + alpha I T-dot)/I on free directors. `director_rate` is
// the rate in the damping force (the predicted one in a step). Also the reactions R = m a - f_ext + f on held and
// prescribed components, and the damping dissipated over dt.
void CentralDifference::accelerate(ShellState& s, LocalId le, double t, double dt, const RateRows& director_rate) {
  using Motion = Constraints::Motion;
  const double alpha = alpha_;
  double diss = 0;
  for (int A = 0; A < position_nodes; ++A) {
    const LocalId i = le * position_nodes + A;
    double* acc = s.a.point(i);
    double* R = s.reaction.point(i);
    const double *v = s.v.point(i), *f = s.internal_force.point(i), *fe = s.external_force.point(i);
    const double m = *model_.mass.point(i);
    const Motion motion = constraints_.motion(i);
    if (motion == Motion::held) {
      for (int c = 0; c < 3; ++c) acc[c] = 0, R[c] = m * acc[c] - fe[c] + f[c];
      continue;
    }
    if (motion == Motion::prescribed) {
      const Vec3 pa = constraints_.prescribed_acceleration(constraints_.prescribing(i), t);
      for (int c = 0; c < 3; ++c) {
        if (constraints_.prescribed(i, c)) {
          acc[c] = pa[c], R[c] = m * acc[c] - fe[c] + f[c];
        } else {
          diss += dt * alpha * m * v[c] * v[c];
          acc[c] = (fe[c] - f[c] - alpha * m * v[c]) / m, R[c] = 0.0;
        }
      }
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      diss += dt * alpha * m * v[c] * v[c];
      acc[c] = (fe[c] - f[c] - alpha * m * v[c]) / m, R[c] = 0.0;
    }
    if (motion == Motion::on_planes) constraints_.position_planes().remove_normal_components(i, acc);
  }
  for (int b = 0; b < director_nodes; ++b) {
    const LocalId j = le * director_nodes + b;
    double L[3][3], fT[2];
    load_matrix(s.rotation.point(j), L);
    if (loads_.has_director_loads()) {  // f_T = Lambda-bar^T (g - g_ext)
      double g[3];
      for (int c = 0; c < 3; ++c) g[c] = s.director_force.point(j)[c] - s.external_director_force.point(j)[c];
      disc::lambda_bar_transpose_times(L, g, fT);
    } else {
      disc::lambda_bar_transpose_times(L, s.director_force.point(j), fT);
    }
    const double I = *model_.inertia.point(j);
    const double* Tp = director_rate.point(j);
    for (int c = 0; c < 2; ++c) {
      diss += dt * alpha * I * Tp[c] * Tp[c];
      fT[c] += alpha * I * Tp[c];
    }
    constraints_.director_constraints().remove_forbidden_components(j, L, s.t.point(j), fT);
    const bool held = constraints_.director_held(j);
    for (int c = 0; c < 2; ++c) s.director_acceleration.point(j)[c] = held ? 0.0 : -fT[c] / I;
  }
  *s.damping_dissipation.at(le) += diss;
}

// Velocities of owned element le at t1 (paper eq. 50, gamma = 1/2): v^{n+1} = v_pre + dt/2 a^{n+1} on free
// components, the program's velocity on prescribed ones; T-dot^{n+1} = T-dot_pre + dt/2 T-ddot^{n+1}.
void CentralDifference::correct_velocities(ShellState& s, LocalId le, double dt, double t1) const {
  using Motion = Constraints::Motion;
  for (LocalId i = le * position_nodes; i < (le + 1) * position_nodes; ++i) {
    double* v = s.v.point(i);
    const double* acc = s.a.point(i);
    const Motion motion = constraints_.motion(i);
    if (motion == Motion::held) continue;
    if (motion == Motion::prescribed) {
      const Vec3 pv = constraints_.prescribed_velocity(constraints_.prescribing(i), t1);
      for (int c = 0; c < 3; ++c) v[c] = constraints_.prescribed(i, c) ? pv[c] : v[c] + 0.5 * dt * acc[c];
      continue;
    }
    for (int c = 0; c < 3; ++c) v[c] += 0.5 * dt * acc[c];
  }
  for (LocalId j = le * director_nodes; j < (le + 1) * director_nodes; ++j)
    for (int c = 0; c < 2; ++c)
      s.director_rate.point(j)[c] = director_rate_predicted_.point(j)[c] + 0.5 * dt * s.director_acceleration.point(j)[c];
}

// Work of the loads and of the reactions on owned element le over the step, by the trapezoidal rule
// (docs/theory.md §9.7).
void CentralDifference::book_work(ShellState& s, LocalId le) const {
  double wext = 0, wreact = 0;
  const double *x = s.x.at(le), *x0 = x_start_.at(le), *fe = s.external_force.at(le), *fe0 = fext_start_.at(le);
  const double *R = s.reaction.at(le), *R0 = reaction_start_.at(le);
  for (int k = 0; k < position_values; ++k) {
    const double dx = x[k] - x0[k];
    wext += 0.5 * (fe0[k] + fe[k]) * dx;
    wreact += 0.5 * (R0[k] + R[k]) * dx;
  }
  if (loads_.has_director_loads()) {  // the work of the edge couples on the directors
    const double *t = s.t.at(le), *t0 = t_start_.at(le), *ge = s.external_director_force.at(le);
    const double* ge0 = gext_start_.at(le);
    for (int k = 0; k < director_values; ++k) wext += 0.5 * (ge0[k] + ge[k]) * (t[k] - t0[k]);
  }
  *s.external_work.at(le) += wext, *s.reaction_work.at(le) += wreact;
}

void CentralDifference::check_finite(const ShellState& s) const {
  GlobalId bad = -1;
  for (LocalId le = 0; le < model_.owned && bad < 0; ++le)
    for (int i = 0; i < position_values; ++i)
      if (!std::isfinite(s.x.at(le)[i]) || !std::isfinite(s.internal_force.at(le)[i])) {
        bad = model_.dm.element_gid(le);
        break;
      }
  const double worst = parallel::max(bad >= 0 ? double(bad) : -1.0, model_.dm.comm());
  if (worst >= 0) {
    std::ostringstream os;
    os << "numerical blow-up at step " << s.step << ", time " << s.time
       << ": non-finite position or force in element " << GlobalId(worst) + 1
       << " (time step too large or unstable input?)";
    throw NumericalError(os.str());  // on every rank (the reduction above)
  }
}

}  // namespace shellfrac::solver
