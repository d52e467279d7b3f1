#!/usr/bin/python3
"""The shared Python package tools/shellfrac_tools, against exact values.

* tables.read_table: columns by name; a partial last line (a run still writing) is left out; a damaged row and a
  missing column are errors naming the file (and the line, or the columns there are).
* decks: parameter lines by Python type (double written exactly, arrays), a substitution that does not apply is an
  error, the torn cylinder template is a valid deck (`shellfrac --check`).
* exodus.ExodusFile and results_files on results written by shellfrac: xml/cantilever_plate_oscillation.xml with
  End Time 0 (the reference state only): one block of 8 x 12 x 2 = 192 TRI6 with 6 DG nodes each (1 152 nodes),
  the plate 1.0 x 1.5 in z = 0, element ids 1..192, zero displacement and owning rank; the global variable
  kinetic_energy is the history's column number for number, and below (1/2) m v^2 = 0.5 x (1.0 x 1.5 x 0.1 x 1)
  x 1^2 = 0.075 (unit velocity, density 1, the clamped root's nodes held). On 2 ranks the per-rank set reads as
  two files holding elements 1..192 once.

usage: test_python_tools.py PROJECT_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]   (tools/ on PYTHONPATH)
"""
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

from shellfrac_tools import decks
from shellfrac_tools.exodus import ExodusFile
from shellfrac_tools.launch import Launcher
from shellfrac_tools.results_files import rank_files
from shellfrac_tools.tables import TableError, column, read_table

PROJECT, SHELLFRAC, MPIEXEC = sys.argv[1:4]
PREFLAGS = sys.argv[4:]
del sys.argv[1:]
launch = Launcher(MPIEXEC, PREFLAGS)


class Scratch(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shellfrac_pytools_")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def write(self, name, text):
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            f.write(text)
        return path


class Tables(Scratch):
    def test_columns_by_name(self):
        t = read_table(self.write("h.csv", "time,step\n0,0\n1e-6,1\n"))
        self.assertEqual(list(t["time"]), [0.0, 1e-6])
        self.assertEqual(list(t["step"]), [0.0, 1.0])

    def test_partial_last_line_left_out(self):
        t = read_table(self.write("h.csv", "time,step\n0,0\n1e-6,1\n2e-6,"))
        self.assertEqual(list(t["step"]), [0.0, 1.0])

    def test_damaged_row_named(self):
        path = self.write("h.csv", "time,step\n0,0\ngarbage,1\n2e-6,2\n")
        with self.assertRaisesRegex(TableError, r"h\.csv: line 3 is not 2 numbers: 'garbage,1'"):
            read_table(path)

    def test_missing_column_lists_the_columns(self):
        path = self.write("h.csv", "time,step\n0,0\n")
        with self.assertRaisesRegex(TableError, r"no column 'energy'; available columns: time, step"):
            column(read_table(path), "energy", path)

    def test_missing_and_empty_files(self):
        with self.assertRaisesRegex(TableError, "missing"):
            read_table(os.path.join(self.dir, "none.csv"))
        with self.assertRaisesRegex(TableError, "is empty"):
            read_table(self.write("e.csv", ""))


class Decks(Scratch):
    def test_parameter_lines(self):
        self.assertEqual(decks.parameter_xml("A", 0.1 + 0.2, 0), '<Parameter name="A" type="double" value="0.30000000000000004"/>\n')
        self.assertEqual(decks.parameter_xml("B", 3, 0), '<Parameter name="B" type="int" value="3"/>\n')
        self.assertEqual(decks.parameter_xml("C", True, 0), '<Parameter name="C" type="bool" value="true"/>\n')
        self.assertEqual(decks.parameter_xml("D", "x", 0), '<Parameter name="D" type="string" value="x"/>\n')
        self.assertEqual(decks.parameter_xml("E", (1, 2.5), 0), '<Parameter name="E" type="Array(double)" value="{1.0, 2.5}"/>\n')
        self.assertEqual(decks.parameter_xml("F", ["a", "b"], 0), '<Parameter name="F" type="Array(string)" value="{a, b}"/>\n')

    def test_substitution_must_apply(self):
        self.assertEqual(decks.substitute("abc", "b", "x"), "axc")
        with self.assertRaisesRegex(decks.DeckError, "deck.xml: 'q' not found"):
            decks.substitute("abc", "q", "x", "deck.xml")

    def test_torn_cylinder_is_a_valid_deck(self):
        text = decks.torn_cylinder(
            radius=0.6, length=1.2, axial=4, circumferential=12,
            material={"Density": 2700.0, "Young's Modulus": 72e9, "Poisson's Ratio": 0.34},
            time_integration={"End Time": 1e-6})
        r = launch([SHELLFRAC, "--check", self.write("torn.xml", text)], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)


class Results(Scratch):
    def run_plate(self, np_):
        with open(os.path.join(PROJECT, "xml", "cantilever_plate_oscillation.xml")) as f:
            text = f.read()
        text = decks.substitute(text, '<Parameter name="End Time" type="double" value="0.3"/>',
                                '<Parameter name="End Time" type="double" value="0.0"/>')
        deck = self.write("plate.xml", text)
        r = launch([SHELLFRAC, "--quiet", deck], cwd=self.dir, np=np_)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        return os.path.join(self.dir, "plate.exo")

    def test_one_file(self):
        exo = self.run_plate(None)
        self.assertEqual(rank_files(exo), [exo])
        with ExodusFile(exo) as f:
            self.assertEqual(list(f.times()), [0.0])
            blocks = f.blocks()
            self.assertEqual([b for b, _ in blocks], [1])
            self.assertEqual(blocks[0][1].shape, (192, 6))
            x = f.coordinates()
            self.assertEqual(x.shape, (1152, 3))
            np.testing.assert_array_equal(x.min(axis=0), [0.0, 0.0, 0.0])
            np.testing.assert_array_equal(x.max(axis=0), [1.0, 1.5, 0.0])
            self.assertEqual(list(f.element_ids()), list(range(1, 193)))
            np.testing.assert_array_equal(f.displacement(0), np.zeros((1152, 3)))
            np.testing.assert_array_equal(f.element("rank", 1, 0), np.zeros(192))
            self.assertIsNone(f.element("no such field", 1, 0))
            kinetic = f.global_variable("kinetic_energy")
        history = read_table(os.path.join(self.dir, "plate_history.csv"))
        self.assertEqual(list(kinetic), list(history["kinetic_energy"]))  # the same numbers, written twice
        self.assertTrue(0 < kinetic[0] < 0.075)  # the clamped root's nodes are held: less than (1/2) m v^2

    def test_per_rank_set(self):
        exo = self.run_plate(2)
        files = rank_files(exo)
        self.assertEqual([os.path.basename(p) for p in files], ["plate.exo.2.0", "plate.exo.2.1"])
        ids = []
        for p in files:
            with ExodusFile(p) as f:
                ids += list(f.element_ids())
                self.assertTrue(all(len(c) > 0 for _, c in f.blocks()))
        self.assertEqual(sorted(ids), list(range(1, 193)))


if __name__ == "__main__":
    unittest.main(verbosity=2)
