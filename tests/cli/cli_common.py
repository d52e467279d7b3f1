"""What the command-line tests share: the environment Open MPI needs to run as root (containers, CI), and
running a command serially or under mpiexec on np ranks."""
import os
import shutil
import subprocess
import tempfile
import unittest

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


class Launcher:
    """launch(args, cwd, np, timeout): runs args (under mpiexec -np np if np is given), capturing its output."""

    def __init__(self, mpiexec, preflags):
        self.mpiexec, self.preflags = mpiexec, list(preflags)

    def __call__(self, args, cwd=None, np=None, timeout=120):
        cmd = ([self.mpiexec, "-np", str(np)] + self.preflags if np else []) + list(args)
        return subprocess.run(cmd, cwd=cwd, env=ENV, capture_output=True, text=True, timeout=timeout)


class DeckTest(unittest.TestCase):
    """Tests that run decks in a scratch directory of their own (self.dir, removed afterwards). BASE is the deck text
    `deck` starts from; PREFIX names the scratch directories."""
    BASE = ""
    PREFIX = "shellfrac_"

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix=self.PREFIX)

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def deck(self, *replacements, name="base.xml", text=None):
        """Writes `text` (default BASE) with each (old, new) replacement, which must apply, as `name`."""
        text = self.BASE if text is None else text
        for old, new in replacements:
            self.assertIn(old, text)
            text = text.replace(old, new)
        with open(os.path.join(self.dir, name), "w") as f:
            f.write(text)
        return name

    def path(self, name):
        return os.path.join(self.dir, name)
