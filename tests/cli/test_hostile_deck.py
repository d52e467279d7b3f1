#!/usr/bin/env python3
"""Hostile decks and options (docs/hostile_input.md, "Input deck"): each bad input ends with its exit code and
one message naming the deck and the parameter, printed once (also on 2 ranks), with nothing written.

usage: test_hostile_deck.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import shutil
import sys
import tempfile
import unittest

from cli_common import Launcher

SRC, SHELLFRAC, MPIEXEC = sys.argv[1:4]
MPI_PREFLAGS = sys.argv[4:]
launch = Launcher(MPIEXEC, MPI_PREFLAGS)

# A 4 x 2 strip (16 TRI6), clamped at x_min, kicked along z.
BASE = """<ParameterList name="shellfrac">
  <ParameterList name="Mesh">
    <Parameter name="Source" type="string" value="Rectangle"/>
    <ParameterList name="Rectangle">
      <Parameter name="Length" type="double" value="4.0"/>
      <Parameter name="Width" type="double" value="1.0"/>
      <Parameter name="Elements Along Length" type="int" value="4"/>
      <Parameter name="Elements Along Width" type="int" value="2"/>
      <Parameter name="Block Name" type="string" value="strip"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Blocks">
    <ParameterList name="strip">
      <Parameter name="Thickness" type="double" value="0.01"/>
      <Parameter name="Material" type="string" value="aluminium"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="aluminium">
      <Parameter name="Density" type="double" value="2700.0"/>
      <Parameter name="Young's Modulus" type="double" value="70.0e9"/>
      <Parameter name="Poisson's Ratio" type="double" value="0.33"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Time Integration">
    <Parameter name="End Time" type="double" value="2e-5"/>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamped root">
      <Parameter name="Type" type="string" value="Clamped"/>
      <Parameter name="Node Set" type="string" value="x_min"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <ParameterList name="kick">
      <Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 1.0}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="Probes" type="Array(string)" value="{x_max}"/>
  </ParameterList>
