#!/usr/bin/env python3
"""The history's rows and columns (docs/output.md "The history CSV").

Rows by time (`Time Integration->History Time Interval`):
* The strip of test_reliability.py (time step 1.58e-6 s, End Time 2 ms) with a row every 0.1 ms: the rows are step 0,
  then for each multiple k * 0.1 ms the first step whose time is within half a step of it or past it (the rule of the
  Exodus frames), each exactly once, and the last step.
* A restart from the checkpoint at step 600 writes the same history, bitwise, as the run without it.
* A History Interval (steps) and a History Time Interval together are refused, naming both.

Single nodes, single elements and blocks (`Output->History Nodes`, `History Elements`, `Block Energies`):
* The strip, free, under gravity g = -10 m/s^2 along z: every node falls as a rigid body, and the central-difference
  scheme integrates a constant acceleration exactly (theory.md §7.1), so node<id>_displ_z = g t^2 / 2,
  node<id>_vel_z = g t and node<id>_acc_z = g to round-off (relative 1e-11, 1e-11, 1e-10 after 1 265 steps), the
  other components at round-off (displacement and velocity 1e-9 of the z component's scale, acceleration 10 (c/h)^2
  2^-52 L); the element's resultants stay at round-off (|N| < 1e-12 E h).
* The strip pulled along x by a line load q = 1000 N/m on x_max, on a symmetry plane at x_min, relaxed to its static
  state (Relaxation Tolerance 1e-6): uniaxial tension, N = q e_x (x) e_x, M = Q = 0, so in an element's local basis
  (e_1 along its first edge, at angle theta to x) N11 = q cos^2 theta, N22 = q sin^2 theta, N12 = -q sin theta cos
  theta, and its strain energy is q^2 / (2 E h) times its area; to 1e-5 q and 1e-5 relative (the residual 1e-6 and
  the strain q / (E h) = 1.4e-6, the difference between the Kirchhoff-type resultants and the applied load per
  reference length).
* xml/plate_on_plate.xml (two blocks) cut to 40 us: at step 0 the striker's kinetic energy is M v^2 / 2 =
  7850 * 0.004 * 0.04^2 * 200^2 / 2 = 1004.8 J (lumped masses sum to rho h A) and the target's 0; at every row the
  blocks' kinetic, strain and plastic energies sum to the totals (relative 1e-13); by 40 us the target moves and
  yields; the history on 2 ranks is bitwise that on 1.
* Unknown and non-positive ids are refused, naming the entry, the id and the mesh's range.

usage: test_history.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import math
import os
import re
import sys
import unittest

import numpy as np

from cli_common import DeckTest
from shellfrac_tools.exodus import ExodusFile
from shellfrac_tools.tables import read_table
from test_reliability import BASE, SRC, md5, run  # the same arguments: the same program

BY_TIME = ('<Parameter name="Output Interval"',
           '<Parameter name="History Time Interval" type="double" value="1e-4"/><Parameter name="Output Interval"')


class HistoryByTime(DeckTest):
    BASE = BASE
    PREFIX = "shellfrac_history_"

    def test_a_row_at_the_first_step_past_each_multiple(self):
        r = run([self.deck(BY_TIME)], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        h = read_table(self.path("base_history.csv"))
        t, dt, step = h["time"], h["dt"], h["step"]
        self.assertEqual(step[0], 0)
        interval, end = 1e-4, 2e-3
        for k in range(1, len(t) - 1):
            multiple = round(t[k] / interval)
            self.assertGreaterEqual(t[k], multiple * interval - 0.5 * dt[k], "row %d at t = %r" % (k, t[k]))
            self.assertLess(t[k] - dt[k], multiple * interval - 0.5 * dt[k], "row %d is not the first step" % k)
            self.assertEqual(multiple, k, "one row per multiple, in order")
        self.assertGreaterEqual(t[-1], end - 0.5 * dt[-1])  # the last step
        self.assertIn(len(t), (21, 22))  # step 0, 20 multiples (the last may be the last step)

    def test_a_restart_continues_the_rows_bitwise(self):
        r = run([self.deck(BY_TIME, name="continuous.xml")], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run([self.deck(BY_TIME, ('value="2e-3"', 'value="1e-3"'))], self.dir)  # stops at step 632
        self.assertEqual(r.returncode, 0, r.stderr)
        self.deck(BY_TIME)
        r = run(["base.xml", "--restart", "base_checkpoint_step600.h5"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(md5(self.path("base_history.csv")), md5(self.path("continuous_history.csv")))

    def test_steps_and_time_together_are_refused(self):
        both = ('<Parameter name="Output Interval"', '<Parameter name="History Interval" type="int" value="5"/>'
                '<Parameter name="Output Interval"')
        r = run(["--check", self.deck(BY_TIME, both)], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base.xml: 'shellfrac->Time Integration': give either a History Interval (steps) or a History "
                      "Time Interval, not both", r.stderr)


# The strip without its clamp and kick, with a History Nodes / History Elements entry (replacements of BASE).
NO_CLAMP = (re.search(r'  <ParameterList name="Boundary Conditions">.*?</ParameterList>\n  </ParameterList>\n', BASE,
                      re.S).group(0), "")
KICK = re.search(r'  <ParameterList name="Initial Conditions">.*?</ParameterList>\n  </ParameterList>\n', BASE,
                 re.S).group(0)
GRAVITY = (KICK, """  <ParameterList name="Loads">
    <ParameterList name="weight">
      <Parameter name="Type" type="string" value="Gravity"/>
      <Parameter name="Acceleration" type="Array(double)" value="{0.0, 0.0, -10.0}"/>
    </ParameterList>
  </ParameterList>
