#!/usr/bin/env python3
"""Results do not depend on the number of ranks x Kokkos OpenMP threads (built against a Trilinos with Kokkos
OpenMP: tools/build-trilinos.sh, README "for threads"; ctest label `threads`).

Each deck runs at (ranks x threads) in {1, 2} x {1, 2, 4} and is compared with the 1 x 1 run, bitwise: the
history and, where the deck fractures, the crack log and the fragment table (files byte for byte), and every
field of the Exodus results at every output (shellfrac_exocompare with zero tolerances, except the element
variable `rank`, which is the owning rank by definition). Decks: the cylindrical panel (elastic-plastic, paper
§6.1) and the beam blast at 225 m/s (plasticity, shear-off with Gamma = 0, fragments; paper §6.3), both shortened
(`END_TIMES`: the beam has sheared off by then), and a cylinder torn open by a pressure pulse (cohesive
activation, softening and separation with Gamma > 0 at high opening rates: the deck of
packages/solver/test/test_fast_fracture.cpp with Weibull edge strengths, docs/theory.md §9.8, drawn per edge from
the seed and the edge's id), so that the suite runs in minutes on 2 cores.

usage: test_threads.py PROJECT_DIR SHELLFRAC EXOCOMPARE MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import re
import shutil
import sys
import tempfile
import unittest

from shellfrac_tools import decks
from shellfrac_tools.launch import Launcher

PROJECT, SHELLFRAC, EXOCOMPARE, MPIEXEC = sys.argv[1:5]
PREFLAGS = sys.argv[5:]
launch = Launcher(MPIEXEC, PREFLAGS)

END_TIMES = {"cylindrical_panel": 2e-4, "beam_blast_225": 3e-5}

TORN_CYLINDER = decks.torn_cylinder(
    radius=0.6, length=1.2, axial=12, circumferential=38,
    material={"Density": 2700.0, "Young's Modulus": 72e9, "Poisson's Ratio": 0.34, "Cohesive Strength": 540e6,
              "Fracture Energy": 50e3, "Strength Distribution": "Weibull", "Weibull Modulus": 8.0,
              "Weibull Reference Length": 0.1},
    fracture=decks.sublist_xml("Fracture", {"Seed": 3}),
    time_integration={"End Time": 1.5e-4, "History Interval": 5, "Output Interval": 5e-5})

LAYOUTS = [(1, 2), (1, 4), (2, 1), (2, 2), (2, 4)]


def prepare(deck, folder):
    """Copies the deck (End Time shortened) and its meshes into folder; returns the deck path."""
    if deck == "torn_cylinder":
        text = TORN_CYLINDER
    else:
        text = open(os.path.join(PROJECT, "xml", deck + ".xml")).read()
        text, n = re.subn(r'(<Parameter name="End Time" type="double" value=")[^"]*"', r'\g<1>%r"' % END_TIMES[deck],
                          text)
        assert n == 1, deck
    os.makedirs(folder)
    shutil.copytree(os.path.join(PROJECT, "xml", "meshes"), os.path.join(folder, "meshes"))
    path = os.path.join(folder, deck + ".xml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run(deck_path, ranks, threads):
    r = launch([SHELLFRAC, "--quiet", os.path.basename(deck_path)], cwd=os.path.dirname(deck_path),
               np=ranks if ranks > 1 else None, timeout=600,
               env={"OMP_NUM_THREADS": str(threads), "OMP_PROC_BIND": "false"})
    assert r.returncode == 0, "%s at %d x %d failed:\n%s%s" % (deck_path, ranks, threads, r.stdout, r.stderr)


def outputs(folder, base):
    """The text outputs of a run that exist (history always; crack log and fragments when the deck fractures)."""
    return [f for f in (base + "_history.csv", base + "_cracks.csv", base + "_fragments.csv")
            if os.path.exists(os.path.join(folder, f))]


class RanksTimesThreads(unittest.TestCase):
    def check_deck(self, deck):
        with tempfile.TemporaryDirectory() as tmp:
            ref = prepare(deck, os.path.join(tmp, "1x1"))
            run(ref, 1, 1)
            ref_dir = os.path.dirname(ref)
            files = outputs(ref_dir, deck)
            self.assertIn(deck + "_history.csv", files)
            if deck == "torn_cylinder":  # it must tear, or the fracture paths go unchecked
                self.assertGreater(len(open(os.path.join(ref_dir, deck + "_cracks.csv")).readlines()), 20)
            tolerances = os.path.join(tmp, "tolerances")
            with open(tolerances, "w") as f:
                f.write("rank absolute 1e9   # the owning rank differs by definition\n")
            for ranks, threads in LAYOUTS:
                with self.subTest(deck=deck, ranks=ranks, threads=threads):
                    path = prepare(deck, os.path.join(tmp, "%dx%d" % (ranks, threads)))
                    run(path, ranks, threads)
                    here = os.path.dirname(path)
                    self.assertEqual(outputs(here, deck), files)
                    for name in files:
                        with open(os.path.join(ref_dir, name), "rb") as a, open(os.path.join(here, name), "rb") as b:
                            self.assertTrue(a.read() == b.read(), "%s differs at %d x %d" % (name, ranks, threads))
                    r = launch([EXOCOMPARE, os.path.join(ref_dir, deck + ".exo"), os.path.join(here, deck + ".exo"),
                                "--tolerances", tolerances])
                    self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_cylindrical_panel(self):
        self.check_deck("cylindrical_panel")

    def test_beam_blast_225(self):
        self.check_deck("beam_blast_225")

    def test_torn_cylinder(self):
        self.check_deck("torn_cylinder")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
