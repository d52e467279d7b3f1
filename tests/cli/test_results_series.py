#!/usr/bin/env python3
"""A run and its restarts read as one result (docs/output.md, "Checkpoints and restart"): a run restarted at step N
writes <base>.exo-s.N (a per-rank set <base>.exo-s.N.<np>.<rank>), which ParaView 5.11's IOSS reader opens with
<base>.exo as one time series; where it would not read as one run the restart says so.

* Same deck, 2 ranks: the restart's frames after its time are the original's (bitwise: the same time step), no
  notice; in ParaView (pvpython, where installed; skipped with a message otherwise) opening base.exo.2.0 gives one
  series: the union of both files' times, up to the restart's end.
* Another time step (Safety Factor, free on a restart): the original's frames after the restart time fall between the
  restart's, and a notice says how many and how to see the restart alone.
* Another rank count: ParaView groups only one layout; a notice says to join the sets (shellfrac_exojoin).
* Another Base Name: the restart's series and history begin at its step; a notice names where the steps before are.
* A new run on the base removes an earlier run's restart members (ParaView would show them as its continuation).

Base deck: the strip of test_reliability.py (16 TRI6, 1265 steps to 2 ms, a checkpoint every 100 steps), frames
every 0.2 ms.

usage: test_results_series.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import shutil
import subprocess
import sys
import unittest

from cli_common import ENV, DeckTest
from shellfrac_tools.exodus import ExodusFile
from test_reliability import BASE, run  # the same arguments: the same program

FRAMES = ('value="1e-3"', 'value="2e-4"')        # Output Interval 0.2 ms
LONGER = ('value="2e-3"', 'value="2.6e-3"')      # End Time of the restarts
SMALLER_STEP = ('<Parameter name="Output Interval"',
                '<Parameter name="Safety Factor" type="double" value="0.5"/><Parameter name="Output Interval"')
CHECKPOINT = "base_checkpoint_step600.h5"
PARAVIEW_TIMES = """
import sys
from paraview.simple import IOSSReader
reader = IOSSReader(FileName=[sys.argv[1]])
reader.UpdatePipelineInformation()
print(" ".join(repr(t) for t in reader.TimestepValues))
"""


def times(path):
    with ExodusFile(path) as f:
        return [float(t) for t in f.times()]


class ResultsSeries(DeckTest):
    BASE = BASE
    PREFIX = "shellfrac_series_"

    def original(self, np=2):
        """The base deck with frames every 0.2 ms, run to 2 ms on np ranks (checkpoints kept: every 100 steps)."""
        keep = ('<Parameter name="Step Interval" type="int" value="100"/>',
                '<Parameter name="Step Interval" type="int" value="100"/><Parameter name="Keep" type="int" value="20"/>')
        r = run([self.deck(FRAMES, keep)], self.dir, np=np)
        self.assertEqual(r.returncode, 0, r.stderr)

    def restart(self, *changes, np=2):
        keep = ('<Parameter name="Step Interval" type="int" value="100"/>',
                '<Parameter name="Step Interval" type="int" value="100"/><Parameter name="Keep" type="int" value="20"/>')
        self.deck(FRAMES, LONGER, keep, *changes)
        r = run(["base.xml", "--restart", CHECKPOINT], self.dir, np=np)
        self.assertEqual(r.returncode, 0, r.stderr)
        return r

    def test_a_restart_continues_the_series_that_paraview_opens_as_one(self):
        self.original()
        r = self.restart()
        self.assertNotIn("notice", r.stderr)
        self.assertIn("wrote base.exo-s.600.2.0 ... (2 files)", r.stdout)
        first, restarted = times(self.path("base.exo.2.0")), times(self.path("base.exo-s.600.2.0"))
        t0 = restarted[0]
        self.assertEqual([t for t in first if t > t0], [t for t in restarted if t <= first[-1] and t > t0],
                         "the restart's frames after its time are the original's (the same time step)")
        self.assertGreater(restarted[-1], first[-1])
        pvpython = shutil.which("pvpython")
        if not pvpython:
            self.skipTest("no pvpython (tools/install-deps.sh --render): the ParaView check is skipped")
        p = subprocess.run([pvpython, "-c", PARAVIEW_TIMES, os.path.abspath(self.path("base.exo.2.0"))],
                           capture_output=True, text=True, timeout=300, env=ENV)
        self.assertEqual(p.returncode, 0, p.stderr)
        seen = [float(t) for t in p.stdout.split()]
        self.assertEqual(seen, sorted(set(first) | set(restarted)), "ParaView reads one series across the restart")

    def test_a_restart_with_another_time_step_says_that_its_frames_interleave(self):
        self.original()
        r = self.restart(SMALLER_STEP)
        first, restarted = times(self.path("base.exo.2.0")), times(self.path("base.exo-s.600.2.0"))
        stray = [t for t in first if t > restarted[0] and t not in restarted]
        self.assertGreater(len(stray), 3)
        self.assertIn("notice: base.exo.2.0 holds %d frame(s) after t = " % len(stray), r.stderr)
        self.assertIn("at times this run wrote no frame (its time step or output times are not those of the run "
                      "before): ParaView's IOSS reader opens the run and its restarts as one series and shows them "
                      "between this run's frames; to see this run alone, open base.exo-s.600 with the reader's "
                      "'Scan For Related Files' off", r.stderr)

    def test_a_restart_on_another_rank_count_says_how_to_join_the_sets(self):
        self.original(np=2)
        r = self.restart(np=None)
        self.assertIn("notice: the results before this restart are not in this run's layout (one file; another rank "
                      "count, or joined): ParaView opens a run and its restarts as one series only when all are in "
                      "one layout; join each per-rank set of the series into one file with shellfrac_exojoin (e.g. "
                      "'shellfrac_exojoin base.exo'), then open base.exo", r.stderr)
        self.assertTrue(os.path.exists(self.path("base.exo-s.600")))

    def test_a_restart_under_another_base_name_says_where_the_steps_before_are(self):
        self.original()
        r = self.restart(('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" value="renamed"/>'
                                                      '<Parameter name="Probes"'))
        self.assertIn("notice: this restart writes its results under renamed, not under " +
                      os.path.realpath(self.path("base")) + " as the run that wrote " + CHECKPOINT +
                      ": its history and Exodus series begin at step 600 (t = ", r.stderr)
        self.assertTrue(os.path.exists(self.path("renamed.exo-s.600.2.0")))
        with open(self.path("renamed_history.csv")) as f:
            self.assertNotIn("\n0,", f.read(), "the renamed history begins at the restart")

    def test_a_new_run_removes_the_restarts_of_an_earlier_one(self):
        self.original()
        self.restart()
        self.assertTrue(os.path.exists(self.path("base.exo-s.600.2.1")))
        self.original()
        self.assertFalse([f for f in os.listdir(self.dir) if "-s." in f], os.listdir(self.dir))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
