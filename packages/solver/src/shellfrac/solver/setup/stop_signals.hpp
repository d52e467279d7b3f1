#pragma once
/// \file stop_signals.hpp
/// SIGTERM and SIGUSR1, as a batch system sends them (docs/output.md, "Checkpoints and restart"): caught from the
/// program's start; SIGUSR1 asks for a checkpoint at the next step; SIGTERM during the time loop for a checkpoint
/// and a stop, during the set-up for a stop at the next phase of the set-up (nothing written yet: exit code 4).
#include <mpi.h>

#include <csignal>
#include <stdexcept>

namespace shellfrac::solver {

/// Catches SIGTERM and SIGUSR1 from now on (a program's first call): a signal before a Simulation exists counts
/// like one during its set-up.
void catch_stop_signals();

/// The signal received and not yet acted on (SIGTERM, SIGUSR1; 0 if none), on this rank.
int received_stop_signal();
/// Forgets a SIGUSR1 once its checkpoint is written.
void clear_checkpoint_signal();

/// Installs the handlers for its lifetime: a Simulation's whole life, set-up included. A signal caught since
/// catch_stop_signals() counts.
class SignalGuard {
 public:
  SignalGuard();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  void (*old_term_)(int);
  void (*old_usr1_)(int);
};

/// Thrown on every rank when SIGTERM arrives during the set-up (before anything is written): the program stops
/// with exit code 4 and says in which phase.
class StoppedDuringSetUp : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Between two phases of the set-up: StoppedDuringSetUp on every rank if any rank has received SIGTERM; `done`
/// names the phase just finished (for the message). Collective.
void stop_if_terminated(const char* done, MPI_Comm comm);

}  // namespace shellfrac::solver
