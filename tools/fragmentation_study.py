#!/usr/bin/python3
"""Fragmentation of an expanding ring against the theories of dynamic fragmentation (docs/fragmentation.md).

A thin ring (a tube one cell long, nu = 0 so that its membrane wave speed is c = sqrt(E/rho)) is launched
outwards at the speed V = eps_dot R and breaks on its axial edges; each edge draws its strength from a
distribution (docs/theory.md §9.8). In the normalisation of Zhou, Molinari & Ramesh (Int. J. Impact Eng. 31,
2005; 33, 2006):
  s0 = E Gamma / sigma_c^2,   t0 = s0 / c,   eps0 = c sigma_c^3 / (E^2 Gamma),   rate = eps_dot / eps0,
and the mean fragment length s = circumference / count, normalised by s0, is compared with
  Grady (1982) energy balance:             s/s0 = (24 / rate^2)^(1/3)
  Glenn & Chudnovsky (1986):               s/s0 = (4 / rate) sinh( asinh(1.5 rate) / 3 )
  Zhou, Molinari & Ramesh (2006) fit:      s/s0 = 4.5 / (1 + 4.5 rate^(2/3))
The ring of each rate is sized to hold about --fragments ZMR fragments on --cells cells (so the mesh resolves
every fragment by cells / fragments elements, 16 by default), its thickness is R/50.

The count's time: fragments are pieces separated by fully broken edges; the count is taken 2 t0 after the last
activation of the run (the run lasts t0/rate + --duration t0; the tool checks that the last activation came at
least 2 t0 before the end, else it says so). The history of the count is kept in the CSV.

usage: fragmentation_study.py SHELLFRAC [--rates 1 3 10 30 100] [--seeds 1 2 3] [--cells 640] [--np 2]
                              [--distribution Weibull|Uniform] [--safety-factor 0.8] [-o fragmentation]
                              [--mpiexec mpiexec]
writes <o>.csv (one row per run), <o>_history.csv (count against time for every run) and <o>.png.
       fragmentation_study.py --combine A.csv B.csv ... [-o fragmentation]
writes the rows of earlier studies (e.g. two meshes) into one <o>.csv and one figure <o>.png.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

E, RHO, SIGMA_C, GAMMA = 70.0e9, 2700.0, 300.0e6, 10.0e3
C = math.sqrt(E / RHO)
S0 = E * GAMMA / SIGMA_C ** 2
T0 = S0 / C
EPS0 = C * SIGMA_C ** 3 / (E ** 2 * GAMMA)


def grady(rate):
    return (24.0 / rate ** 2) ** (1.0 / 3.0)


def glenn_chudnovsky(rate):
    return 4.0 / rate * math.sinh(math.asinh(1.5 * rate) / 3.0)


def zmr(rate):
    return 4.5 / (1.0 + 4.5 * rate ** (2.0 / 3.0))


def strength_xml(distribution, reference_length):
    """The material's strength-distribution parameters: Weibull m = 12 with the given reference length, or
    Uniform +-10 %."""
    if distribution == "Weibull":
        return ('<Parameter name="Strength Distribution" type="string" value="Weibull"/>'
                '<Parameter name="Weibull Modulus" type="double" value="12.0"/>'
                f'<Parameter name="Weibull Reference Length" type="double" value="{reference_length:.17g}"/>')
    if distribution == "Uniform":
        return ('<Parameter name="Strength Distribution" type="string" value="Uniform"/>'
                '<Parameter name="Strength Spread" type="double" value="0.1"/>')
    return ""  # Constant


def ring_xml(radius, length, cells, thickness, speed, end_time, strength="", seed=0, checkpoint_steps=0,
             fields="fragment_id", safety_factor=0.8):
    """A ring (a tube of one cell along its axis) of the study's material launched outward at `speed`, every edge
    breakable; `strength` holds the material's distribution parameters (strength_xml); the time step is
    `safety_factor` times the stable estimate (0.8, shellfrac's default)."""
    return f"""<ParameterList name="shellfrac">
  <ParameterList name="Mesh">
    <Parameter name="Source" type="string" value="Cylinder"/>
    <ParameterList name="Cylinder">
      <Parameter name="Radius" type="double" value="{radius:.17g}"/>
      <Parameter name="Length" type="double" value="{length:.17g}"/>
      <Parameter name="Axial Elements" type="int" value="1"/>
      <Parameter name="Circumferential Elements" type="int" value="{cells}"/>
      <Parameter name="Block Name" type="string" value="ring"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Blocks">
    <ParameterList name="ring">
      <Parameter name="Thickness" type="double" value="{thickness:.17g}"/>
      <Parameter name="Material" type="string" value="m"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="m">
      <Parameter name="Density" type="double" value="{RHO}"/>
      <Parameter name="Young's Modulus" type="double" value="{E}"/>
      <Parameter name="Poisson's Ratio" type="double" value="0.0"/>
      <Parameter name="Cohesive Strength" type="double" value="{SIGMA_C}"/>
      <Parameter name="Fracture Energy" type="double" value="{GAMMA}"/>
      {strength}
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <ParameterList name="launch">
      <Parameter name="Normal Velocity" type="double" value="{speed:.17g}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Fracture">
    <Parameter name="Seed" type="int" value="{seed}"/>
  </ParameterList>
  <ParameterList name="Time Integration">
    <Parameter name="End Time" type="double" value="{end_time:.17g}"/>
    <Parameter name="Safety Factor" type="double" value="{safety_factor:.17g}"/>
    <Parameter name="Output Interval" type="double" value="0"/>
  </ParameterList>
  <ParameterList name="Checkpoint">
    <Parameter name="Step Interval" type="int" value="{checkpoint_steps}"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="Progress Interval" type="double" value="0"/>
    <Parameter name="Fields" type="Array(string)" value="{{{fields}}}"/>
  </ParameterList>
</ParameterList>
"""


def ring_deck(rate, seed, cells, fragments, distribution, duration, safety_factor=0.8):
    """The study's ring at `rate` and its geometry (circumference, end time)."""
    circumference = fragments * zmr(rate) * S0
    radius = circumference / (2 * math.pi)
    edge = circumference / cells
    end_time = T0 / rate + duration * T0
    deck = ring_xml(radius, edge, cells, radius / 50, rate * EPS0 * radius, end_time,
                    strength_xml(distribution, edge), seed, safety_factor=safety_factor)
    return deck, circumference, end_time


def read_table(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head = rows[0]
    return {name: [float(r[k]) for r in rows[1:]] for k, name in enumerate(head)}


def count_at_rest(history, cracks, end_time):
    """(count, time of the count, last activation, whether the run lasted long enough), and the count history."""
    last = max(cracks["time"]) if cracks.get("time") else 0.0
    t_count = last + 2 * T0
    long_enough = t_count <= end_time * (1 + 1e-9)
    times, counts = history["time"], history["num_fragments"]
    pick = len(times) - 1
    for k, t in enumerate(times):
        if t >= t_count:
            pick = k
            break
    return counts[pick], times[pick], last, long_enough, list(zip(times, counts))


def run_ring(shellfrac, mpiexec, np, rate, seed, cells, fragments, distribution, duration, workdir, safety_factor=0.8):
    deck, circumference, end_time = ring_deck(rate, seed, cells, fragments, distribution, duration, safety_factor)
    sub = os.path.join(workdir, f"ring_r{rate:g}_c{cells}_s{seed}_sf{safety_factor:g}")
    os.makedirs(sub, exist_ok=True)
    with open(os.path.join(sub, "ring.xml"), "w") as f:
        f.write(deck)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ([mpiexec, "-np", str(np), "--oversubscribe"] if np > 1 else []) + [shellfrac, "ring.xml"]
    r = subprocess.run(cmd, cwd=sub, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"fragmentation_study.py: the ring at rate {rate} seed {seed} failed:\n{r.stdout}{r.stderr}")
    history = read_table(os.path.join(sub, "ring_history.csv"))
    cracks = read_table(os.path.join(sub, "ring_cracks.csv"))
    count, t_count, last, long_enough, counts = count_at_rest(history, cracks, end_time)
    k0 = history["kinetic_energy"][0]
    dissipation = history["cohesive_dissipation"][-1]
    worst = max(abs(e) for e in history["energy_balance_error"])
    row = {"rate": rate, "seed": seed, "cells": cells, "distribution": distribution, "safety_factor": safety_factor,
           "circumference": circumference, "fragments": count, "count_time_t0": t_count / T0,
           "last_activation_t0": last / T0, "run_long_enough": int(long_enough),
           "activated_edges": len(cracks["time"]) if cracks.get("time") else 0,
           "s_over_s0": circumference / max(count, 1) / S0, "zmr": zmr(rate), "grady": grady(rate),
           "glenn_chudnovsky": glenn_chudnovsky(rate), "balance_error_over_k0": worst / k0,
           "balance_error_over_dissipation": worst / dissipation if dissipation > 0 else float("nan")}
    row["s_over_zmr"] = row["s_over_s0"] / row["zmr"]
    return row, [(rate, seed, cells, t / T0, n) for t, n in counts]


def trusted_run(row):
    """A run whose count is taken at its defined time and whose energy balance closes to 0.5 % of the dissipation."""
    return bool(row["run_long_enough"]) and row["balance_error_over_dissipation"] <= 0.005


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(figsize=(7, 5))
    r = np.logspace(-0.3, 2.3, 200)
    ax.loglog(r, [grady(x) for x in r], "k--", label="Grady (1982)")
    ax.loglog(r, [glenn_chudnovsky(x) for x in r], "k:", label="Glenn & Chudnovsky (1986)")
    ax.loglog(r, [zmr(x) for x in r], "k-", label="Zhou, Molinari & Ramesh (2006)")
    colours = {}
    for row in rows:
        colours.setdefault(row["cells"], f"C{len(colours)}")
    for cells, colour in colours.items():
        for trusted in (True, False):
            sel = [row for row in rows if row["cells"] == cells and trusted_run(row) == trusted]
            if not sel:
                continue
            label = f"shellfrac, {cells:g} cells per ring" + ("" if trusted else
                                                          " (balance error > 0.5 % of dissipation or count late)")
            ax.loglog([row["rate"] for row in sel], [row["s_over_s0"] for row in sel], "o",
                      color=colour, mfc=colour if trusted else "none", label=label)
    ax.set_xlabel(r"normalised strain rate $\dot\varepsilon/\dot\varepsilon_0$, $\dot\varepsilon_0 = c\sigma_c^3/(E^2\Gamma)$")
    ax.set_ylabel(r"mean fragment length $s/s_0$, $s_0 = E\Gamma/\sigma_c^2$")
    ax.set_title("Expanding ring: fragment size against strain rate")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def write_rows(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def read_rows(path):
    """The rows of a study's CSV, numbers as floats."""
    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    try:
        with open(path, newline="") as f:
            rows = [{k: value(v) for k, v in row.items()} for row in csv.DictReader(f)]
    except OSError as e:
        sys.exit(f"fragmentation_study.py: {path}: {e.strerror}")
    if not rows or "s_over_s0" not in rows[0]:
        sys.exit(f"fragmentation_study.py: {path}: not a table written by this tool (no s_over_s0 column)")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("shellfrac", nargs="?")
    ap.add_argument("--combine", nargs="+", metavar="CSV", help="combine the rows of earlier studies; run nothing")
    ap.add_argument("--rates", type=float, nargs="+", default=[1, 3, 10, 30, 100])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--cells", type=int, nargs="+", default=[640])
    ap.add_argument("--fragments", type=float, default=40, help="ZMR fragments the ring is sized for")
    ap.add_argument("--duration", type=float, default=6, help="run length after the first activation [t0]")
    ap.add_argument("--distribution", choices=["Weibull", "Uniform"], default="Weibull")
    ap.add_argument("--safety-factor", type=float, default=0.8,
                    help="time step / stable estimate (0.8 is shellfrac's default; 0.4 halves the step)")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--mpiexec", default="mpiexec")
    ap.add_argument("-o", "--output", default="fragmentation")
    a = ap.parse_args()
    if a.combine:
        rows = [row for path in a.combine for row in read_rows(path)]
        write_rows(rows, a.output + ".csv")
        plot(rows, a.output + ".png")
        print(f"wrote {a.output}.csv, {a.output}.png")
        return
    if a.shellfrac is None:
        ap.error("SHELLFRAC (the program) or --combine is needed")
    if not os.path.isfile(a.shellfrac):
        sys.exit(f"fragmentation_study.py: {a.shellfrac}: no such program")
    workdir = tempfile.mkdtemp(prefix="shellfrac_fragmentation_")
    rows, history = [], []
    try:
        for cells in a.cells:
            for rate in a.rates:
                for seed in a.seeds:
                    row, h = run_ring(os.path.abspath(a.shellfrac), a.mpiexec, a.np, rate, seed, cells, a.fragments,
                                      a.distribution, a.duration, workdir, a.safety_factor)
                    rows.append(row)
                    history += h
                    print(f"rate {rate:g} cells {cells} seed {seed}: {row['fragments']:g} fragments, s/s0 "
                          f"{row['s_over_s0']:.4g} (ZMR {row['zmr']:.4g}, ratio {row['s_over_zmr']:.3f}), last "
                          f"activation {row['last_activation_t0']:.3g} t0, balance error "
                          f"{100 * row['balance_error_over_dissipation']:.3g} % of the dissipation"
                          + ("" if row["run_long_enough"] else "  [the run ended before the count's time]"),
                          flush=True)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    write_rows(rows, a.output + ".csv")
    with open(a.output + "_history.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["rate", "seed", "cells", "time_t0", "fragments"])
        w.writerows(history)
    plot(rows, a.output + ".png")
    print(f"wrote {a.output}.csv, {a.output}_history.csv, {a.output}.png")


if __name__ == "__main__":
    main()
