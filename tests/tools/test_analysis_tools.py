#!/usr/bin/env python3
"""The pure parts of the post-processing tools, against exact values.

* tools/scaling.py: the weak study keeps 16 000 elements per core for every power of 2 (the paper's §6.4 strip,
  200 x 40 cells of two triangles, refined x4 per cores x4 and doubled along the length in between); the strong
  sizes map to the refinements of the same strip; the size study's strips keep its aspect (10 w^2 elements).
* tools/fracture_summary.py: the length of the edge two P2 (or P1) elements share, measured along the edge's
  quadratic curve. For a straight edge whose mid-side node sits anywhere strictly inside it the curve runs
  monotonically along the chord, so the length is the chord exactly (the speed |x'(s)| is linear in s, which
  the 3-point Gauss rule integrates exactly); a circular arc of angle 2a through three nodes is a parabola whose
  length has a closed form. Each Exodus TRI6 edge (01, 12, 20) must use its own mid-side node (3, 4, 5).
* tools/fragmentation_study.py --combine: the rows of two studies (two meshes) come out in one table, in the order
  given, values unchanged; a table that is not a study's is refused with a line naming it.

usage: test_analysis_tools.py PROJECT_DIR
"""
import math
import os
import sys
import unittest

import numpy as np

PROJECT = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
import fracture_summary  # noqa: E402
from shellfrac_tools.units import SYSTEMS  # noqa: E402  (tools/ on PYTHONPATH: ctest sets it)
import fragmentation_study  # noqa: E402
import plot_results  # noqa: E402
import scaling  # noqa: E402
from shellfrac_tools import results_files  # noqa: E402


class ResultNamesAndTables(unittest.TestCase):
    """Result names are literal, per-rank sets complete, CSV rows whole. Found on an earlier version:
    plot_results.py 'case[a].exo' globbed (and read case a.exo's set), plot_results.py and render.py drew a set with
    a rank file missing, fracture_summary.py crashed with a traceback on a partial last line."""

    def setUp(self):
        import tempfile
        self.dir = tempfile.mkdtemp(prefix="shellfrac_tools_")

    def tearDown(self):
        import shutil
        shutil.rmtree(self.dir, ignore_errors=True)

    def touch(self, *names):
        for n in names:
            open(os.path.join(self.dir, n), "w").close()

    def test_names_are_literal_and_sets_complete(self):
        base = os.path.join(self.dir, "case[a].exo")
        self.touch("casea.exo.2.0", "casea.exo.2.1")  # what the glob 'case[a].exo.*.*' matched
        with self.assertRaisesRegex(results_files.ResultsError, r"no such results file"):
            results_files.rank_files(base)
        self.touch("case[a].exo.12.00", "case[a].exo.12.01")
        with self.assertRaisesRegex(results_files.ResultsError, r"incomplete: .*case\[a\]\.exo\.12\.02 is missing"):
            results_files.rank_files(base)
        for r in range(2, 12):
            self.touch("case[a].exo.12.%02d" % r)
        self.assertEqual(results_files.rank_files(base), [base + ".12.%02d" % r for r in range(12)])
        self.touch("case[a].exo.3.0")
        with self.assertRaisesRegex(results_files.ResultsError, r"several per-rank sets are present \(np = 3, 12\)"):
            results_files.rank_files(base)
        self.touch("case[a].exo")
        self.assertEqual(results_files.rank_files(base), [base])

    def test_a_partial_last_line_is_left_out_and_a_damaged_row_named(self):
        path = os.path.join(self.dir, "run_history.csv")
        with open(path, "w") as f:
            f.write("time,step\n0,0\n1e-6,1\n2e-6,")
        table = fracture_summary.read_csv(path)
        self.assertEqual(list(table["step"]), [0.0, 1.0])
        with open(path, "w") as f:
            f.write("time,step\n0,0\ngarbage,1\n2e-6,2\n")
        with self.assertRaises(SystemExit):
            fracture_summary.read_csv(path)


class WeakAndStrongSizes(unittest.TestCase):
    def test_sixteen_thousand_elements_per_core(self):
        for cores in (1, 2, 4, 8, 16, 32, 64, 128, 256):
            nx, ny = scaling.cells_for_weak(cores)
            self.assertEqual(2 * nx * ny, 16000 * cores, cores)
            self.assertIn(nx * 40 / (ny * 200), (1.0, 2.0), cores)  # square cells, or doubled along x

    def test_uniform_refinement_at_powers_of_four(self):
        self.assertEqual(scaling.cells_for_weak(4), (400, 80))
        self.assertEqual(scaling.cells_for_weak(16), (800, 160))
        self.assertEqual(scaling.cells_for_weak(2), (400, 40))

    def test_strong_sizes(self):
        self.assertEqual(scaling.cells_for_size(16000), (200, 40))
        self.assertEqual(scaling.cells_for_size(64000), (400, 80))
        self.assertEqual(scaling.cells_for_size(256000), (800, 160))

    def test_size_study_strips_keep_the_aspect(self):
        # 10 w^2 elements: 5 w x w cells of two triangles (the 200 x 40 strip's aspect, 686 440 ~ the A319 size)
        self.assertEqual(scaling.cells_for_strip(16000), (200, 40))
        self.assertEqual(scaling.cells_for_strip(686440), (1310, 262))
        self.assertIsNone(scaling.cells_for_strip(687000))


