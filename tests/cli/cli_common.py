"""What the command-line tests share: the environment Open MPI needs to run as root (containers, CI), and
running a command serially or under mpiexec on np ranks."""
import os
import subprocess

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


class Launcher:
    """launch(args, cwd, np, timeout): runs args (under mpiexec -np np if np is given), capturing its output."""

    def __init__(self, mpiexec, preflags):
        self.mpiexec, self.preflags = mpiexec, list(preflags)

    def __call__(self, args, cwd=None, np=None, timeout=120):
        cmd = ([self.mpiexec, "-np", str(np)] + self.preflags if np else []) + list(args)
        return subprocess.run(cmd, cwd=cwd, env=ENV, capture_output=True, text=True, timeout=timeout)
