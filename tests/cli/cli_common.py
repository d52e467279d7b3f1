"""What the command-line tests share: DeckTest, and (from shellfrac_tools.launch) the environment Open MPI needs to
run as root and running a command serially or under mpiexec on np ranks. Needs tools/ on PYTHONPATH (ctest sets it)."""
import os
import shutil
import tempfile
import unittest

from shellfrac_tools.launch import ENV, Launcher  # noqa: F401 (the tests import them from here)


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