""")
PROBES = '<Parameter name="Probes" type="Array(string)" value="{x_max}"/>'


def points(nodes="", elements=""):
    """The Output entries of single nodes and elements."""
    text = ""
    if nodes:
        text += '<Parameter name="History Nodes" type="Array(int)" value="{%s}"/>' % nodes
    if elements:
        text += '<Parameter name="History Elements" type="Array(int)" value="{%s}"/>' % elements
    return (PROBES, PROBES + text)


E, H, Q = 70.0e9, 0.01, 1000.0  # the strip's Young's modulus and thickness; the line load of the tension case


class NodeElementBlockHistories(DeckTest):
    BASE = BASE
    PREFIX = "shellfrac_history_points_"

    def test_a_falling_node_follows_the_exact_free_fall(self):
        r = run([self.deck(NO_CLAMP, GRAVITY, points("3, 7", "2"))], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        h = read_table(self.path("base_history.csv"))
        t, g = np.asarray(h["time"]), -10.0
        self.assertGreater(len(t), 1000)
        for node in ("node3", "node7"):
            # In the plane only round-off: positions to 2^-52 L = 9e-16 m, which the membrane stiffness turns into
            # accelerations of (c / h)^2 2^-52 L = 4e-7 m/s^2 (c = 5 394 m/s, h = 0.25 m).
            rounding = (math.sqrt(E / (2700.0 * (1 - 0.33 ** 2))) / 0.25) ** 2 * 2.0 ** -52 * 4.0
            bound = {"displ": 1e-9 * 0.5 * abs(g) * t[-1] ** 2, "vel": 1e-9 * abs(g) * t[-1], "acc": 10 * rounding}
            for c in "xy":
                for q in ("displ", "vel", "acc"):
                    self.assertLess(np.max(np.abs(h["%s_%s_%s" % (node, q, c)])), bound[q], (node, q, c))
            later = t > 0
            np.testing.assert_allclose(np.asarray(h[node + "_displ_z"])[later], 0.5 * g * t[later] ** 2, rtol=1e-11)
            np.testing.assert_allclose(np.asarray(h[node + "_vel_z"])[later], g * t[later], rtol=1e-11)
            np.testing.assert_allclose(h[node + "_acc_z"], g, rtol=1e-10)
        for q in ("N11", "N22", "N12", "M11", "M22", "M12", "Q1", "Q2", "eq_plastic_strain"):
            self.assertLess(np.max(np.abs(h["element2_" + q])), 1e-12 * E * H, q)

    def test_an_element_in_uniaxial_tension_has_the_exact_resultants(self):
        pull = (KICK, """  <ParameterList name="Loads">
    <ParameterList name="pull">
      <Parameter name="Type" type="string" value="Line Load"/>
      <Parameter name="Side Set" type="string" value="x_max"/>
      <Parameter name="Force Per Length" type="Array(double)" value="{%r, 0.0, 0.0}"/>
    </ParameterList>
  </ParameterList>