</ParameterList>
"""

# Two triangles of a unit square that do not share their diagonal: nodes 5 and 6 repeat nodes 3 and 1.
SPLIT_SQUARE_MSH = """$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "plate"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 1 1 0
6 0 0 0
$EndNodes
$Elements
2
1 2 2 1 1 1 2 3
2 2 2 1 1 6 5 4
$EndElements
"""


def run(args, cwd=None, np=None):
    return launch(args, cwd, np)


class HostileDeck(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shellfrac_hostile_")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def deck(self, name, *replacements, text=None):
        text = BASE if text is None else text
        for old, new in replacements:
            self.assertIn(old, text)
            text = text.replace(old, new, 1)
        path = os.path.join(self.dir, name)
        with open(path, "wb") as f:
            f.write(text.encode("latin-1"))
        return name  # the runs start in self.dir: messages name the deck as given

    def expect_error(self, args, message, code=1, nps=(None, 2)):
        """The run ends with `code`, prints `message` once (rank 0) and leaves only the files it found."""
        before = sorted(os.listdir(self.dir))
        for np in nps:
            r = run([SHELLFRAC] + args, cwd=self.dir, np=np)
            self.assertEqual(r.returncode, code, r.stdout + r.stderr)
            self.assertEqual(r.stderr.count("shellfrac: error: " + message), 1, r.stderr)
            self.assertEqual(sorted(os.listdir(self.dir)), before)

    def test_deep_nesting_is_refused_before_the_parser_sees_it(self):
        # 10 000 nested sublists crashed the XML parameter list conversion (SIGSEGV) on 1 and 2 ranks.
        deck = self.deck("deep.xml", ('<ParameterList name="Output">',
                                      '<ParameterList name="Output">\n' + '<ParameterList name="a">' * 10000 +
                                      '</ParameterList>' * 10000))
        self.expect_error([deck], "deep.xml: line 40: the XML elements are nested more than 64 levels deep (a deck "
                                  "needs only a few levels of sublists)")

    def test_malformed_kokkos_options_are_usage_errors(self):
        # '--kokkos-threads=abc' aborted in the Kokkos start-up with an uncaught exception (exit 134).
        deck = self.deck("ok.xml")
        cases = [("--kokkos-threads=abc", "option '--kokkos-threads=abc' needs a whole number >= 0 "
                                          "(--kokkos-threads=N)"),
                 ("--kokkos-threads", "option '--kokkos-threads' needs a whole number >= 0 (--kokkos-threads=N)"),
                 ("--kokkos-numa=99999999999", "option '--kokkos-numa=99999999999' needs a whole number >= 0"),
                 ("--kokkos-device-id=-1", "option '--kokkos-device-id=-1' needs a whole number >= 0"),
                 ("--kokkos-num-devices=1,x", "option '--kokkos-num-devices=1,x' needs one or two whole numbers"),
                 ("--kokkos-disable-warnings=yes", "option '--kokkos-disable-warnings=yes' takes no value"),
                 ("--threads=abc", "unknown option '--threads=abc'"),
                 ("--kokkos-frobnicate", "unknown option '--kokkos-frobnicate'")]
        for option, message in cases:
            self.expect_error([option, "--check", deck], message, code=2)
        r = run([SHELLFRAC, "--kokkos-threads=1", "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_a_parameter_or_sublist_given_twice_is_refused_with_both_lines(self):
        thickness = '<Parameter name="Thickness" type="double" value="0.01"/>'
        deck = self.deck("twice.xml", (thickness, thickness + "\n      " + thickness.replace("0.01", "0.02")))
        self.expect_error([deck], "twice.xml: 'shellfrac->Blocks->strip->Thickness' is given twice, on lines 14 and "
                                  "15 (only the last would count); give each parameter or sublist once")
        deck = self.deck("twice_list.xml", ('<ParameterList name="Output">',
                                            '<ParameterList name="Materials"/>\n  <ParameterList name="Output">'))
        self.expect_error([deck], "twice_list.xml: 'shellfrac->Materials' is given twice, on lines 18 and 39")

    def test_devices_directories_and_huge_decks_are_refused_before_reading(self):
        # /dev/zero was read to 2.1 GB before the program died.
        self.expect_error(["/dev/zero"], "/dev/zero: the input deck is a device, not a regular file; name the file "
                                         "itself")
        self.expect_error([self.dir], self.dir + ": is a directory, not an input deck")
        with open(os.path.join(self.dir, "huge.xml"), "wb") as f:
            f.truncate(17 * 2**20)
        self.expect_error(["huge.xml"], "huge.xml: the input deck has 17825792 bytes, more than the 16 MiB a deck may have",
                          nps=(None,))

    def test_the_deck_is_stored_once_per_result_set(self):
        deck = self.deck("set.xml")
        r = run([SHELLFRAC, "--quiet", deck], cwd=self.dir, np=2)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(self.dir, "set.exo.2.0"), "rb") as f0, open(os.path.join(self.dir, "set.exo.2.1"),
                                                                           "rb") as f1:
            self.assertIn(b"<ParameterList", f0.read())  # the information records: the expanded deck
            self.assertNotIn(b"<ParameterList", f1.read())

    def test_names_must_be_printable_utf8(self):
        cases = [(("clamped root", "clamped r\xf6ot"), "the name 'shellfrac->Boundary Conditions->clamped r\\xf6ot' "
                                                       "has a byte that is not UTF-8 (0xf6) at position 10"),
                 (('value="strip"/>', 'value="str\x01ip"/>'), "the value 'str\\x01ip' of 'shellfrac->Mesh->Rectangle->"
                                                              "Block Name' has a control character (byte 0x01) at "
                                                              "position 4"),
                 (("{x_max}", "{x_max, \x1b[31m}"), "the element '\\x1b[31m' of 'shellfrac->Output->Probes' has a "
                                                    "control character (byte 0x1b) at position 1"),
                 (('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" value="r\xc2\x85n"/>'
                                               '<Parameter name="Probes"'),
                  "the value 'r\\xc2\\x85n' of 'shellfrac->Output->Base Name' has a control character (U+0085) at "
                  "position 2")]
        for (old, new), message in cases:
            deck = self.deck("names.xml", (old, new))
            self.expect_error([deck], "names.xml: " + message + "; names and text must be printable UTF-8")
        deck = self.deck("utf8.xml", ('"aluminium"', '"alumin\xc3\xadum"'), ('"aluminium"', '"alumin\xc3\xadum"'))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)  # UTF-8 names pass

    def test_non_finite_and_absurd_velocities_and_pressures(self):
        # Each passed --check and blew up at step 1 with a message that blamed the time step.
        kick = '<Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 1.0}"/>'
        pressure = ('<ParameterList name="Loads"><ParameterList name="blast">'
                    '<Parameter name="Pressure" type="double" value="%s"/></ParameterList></ParameterList>\n'
                    '  <ParameterList name="Output">')
        cases = [((kick, kick.replace("1.0}", "1e300}")),
                  "'shellfrac->Initial Conditions->kick->Velocity' has the magnitude 1e+300, more than the elastic "
                  "wave speed sqrt(E/rho) = 5091.75 of material 'aluminium', the fastest of the deck; a velocity "
                  "above it strains the shell by more than 100 % at once"),
                 ((kick, kick + '<Parameter name="Normal Velocity" type="double" value="-6000"/>'),
                  "'shellfrac->Initial Conditions->kick->Normal Velocity' has the magnitude 6000, more than the "
                  "elastic wave speed"),
                 ((kick, kick + '<Parameter name="Normal Velocity" type="double" value="nan"/>'),
                  "invalid value 'nan' for parameter 'shellfrac->Initial Conditions->kick->Normal Velocity' (Speed "
                  "along the reference normal"),
                 (('<ParameterList name="Output">', pressure % "1e300"),
                  "'shellfrac->Loads->blast->Pressure' reaches 1e+300, more than Young's Modulus 7e+10 of material "
                  "'aluminium', the stiffest of the deck; a pressure above it compresses the shell by more than 100 %"),
                 (('<ParameterList name="Output">', pressure % "-inf"),
                  "invalid value '-inf' for parameter 'shellfrac->Loads->blast->Pressure' (p0 [force/length^2]): "
                  "value -inf is out of range: must be finite")]
        for (old, new), message in cases:
            deck = self.deck("fast.xml", (old, new))
            self.expect_error(["--check", deck], "fast.xml: " + message, nps=(None,))

    def test_tiny_yield_stress_is_an_input_error(self):
        # Yield Stress 1e-300 ended in "internal error ... return map did not converge" with a source path.
        deck = self.deck("yield.xml", ('value="0.33"/>', 'value="0.33"/><Parameter name="Model" type="string" '
                                       'value="Resultant Plasticity"/><Parameter name="Yield Stress" type="double" '
                                       'value="1e-300"/>'))
        self.expect_error([deck], "yield.xml: 'shellfrac->Materials->aluminium->Yield Stress' = 1e-300 is below 1e-06 "
                                  "x Young's Modulus = 70000; no material yields at so small a strain (metals: 1e-4 "
                                  "to 1e-2), and the return map cannot resolve it (docs/theory.md §4.3)")

    def test_a_time_step_beyond_end_time_is_a_warning(self):
        # E = 1e-300 gave a time step far above End Time and 0 steps without a word.
        deck = self.deck("soft.xml", ('value="70.0e9"', 'value="1e-300"'), ("{0.0, 0.0, 1.0}", "{0.0, 0.0, 0.0}"))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir, np=2)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr.count("shellfrac: warning: "), 2, r.stderr)
        self.assertIn("shellfrac: warning: soft.xml: 'Materials->aluminium->Young's Modulus' = 1e-300 Pa is below "
                      "what solids have (100000 to 1.5e+12 Pa) in the declared 'Units' = SI", r.stderr)
        self.assertRegex(r.stderr, r"shellfrac: warning: soft.xml: the time step [0-9.e+]+ is more than twice "
                                   r"'Time Integration->End Time' = 2e-05, so no step is taken and only the initial "
                                   r"state is written \(are Young's Modulus and Density right\?\)")

    def test_a_prescribed_velocity_that_a_clamp_overrides_is_refused(self):
        pull = ('</ParameterList>\n  </ParameterList>\n  <ParameterList name="Initial Conditions">',
                '</ParameterList>\n    <ParameterList name="pull">'
                '<Parameter name="Type" type="string" value="Prescribed Velocity"/>'
                '<Parameter name="Node Set" type="string" value="x_min"/>'
                '<Parameter name="Velocity" type="Array(double)" value="{1.0, 0.0, 0.0}"/></ParameterList>\n'
                '  </ParameterList>\n  <ParameterList name="Initial Conditions">')
        deck = self.deck("pull.xml", pull)
        self.expect_error([deck], "pull.xml: boundary condition 'pull' (Prescribed Velocity) has no effect: every node "
                                  "of its Node Set 'x_min' is taken by boundary condition 'clamped root', which takes "
                                  "precedence (docs/theory.md §10.1); remove one of them or give them different node "
                                  "sets")
        deck = self.deck("pull_end.xml", pull, ('value="x_min"/><Parameter name="Velocity"',
                                                'value="x_max"/><Parameter name="Velocity"'))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_a_set_that_selects_nothing_is_refused_where_something_must_be_acted_on(self):
        # A region outside the mesh, as the only set of a support, a load, an initial velocity or a probe, ran with
        # exit 0 (the probe columns written as exact zeros).
        region = ('<ParameterList name="Output">',
                  '<ParameterList name="Regions"><ParameterList name="off mesh">'
                  '<Parameter name="Shape" type="string" value="Box"/>'
                  '<Parameter name="Min" type="Array(double)" value="{10.0, 10.0, -1.0}"/>'
                  '<Parameter name="Max" type="Array(double)" value="{11.0, 11.0, 1.0}"/>'
                  '</ParameterList></ParameterList>\n  <ParameterList name="Output">')
        nothing = ("' acts on 'off mesh', which selects nothing in the mesh (rectangle(4, 1, 4, 2)): a region outside the "
                   "mesh, an empty set, or a node set that none of its elements touch? It would act on nothing")
        cases = [
            ("support.xml", ('value="x_min"', 'value="off mesh"'), "boundary condition 'clamped root"),
            ("probe.xml", ("{x_max}", "{off mesh}"), "'Output->Probes"),
            ("kick.xml", ('<Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 1.0}"/>',
                          '<Parameter name="Elements" type="string" value="off mesh"/>'
                          '<Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 1.0}"/>'),
             "initial condition 'kick"),
            ("load.xml", ('<ParameterList name="Output">',
                          '<ParameterList name="Loads"><ParameterList name="push">'
                          '<Parameter name="Type" type="string" value="Nodal Force"/>'
                          '<Parameter name="Node Set" type="string" value="off mesh"/>'
                          '<Parameter name="Force" type="Array(double)" value="{0.0, 0.0, 1.0}"/>'
                          '</ParameterList></ParameterList>\n  <ParameterList name="Output">'), "load 'push"),
        ]
        for name, change, what in cases:
            deck = self.deck(name, change, region)
            self.expect_error([deck], name + ": " + what + nothing, nps=(None,))
            self.expect_error(["--check", deck], name + ": " + what + nothing, nps=(2,))

    def test_parameters_of_another_type_are_refused(self):
        # A Velocity on a Clamped support, a Force on a Pressure load were ignored without a word.
        deck = self.deck("clamped.xml", ('<Parameter name="Node Set" type="string" value="x_min"/>',
                                         '<Parameter name="Node Set" type="string" value="x_min"/>'
                                         '<Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 2.0}"/>'))
        self.expect_error([deck], "clamped.xml: 'shellfrac->Boundary Conditions->clamped root->Velocity' = {0, 0, 2} "
                                  "does not apply to a 'Clamped' boundary condition and would be ignored; the "
                                  "parameters of a 'Clamped' boundary condition are 'Type', 'Node Set', 'Elements'. "
                                  "Remove it, or choose the kind it belongs to")
        load = ('<ParameterList name="Output">',
                '<ParameterList name="Loads"><ParameterList name="blast">'
                '<Parameter name="Pressure" type="double" value="1000.0"/>%s'
                '</ParameterList></ParameterList>\n  <ParameterList name="Output">')
        deck = self.deck("force.xml", (load[0], load[1] % '<Parameter name="Force" type="Array(double)" '
                                                         'value="{0.0, 0.0, 5.0}"/>'))
        self.expect_error([deck], "force.xml: 'shellfrac->Loads->blast->Force' = {0, 0, 5} does not apply to a "
                                  "'Pressure' load with Function 'Constant' and would be ignored; the parameters of a "
                                  "'Pressure' load with Function 'Constant' are 'Type', 'Elements', 'Function', "
                                  "'Pressure'. Remove it, or choose the kind it belongs to", nps=(None,))
        deck = self.deck("decay.xml", (load[0], load[1] % '<Parameter name="Decay Time" type="double" value="1e-3"/>'))
        self.expect_error([deck], "decay.xml: 'shellfrac->Loads->blast->Decay Time' = 0.001 does not apply to a "
                                  "'Pressure' load with Function 'Constant'", nps=(None,))
        # A parameter at its default means nothing and passes (the --print-valid-parameters skeleton has them all).
        deck = self.deck("zero.xml", ('<Parameter name="Node Set" type="string" value="x_min"/>',
                                      '<Parameter name="Node Set" type="string" value="x_min"/>'
                                      '<Parameter name="Velocity" type="Array(double)" value="{0.0, 0.0, 0.0}"/>'))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_units_that_cannot_go_together_are_reported(self):
        # A thickness of 10 m on 1 m elements passed without a word; a modulus typed as 70e3 instead of 70e9 was
        # noticed only through a sliver warning. Stresses above the modulus are strains above 100 % (unit-free).
        deck = self.deck("yield.xml", ("70.0e9", "70.0e3"),
                         ('<Parameter name="Poisson\'s Ratio" type="double" value="0.33"/>',
                          '<Parameter name="Poisson\'s Ratio" type="double" value="0.33"/>'
                          '<Parameter name="Cohesive Strength" type="double" value="300e6"/>'))
        self.expect_error([deck], "yield.xml: 'shellfrac->Materials->aluminium->Cohesive Strength' = 3e+08 is not "
                                  "below Young's Modulus = 70000 (a strain of 4285.71 at that stress; metals yield and "
                                  "break at 1e-4 to 1e-1): are they in the same units?")
        deck = self.deck("thick.xml", ('value="0.01"', 'value="10.0"'))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("shellfrac: warning: thick.xml: block 'strip' has the Thickness 10, 10 times its median element "
                      "edge 1: a shell thicker than its elements are wide (the thickness in other units than the "
                      "mesh, or a solid meshed as a shell?)", r.stderr)
        # E 1000 times too low (MPa typed as Pa) with End Time chosen for the physics (0.1 ms): 2 steps.
        deck = self.deck("soft.xml", ("70.0e9", "70.0e6"), ('value="2e-5"', 'value="1e-4"'))
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stderr, r"shellfrac: warning: soft.xml: the run takes only [2-9] steps of [0-9.e+-]+ to End "
                                   r"Time 0.0001: a wave crosses an element only that often in the whole run \(are "
                                   r"Young's Modulus and Density in the units of the mesh and End Time\?\)")
        r = run([SHELLFRAC, "--check", self.deck("base.xml")], cwd=self.dir)
        self.assertNotIn("warning", r.stderr)

    def test_probes_named_twice_are_refused(self):
        deck = self.deck("probes.xml", ("{x_max}", "{x_max, x_min, x_max}"))
        self.expect_error([deck], "probes.xml: 'shellfrac->Output->Probes' names 'x_max' twice; each probe gives its "
                                  "own history columns, so name each set once")

    def test_separate_nodes_at_one_point_are_a_warning(self):
        with open(os.path.join(self.dir, "split.msh"), "w") as f:
            f.write(SPLIT_SQUARE_MSH)
        text = BASE.replace('<Parameter name="Source" type="string" value="Rectangle"/>',
                            '<Parameter name="Source" type="string" value="File"/>'
                            '<Parameter name="File" type="string" value="split.msh"/>')
        text = text.replace('name="strip"', 'name="plate"').replace("{x_max}", "{}")
        start, end = text.index('<ParameterList name="Rectangle">'), text.index('</ParameterList>') + 16
        text = text[:start] + text[end:]
        start, end = text.index('<ParameterList name="Boundary Conditions">'), text.index('<ParameterList name="Init')
        deck = self.deck("split.xml", text=text[:start] + text[end:])
        r = run([SHELLFRAC, "--check", deck], cwd=self.dir, np=2)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr.count("shellfrac: warning: "), 1, r.stderr)
        self.assertIn("split.msh: 3 mesh node(s) lie at the position of another node without being shared with it, "
                      "e.g. at (0, 0, 0); the elements there are not connected: a seam or a crack if that is meant, "
                      "otherwise merge the duplicate nodes", r.stderr)
        r = run([SHELLFRAC, "--check", self.deck("ok.xml")], cwd=self.dir)
        self.assertNotIn("warning", r.stderr)  # the generated strip shares its nodes

    def test_an_output_directory_that_is_a_file_or_not_writable(self):
        with open(os.path.join(self.dir, "afile"), "w") as f:
            f.write("x")
        out = '<ParameterList name="Output">'
        deck = self.deck("dir.xml", (out, out + '<Parameter name="Directory" type="string" value="afile"/>'))
        self.expect_error([deck], "dir.xml: 'Output->Directory' = 'afile' is not an existing directory")
        locked = os.path.join(self.dir, "locked")
        os.mkdir(locked)
        os.chmod(locked, 0o555)
        if os.access(locked, os.W_OK):  # the superuser may write anywhere; /proc/1 refuses even the superuser
            locked = "/proc/1"
            if os.access(locked, os.W_OK):
                self.skipTest("no unwritable directory available")
        deck = self.deck("ro.xml", (out, out + '<Parameter name="Directory" type="string" value="%s"/>' % locked))
        self.expect_error([deck], "ro.xml: 'Output->Directory' = '%s' is not writable (no permission, or a read-only "
                                  "file system)" % locked)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
