#!/usr/bin/env python3
"""History rows by time (`Time Integration->History Time Interval`, docs/output.md "The history CSV").

* The strip of test_reliability.py (time step 1.58e-6 s, End Time 2 ms) with a row every 0.1 ms: the rows are step 0,
  then for each multiple k * 0.1 ms the first step whose time is within half a step of it or past it (the rule of the
  Exodus frames), each exactly once, and the last step.
* A restart from the checkpoint at step 600 writes the same history, bitwise, as the run without it.
* A History Interval (steps) and a History Time Interval together are refused, naming both.

usage: test_history.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import sys
import unittest

from cli_common import DeckTest
from shellfrac_tools.tables import read_table
from test_reliability import BASE, md5, run  # the same arguments: the same program

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


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
