"""Running shellfrac (or any program) serially or under mpiexec, with the environment Open MPI needs to run as root
(containers, CI)."""
import os
import subprocess

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


class Launcher:
    """launch(args, cwd, np, timeout, env): runs args (under `mpiexec -np np <preflags>` if np is given), capturing
    its output; returns the CompletedProcess. `env` adds to ENV (e.g. OMP_NUM_THREADS)."""

    def __init__(self, mpiexec="mpirun", preflags=()):
        self.mpiexec, self.preflags = mpiexec, list(preflags)

    def command(self, args, np=None):
        return ([self.mpiexec, "-np", str(np)] + self.preflags if np else []) + [str(a) for a in args]

    def __call__(self, args, cwd=None, np=None, timeout=120, env=None):
        return subprocess.run(self.command(args, np), cwd=cwd, env=dict(ENV, **(env or {})), capture_output=True,
                              text=True, timeout=timeout)