""" % Q)
        symmetry = ('<Parameter name="Type" type="string" value="Clamped"/>',
                    '<Parameter name="Type" type="string" value="Symmetry"/>'
                    '<Parameter name="Normal" type="Array(double)" value="{1.0, 0.0, 0.0}"/>')
        relax = ('<Parameter name="End Time" type="double" value="2e-3"/>',
                 '<Parameter name="End Time" type="double" value="0.5"/>'
                 '<Parameter name="Static Relaxation" type="bool" value="true"/>'
                 '<Parameter name="History Interval" type="int" value="1000"/>')
        elements = [1, 8, 16]
        r = run([self.deck(symmetry, pull, relax, points("", ", ".join(map(str, elements))))], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("static equilibrium reached", r.stdout + r.stderr)
        h = read_table(self.path("base_history.csv"))
        with ExodusFile(self.path("base.exo")) as exo:
            x = exo.coordinates()
            connectivity = np.concatenate([c for _, c in exo.blocks()])
            ids = list(exo.element_ids())  # the generated mesh's ids are the positions + 1
        angles = []
        for e in elements:
            vertices = x[connectivity[ids.index(e)][:3]]
            edge = vertices[1] - vertices[0]
            theta = math.atan2(edge[1], edge[0])
            c, s = math.cos(theta), math.sin(theta)
            area = 0.5 * abs(np.cross(vertices[1] - vertices[0], vertices[2] - vertices[0])[2])
            expected = {"N11": Q * c * c, "N22": Q * s * s, "N12": -Q * s * c, "M11": 0, "M22": 0, "M12": 0,
                        "Q1": 0, "Q2": 0, "eq_plastic_strain": 0}
            for q, value in expected.items():
                self.assertAlmostEqual(h["element%d_%s" % (e, q)][-1], value, delta=1e-5 * Q, msg=(e, q))
            self.assertAlmostEqual(h["element%d_strain_energy" % e][-1] / (Q * Q / (2 * E * H) * area), 1, delta=1e-5)
            angles.append(theta)
        self.assertGreater(max(abs(a) for a in angles), 0.1, "an element whose first edge is not along x")

    def test_block_energies_sum_to_the_totals_on_any_rank_count(self):
        deck = open(os.path.join(SRC, "xml", "plate_on_plate.xml")).read()
        deck = deck.replace("meshes/plate_on_plate.msh", os.path.join(SRC, "xml", "meshes", "plate_on_plate.msh"))
        deck = deck.replace('<Parameter name="Base Name" type="string" value="plate"/>', "")  # the deck's name
        deck = re.sub(r'<Parameter name="End Time" type="double" value="[^"]*"/>',
                      '<Parameter name="End Time" type="double" value="4e-5"/>', deck)
        for np_, name in ((1, "one.xml"), (2, "two.xml")):
            self.deck(text=deck, name=name)
            r = run([name], self.dir, np=np_)
            self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(md5(self.path("one_history.csv")), md5(self.path("two_history.csv")))
        h = read_table(self.path("one_history.csv"))
        self.assertAlmostEqual(h["striker_kinetic_energy"][0] / (0.5 * 7850 * 0.004 * 0.04 ** 2 * 200 ** 2), 1,
                               delta=1e-13)
        self.assertEqual(h["target_kinetic_energy"][0], 0)
        for total, block in (("kinetic_energy", "_kinetic_energy"), ("strain_energy", "_strain_energy"),
                             ("plastic_dissipation", "_plastic_dissipation")):
            parts = np.asarray(h["striker" + block]) + np.asarray(h["target" + block])
            np.testing.assert_allclose(parts, h[total], rtol=1e-13, atol=1e-300)
        self.assertGreater(h["target_kinetic_energy"][-1], 100)  # the target is thrown ahead
        self.assertGreater(h["target_plastic_dissipation"][-1], 100)  # and yields

    def test_unknown_ids_are_refused(self):
        r = run(["--check", self.deck(points("3, 999"))], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base.xml: 'Output->History Nodes' names node 999, which the mesh (", r.stderr)
        self.assertIn(") does not have (its ids run from 1 to 45)", r.stderr)
        r = run(["--check", self.deck(points("", "17"))], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("'Output->History Elements' names element 17, which the mesh (", r.stderr)
        self.assertIn("(its ids run from 1 to 16)", r.stderr)
        r = run(["--check", self.deck(points("0"))], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base.xml: 'Output->History Nodes' names 0; ids are the mesh file's, which are positive",
                      r.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
