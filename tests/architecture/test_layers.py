#!/usr/bin/python3
"""The dependency direction of packages/ (packages/layers.txt, docs/architecture.md) holds, and the check can fail.

* The tree: tools/check_layers.py finds no include of a higher or sideways layer in any package or solver room.
* The check itself, on a small tree made here: an upward include between rooms, a sideways include between
  packages, a folder that is no room, and a cycle in layers.txt are each reported with a non-zero exit.

usage: test_layers.py PROJECT_DIR
"""
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

PROJECT = pathlib.Path(sys.argv.pop(1) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
CHECK = PROJECT / "tools" / "check_layers.py"

LAYERS = """core:
disc: core
materials: core
solver/input: materials
solver/step: solver/input disc
solver: solver/step
"""


def check(root):
    return subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True, text=True)


class TheTree(unittest.TestCase):
    def test_no_upward_include(self):
        r = check(PROJECT)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn(" 0 upward or sideways includes", r.stdout)


class TheCheck(unittest.TestCase):
    def setUp(self):
        self.root = pathlib.Path(tempfile.mkdtemp(prefix="shellfrac_layers_"))
        (self.root / "packages").mkdir()
        (self.root / "packages" / "layers.txt").write_text(LAYERS)
        self.write("core/error.hpp", "")
        self.write("disc/quadrature.hpp", '#include "shellfrac/core/error.hpp"\n')
        self.write("materials/law.hpp", '#include "shellfrac/core/error.hpp"\n')
        self.write("solver/input/deck.hpp", '#include "shellfrac/materials/law.hpp"\n')
        self.write("solver/step/loads.cpp", '#include "shellfrac/solver/input/deck.hpp"\n'
                   '#include "shellfrac/disc/quadrature.hpp"\n#include "shellfrac/core/error.hpp"\n')
        self.write("solver/simulation.cpp", '#include "shellfrac/solver/step/loads.hpp"\n')

    def tearDown(self):
        shutil.rmtree(self.root, ignore_errors=True)

    def write(self, rel, text):
        package = rel.split("/")[0]
        path = self.root / "packages" / package / "src" / "shellfrac" / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)

    def test_clean_tree_passes(self):
        r = check(self.root)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_upward_include_between_rooms_fails(self):
        self.write("solver/input/deck.cpp", '#include "shellfrac/solver/step/loads.hpp"\n')
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("solver/input/deck.cpp:1: layer solver/input includes solver/step", r.stdout)

    def test_sideways_include_between_packages_fails(self):
        self.write("materials/law.cpp", '#include "shellfrac/disc/quadrature.hpp"\n')
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("layer materials includes disc", r.stdout)

    def test_folder_that_is_no_room_fails(self):
        self.write("solver/contact/search.hpp", "")
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("solver/contact/search.hpp: belongs to no layer", r.stderr)

    def test_cycle_in_layers_fails(self):
        (self.root / "packages" / "layers.txt").write_text(LAYERS + "disc2: disc3\ndisc3: disc2\n")
        r = check(self.root)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("cycle", r.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
