#include "shellfrac/solver/setup/stop_signals.hpp"

#include <string>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {

/// Signal number received (SIGTERM / SIGUSR2 / SIGUSR1), polled once per step and between phases of the set-up.
/// A stop signal is never replaced by a later SIGUSR1.
volatile std::sig_atomic_t received_signal = 0;
extern "C" void on_signal(int sig) {
  if (sig == SIGUSR1 && (received_signal == SIGTERM || received_signal == SIGUSR2)) return;
  received_signal = sig;
}

}  // namespace

void catch_stop_signals() {
  std::signal(SIGTERM, on_signal), std::signal(SIGUSR2, on_signal), std::signal(SIGUSR1, on_signal);
}

int received_stop_signal() { return static_cast<int>(received_signal); }

bool is_stop_signal(int signal) { return signal == SIGTERM || signal == SIGUSR2; }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGTERM: return "SIGTERM";
    case SIGUSR2: return "SIGUSR2";
    case SIGUSR1: return "SIGUSR1";
    default: return "a signal";
  }
}

void clear_checkpoint_signal() {
  if (received_signal == SIGUSR1) received_signal = 0;
}

SignalGuard::SignalGuard()
    : old_term_(std::signal(SIGTERM, on_signal)),
      old_usr2_(std::signal(SIGUSR2, on_signal)),
      old_usr1_(std::signal(SIGUSR1, on_signal)) {
  if (old_term_ != on_signal) received_signal = 0;
}

SignalGuard::~SignalGuard() {
  std::signal(SIGTERM, old_term_), std::signal(SIGUSR2, old_usr2_), std::signal(SIGUSR1, old_usr1_);
}

void stop_if_terminated(const char* done, MPI_Comm comm) {
  // The largest stop signal number any rank received (SIGTERM 15 > SIGUSR2 12), or 0.
  int mine = is_stop_signal(received_signal) ? int(received_signal) : 0, any = 0;
  SHELLFRAC_REQUIRE(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm) == MPI_SUCCESS,
                    "MPI_Allreduce of the stop signal failed");
  if (any)
    throw StoppedDuringSetUp(std::string("stopped by ") + signal_name(any) + " during the set-up (after " + done +
                             "); nothing was written: run it again");
}

}  // namespace shellfrac::solver
