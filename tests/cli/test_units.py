#!/usr/bin/env python3
"""The declared system of units (`Units`, docs/input_reference.xml; solver/input/units.hpp).

* The code is unit-agnostic: the strip of test_reliability.py in SI and the same strip in mm-t-s (lengths x 1e3,
  density x 1e-12, modulus x 1e-6, velocity x 1e3; times unchanged) give the same time steps and a tip
  displacement 1e3 times the SI one, kinetic energy 1e3 times (J -> mJ), to 1e-12 relative (round-off of the
  scaled constants; exact dimensional similarity otherwise).
* Both declare their system in the Exodus information records and <base>_summary.json, which the tools read for
  their labels (shellfrac_tools.units); neither gets a warning.
* A constant outside what real shells have in the declared system is a warning naming the parameter and the system
  (the SI deck declared mm-t-s; a modulus typed 70e3 instead of 70e9 in SI); `none` switches the check off; an
  unknown name is an input error listing the systems.

usage: test_units.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import json
import sys
import unittest

import numpy as np

from cli_common import DeckTest
from shellfrac_tools.exodus import ExodusFile
from shellfrac_tools.tables import read_table
from shellfrac_tools.units import declared_units
from test_reliability import BASE, run  # the same arguments: the same program

NO_CHECKPOINTS = ('<Parameter name="Step Interval" type="int" value="100"/>', '')
MM_T_S = [('value="4.0"', 'value="4000.0"'), ('name="Width" type="double" value="0.5"', 'name="Width" type="double" value="500.0"'),
          ('value="0.01"', 'value="10.0"'), ('value="2700.0"', 'value="2.7e-9"'), ('value="70.0e9"', 'value="70.0e3"'),
          ('value="{0.0, 0.0, 1.0}"', 'value="{0.0, 0.0, 1000.0}"')]


def declare(units):
    return ('<ParameterList name="shellfrac">',
            '<ParameterList name="shellfrac">\n  <Parameter name="Units" type="string" value="%s"/>' % units)


class Units(DeckTest):
    BASE = BASE
    PREFIX = "shellfrac_units_"

    def run_deck(self, *changes, name="base.xml"):
        r = run([self.deck(NO_CHECKPOINTS, *changes, name=name)], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        return r

    def info_units(self, exo):
        with ExodusFile(self.path(exo)) as f:
            info = [b"".join(c for c in row if c).decode("utf-8", "replace").strip()
                    for row in f.ds.variables["info_records"][:].data]
        return [line for line in info if line.startswith("units: ")]

    def test_the_same_strip_in_si_and_in_mm_t_s(self):
        si = self.run_deck(name="si.xml")
        mm = self.run_deck(declare("mm-t-s"), *MM_T_S, name="mm.xml")
        self.assertNotIn("warning", si.stderr + mm.stderr)
        a, b = read_table(self.path("si_history.csv")), read_table(self.path("mm_history.csv"))
        np.testing.assert_allclose(b["time"], a["time"], rtol=1e-12, atol=0)
        tip = "x_max_displ_z"
        self.assertGreater(np.max(np.abs(a[tip])), 1e-5)
        np.testing.assert_allclose(b[tip], 1e3 * a[tip], rtol=1e-12, atol=1e-12 * 1e3 * np.max(np.abs(a[tip])))
        np.testing.assert_allclose(b["kinetic_energy"], 1e3 * a["kinetic_energy"], rtol=1e-12,
                                   atol=1e-12 * 1e3 * np.max(a["kinetic_energy"]))
        self.assertEqual(self.info_units("si.exo"), ["units: SI (length m, mass kg, time s, force N, stress Pa, "
                                                     "energy J)"])
        self.assertEqual(self.info_units("mm.exo"), ["units: mm-t-s (length mm, mass t, time s, force N, stress "
                                                     "MPa, energy mJ)"])
        with open(self.path("mm_summary.json")) as f:
            self.assertEqual(json.load(f)["units"], "mm-t-s")
        self.assertEqual(declared_units(self.path("mm.exo")).name, "mm-t-s")  # what the tools label with
        self.assertEqual(declared_units(self.path("si.exo")).length, "m")
        with open(self.path("si_summary.json")) as f:
            self.assertEqual(json.load(f)["units"], "SI")

    def test_implausible_constants_are_named(self):
        r = self.run_deck(declare("mm-t-s"))
        for parameter, value in [("Materials->aluminium->Density", "2700 t/mm^3 is above"),
                                 ("Materials->aluminium->Young's Modulus", "7e+10 MPa is above")]:
            self.assertIn("warning: base.xml: '%s' = %s what" % (parameter, value), r.stderr)
        self.assertIn("in the declared 'Units' = mm-t-s: is the deck in another system? Name it with 'Units' (SI, "
                      "mm-t-s, mm-kg-ms, mm-g-ms, in-lbf-s, none)", r.stderr)
        typo = self.run_deck(('value="70.0e9"', 'value="70.0e3"'))  # SI by default
        self.assertIn("warning: base.xml: 'Materials->aluminium->Young's Modulus' = 70000 Pa is below what solids have "
                      "(100000 to 1.5e+12 Pa)", typo.stderr)
        unchecked = self.run_deck(declare("none"), ('value="70.0e9"', 'value="70.0e3"'))
        self.assertNotIn("'Materials->aluminium->Young's Modulus' =", unchecked.stderr)
        self.assertEqual(self.info_units("base.exo"), ["units: none (not declared)"])

    def test_an_unknown_system_is_an_input_error(self):
        r = run([self.deck(declare("cgs"))], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("invalid value 'cgs' for parameter 'shellfrac->Units'", r.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