def tri6(v0, v1, v2, m01=None, m12=None, m20=None):
    """A TRI6 node array (Exodus order: vertices, then the mid-side nodes of edges 01, 12, 20)."""
    v = [np.array(x, dtype=float) for x in (v0, v1, v2)]
    mids = [m if m is not None else 0.5 * (a + b) for m, a, b in ((m01, v[0], v[1]), (m12, v[1], v[2]),
                                                                    (m20, v[2], v[0]))]
    return np.array(v + [np.array(m, dtype=float) for m in mids])


class SharedEdgeLength(unittest.TestCase):
    def test_straight_edge_with_an_off_centre_mid_node_is_its_chord(self):
        a, b = np.array([0.0, 0.0, 0.0]), np.array([3.0, 4.0, 0.0])  # length 5
        mid = a + 0.3 * (b - a)
        minus = tri6(a, b, [0.0, 5.0, 1.0], m01=mid, m12=[9, 9, 9], m20=[-9, 9, 9])
        plus = tri6(b, a, [4.0, -1.0, 0.0], m01=mid)
        self.assertAlmostEqual(fracture_summary.edge_length(minus, plus), 5.0, places=12)

    def test_each_edge_uses_its_own_mid_side_node(self):
        a, b, c = [0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]
        far = [50.0, 50.0, 50.0]  # a wrong mid-side node would give a length far from 2
        for edge, (p, q) in enumerate(((a, b), (b, c), (c, a))):
            mids = [far, far, far]
            mids[edge] = list(0.5 * (np.array(p) + np.array(q)))
            minus = tri6(a, b, c, *mids)
            plus = tri6(q, p, [5.0, 5.0, -3.0])
            self.assertAlmostEqual(fracture_summary.edge_length(minus, plus), float(np.linalg.norm(np.subtract(q, p))),
                                   places=12, msg="edge %d" % edge)

    def test_circular_arc_through_three_nodes(self):
        # nodes on a circle of radius R at angles -a, 0, a: the P2 curve through them is the parabola
        # y(x) = R cos a - ... ; its exact length L = 2 int_0^w sqrt(1 + (2 k x)^2) dx with half-width w = R sin a
        # and k = (R - R cos a) / w^2 (the sagitta over w^2); the 3-point Gauss rule integrates it to 1e-4 here.
        R, half = 2.0, 0.05
        p = [R * math.sin(-half), R * math.cos(half) - R, 0.0]
        q = [R * math.sin(half), R * math.cos(half) - R, 0.0]
        mid = [0.0, 0.0, 0.0]
        w = R * math.sin(half)
        k = (R - R * math.cos(half)) / w ** 2
        exact = 2 * (w * math.sqrt(1 + (2 * k * w) ** 2) / 2 + math.asinh(2 * k * w) / (4 * k))
        minus = tri6(p, q, [0.0, -1.0, 0.0], m01=mid)
        plus = tri6(q, p, [0.0, 1.0, 0.0], m01=mid)
        length = fracture_summary.edge_length(minus, plus)
        self.assertAlmostEqual(length, exact, delta=1e-4 * exact)
        self.assertGreater(length, float(np.linalg.norm(np.subtract(q, p))))  # longer than the chord

    def test_p1_elements_use_the_chord(self):
        minus = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        plus = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.5, -1.0, 0.0]])
        self.assertAlmostEqual(fracture_summary.edge_length(minus, plus), 1.0, places=14)

    def test_elements_without_a_shared_edge(self):
        minus = tri6([0, 0, 0], [1, 0, 0], [0, 1, 0])
        plus = tri6([5, 0, 0], [6, 0, 0], [5, 1, 0])
        self.assertIsNone(fracture_summary.edge_length(minus, plus))



