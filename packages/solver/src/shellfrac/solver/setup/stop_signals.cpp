#include "shellfrac/solver/setup/stop_signals.hpp"

#include <string>

#include "shellfrac/core/error.hpp"

namespace shellfrac::solver {

namespace {

/// Signal number received (SIGTERM / SIGUSR1), polled once per step and between phases of the set-up.
volatile std::sig_atomic_t received_signal = 0;
extern "C" void on_signal(int sig) { received_signal = sig; }

}  // namespace

void catch_stop_signals() { std::signal(SIGTERM, on_signal), std::signal(SIGUSR1, on_signal); }

int received_stop_signal() { return static_cast<int>(received_signal); }

void clear_checkpoint_signal() {
  if (received_signal == SIGUSR1) received_signal = 0;
}

SignalGuard::SignalGuard() : old_term_(std::signal(SIGTERM, on_signal)), old_usr1_(std::signal(SIGUSR1, on_signal)) {
  if (old_term_ != on_signal) received_signal = 0;
}

SignalGuard::~SignalGuard() { std::signal(SIGTERM, old_term_), std::signal(SIGUSR1, old_usr1_); }

void stop_if_terminated(const char* done, MPI_Comm comm) {
  int mine = received_signal == SIGTERM ? 1 : 0, any = 0;
  SHELLFRAC_REQUIRE(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm) == MPI_SUCCESS,
                    "MPI_Allreduce of the stop signal failed");
  if (any)
    throw StoppedDuringSetUp(std::string("stopped by SIGTERM during the set-up (after ") + done +
                             "); nothing was written: run it again");
}

}  // namespace shellfrac::solver
