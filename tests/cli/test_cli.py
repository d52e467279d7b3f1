#!/usr/bin/env python3
"""Command-line contract of shellfrac and shellfrac_meshtool (issue: foundation, items 3-5, acceptance):
exit codes, one clear message naming the file and parameter, nothing written on bad input, the input
reference in docs/ equal to what the program prints, every example deck valid.

usage: test_cli.py SOURCE_DIR SHELLFRAC MESHTOOL MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

from cli_common import ENV, Launcher

SRC, SHELLFRAC, MESHTOOL, MPIEXEC = sys.argv[1:5]
MPI_PREFLAGS = sys.argv[5:]
launch = Launcher(MPIEXEC, MPI_PREFLAGS)


def run(args, cwd=None, np=None):
    return launch(args, cwd, np)


class Shellfrac(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shellfrac_cli_")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def deck(self, name, replace=None):
        text = open(os.path.join(SRC, "xml", "cantilever_200x40.xml")).read()
        if replace:
            self.assertIn(replace[0], text)
            text = text.replace(*replace)
        path = os.path.join(self.dir, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def test_help_and_usage_errors(self):
        r = run([SHELLFRAC, "--help"])
        self.assertEqual(r.returncode, 0)
        self.assertIn("usage: shellfrac", r.stdout)
        # shellfrac's own usage first, Kokkos' options after a heading (Kokkos printed its own first, issue #31).
        self.assertTrue(r.stdout.startswith("usage: shellfrac"), r.stdout[:200])
        kokkos = r.stdout.index("Kokkos options (shellfrac accepts them too):")
        self.assertIn("--kokkos-threads", r.stdout[kokkos:])
        self.assertNotIn("Kokkos command line arguments", r.stdout[:kokkos])
        r = run([SHELLFRAC])
        self.assertEqual(r.returncode, 2)
        self.assertIn("no input deck given", r.stderr)
        r = run([SHELLFRAC, "--frobnicate", "x.xml"])
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown option '--frobnicate'", r.stderr)

    def test_misspelled_parameter_names_it_once_and_writes_nothing(self):
        deck = self.deck("typo.xml", ('name="Thickness"', 'name="Thicknes"'))
        for np in (None, 2):
            r = run([SHELLFRAC, deck], cwd=self.dir, np=np)
            self.assertEqual(r.returncode, 1, r.stderr)
            msg = "typo.xml: unknown parameter 'Thicknes' in 'shellfrac->Blocks->strip'. Did you mean 'Thickness'?"
            self.assertEqual(r.stderr.count(msg), 1, r.stderr)  # printed once, also on 2 ranks
            self.assertIn("Valid names here: 'Thickness', 'Material'.", r.stderr)
            self.assertEqual(sorted(os.listdir(self.dir)), ["typo.xml"])  # nothing half-written

    def test_out_of_range_and_missing_mesh_file(self):
        deck = self.deck("neg.xml", ('value="0.01"', 'value="-0.01"'))
        r = run([SHELLFRAC, deck], cwd=self.dir)
        self.assertEqual(r.returncode, 1)
        self.assertIn("invalid value '-0.01' for parameter 'shellfrac->Blocks->strip->Thickness'", r.stderr)
        self.assertIn("must be > 0", r.stderr)
        deck = self.deck("nofile.xml", ('value="Rectangle"/>', 'value="File"/><Parameter name="File" type="string" '
                                        'value="wing.msh"/>'))
        text = open(deck).read()
        text = re.sub(r'<ParameterList name="Rectangle">.*?</ParameterList>', "", text, flags=re.S)
        open(deck, "w").write(text)
        r = run([SHELLFRAC, deck], cwd=self.dir, np=2)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("wing.msh", r.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["neg.xml", "nofile.xml"])

    def test_input_reference_in_docs_is_current_and_runnable(self):
        ref = os.path.join(self.dir, "ref.xml")
        r = run([SHELLFRAC, "--print-valid-parameters", ref])
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(ref) as a, open(os.path.join(SRC, "docs", "input_reference.xml")) as b:
            self.assertEqual(a.read(), b.read(),
                             "docs/input_reference.xml is stale: regenerate it with shellfrac --print-valid-parameters")
        r = run([SHELLFRAC, "--check", ref], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("nothing written", r.stdout)
        self.assertEqual(sorted(os.listdir(self.dir)), ["ref.xml"])

    def test_every_example_deck_is_valid(self):
        decks = sorted(f for f in os.listdir(os.path.join(SRC, "xml")) if f.endswith(".xml"))
        self.assertTrue(decks)
        for d in decks:
            r = run([SHELLFRAC, "--check", os.path.join(SRC, "xml", d)], cwd=self.dir, np=2)
            self.assertEqual(r.returncode, 0, d + ": " + r.stderr)

    def test_run_writes_exodus_set_and_history(self):
        deck = self.deck("run.xml")
        r = run([SHELLFRAC, deck], cwd=self.dir, np=3)
        self.assertEqual(r.returncode, 0, r.stderr)
        files = sorted(os.listdir(self.dir))
        self.assertEqual(files, ["run.exo.3.0", "run.exo.3.1", "run.exo.3.2", "run.xml", "run_history.csv",
                                 "run_summary.json"])
        # the run summary (docs/output.md "The run summary"): no edge can break here, no block is plastic
        with open(os.path.join(self.dir, "run_summary.json")) as f:
            summary = json.load(f)
        self.assertEqual((summary["fracture"], summary["plasticity"], summary["fragments"]), (False, False, 1))
        self.assertIsNone(summary["first_activation_time"])
        self.assertGreaterEqual(summary["largest_energy_balance_error"], 0.0)
        self.assertLess(summary["largest_energy_balance_error"], 1e-3)
        self.assertIn("physics: largest energy-balance error", r.stdout)
        with open(os.path.join(self.dir, "run_history.csv")) as f:
            header = f.readline().strip()
        self.assertTrue(header.startswith("step,time,dt,kinetic_energy,strain_energy,penalty_energy,external_work,"
                                          "energy_balance_error,x_max_displ_x"), header)
        # a later serial run replaces the set by one file (no stale pieces left for ParaView to pick up)
        r = run([SHELLFRAC, deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["run.exo", "run.xml", "run_history.csv", "run_summary.json"])

    def test_progress_lines_with_an_eta_and_quiet(self):
        # Progress Interval 1e-9 s: a line after every step, on rank 0 only; the plan comes first.
        deck = self.deck("progress.xml", ('<ParameterList name="Output">',
                                          '<ParameterList name="Output">'
                                          '<Parameter name="Progress Interval" type="double" value="1e-9"/>'))
        r = run([SHELLFRAC, deck], cwd=self.dir, np=2)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r"planned: \d+ steps to t = [0-9.e+-]+, results about [0-9.]+ [KMG]?i?B")
        lines = [l for l in r.stdout.splitlines() if l.strip().startswith("step ")]
        self.assertGreater(len(lines), 5, r.stdout)
        self.assertRegex(lines[-1], r"100\.0 %.*steps/s +elapsed \d+:\d\d:\d\d +ETA 0:00:00 +balance error [0-9.e+-]+$")
        steps = [int(l.split()[1]) for l in lines]
        self.assertEqual(steps, sorted(set(steps)), "one line per step, printed once (rank 0)")
        r = run([SHELLFRAC, "--quiet", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("ETA", r.stdout)

    def test_sigterm_writes_a_checkpoint_and_the_run_restarts_from_it(self):
        # Issue #6: SIGTERM (a batch system's warning) leaves a readable checkpoint and Exodus file and exit
        # code 4; --restart continues from it.
        deck = self.deck("long.xml", ('name="End Time" type="double" value="8.8e-5"',
                                      'name="End Time" type="double" value="1.0"'))
        proc = subprocess.Popen([SHELLFRAC, deck], cwd=self.dir, env=ENV, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        history = os.path.join(self.dir, "long_history.csv")
        for _ in range(600):  # wait until it is stepping (a few history rows)
            if os.path.exists(history) and sum(1 for _ in open(history)) > 5:
                break
            time.sleep(0.1)
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=120)
        self.assertEqual(proc.returncode, 4, err)
        m = re.search(r"stopped by SIGTERM at step (\d+); continue with --restart (\S+)", out)
        self.assertTrue(m, out)
        checkpoint = m.group(2)
        self.assertEqual(os.path.basename(checkpoint), "long_checkpoint_step%s.h5" % m.group(1))
        self.assertTrue(os.path.exists(os.path.join(self.dir, checkpoint)))
        self.assertFalse([f for f in os.listdir(self.dir) if f.endswith(".tmp")])
        rows = sum(1 for _ in open(history))
        # the Exodus file is complete enough to read back: compare it with itself
        exo = os.path.join(self.dir, "long.exo")
        r = run([os.path.join(os.path.dirname(MESHTOOL), "..", "exotools", "shellfrac_exocompare"), exo, exo])
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # restart with a short end time: continues from the checkpoint's step and appends to the history
        text = open(deck).read().replace('value="1.0"', 'value="9e-5"')
        with open(deck, "w") as f:
            f.write(text)
        r = run([SHELLFRAC, deck, "--restart", os.path.join(self.dir, checkpoint)], cwd=self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertGreaterEqual(sum(1 for _ in open(history)), rows)
        self.assertTrue(any(f.startswith("long.exo-s.") for f in os.listdir(self.dir)), os.listdir(self.dir))
        # a missing or foreign checkpoint is an input error naming the file
        r = run([SHELLFRAC, deck, "--restart", deck], cwd=self.dir)
        self.assertEqual(r.returncode, 1)
        self.assertIn("long.xml: cannot open the checkpoint", r.stderr)

    def test_sigusr2_to_mpirun_stops_every_rank_after_a_checkpoint(self):
        # Issue #27: Open MPI's mpirun forwards a SIGTERM to the ranks and SIGKILLs them 1 s later, which cuts a
        # large run's checkpoint off. It forwards SIGUSR2 and lets the ranks finish: SIGUSR2 is a stop signal
        # like SIGTERM. Before, SIGUSR2 killed every rank at once (no checkpoint, not exit code 4).
        deck = self.deck("long.xml", ('name="End Time" type="double" value="8.8e-5"',
                                      'name="End Time" type="double" value="1.0"'))
        proc = subprocess.Popen(launch.command([SHELLFRAC, deck], np=2), cwd=self.dir, env=ENV,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        history = os.path.join(self.dir, "long_history.csv")
        for _ in range(600):  # wait until it is stepping (a few history rows)
            if os.path.exists(history) and sum(1 for _ in open(history)) > 5:
                break
            time.sleep(0.1)
        proc.send_signal(signal.SIGUSR2)  # to mpirun, as `kill -USR2 <pid of mpirun>` or a batch system would
        out, err = proc.communicate(timeout=120)
        self.assertEqual(proc.returncode, 4, out + err)
        m = re.search(r"stopped by SIGUSR2 at step (\d+); continue with --restart (\S+)", out)
        self.assertTrue(m, out + err)
        self.assertTrue(os.path.exists(os.path.join(self.dir, m.group(2))), os.listdir(self.dir))
        self.assertFalse([f for f in os.listdir(self.dir) if f.endswith(".tmp")])
        self.assertNotIn("internal error", out + err)

    def test_unstable_time_step_stops_with_a_message(self):
        # Issue #6: a forced time step far above the stable one blows up; the run names the step, time and
        # element, writes its last good state (a copy kept every 50 steps) and exits with 3.
        deck = self.deck("unstable.xml", ('<Parameter name="End Time" type="double" value="8.8e-5"/>',
                                          '<Parameter name="End Time" type="double" value="8.8e-5"/>'
                                          '<Parameter name="Time Step" type="double" value="5e-6"/>'
                                          '<Parameter name="Force Time Step" type="bool" value="true"/>'))
        r = run([SHELLFRAC, deck], cwd=self.dir)
        self.assertEqual(r.returncode, 3, r.stdout + r.stderr)
        self.assertRegex(r.stderr, r"numerical blow-up at step [0-9]+, time [0-9.e+-]+: non-finite position or force "
                                   r"in element [0-9]+")
        # The physics, not a bug: one line, without an "internal error" label or the MPI abort banner.
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertTrue(r.stderr.startswith("shellfrac: error: numerical blow-up"), r.stderr)
        # ... and writes the last good state as a checkpoint, from which a run can restart
        m = re.search(r"The last good state \(step (\d+), time [0-9.e+-]+\) is in (\S+);", r.stderr)
        self.assertTrue(m, r.stderr)
        self.assertEqual(m.group(2), "unstable_checkpoint_step%s.h5" % m.group(1))
        self.assertTrue(os.path.exists(os.path.join(self.dir, m.group(2))))
        # With a checkpoint schedule the run keeps no copy in memory (docs/output.md): the last good state is the
        # last checkpoint written (every 10 steps here), or none if the blow-up comes before the first one.
        for interval, expect_file in ((10, True), (100000, False)):
            deck = self.deck("scheduled.xml", ('<Parameter name="History Interval" type="int" value="10"/>\n'
                                               '  </ParameterList>',
                                               '<Parameter name="History Interval" type="int" value="10"/>'
                                               '<Parameter name="Time Step" type="double" value="5e-6"/>'
                                               '<Parameter name="Force Time Step" type="bool" value="true"/>'
                                               '</ParameterList><ParameterList name="Checkpoint">'
                                               '<Parameter name="Step Interval" type="int" value="%d"/>'
                                               '</ParameterList>' % interval))
            r = run([SHELLFRAC, deck], cwd=self.dir)
            self.assertEqual(r.returncode, 3, r.stdout + r.stderr)
            m = re.search(r"The last good state \(step (\d+), time [0-9.e+-]+\) is in (\S+);", r.stderr)
            if expect_file:
                self.assertTrue(m, r.stderr)
                self.assertEqual(int(m.group(1)) % interval, 0, r.stderr)
                self.assertEqual(m.group(2), "scheduled_checkpoint_step%s.h5" % m.group(1))
                self.assertTrue(os.path.exists(os.path.join(self.dir, m.group(2))))
            else:
                self.assertIsNone(m, r.stderr)
                self.assertIn("No checkpoint was written before the blow-up; rerun with a smaller Time Step or "
                              "Safety Factor", r.stderr)


class MeshTool(unittest.TestCase):
    def test_convert_info_and_errors(self):
        d = tempfile.mkdtemp(prefix="shellfrac_meshtool_")
        try:
            src = os.path.join(SRC, "tests", "data", "gmsh", "square_v22.msh")
            out = os.path.join(d, "square.exo")
            r = run([MESHTOOL, "convert", src, out, "--p2", "--refine", "2"])
            self.assertEqual(r.returncode, 0, r.stderr)
            r = run([MESHTOOL, "info", out])
            self.assertEqual(r.returncode, 0, r.stderr)
            # 4 triangles, promoted to TRI6, refined twice: 4 * 16 = 64 elements
            self.assertIn("elements: 64 TRI6", r.stdout)
            r = run([MESHTOOL, "info", os.path.join(d, "none.msh")])
            self.assertEqual(r.returncode, 1)
            self.assertIn("none.msh", r.stderr)
            r = run([MESHTOOL, "refine", src, out, "eleven"])
            self.assertEqual(r.returncode, 1)
            self.assertIn("refinement count 'eleven' must be 0..10", r.stderr)
            # The output never replaces the input (`convert a.exo a.exo` replaced the source, exit 0).
            with open(out, "rb") as f:
                before = f.read()
            for cmd in (["convert", out, out], ["refine", out, out, "1"]):
                r = run([MESHTOOL] + cmd)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertIn("the output %s is the input mesh %s; name another output file" % (out, out), r.stderr)
            with open(out, "rb") as f:
                self.assertEqual(f.read(), before)
        finally:
            shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
