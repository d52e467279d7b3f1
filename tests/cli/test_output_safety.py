#!/usr/bin/env python3
"""Runs that must not destroy, mix or misplace results (docs/hostile_input.md, "Files, links and locks" and
"Restarts"): two runs on one output base, result files that are links, result names outside the output directory,
restarts that would cut or mix another run's tables or checkpoints, and inputs that are not regular files. Each
case was found on an earlier version, which gave exit 0 with altered or lost data, or hung; for data loss the test
asserts the md5 of what must survive.

Base deck: the strip of test_reliability.py (16 TRI6, 1265 steps to 2 ms, a checkpoint every 100 steps).

usage: test_output_safety.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

from cli_common import ENV, DeckTest
from shellfrac_tools.exodus import ExodusFile
from test_reliability import BASE, md5, run  # the same arguments: the same program

SHELLFRAC, MPIEXEC = sys.argv[2:4]  # SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...], as test_reliability.py
MPI_PREFLAGS = sys.argv[4:]

LONG_RUN = ('value="2e-3"', 'value="50.0"')  # a run that goes on until it is stopped


class OutputSafety(DeckTest):
    BASE = BASE
    PREFIX = "shellfrac_output_safety_"

    def setUp(self):
        super().setUp()
        self.outside = tempfile.mkdtemp(prefix="shellfrac_outside_")  # where no result may ever go
        self.victim = os.path.join(self.outside, "precious.txt")
        with open(self.victim, "w") as f:
            f.write("a file of the user's, outside the output directory\n")
        self.victim_md5 = md5(self.victim)

    def tearDown(self):
        super().tearDown()
        shutil.rmtree(self.outside, ignore_errors=True)

    def assert_victim_intact(self):
        self.assertEqual(md5(self.victim), self.victim_md5, "a file outside the output directory was written")

    def start_long_run(self, deck):
        """A run in the background, returned once it holds its lock and has written its first history row."""
        proc = subprocess.Popen([SHELLFRAC, "--quiet", deck], cwd=self.dir, env=ENV, stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        for _ in range(600):
            if os.path.exists(self.path("base.lock")) and os.path.exists(self.path("base_history.csv")):
                return proc
            if proc.poll() is not None:
                self.fail("the background run ended early: " + proc.stderr.read())
            time.sleep(0.05)
        proc.kill()
        self.fail("the background run did not start")

    # --- one run per output base ------------------------------------------------------------------------

    def test_a_second_run_on_the_same_base_is_refused_while_the_first_runs(self):
        # Without a lock a resubmitted job wrote into the running one's files: garbled Exodus variable names,
        # times of 1e+240, the other run's history rows, and a false "disk full".
        first = self.start_long_run(self.deck(LONG_RUN))
        try:
            # A resubmitted job on 1 or 2 ranks, and a restart started beside the running job (from a copy of one
            # of its checkpoints, which it removes as it writes newer ones).
            while not os.path.exists(self.path("copy.h5")):
                try:
                    shutil.copy(self.path(min((f for f in os.listdir(self.dir) if f.endswith(".h5")),
                                              key=lambda f: int(f[len("base_checkpoint_step"):-3]))),
                                self.path("copy.h5"))
                except (OSError, ValueError):
                    time.sleep(0.05)
            for args, np in ((["base.xml"], None), (["base.xml"], 2), (["base.xml", "--restart", "copy.h5"], None)):
                r = run(args, self.dir, np=np)
                self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
                self.assertRegex(r.stderr, r"base: another run is writing results of this name \(host [^,]+, pid "
                                           r"%d, started [^,]+, deck base.xml; lock file base.lock\); wait for it "
                                           r"to end, or give this run another 'Output->Base Name' or "
                                           r"'Output->Directory'" % first.pid)
                self.assertEqual(r.stderr.count("error:"), 1, r.stderr)
            self.assertIsNone(first.poll(), "the first run was disturbed")
        finally:
            first.send_signal(signal.SIGTERM)
            out, err = first.communicate(timeout=120)
        self.assertEqual(first.returncode, 4, out + err)  # stopped by the signal, with a checkpoint
        self.assertFalse(os.path.exists(self.path("base.lock")), "the lock file outlived its run")
        with open(self.path("base_history.csv")) as f:
            rows = f.read().splitlines()
        steps = [float(line.split(",")[0]) for line in rows[1:]]
        self.assertEqual(steps, sorted(set(steps)), "the history holds rows of two runs")
        # Once the first run has ended, the base is free.
        self.deck()
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_the_lock_is_released_by_a_run_that_is_killed(self):
        # flock is released by the kernel when the process dies: a stale lock file never blocks the next run.
        first = self.start_long_run(self.deck(LONG_RUN))
        first.kill()
        first.communicate(timeout=60)
        self.assertTrue(os.path.exists(self.path("base.lock")))
        self.deck()
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse(os.path.exists(self.path("base.lock")))

    # --- links and names -----------------------------------------------------------------------------------

    def test_a_link_named_like_a_result_is_refused_not_written_through(self):
        # A symlink named like the history file made the run overwrite the file it points to, exit 0.
        self.deck()
        for result in ("base_history.csv", "base_checkpoint_step100.h5"):
            os.symlink(self.victim, self.path(result))
            r = run(["base.xml"], self.dir)
            self.assertEqual(r.returncode, 6, r.stderr)
            self.assertIn(result + ": a result file of this name is a symbolic link; shellfrac writes its results "
                          "only to files of their own (never through a link)", r.stderr)
            self.assertNotIn("internal error", r.stderr)
            self.assert_victim_intact()
            os.remove(self.path(result))

    def test_a_link_named_like_a_temporary_file_is_removed_not_followed(self):
        # A symlink named like the checkpoint's temporary file made the run overwrite its target, exit 0.
        self.deck()
        os.symlink(self.victim, self.path("base_checkpoint_step100.h5.tmp"))
        os.symlink(self.path("base_checkpoint_step1200.h5"), self.path("base_checkpoint_step1200.h5.tmp"))  # dangling
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assert_victim_intact()
        self.assertFalse(os.path.lexists(self.path("base_checkpoint_step100.h5.tmp")))
        self.assertFalse(os.path.islink(self.path("base_checkpoint_step1200.h5")))

    def test_an_exodus_result_that_is_a_link_is_refused_too(self):
        # Every result name that is a link is refused the same way, the Exodus file and the files of a per-rank set
        # included (a link is neither followed nor silently removed: it may be the user's, pointing elsewhere).
        self.deck()
        for result, np in (("base.exo", None), ("base.exo.2.1", 2)):
            os.symlink(self.victim, self.path(result))
            r = run(["base.xml"], self.dir, np=np)
            self.assertEqual(r.returncode, 6, r.stderr)
            self.assertIn(result + ": a result file of this name is a symbolic link", r.stderr)
            self.assertTrue(os.path.islink(self.path(result)))
            self.assert_victim_intact()
            os.remove(self.path(result))

    def test_a_base_name_with_a_directory_part_is_refused(self):
        # Base Name ../../x wrote two levels above the output directory. The run is two levels down in the scratch
        # directory, so that anything written above stays inside it and is seen.
        work = self.path(os.path.join("a", "b"))
        os.makedirs(os.path.join(work, "out"))
        for base in ("../../x", "../x", "sub/x", "..", ".", os.path.join(self.outside, "x")):
            self.deck(('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" value="%s"/>'
                                                   '<Parameter name="Directory" type="string" value="out"/>'
                                                   '<Parameter name="Probes"' % base), name="a/b/base.xml")
            for check in ([], ["--check"]):
                r = run(check + ["base.xml"], work)
                self.assertEqual(r.returncode, 1, r.stderr)
                self.assertIn("base.xml: 'Output->Base Name' = '%s' is not a file name: the results are written in "
                              "'Output->Directory' under names made of the base name, which must not contain '/' or "
                              "be '.' or '..'" % base, r.stderr)
        written = sorted(os.path.relpath(os.path.join(d, f), self.dir) for d, _, fs in os.walk(self.dir) for f in fs)
        self.assertEqual(written, [os.path.join("a", "b", "base.xml")])
        self.assertEqual(os.listdir(self.outside), ["precious.txt"])

    def test_a_checkpoint_directory_that_does_not_exist_is_refused_by_check(self):
        # It passed --check and failed at the first checkpoint, hours later, guessing "disk full".
        self.deck(('<Parameter name="Step Interval" type="int" value="100"/>',
                   '<Parameter name="Step Interval" type="int" value="100"/>'
                   '<Parameter name="File" type="string" value="no_such_dir/ck.h5"/>'))
        r = run(["--check", "base.xml"], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base.xml: the directory of 'Checkpoint->File' ('no_such_dir/ck.h5') = 'no_such_dir' is not an "
                      "existing directory", r.stderr)

    def test_print_valid_parameters_never_overwrites_a_file(self):
        # `shellfrac --check --print-valid-parameters deck.xml` replaced the user's deck, exit 0.
        self.deck()
        digest = md5(self.path("base.xml"))
        r = run(["--check", "--print-valid-parameters", "base.xml"], self.dir)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("--print-valid-parameters base.xml: the file exists; this option writes a new file and never "
                      "replaces one", r.stderr)
        self.assertEqual(md5(self.path("base.xml")), digest)
        os.symlink(self.victim, self.path("link.xml"))
        r = run(["--print-valid-parameters", "link.xml"], self.dir)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assert_victim_intact()
        r = run(["--print-valid-parameters", "reference.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.path("reference.xml")) as f:
            self.assertIn('<ParameterList name="shellfrac">', f.read())

    def test_a_failed_write_stops_the_run_with_exit_6_and_one_line(self):
        # Every write is checked: once the running job's files are limited to 300 kB beyond the history's size
        # (RLIMIT_FSIZE, set from outside after MPI_Init, whose shared-memory files it would break; a write beyond it
        # fails with EFBIG, as on a full disk), the history, which grows fastest, fails. A history written through a
        # link to /dev/full used to print "wrote ..._history.csv" and exit 0.
        proc = subprocess.Popen([SHELLFRAC, "--quiet", self.deck(LONG_RUN)], cwd=self.dir, env=ENV,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        while not os.path.exists(self.path("base_history.csv")):
            time.sleep(0.01)
        limit = os.path.getsize(self.path("base_history.csv")) + 300000
        resource.prlimit(proc.pid, resource.RLIMIT_FSIZE, (limit, limit))
        out, err = proc.communicate(timeout=120)
        self.assertEqual(proc.returncode, 6, out + err)
        self.assertEqual(err.strip().splitlines(), [
            "shellfrac: error: base_history.csv: writing failed (File too large; disk full, quota or file removed?); "
            "the run stops"])
        self.assertNotIn("wrote", out)
        self.assertFalse(os.path.exists(self.path("base.lock")))

    def test_a_failed_exodus_write_stops_every_rank_with_exit_6_and_one_line(self):
        # A full disk during an Exodus frame gave "internal error ... [source path:line]", the MPI abort banner and
        # exit 3; on 2 ranks the other rank ran on alone. Frames every 1e-5 s, history rows every 100 000 steps: the
        # Exodus files grow fastest; the limit is set on one rank's process only.
        self.deck(LONG_RUN, ('<Parameter name="Output Interval" type="double" value="1e-3"/>',
                             '<Parameter name="Output Interval" type="double" value="1e-5"/>'
                             '<Parameter name="History Interval" type="int" value="100000"/>'))
        for np in (None, 2):
            cmd = ([MPIEXEC, "-np", str(np)] + MPI_PREFLAGS if np else []) + [SHELLFRAC, "--quiet", "base.xml"]
            proc = subprocess.Popen(cmd, cwd=self.dir, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                    text=True)  # shellfrac ignores SIGXFSZ itself: the write fails with EFBIG
            exodus = self.path("base.exo" if np is None else "base.exo.2.1")
            while not os.path.exists(exodus) or os.path.getsize(exodus) == 0:
                time.sleep(0.01)
            ranks = [pid for pid in map(int, filter(str.isdigit, os.listdir("/proc")))
                     if self.argv0(pid) == SHELLFRAC and self.cwd(pid) == os.path.realpath(self.dir)]
            self.assertEqual(len(ranks), np or 1)
            limit = max(os.path.getsize(self.path(f)) for f in os.listdir(self.dir)) + 200000
            resource.prlimit(ranks[-1], resource.RLIMIT_FSIZE, (limit, limit))
            out, err = proc.communicate(timeout=120)
            self.assertEqual(proc.returncode, 6, out + err)
            lines = [line for line in err.splitlines() if line.startswith("shellfrac")]  # mpiexec adds its notice
            self.assertEqual(len(lines), 1, err)
            self.assertNotIn("MPI_ABORT", err)
            # The file size limit may strike in any part of the frame: the message then names it ("step 28, global
            # variables: writing failed (ex_put_var: ...)", "step 72, element variable 5, block 1: ...").
            m = re.match(r"^shellfrac: error: (rank [01]: )?base\.exo(\.2\.[01])?: step ([0-9]+)"
                         r"(, [a-z ]+( [0-9]+)?(, block [0-9]+)?)?: "
                         r"writing failed \(.*; disk full, quota or file removed\?\); the results files now end at "
                         r"step ([0-9]+)$", lines[0])
            self.assertTrue(m, lines[0])
            self.assertEqual(int(m.group(7)), int(m.group(3)) - 1)
            self.assertFalse(os.path.exists(self.path("base.lock")))
            # Every file of the set ends on the same, whole frame: the frame the limit struck in is cut off on
            # every rank (before, the other rank kept it whole and the failing rank kept it partial, or not at all).
            names = ["base.exo"] if np is None else ["base.exo.2.0", "base.exo.2.1"]
            files = [ExodusFile(self.path(n)) for n in names]
            try:
                for f in files:
                    self.assertEqual(len(f.times()), int(m.group(7)), f.path)
                    # the history columns of each frame are the frame's: its own time and step
                    np_time = f.global_variable("time")
                    self.assertEqual(list(np_time), list(f.times()), f.path)
                for f in files[1:]:
                    for name in ("step", "time", "kinetic_energy"):
                        self.assertEqual(list(f.global_variable(name)), list(files[0].global_variable(name)), name)
            finally:
                for f in files:
                    f.close()

    @staticmethod
    def cwd(pid):
        try:
            return os.readlink("/proc/%d/cwd" % pid)
        except OSError:
            return ""

    @staticmethod
    def argv0(pid):
        try:
            with open("/proc/%d/cmdline" % pid, "rb") as f:
                return f.read().split(b"\0")[0].decode()
        except OSError:
            return ""

    # --- inputs that are not regular files -------------------------------------------------------------------

    def test_special_files_as_inputs_are_refused_at_once(self):
        # --restart or Restart From naming a FIFO blocked in open() and ignored SIGTERM; --restart "" started from
        # t = 0 without a word.
        os.mkfifo(self.path("pipe"))
        self.deck()
        for args, message in (
                (["base.xml", "--restart", "pipe"], "pipe: the checkpoint to restart from is a FIFO (named pipe), "
                                                    "not a regular file; name the file itself"),
                (["base.xml", "--restart", "/dev/null"], "/dev/null: the checkpoint to restart from is a device, not "
                                                         "a regular file"),
                (["base.xml", "--restart", self.outside], self.outside + ": the checkpoint to restart from is a "
                                                                         "directory, not a regular file"),
                (["pipe"], "pipe: the input deck is a FIFO (named pipe), not a regular file")):
            r = run(args, self.dir, timeout=30)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertIn(message, r.stderr)
        self.deck(('<Parameter name="Step Interval" type="int" value="100"/>',
                   '<Parameter name="Step Interval" type="int" value="100"/>'
                   '<Parameter name="Restart From" type="string" value="pipe"/>'))
        r = run(["base.xml"], self.dir, timeout=30)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("pipe: the checkpoint to restart from is a FIFO (named pipe)", r.stderr)
        self.deck(('<Parameter name="Source" type="string" value="Rectangle"/>',
                   '<Parameter name="Source" type="string" value="File"/>'
                   '<Parameter name="File" type="string" value="pipe.msh"/>'))
        os.mkfifo(self.path("pipe.msh"))
        r = run(["base.xml"], self.dir, timeout=30)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("pipe.msh: the mesh file is a FIFO (named pipe), not a regular file", r.stderr)
        r = run(["base.xml", "--restart", ""], self.dir, timeout=30)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertIn("--restart was given an empty file name", r.stderr)

    # --- restarts ----------------------------------------------------------------------------------------------

    def test_a_restart_with_other_physics_never_writes_over_its_origin(self):
        # --allow-physics-change with the same base name replaced the original run's later checkpoints and cut its
        # history at the restart step.
        self.deck()
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        kept = {f: md5(self.path(f)) for f in os.listdir(self.dir) if f.startswith("base") and f != "base.xml"}
        self.deck(("70.0e9", "72e9"))
        r = run(["base.xml", "--restart", "base_checkpoint_step1100.h5", "--allow-physics-change"], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base.xml: this restart changes the physics (--allow-physics-change) but would write its "
                      "results under the same 'Output->Base Name' and 'Output->Directory' as the run that wrote "
                      "base_checkpoint_step1100.h5", r.stderr)
        # Another base name, the same checkpoint series (Checkpoint->File): refused too.
        self.deck(("70.0e9", "72e9"), ('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" '
                                                                  'value="stiffer"/><Parameter name="Probes"'),
                  ('<Parameter name="Step Interval" type="int" value="100"/>',
                   '<Parameter name="Step Interval" type="int" value="100"/>'
                   '<Parameter name="File" type="string" value="base_checkpoint.h5"/>'))
        r = run(["base.xml", "--restart", "base_checkpoint_step1100.h5", "--allow-physics-change"], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("would write its checkpoints into the series 'base_checkpoint.h5' as the run that wrote "
                      "base_checkpoint_step1100.h5", r.stderr)
        # Its own names: accepted, and the original run's files are untouched.
        self.deck(("70.0e9", "72e9"), ('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" '
                                                                  'value="stiffer"/><Parameter name="Probes"'))
        r = run(["base.xml", "--restart", "base_checkpoint_step1100.h5", "--allow-physics-change"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual({f: md5(self.path(f)) for f in kept}, kept)
        self.assertTrue(any(f.startswith("stiffer_checkpoint_step") for f in os.listdir(self.dir)))
        self.assertTrue(os.path.exists(self.path("stiffer.exo-s.1100")))

    def test_a_restart_continues_only_the_tables_that_are_provably_its_own(self):
        # A restart kept whatever history rows were on disk before its step, even another run's (a jump of the
        # kinetic energy at the seam, exit 0); a damaged row gave "internal error: stod" and an MPI abort banner.
        self.deck()
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.path("base_history.csv")) as f:
            original = f.read()
        # Another run on the same base, without checkpoints, replaces the history.
        self.deck(("70.0e9", "60e9"), ('<Parameter name="Step Interval" type="int" value="100"/>', ''),
                  ('<Parameter name="Probes"', '<Parameter name="Base Name" type="string" value="base"/>'
                                               '<Parameter name="Probes"'), name="other.xml")
        r = run(["other.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        others = md5(self.path("base_history.csv"))
        r = run(["base.xml", "--restart", "base_checkpoint_step1100.h5"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("shellfrac: notice: base_history.csv does not hold exactly the rows the checkpoint was written "
                      "after (missing, changed, or written by another run since): it is left as it is, and this run's "
                      "history rows from step 1100 on go to base.restart1100_history.csv", r.stderr)
        self.assertEqual(md5(self.path("base_history.csv")), others)
        with open(self.path("base.restart1100_history.csv")) as f:
            restarted = f.read().splitlines()
        self.assertEqual(restarted[0], original.splitlines()[0])
        step = original.splitlines()[0].split(",").index("step")
        self.assertEqual(restarted[1:], [row for row in original.splitlines()[1:] if int(row.split(",")[step]) > 1100],
                         "the rows after the restart differ from the original run's")
        # That restart's own checkpoints name its own history, which a restart from them continues in place.
        continued = md5(self.path("base.restart1100_history.csv"))
        r = run(["base.xml", "--restart", "base_checkpoint_step1200.h5"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("does not hold exactly the rows", r.stderr)
        self.assertEqual(md5(self.path("base.restart1100_history.csv")), continued)
        # base.exo is the other run's (another modulus: other steps), and ParaView would show its frames in the series.
        self.assertIn("notice: base.exo holds 1 frame(s) after t = ", r.stderr)
        # The original run again; a damaged row in its history: a new file as above, never a crash.
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = original.splitlines(keepends=True)
        lines[5] = "garbage,\n"
        with open(self.path("base_history.csv"), "w") as f:
            f.writelines(lines)
        r = run(["base.xml", "--restart", "base_checkpoint_step1200.h5"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("internal error", r.stderr)
        self.assertIn("this run's history rows from step 1200 on go to base.restart1200_history.csv", r.stderr)
        # The history as written: continued in place, bitwise the same as the continuous run's.
        with open(self.path("base_history.csv"), "w") as f:
            f.write(original)
        r = run(["base.xml", "--restart", "base_checkpoint_step1200.h5"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("notice", r.stderr)
        with open(self.path("base_history.csv")) as f:
            self.assertEqual(f.read(), original)

    def test_a_restart_on_a_mesh_with_other_sets_is_refused(self):
        # The fingerprint covered ids, blocks and coordinates only: a mesh whose node set moved restarted with the
        # probe (or a support) on other nodes, exit 0. The strip as a Gmsh file, then the same nodes and elements
        # with x_max on the next column of nodes.
        rectangle = BASE[BASE.index('    <Parameter name="Source"'):BASE.index('  </ParameterList>\n  <ParameterList name="Blocks">')]
        self.deck((rectangle, '    <Parameter name="Source" type="string" value="File"/>\n'
                              '    <Parameter name="File" type="string" value="strip.msh"/>\n'))
        with open(self.path("strip.msh"), "w") as f:
            f.write(strip_msh(x_max_column=8))
        r = run(["base.xml"], self.dir)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(self.path("strip.msh"), "w") as f:
            f.write(strip_msh(x_max_column=6))
        r = run(["base.xml", "--restart", "base_checkpoint_step1200.h5"], self.dir)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("base_checkpoint_step1200.h5: the checkpoint was written for a mesh with other node, side or "
                      "element sets", r.stderr)


def strip_msh(x_max_column):
    """The base deck's strip (4 m x 0.5 m, 4 x 2 cells, 'Right' diagonals, 16 TRI6) as a Gmsh 2.2 file: surface
    'strip', curves 'x_min' (node column 0) and 'x_max' (node column `x_max_column`, 8 = the edge x = 4)."""
    nx, ny, length, width = 4, 2, 4.0, 0.5
    columns = 2 * nx + 1

    def node(i, j):
        return 1 + i + j * columns

    nodes = ["%d %.17g %.17g 0" % (node(i, j), i * length / (2 * nx), j * width / (2 * ny))
             for j in range(2 * ny + 1) for i in range(columns)]
    elements = []
    for i in (0, x_max_column):  # 3-node lines: ends, then the middle
        for k in range(ny):
            elements.append("8 2 %d %d %d %d %d" % (2 if i == 0 else 3, 2 if i == 0 else 3, node(i, 2 * k),
                                                  node(i, 2 * k + 2), node(i, 2 * k + 1)))
    for cy in range(ny):
        for cx in range(nx):
            i, j = 2 * cx, 2 * cy
            for tri in ((node(i, j), node(i + 2, j), node(i + 2, j + 2), node(i + 1, j), node(i + 2, j + 1),
                         node(i + 1, j + 1)),
                        (node(i, j), node(i + 2, j + 2), node(i, j + 2), node(i + 1, j + 1), node(i + 1, j + 2),
                         node(i, j + 1))):
                elements.append("9 2 1 1 " + " ".join(map(str, tri)))
    return ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 2 \"x_min\"\n1 3 \"x_max\"\n"
            "2 1 \"strip\"\n$EndPhysicalNames\n$Nodes\n%d\n%s\n$EndNodes\n$Elements\n%d\n%s\n$EndElements\n"
            % (len(nodes), "\n".join(nodes), len(elements),
               "\n".join("%d %s" % (k + 1, e) for k, e in enumerate(elements))))

if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0], "-v"])
