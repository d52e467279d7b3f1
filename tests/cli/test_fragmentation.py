#!/usr/bin/env python3
"""Fragmentation of an expanding ring with scattered edge strengths (docs/theory.md §9.8, docs/fragmentation.md).

The ring: a short aluminium tube (radius 50 mm, 100 cells around, one along the axis, h = 1 mm), every node
launched outwards at the same speed, every edge breakable. sigma_c = 300 MPa, Gamma = 10 kJ/m2, E = 70 GPa:
s0 = E Gamma / sigma_c^2 = 7.78 mm, t0 = s0 / c = 1.53 us, eps0 = c sigma_c^3 / (E^2 Gamma) = 2 806 /s
(Zhou, Molinari & Ramesh, Int. J. Impact Eng. 31, 2005). The launch speed 70 m/s is a strain rate of 1 400 /s.

Asserted:
  * with one strength for every edge the hoop stress is uniform, and every axial edge activates in the same step
    (the defect scattered strengths remove: where cracks fall is then decided by round-off);
  * with a Uniform +-10 % strength the activations spread over many steps, the first step activating the weakest
    edges only;
  * a Weibull strength gives bitwise the same history, crack log and fragment table on 1, 2 and 3 ranks and through
    a restart written on 3 ranks and continued on 2; another seed gives other cracks; the crack log carries each
    edge's drawn strength, within the distribution's bounds;
  * the run summary (<base>_summary.json, docs/output.md "The run summary") says what the tables say: the
    largest energy-balance error of the history rows over the largest |E0| + |W_ext| + |W_react|, the first
    activation of the crack log, the first history row with a separated edge, the last row's edge and fragment
    counts, the heaviest and the fastest piece of the last fragment table; and it is the same on 1, 2 and 3 ranks and
    through the restart (the checkpoint carries it);
  * fragment size against theory (docs/fragmentation.md, tools/fragmentation_study.py): the ring sized for 40
    fragments of the Zhou-Molinari-Ramesh size at eps_dot/eps0 = 10 (Int. J. Impact Eng. 33, 2006:
    s/s0 = 4.5/(1 + 4.5 rate^(2/3)) = 0.2056), 640 cells, Weibull m = 12, seed 1: the mean fragment length at the
    count's time (2 t0 after the last activation) within BAND of the ZMR size, and the energy balance within
    0.5 % of the cohesive dissipation. The band holds the three seeds and two meshes of docs/fragmentation.md at
    this rate (measured 1.03-1.21 s_ZMR; this run 1.21, balance 0.0003 %) with room for changes of round-off;
  * the energy balance at a high rate (docs/theory.md §9.4, eq. 9.4b): the same ring at eps_dot/eps0 = 100, seed 1,
    keeps its balance error within 0.5 % of the cohesive dissipation and 1e-5 of the launch kinetic energy K0, at
    the default step (safety factor 0.8) and at half of it (0.4: a balance that closes by a fault of the forces
    would not close at both). Measured on 2 ranks: 3.7e-6 of the dissipation (2.8e-7 K0) at 0.8, 8.8e-7 (6.8e-8
    K0) at 0.4, a ratio of 4.2: the error of a second-order integrator, not of the forces. Forces that hold the
    interface frame fixed (before eq. 9.4b) lost 70 % of the dissipation (9.3e-2 K0) on this ring.

usage: test_fragmentation.py SOURCE_DIR SHELLFRAC MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import csv
import filecmp
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import fragmentation_study as study  # tools/ (on PYTHONPATH)
from cli_common import Launcher

SRC, SHELLFRAC, MPIEXEC = sys.argv[1:4]
launch = Launcher(MPIEXEC, sys.argv[4:])

CELLS = 100  # around the ring: 100 axial edges
BAND = (0.9, 1.4)  # s / s_ZMR at rate 10 (see the module's text)



def ring_deck(strength="", seed=0, end_time=8e-6, checkpoint_steps=0):
    """The ring's deck; `strength` holds the material's distribution parameters (study.strength_xml)."""
    return study.ring_xml(0.05, 0.00314159, CELLS, 0.001, 70.0, end_time, strength, seed, checkpoint_steps,
                          "damage, fragment_id, edge_strength")


UNIFORM = study.strength_xml("Uniform", 0.0)
WEIBULL = study.strength_xml("Weibull", 0.00314159)


def read_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


class Ring(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="shellfrac_ring_")

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def run_deck(self, name, text, np=None, extra=()):
        sub = os.path.join(self.dir, name)
        os.makedirs(sub, exist_ok=True)
        deck = os.path.join(sub, "ring.xml")
        with open(deck, "w") as f:
            f.write(text)
        r = launch([SHELLFRAC, *extra, deck], cwd=sub, np=np, timeout=600)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        return sub, r.stdout

    def axial_activations_by_step(self, sub):
        """{step: activated interfaces} of the crack log, and the log's rows."""
        head, rows = read_csv(os.path.join(sub, "ring_cracks.csv"))
        steps = {}
        for r in rows:
            steps[int(r[head.index("step")])] = steps.get(int(r[head.index("step")]), 0) + 1
        return steps, head, rows

    def summary_of(self, sub):
        """The run summary of the run in `sub`, checked against its history, crack log and fragment table; without
        the deck's path (which names the run's directory)."""
        with open(os.path.join(sub, "ring_summary.json")) as f:
            summary = json.load(f)
        head, rows = read_csv(os.path.join(sub, "ring_history.csv"))
        col = {name: head.index(name) for name in head}
        stored = ("kinetic_energy", "strain_energy", "penalty_energy", "damping_dissipation", "plastic_dissipation",
                  "cohesive_energy", "cohesive_dissipation", "activation_loss")
        first = rows[0]
        e0 = (sum(first[col[n]] for n in stored) - first[col["external_work"]] - first[col["reaction_work"]]
              - first[col["energy_balance_error"]])
        put_in = max(abs(e0) + abs(r[col["external_work"]]) + abs(r[col["reaction_work"]]) for r in rows)
        relative = max(abs(r[col["energy_balance_error"]]) for r in rows) / put_in
        self.assertAlmostEqual(summary["largest_energy_put_in"], put_in, delta=1e-12 * put_in)
        self.assertAlmostEqual(summary["largest_energy_balance_error"], relative, delta=1e-9 * relative)
        last = rows[-1]
        self.assertEqual(summary["activated_edges"], last[col["num_cohesive_edges"]])
        self.assertEqual(summary["separated_edges"], last[col["num_separated_edges"]])
        self.assertEqual(summary["fragments"], last[col["num_fragments"]])
        separated = [r[col["time"]] for r in rows if r[col["num_separated_edges"]] > 0]
        self.assertEqual(summary["first_separation_time"], separated[0] if separated else None)
        crack_head, cracks = read_csv(os.path.join(sub, "ring_cracks.csv"))
        self.assertEqual(summary["first_activation_time"], cracks[0][crack_head.index("time")] if cracks else None)
        frag_head, frames = read_csv(os.path.join(sub, "ring_fragments.csv"))
        pieces = [p for p in frames if p[0] == frames[-1][0]]  # the table of the last frame (the end of the run)
        mass = frag_head.index("mass")
        momentum = [frag_head.index(f"momentum_{c}") for c in "xyz"]
        speeds = [(p[mass], math.sqrt(sum(p[k] ** 2 for k in momentum)) / p[mass]) for p in pieces]
        heaviest = max(speeds, key=lambda ms: ms[0])
        fastest = max(speeds, key=lambda ms: ms[1])
        self.assertAlmostEqual(summary["largest_fragment"]["mass"], heaviest[0], delta=1e-12 * heaviest[0])
        self.assertAlmostEqual(summary["largest_fragment"]["speed"], heaviest[1], delta=1e-9 * heaviest[1])
        self.assertAlmostEqual(summary["fastest_fragment"]["speed"], fastest[1], delta=1e-9 * fastest[1])
        self.assertTrue(summary["fracture"])
        del summary["deck"]
        return summary

    def test_one_strength_activates_every_axial_edge_in_one_step(self):
        sub, _ = self.run_deck("constant", ring_deck())
        steps, _, _ = self.axial_activations_by_step(sub)
        first = min(steps)
        self.assertGreaterEqual(steps[first], CELLS, steps)

    def test_scattered_strength_spreads_the_activations(self):
        sub, out = self.run_deck("uniform", ring_deck(UNIFORM, seed=1))
        steps, head, rows = self.axial_activations_by_step(sub)
        first = min(steps)
        # The hoop stress rises by 2 % of sigma_c a step: the first step takes the edges within 2 % of the weakest
        # (about a tenth of them), the rest follow over the next steps.
        self.assertLessEqual(steps[first], CELLS // 5, steps)
        self.assertGreaterEqual(len(steps), 8, steps)
        strengths = [r[head.index("cohesive_strength")] for r in rows]
        self.assertGreaterEqual(min(strengths), 270e6)
        self.assertLessEqual(max(strengths), 330e6)
        self.assertIn("drawn with Fracture->Seed 1", out)
        # The first edges to break are the weakest ones loaded most: below the mean strength.
        self.assertLess(rows[0][head.index("cohesive_strength")], 300e6)

    def test_weibull_strengths_are_the_same_on_any_rank_count_and_through_a_restart(self):
        outputs = {}
        for np in (1, 2, 3):
            outputs[np], _ = self.run_deck(f"np{np}", ring_deck(WEIBULL, seed=5, checkpoint_steps=60), np=np)
        for suffix in ("_history.csv", "_cracks.csv", "_fragments.csv"):
            for np in (2, 3):
                self.assertTrue(filecmp.cmp(os.path.join(outputs[1], "ring" + suffix),
                                            os.path.join(outputs[np], "ring" + suffix), shallow=False),
                                f"ring{suffix} differs between 1 and {np} ranks")
        _, _, rows = self.axial_activations_by_step(outputs[1])
        self.assertGreater(len(rows), 10, "the ring must break")
        summary = self.summary_of(outputs[1])
        self.assertGreater(summary["fragments"], 1, summary)
        # the picture of the broken ring: by piece, with its legend (tools/plot_results.py)
        plot = subprocess.run(["/usr/bin/python3", os.path.join(SRC, "tools", "plot_results.py"),
                               os.path.join(outputs[3], "ring.exo")], capture_output=True, text=True, timeout=300)
        self.assertEqual(plot.returncode, 0, plot.stdout + plot.stderr)
        self.assertGreater(os.path.getsize(os.path.join(outputs[3], "ring.png")), 10000)
        # ... and in ParaView (tools/render.py), where it is installed: the pieces' legend in the declared units.
        if shutil.which("pvpython"):
            picture = os.path.join(outputs[3], "ring_render.png")
            render = subprocess.run(["/usr/bin/python3", os.path.join(SRC, "tools", "render.py"),
                                     os.path.join(outputs[3], "ring.exo"), "--field", "fragment_id", "-o", picture],
                                    capture_output=True, text=True, timeout=600)
            self.assertEqual(render.returncode, 0, render.stdout + render.stderr)
            self.assertIn("render.py: wrote %s (fragment_id, iso view, t = " % picture, render.stdout)
            self.assertGreater(os.path.getsize(picture), 10000)
        for np in (2, 3):
            self.assertEqual(self.summary_of(outputs[np]), summary, f"the run summary differs between 1 and {np} ranks")
        # Restart the 3-rank run's first checkpoint on 2 ranks in a copy of its directory.
        restart = os.path.join(self.dir, "restart")
        shutil.copytree(outputs[3], restart)
        checkpoint = sorted(glob.glob(os.path.join(restart, "ring_checkpoint_step*.h5")),
                            key=lambda p: int(p.rsplit("step", 1)[1][:-3]))[0]
        r = launch([SHELLFRAC, "--restart", checkpoint, os.path.join(restart, "ring.xml")], cwd=restart, np=2,
                   timeout=600)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        for suffix in ("_history.csv", "_cracks.csv", "_fragments.csv"):
            self.assertTrue(filecmp.cmp(os.path.join(outputs[1], "ring" + suffix),
                                        os.path.join(restart, "ring" + suffix), shallow=False),
                            f"ring{suffix} after the restart on 2 ranks differs from the uninterrupted run")
        self.assertEqual(self.summary_of(restart), summary, "the run summary after the restart differs")
        # Another seed: other flaws, other cracks.
        other, _ = self.run_deck("seed6", ring_deck(WEIBULL, seed=6))
        self.assertFalse(filecmp.cmp(os.path.join(outputs[1], "ring_cracks.csv"),
                                     os.path.join(other, "ring_cracks.csv"), shallow=False))


class FragmentSize(unittest.TestCase):
    def test_ring_at_rate_10_breaks_into_fragments_of_the_zmr_size(self):
        work = tempfile.mkdtemp(prefix="shellfrac_zmr_")
        try:
            row, _ = study.run_ring(SHELLFRAC, MPIEXEC, 2, 10.0, 1, 640, 40, "Weibull", 6, work)
        finally:
            shutil.rmtree(work, ignore_errors=True)
        print(f"rate 10: {row['fragments']:g} fragments, s/s_ZMR {row['s_over_zmr']:.3f}, last activation "
              f"{row['last_activation_t0']:.3g} t0, balance error {100 * row['balance_error_over_dissipation']:.3g} %")
        self.assertTrue(row["run_long_enough"], row)
        self.assertGreaterEqual(row["s_over_zmr"], BAND[0], row)
        self.assertLessEqual(row["s_over_zmr"], BAND[1], row)
        self.assertLessEqual(row["balance_error_over_dissipation"], 0.005, row)

    def test_ring_at_rate_100_keeps_its_energy_balance_at_two_time_steps(self):
        for safety in (0.8, 0.4):
            work = tempfile.mkdtemp(prefix="shellfrac_rate100_")
            try:
                row, _ = study.run_ring(SHELLFRAC, MPIEXEC, 2, 100.0, 1, 640, 40, "Weibull", 6, work, safety)
            finally:
                shutil.rmtree(work, ignore_errors=True)
            print(f"rate 100, safety factor {safety}: {row['fragments']:g} fragments, balance error "
                  f"{row['balance_error_over_dissipation']:.3g} of the dissipation, {row['balance_error_over_k0']:.3g} K0")
            self.assertLessEqual(row["balance_error_over_dissipation"], 0.005, row)
            self.assertLessEqual(row["balance_error_over_k0"], 1e-5, row)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