class FragmentationStudyTables(unittest.TestCase):
    def setUp(self):
        import tempfile
        self.dir = tempfile.mkdtemp(prefix="shellfrac_study_")

    def tearDown(self):
        import shutil
        shutil.rmtree(self.dir, ignore_errors=True)

    def row(self, rate, cells, s):
        return {"rate": rate, "seed": 1.0, "cells": cells, "distribution": "Weibull", "fragments": 40.0,
                "run_long_enough": 1.0, "s_over_s0": s, "balance_error_over_dissipation": 3.7e-06}

    def test_two_studies_combine_into_one_table(self):
        import subprocess
        coarse, fine = os.path.join(self.dir, "coarse.csv"), os.path.join(self.dir, "fine.csv")
        fragmentation_study.write_rows([self.row(10.0, 640.0, 0.2492), self.row(100.0, 640.0, 0.04594)], coarse)
        fragmentation_study.write_rows([self.row(10.0, 1280.0, 0.225)], fine)
        out = os.path.join(self.dir, "both")
        r = subprocess.run([sys.executable, fragmentation_study.__file__, "--combine", coarse, fine, "-o", out],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = fragmentation_study.read_rows(out + ".csv")
        self.assertEqual([(x["cells"], x["rate"], x["s_over_s0"]) for x in rows],
                         [(640.0, 10.0, 0.2492), (640.0, 100.0, 0.04594), (1280.0, 10.0, 0.225)])
        self.assertTrue(os.path.getsize(out + ".png") > 0)

    def test_a_table_that_is_not_a_study_is_refused(self):
        import subprocess
        other = os.path.join(self.dir, "history.csv")
        with open(other, "w") as f:
            f.write("time,kinetic_energy\n0,1\n")
        r = subprocess.run([sys.executable, fragmentation_study.__file__, "--combine", other, "-o",
                            os.path.join(self.dir, "x")], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(other, r.stderr)
        self.assertIn("not a table written by this tool", r.stderr)


class PictureColoursAndLabels(unittest.TestCase):
    """plot_results.py: an id field (a fragment, a rank) gets one distinct colour per id and a legend, never a
    continuous map under which the span and a stub come out the same colour; times and axes carry units."""

    def test_ids_get_distinct_colours_and_a_legend_with_mass_and_speed(self):
        values = np.array([3.0] * 380 + [1.0] * 10 + [79.0] * 10)  # the beam shear-off: span and two stubs
        self.assertTrue(plot_results.is_id_field("fragment_id", values))
        colours = plot_results.id_colours(values)
        self.assertEqual(len(set(colours.values())), 3)
        motion = {3: (0.0835, 221.0), 1: (0.0022, 3.91), 79: (0.0022, 3.91)}
        labels = [h.get_label() for h in plot_results.id_legend("fragment_id", values, colours, motion, SYSTEMS["SI"])]
        self.assertEqual(labels[0], "piece 3: 380 elements, 0.0835 kg at 221 m/s")  # the largest first
        self.assertEqual(len(labels), 3)
        many = np.arange(30.0)
        labels = [h.get_label() for h in plot_results.id_legend("rank", many, plot_results.id_colours(many), {},
                                                          SYSTEMS["SI"])]
        self.assertEqual(len(labels), plot_results.LEGEND_ENTRIES + 1)
        self.assertEqual(labels[-1], "... 18 more (18 elements)")

    def test_pieces_of_a_frame_largest_first_with_their_speed(self):
        import tempfile
        from shellfrac_tools import tables
        work = tempfile.mkdtemp(prefix="shellfrac_pieces_")
        with open(os.path.join(work, "run_fragments.csv"), "w") as f:
            f.write("time,fragment_id,elements,mass,com_x,com_y,com_z,momentum_x,momentum_y,momentum_z\n"
                    "1e-05,1,10,0.5,0,0,0,1,0,0\n"
                    "2e-05,1,10,0.5,0,0,0,3,4,0\n2e-05,3,380,2.0,0,0,0,0,0,-442\n2e-05,79,10,0.5,0,0,0,0,0,1\n")
        for name in ("run.exo", "run.exo.2.1", "run"):
            self.assertEqual(tables.fragments_path(os.path.join(work, name)), os.path.join(work, "run_fragments.csv"))
        pieces = tables.pieces_at(os.path.join(work, "run.exo"), 2e-05)
        self.assertEqual([p[:3] for p in pieces], [(3, 380, 2.0), (1, 10, 0.5), (79, 10, 0.5)])  # ties: lower id
        self.assertEqual([p[3] for p in pieces], [221.0, 10.0, 2.0])  # |momentum| / mass
        self.assertEqual(tables.pieces_at(os.path.join(work, "run.exo"), 3e-05), [])
        self.assertEqual(tables.pieces_at(os.path.join(work, "other.exo"), 2e-05), [])

    def test_quantities_get_a_colour_map(self):
        self.assertFalse(plot_results.is_id_field("eq_plastic_strain", np.array([0.0, 0.1, 0.38])))
        self.assertFalse(plot_results.is_id_field("damage", np.linspace(0.0, 1.0, 50)))

    def test_times_in_readable_units(self):
        si, mm_t_s, mm_kg_ms, none = (SYSTEMS[n] for n in ("SI", "mm-t-s", "mm-kg-ms", "none"))
        self.assertEqual(plot_results.time_text(9.995e-5, si), "t = 99.95 us")
        self.assertEqual(plot_results.time_text(0.0025, si), "t = 2.5 ms")
        self.assertEqual(plot_results.time_text(0.3, none), "t = 0.3")
        self.assertEqual(plot_results.time_text(0.0025, mm_t_s), "t = 0.0025 s")
        self.assertEqual(plot_results.time_text(0.5, mm_kg_ms), "t = 500 us")  # 0.5 ms
        t, label = plot_results.time_axis(np.array([0.0, 1e-4]), si)
        self.assertEqual(label, "time [us]")
        self.assertAlmostEqual(t[-1], 100.0)
        self.assertEqual(plot_results.unit(mm_t_s.length), " [mm]")
        self.assertEqual(plot_results.unit(none.length), "")
        self.assertEqual(mm_kg_ms.speed, "mm/ms")

if __name__ == "__main__":
    unittest.main(verbosity=1)
