#!/usr/bin/env python3
"""What rotary-inertia scaling and selective mass scaling change in a fuselage-like fracture run (docs/a319.md).

A closed cylinder of the A319's radius class (R = 2 m, L = 4 m, 40 x 126 cells of about 0.1 m, 10 080 TRI6) with
the skin data of the paper's Table 4 (E = 72 GPa, nu = 0.34, h = 1.5 mm, rho = 2700 kg/m^3, Resultant
Plasticity Y0 = 490 MPa, H = 933 MPa, sigma_c = 540 MPa) is loaded by the decompression pulse
p(t) = p0 exp(-t/tp)(1 - t/tp), p0 = 3.37 MPa, tp = 692 us, on a cylinder sector (22.5 to 135 degrees from the
vertical, x from 1 to 3 m). Each variant (a named set of Time Integration parameters) runs the same deck; the
table compares the step (s_I raises the director limit; the last variant doubles the step again by mass
scaling), the wall time, the deflection at the patch centre (a probe), the crack counts, the
fragments, the energies and the balance error against the unscaled reference (the first variant).

  /usr/bin/python3 tools/time_step_study.py -o /tmp/tss                 # the default variants, Gamma = 150 kJ/m^2
  /usr/bin/python3 tools/time_step_study.py -o /tmp/tss -g 3.2e6 -t 1e-3 -n 2

Writes <outdir>/study.csv and prints a Markdown table. As root, `source tools/mpi-env.sh` first (Open MPI).
"""
import argparse, csv, math, os, subprocess, sys, time

from shellfrac_tools import decks
from shellfrac_tools.launch import ENV, Launcher
from shellfrac_tools.tables import read_table

OUTPUT = """  <ParameterList name="Output">
    <Parameter name="Base Name" type="string" value="run"/>
    <Parameter name="Fields" type="Array(string)" value="{displ, damage, fragment_id}"/>
    <Parameter name="Probes" type="Array(string)" value="{centre}"/>
  </ParameterList>
"""

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_BINARY = os.path.join(ROOT, "build", "apps", "shellfrac", "shellfrac")

# name -> Time Integration parameters (besides End Time and History Interval)
VARIANTS = {
    "reference": {},
    "s_I = 4": {"Rotary Inertia Scale": 4.0},
    "s_I = 25": {"Rotary Inertia Scale": 25.0},
    # twice the step of the variant before it, by selective mass scaling (on this uniform mesh: every element)
    "s_I = 25, mass-scaled to 2x": {"Rotary Inertia Scale": 25.0, "Target Time Step": "2x", "Force Mass Scaling": True},
}

COLUMNS = ["variant", "dt_us", "steps", "wall_s", "us_per_elem_step", "added_mass_pct", "w_peak_mm", "w_end_mm",
           "t_first_crack_us", "cohesive_edges", "separated_edges", "fragments", "kinetic_J", "plastic_J",
           "cohesive_dissipation_J", "external_work_J", "balance_error_pct_of_work"]


def run_variant(args, name, params, previous_dt):
    folder = os.path.join(args.outdir, name.replace(" ", "").replace(",", "_").replace("=", ""))
    os.makedirs(folder, exist_ok=True)
    time_integration = {"End Time": args.end_time, "History Interval": args.history_interval,
                        "Output Interval": args.end_time}
    for key, value in params.items():
        time_integration[key] = 2.0 * previous_dt if value == "2x" else value
    theta = math.radians(0.5 * (22.5 + 135.0))  # the patch centre: counter-clockwise about +x from +z
    centre = decks.sublist_xml("centre", {"Shape": "Sphere", "Center": (2.0, -2.0 * math.sin(theta),
                                                                        2.0 * math.cos(theta)), "Radius": 0.03}, 4)
    deck = decks.torn_cylinder(
        radius=2.0, length=4.0, axial=40, circumferential=126,
        material={"Density": 2700.0, "Young's Modulus": 72e9, "Poisson's Ratio": 0.34,
                  "Model": "Resultant Plasticity", "Yield Stress": 490e6, "Hardening Modulus": 933e6,
                  "Cohesive Strength": 540e6, "Fracture Energy": args.gamma},
        time_integration=time_integration, regions=centre,
        output=OUTPUT)
    with open(os.path.join(folder, "run.xml"), "w") as f:
        f.write(deck)
    command = Launcher("mpirun").command([args.binary, "run.xml"], np=args.ranks if args.ranks > 1 else None)
    start = time.time()
    with open(os.path.join(folder, "run.log"), "w") as log:
        rc = subprocess.call(command, cwd=folder, stdout=log, stderr=subprocess.STDOUT, env=ENV)
    wall = time.time() - start
    text = open(os.path.join(folder, "run.log")).read()
    if rc != 0:
        sys.exit("%s: shellfrac failed (exit %d), see %s" % (name, rc, os.path.join(folder, "run.log")))
    added = 0.0
    for line in text.splitlines():  # "mass scaling: ... added mass 0.0326 = 1.23 % of 2.65; ..."
        if "added mass" in line and "%" in line:
            added = float(line.split("=")[1].split("%")[0])
    h = read_table(os.path.join(folder, "run_history.csv"))
    rows = [dict(zip(h, values)) for values in zip(*h.values())]
    radial = [math.hypot(r["centre_displ_y"], r["centre_displ_z"]) for r in rows]  # the probe's motion in y-z
    first_crack = next((r["time"] for r in rows if r["num_cohesive_edges"] > 0), float("nan"))
    last = rows[-1]
    elements = 40 * 126 * 2
    return {
        "variant": name, "dt_us": 1e6 * last["dt"], "steps": int(last["step"]), "wall_s": wall,
        "us_per_elem_step": 1e6 * wall / (elements * max(1, last["step"])), "added_mass_pct": added,
        "w_peak_mm": 1e3 * max(radial), "w_end_mm": 1e3 * radial[-1], "t_first_crack_us": 1e6 * first_crack,
        "cohesive_edges": int(last["num_cohesive_edges"]), "separated_edges": int(last["num_separated_edges"]),
        "fragments": int(last["num_fragments"]), "kinetic_J": last["kinetic_energy"],
        "plastic_J": last["plastic_dissipation"], "cohesive_dissipation_J": last["cohesive_dissipation"],
        "external_work_J": last["external_work"],
        "balance_error_pct_of_work": 100 * last["energy_balance_error"] / max(1e-300, last["external_work"]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--outdir", required=True)
    ap.add_argument("-g", "--gamma", type=float, default=150e3, help="Fracture Energy [J/m^2] (default 150e3)")
    ap.add_argument("-t", "--end-time", type=float, default=6e-4)
    ap.add_argument("--history-interval", type=int, default=20)
    ap.add_argument("-n", "--ranks", type=int, default=2)
    ap.add_argument("-b", "--binary", default=DEFAULT_BINARY)
    ap.add_argument("--variants", nargs="*", default=list(VARIANTS), help="names from: " + ", ".join(VARIANTS))
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    results, previous_dt = [], 0.0
    for name in args.variants:
        r = run_variant(args, name, VARIANTS[name], previous_dt)
        previous_dt = 1e-6 * r["dt_us"]
        results.append(r)
        print("%s: done in %.0f s" % (name, r["wall_s"]), file=sys.stderr)
    with open(os.path.join(args.outdir, "study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(results)
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for r in results:
        print("| " + " | ".join(("%.4g" % r[c]) if isinstance(r[c], float) else str(r[c]) for c in COLUMNS) + " |")


if __name__ == "__main__":
    main()
