#pragma once
/// \file stop_signals.hpp
/// SIGTERM, SIGUSR2 and SIGUSR1, as a batch system or a user sends them (docs/output.md, "Checkpoints and
/// restart"): caught from the program's start; SIGUSR1 asks for a checkpoint at the next step; SIGTERM or SIGUSR2
/// (the stop signals) during the time loop for a checkpoint and a stop, during the set-up for a stop at the next
/// phase of the set-up (nothing written yet: exit code 4). SIGUSR2 is the stop signal to send to Open MPI's
/// `mpirun`: it forwards SIGUSR1/SIGUSR2 to the ranks and lets them finish, while after a SIGTERM it kills them 1 s
/// later.
#include <mpi.h>

#include <csignal>
#include <stdexcept>

namespace shellfrac::solver {

/// Catches SIGTERM, SIGUSR2 and SIGUSR1 from now on (a program's first call): a signal before a Simulation exists counts
/// like one during its set-up.
void catch_stop_signals();

/// The signal received and not yet acted on (SIGTERM, SIGUSR2, SIGUSR1; 0 if none), on this rank. When several
/// came, a stop signal wins over SIGUSR1.
int received_stop_signal();
/// Whether `signal` asks the run to stop (SIGTERM or SIGUSR2), not only for a checkpoint.
bool is_stop_signal(int signal);
/// "SIGTERM", "SIGUSR2", "SIGUSR1" (for messages).
const char* signal_name(int signal);
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
  void (*old_usr2_)(int);
  void (*old_usr1_)(int);
};

/// Thrown on every rank when a stop signal arrives during the set-up (before anything is written): the program stops
/// with exit code 4 and says in which phase.
class StoppedDuringSetUp : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Between two phases of the set-up: StoppedDuringSetUp on every rank if any rank has received a stop signal; `done`
/// names the phase just finished (for the message). Collective.
void stop_if_terminated(const char* done, MPI_Comm comm);

}  // namespace shellfrac::solver
