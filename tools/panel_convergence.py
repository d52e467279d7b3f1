#!/usr/bin/python3
"""Mesh convergence of the impulsively loaded cylindrical panel (xml/cylindrical_panel.xml, paper §6.1).

usage: panel_convergence.py [--out DIR] [--np N] [--levels 0 1 2]

For each level L of Mesh->Uniform Refinements (6 x 16 cells on the half model times 2^L in each direction),
writes DIR/panel_L<L>.xml (a copy of the deck with an absolute mesh path, the refinement level and
Output->Directory = DIR), runs shellfrac on N ranks (log: DIR/panel_L<L>.log), and reads the history
DIR/panel_L<L>_history.csv. Writes DIR/panel_convergence.png (centre deflection histories) and a Markdown
table to stdout and DIR/panel_convergence.md.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

from plot_history import plot_histories
from shellfrac_tools.tables import column, read_table

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "xml", "cylindrical_panel.xml")
BINARY = os.path.join(ROOT, "build", "apps", "shellfrac", "shellfrac")
MPI_ENV = os.path.join(ROOT, "tools", "mpi-env.sh")
TIMES_MS = [0.2, 0.4, 0.6, 0.8, 1.0]
# 1/2 rho h A V0^2 for the half patch (30 deg of arc x 10.205 in): the exact initial kinetic energy.
RHO, H, R, A_AX, V0 = 2.5e-4, 0.125, 2.9375, 10.205, 5650.0
KE_EXACT = 0.5 * RHO * H * (R * math.pi / 6.0) * A_AX * V0**2


def substitute(text, pattern, repl, what):
    new, n = re.subn(pattern, repl, text)
    if n != 1:
        sys.exit(f"panel_convergence.py: {DECK}: expected one {what}, found {n}")
    return new


def write_deck(level, out_dir):
    with open(DECK) as f:
        text = f.read()
    mesh_dir = os.path.join(os.path.dirname(DECK), "meshes") + "/"
    text = substitute(text, r'value="meshes/', f'value="{mesh_dir}', "relative mesh path")
    text = substitute(text, r'(<Parameter name="Uniform Refinements" type="int" value=")\d+("/>)',
                      rf"\g<1>{level}\g<2>", "Uniform Refinements parameter")
    base = f"panel_L{level}"
    text = substitute(text, r'(<ParameterList name="Output">\n)',
                      rf'\g<1>    <Parameter name="Directory" type="string" value="{out_dir}"/>\n'
                      rf'    <Parameter name="Base Name" type="string" value="{base}"/>\n',
                      "Output list")
    text = (f"<!-- Written by tools/panel_convergence.py from xml/cylindrical_panel.xml: "
            f"Uniform Refinements = {level}, absolute mesh path, Output to {out_dir}. -->\n" + text)
    deck = os.path.join(out_dir, base + ".xml")
    with open(deck, "w") as f:
        f.write(text)
    return deck, base


def run(deck, base, out_dir, np_ranks):
    cmd = ["mpiexec"] + (["--oversubscribe"] if np_ranks > 2 else []) + ["-np", str(np_ranks), BINARY, deck]
    log = os.path.join(out_dir, base + ".log")
    print(f"running {' '.join(cmd)} (log {log})", file=sys.stderr, flush=True)
    t0 = time.perf_counter()
    p = subprocess.run(["bash", "-c", 'source "$0" && exec "$@"', MPI_ENV] + cmd, cwd=out_dir,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - t0
    with open(log, "w") as f:
        f.write(p.stdout)
    if p.returncode != 0:
        sys.stderr.write(p.stdout[-3000:])
        sys.exit(f"panel_convergence.py: shellfrac failed (exit {p.returncode}) for {deck}")
    m = re.search(r"mesh: (\d+) \w+ elements", p.stdout)
    return wall, int(m.group(1)) if m else -1


def measures(hist_path):
    h = read_table(hist_path)
    t, w = column(h, "time", hist_path), column(h, "centre_displ_z", hist_path)
    ke = column(h, "kinetic_energy", hist_path)
    ke0 = ke[0]
    ipk = int(np.argmax(np.abs(w)))
    return {
        "w": [float(np.interp(tm * 1e-3, t, w, right=np.nan)) for tm in TIMES_MS],
        "peak": abs(w[ipk]), "t_peak": t[ipk] * 1e3, "ke0": ke0,
        "ebe": np.max(np.abs(column(h, "energy_balance_error", hist_path))) / ke0,
        "wp": column(h, "plastic_dissipation", hist_path)[-1] / ke0,
        "steps": int(column(h, "step", hist_path)[-1]), "t_end": t[-1],
    }


def table(rows):
    head = (["mesh (half model)", "elements"] + [f"w({tm:g} ms) [in]" for tm in TIMES_MS]
            + ["peak \\|w\\| [in] (at ms)", "KE0 [lbf·in]", "KE0 / ½ρhAV0²", "max \\|E_err\\| / KE0",
               "W_p(end) / KE0", "steps", "wall [s]"])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        m = r["m"]
        cells = ([r["mesh"], str(r["elements"])] + [f"{x:.4f}" for x in m["w"]]
                 + [f"{m['peak']:.4f} ({m['t_peak']:.3f})", f"{m['ke0']:.4g}", f"{m['ke0'] / KE_EXACT:.4f}",
                    f"{m['ebe']:.2e}", f"{m['wp']:.4f}", str(m["steps"]), f"{r['wall']:.1f}"])
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"½ρhAV0² (half patch, A = {R * math.pi / 6:.4f} in × {A_AX} in) = {KE_EXACT:.4g} lbf·in. "
                 "w = centre_displ_z (negative = downward), linearly interpolated in time.")
    if len(rows) > 1:
        lines += ["", "Change of w between successive meshes [in]:", "",
                  "| meshes | " + " | ".join(f"Δw({tm:g} ms)" for tm in TIMES_MS) + " | Δ peak \\|w\\| |",
                  "|" + "---|" * (len(TIMES_MS) + 2)]
        for a, b in zip(rows, rows[1:]):
            d = [y - x for x, y in zip(a["m"]["w"], b["m"]["w"])]
            lines.append(f"| {a['mesh']} → {b['mesh']} | " + " | ".join(f"{x:+.4f}" for x in d)
                         + f" | {b['m']['peak'] - a['m']['peak']:+.4f} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "panel_convergence"),
                    help="output directory (default: results/panel_convergence of the project)")
    ap.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2], help="uniform refinement levels")
    a = ap.parse_args()
    out_dir = os.path.abspath(a.out)
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for level in a.levels:
        deck, base = write_deck(level, out_dir)
        wall, elements = run(deck, base, out_dir, a.np)
        hist = os.path.join(out_dir, base + "_history.csv")
        n = 2**level
        rows.append({"mesh": f"{6 * n} × {16 * n}", "elements": elements, "wall": wall, "hist": hist,
                     "m": measures(hist)})
        print(f"  level {level}: {elements} elements, wall {wall:.1f} s", file=sys.stderr, flush=True)
    md = table(rows) + f"\nRun with {a.np} MPI rank(s): tools/panel_convergence.py --np {a.np} --levels " \
        + " ".join(map(str, a.levels)) + "\n"
    sys.stdout.write(md)
    with open(os.path.join(out_dir, "panel_convergence.md"), "w") as f:
        f.write(md)
    png = os.path.join(out_dir, "panel_convergence.png")
    plot_histories([r["hist"] for r in rows], "centre_displ_z", png,
                   labels=[f"{r['mesh']} cells ({r['elements']} TRI6)" for r in rows], time_scale=1e3,
                   time_unit="ms", ylabel="centre deflection w [in]",
                   title="Cylindrical panel (half model): centre deflection")
    print(f"wrote {png} and {os.path.join(out_dir, 'panel_convergence.md')}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
