#!/usr/bin/python3
"""Initial-velocity sweep of the clamped 6061-T6 beam-blast case (paper §6.3, docs/verification.md §2).

For each V0 this writes a Gmsh mesh (the Rectangle generator's 'Alternating' mesh, plus a node set
'centre' on the line x = L/2 for a probe) and a deck, runs shellfrac serially, and reports the first
activation time, the centre deflection then, the broken edges' distance from the nearer support, and
the plastic strain there. Writes <outdir>/sweep.csv and prints a Markdown table.

Columns: t_act/w_act = time and |centre deflection| of the first activation (history, every step);
t_last_act/w_last_act = the same for the last one; where_first/dist_first_mm = centroid distances from
the nearer support of the elements damaged at the first Exodus output with damage ('supports' = within
15 mm or 2 cells); where_end/dist_end_mm = the same at the last output; eps_p_frame = max plastic strain
of those elements at that first output (t_frame); v_centre_end = downward centre velocity at the end
(about V0: the beam has come off the supports).

Regime of a run (column `regime`, from the crack log <name>_cracks.csv): I = no edge broke; otherwise the
mode of the first activation step (`mode_first`), from the mean shares of the terms of n_eq^2 over the edges
that activated in that step: 'shear' (transverse sliding, the shear-off term) when it is the largest of
{in-plane (normal + in-plane sliding), transverse sliding, couples}, giving regime III; else regime II.
With --thresholds the grid is refined by bisection where the regime changes (to --tol), and the two
thresholds (I->II, II->III) are printed and, with --doc, written as a Markdown section.

  /usr/bin/python3 tools/beam_blast_sweep.py -v 40:240:20 -c 40x5 -t 1e-3 -o /tmp/blast_sweep
  /usr/bin/python3 tools/beam_blast_sweep.py -v 62 101 225 -c 80x10 -t 2e-4 -o /tmp/b --alpha1 2
  /usr/bin/python3 tools/beam_blast_sweep.py -v 40:240:20 -c 40x5 -t 4e-4 -o /tmp/b --shear-yield \
      --alpha1 0.5773502691896258 --thresholds --doc docs/beam_blast_thresholds.md
"""
import argparse, csv, os, subprocess, sys
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
L, W, H, RHO, SIGC, E, NU = 0.2, 0.025, 6.53e-3, 2693.0, 375e6, 68.9e9, 0.343

COLUMNS = ["V0", "mesh", "alpha1", "shear_yield", "fixture", "regime", "mode_first", "share_inplane",
           "share_transverse", "t_act_us", "w_act_mm", "where_first", "dist_first_mm", "t_last_act_us",
           "w_last_act_mm", "n_act_events", "n_sep", "n_frag", "where_end", "dist_end_mm", "w_max_mm",
           "v_centre_end", "t_frame_us", "eps_p_frame", "W_p_J", "rel_energy_err", "t_end_us", "rc"]

DECK = """<ParameterList name="shellfrac">
  <ParameterList name="Mesh">
    <Parameter name="Source" type="string" value="File"/>
    <Parameter name="File" type="string" value="{mesh}"/>
  </ParameterList>
  <ParameterList name="Blocks"><ParameterList name="beam">
    <Parameter name="Thickness" type="double" value="{h}"/>
    <Parameter name="Material" type="string" value="6061-T6"/>
  </ParameterList>{clamp_block}</ParameterList>
  <ParameterList name="Materials"><ParameterList name="6061-T6">
    <Parameter name="Model" type="string" value="Resultant Plasticity"/>
    <Parameter name="Density" type="double" value="{rho}"/>
    <Parameter name="Young's Modulus" type="double" value="{E}"/>
    <Parameter name="Poisson's Ratio" type="double" value="{nu}"/>
    <Parameter name="Yield Stress" type="double" value="275e6"/>
    <Parameter name="Hardening Modulus" type="double" value="1.33e9"/>
    <Parameter name="Shear Yield" type="bool" value="{shear_yield}"/>
    <Parameter name="Cohesive Strength" type="double" value="{sigc}"/>
    <Parameter name="Fracture Energy" type="double" value="0"/>
  </ParameterList></ParameterList>
  <ParameterList name="Fracture">
    <Parameter name="Alpha 1" type="double" value="{alpha1}"/>
  </ParameterList>
  <ParameterList name="Time Integration">
    <Parameter name="End Time" type="double" value="{tend}"/>
    <Parameter name="History Interval" type="int" value="1"/>
    <Parameter name="Output Interval" type="double" value="{dtout}"/>
  </ParameterList>
  <ParameterList name="Boundary Conditions">{bcs}
  </ParameterList>
  <ParameterList name="Initial Conditions"><ParameterList name="impulse">
    <Parameter name="Elements" type="string" value="beam"/>
    <Parameter name="Velocity" type="Array(double)" value="{{0.0, 0.0, {vz}}}"/>
  </ParameterList></ParameterList>
  <ParameterList name="Output">
    <Parameter name="Base Name" type="string" value="{name}"/>
    <Parameter name="Probes" type="Array(string)" value="{{centre}}"/>
  </ParameterList>
</ParameterList>
"""


def write_mesh(path, nx, ny, nc=0):
    """Gmsh 2.2: nx x ny cells over the span, chessboard diagonals, curves x_min/x_max (x = 0, L), point set
    centre (x = L/2). nc > 0: nc more columns of cells on each side (x < 0 and x > L) in block 'clamps': the
    fixture, held through its elements only (Node Set = all, Elements = clamps), so that the edges at x = 0 and
    x = L are interior edges that can break."""
    dx, nt = L / nx, nx + 2 * nc
    tag = lambda i, j: j * (nt + 1) + i + 1          # i = 0 .. nt (x = (i - nc) dx)
    nodes = [f"{tag(i, j)} {(i - nc) * dx:.16g} {j * W / ny:.16g} 0" for j in range(ny + 1) for i in range(nt + 1)]
    lines = []
    for j in range(ny):
        for i in range(nt):
            a, b, c, d = tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)
            g = 1 if nc <= i < nc + nx else 5
            for t in ([[a, b, c], [a, c, d]] if (i - nc + j) % 2 == 0 else [[a, b, d], [b, c, d]]):
                lines.append(f"2 2 {g} {g} {' '.join(map(str, t))}")
    lines += [f"1 2 {g} {g} {tag(i, j)} {tag(i, j + 1)}" for g, i in ((2, nc), (3, nc + nx)) for j in range(ny)]
    lines += [f"15 2 4 4 {tag(nc + nx // 2, j)}" for j in range(ny + 1)]
    names = ['2 1 "beam"', '1 2 "x_min"', '1 3 "x_max"', '0 4 "centre"'] + (['2 5 "clamps"'] if nc else [])
    with open(path, "w") as f:
        f.write(f"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n{len(names)}\n" + "\n".join(names)
                + "\n$EndPhysicalNames\n")
        f.write(f"$Nodes\n{len(nodes)}\n" + "\n".join(nodes) + "\n$EndNodes\n")
        f.write(f"$Elements\n{len(lines)}\n" + "\n".join(f"{k + 1} {s}" for k, s in enumerate(lines))
                + "\n$EndElements\n")


BCS_EDGES = """
    <ParameterList name="left"><Parameter name="Type" type="string" value="Clamped"/>
      <Parameter name="Node Set" type="string" value="x_min"/></ParameterList>
    <ParameterList name="right"><Parameter name="Type" type="string" value="Clamped"/>
      <Parameter name="Node Set" type="string" value="x_max"/></ParameterList>"""
BCS_FIXTURE = """
    <ParameterList name="fixture"><Parameter name="Type" type="string" value="Clamped"/>
      <Parameter name="Node Set" type="string" value="all"/>
      <Parameter name="Elements" type="string" value="clamps"/></ParameterList>"""
CLAMP_BLOCK = """<ParameterList name="clamps">
    <Parameter name="Thickness" type="double" value="{h}"/>
    <Parameter name="Material" type="string" value="6061-T6"/>
  </ParameterList>"""


def damage_info(exo, nx):
    """Damaged elements (Gamma = 0: damage = 1 once an edge of the element is activated) at the first
    output with damage and at the last output: distances [mm] of their centroids from the nearer support,
    and their max eq. plastic strain at that first output (time t_frame)."""
    from shellfrac_tools.exodus import ExodusFile
    with ExodusFile(exo) as d:
        block, conn = d.blocks()[0]
        dam, eps, t = d.element("damage", block), d.element("eq_plastic_strain", block), d.times()
        xc = d.coordinates()[:, 0][conn[:, :3]].mean(axis=1)
    hit = np.nonzero((dam > 0).any(axis=1))[0]
    if not len(hit):
        return {}
    dist = np.minimum(xc, L - xc) * 1e3
    near = max(15.0, 2 * L / nx * 1e3)          # "at the supports": within 15 mm (2.3 h) or 2 cells
    e0, e1 = np.nonzero(dam[hit[0]] > 0)[0], np.nonzero(dam[-1] > 0)[0]
    where = lambda d: "supports" if d.max() <= near else ("elsewhere" if d.min() > near else "both")
    dlist = lambda d: " ".join(f"{v:.1f}" for v in np.unique(np.round(d, 1)))
    return dict(where_first=where(dist[e0]), dist_first_mm=dlist(dist[e0]), t_frame_us=t[hit[0]] * 1e6,
                eps_p_frame=float(eps[hit[0], e0].max()), where_end=where(dist[e1]), dist_end_mm=dlist(dist[e1]))


def run_one(v0, nx, ny, tend, outdir, binary, alpha1, dtout, shear_yield, nc):
    name = (f"v{v0:g}_{nx}x{ny}" + ("" if alpha1 == 1 else f"_a{alpha1:g}") + ("_sy" if shear_yield else "")
            + (f"_fix{nc}" if nc else ""))
    mesh = os.path.join(outdir, f"beam_{nx}x{ny}" + (f"_fix{nc}" if nc else "") + ".msh")
    if not os.path.exists(mesh):
        write_mesh(mesh, nx, ny, nc)
    deck = os.path.join(outdir, name + ".xml")
    with open(deck, "w") as f:
        f.write(DECK.format(mesh=os.path.basename(mesh), h=H, rho=RHO, E=E, nu=NU, sigc=SIGC, alpha1=alpha1, tend=tend,
                            dtout=dtout, vz=-v0, name=name, shear_yield="true" if shear_yield else "false",
                            clamp_block=CLAMP_BLOCK.format(h=H) if nc else "", bcs=BCS_FIXTURE if nc else BCS_EDGES))
    with open(os.path.join(outdir, name + ".log"), "w") as log:
        rc = subprocess.run([binary, deck], cwd=outdir, stdout=log, stderr=subprocess.STDOUT,
                            env=dict(os.environ, OMP_NUM_THREADS="1")).returncode
    row = dict(V0=v0, mesh=f"{nx}x{ny}", alpha1=alpha1, shear_yield=int(shear_yield), fixture=nc, rc=rc)
    try:
        hist = np.genfromtxt(os.path.join(outdir, name + "_history.csv"), delimiter=",", names=True)
    except OSError:
        return row
    t, w, ncoh = hist["time"], np.abs(hist["centre_displ_z"]), hist["num_cohesive_edges"]
    act = np.nonzero(np.diff(ncoh) > 0)[0] + 1          # rows where edges were activated
    row.update(t_end_us=t[-1] * 1e6, n_act_events=len(act))
    if len(act):
        k, kl = act[0], act[-1]
        row.update(t_act_us=t[k] * 1e6, w_act_mm=w[k] * 1e3, t_last_act_us=t[kl] * 1e6, w_last_act_mm=w[kl] * 1e3)
    row.update(w_max_mm=w.max() * 1e3, v_centre_end=-hist["centre_vel_z"][-1],
               n_sep=int(hist["num_separated_edges"][-1]), n_frag=int(hist["num_fragments"][-1]))
    try:
        row.update(damage_info(os.path.join(outdir, name + ".exo"), nx))
    except (OSError, KeyError, ValueError) as e:
        print(f"  {name}.exo: {e}", file=sys.stderr)
    row.update(W_p_J=hist["plastic_dissipation"][-1],
               rel_energy_err=np.max(np.abs(hist["energy_balance_error"])) / hist["kinetic_energy"][0])
    row.update(first_mode(os.path.join(outdir, name + "_cracks.csv")))
    return row


def first_mode(path):
    """Regime and dominant mode of the first activation step from the crack log (see the module comment)."""
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError:
        return {}
    if not rows:
        return dict(regime="I", mode_first="none")
    first = [r for r in rows if r["step"] == rows[0]["step"]]
    mean = lambda *keys: float(np.mean([sum(float(r[k]) for k in keys) for r in first]))
    inplane, transverse = mean("share_normal", "share_inplane_shear"), mean("share_transverse_shear")
    couples = mean("share_couple_normal", "share_couple_shear")
    mode = max((inplane, "in-plane"), (transverse, "shear"), (couples, "couples"))[1]
    return dict(regime="III" if mode == "shear" else "II", mode_first=mode, share_inplane=inplane,
                share_transverse=transverse)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("-v", "--velocities", nargs="+", required=True, help="V0 [m/s] values or ranges lo:hi:step")
    p.add_argument("-c", "--cells", default="40x5", help="cells along x and y, e.g. 40x5 (x even)")
    p.add_argument("-t", "--end-time", type=float, default=1e-3)
    p.add_argument("-o", "--outdir", default="beam_blast_sweep")
    p.add_argument("--alpha1", type=float, default=1.0, help="Fracture->Alpha 1 (1 = paper)")
    p.add_argument("--shear-yield", action="store_true",
                   help="Shear Yield = true: transverse shear in the yield function (docs/theory.md §4.1)")
    p.add_argument("--fixture", type=int, default=0,
                   help="columns of cells of clamping fixture on each side (0: clamped end edges, which cannot break)")
    p.add_argument("--thresholds", action="store_true",
                   help="bisect between grid velocities where the regime changes, to --tol")
    p.add_argument("--tol", type=float, default=2.0, help="threshold bisection tolerance [m/s]")
    p.add_argument("--doc", help="write the thresholds and the runs as a Markdown file")
    p.add_argument("--output-interval", type=float, default=1e-5, help="Exodus output interval [s]")
    p.add_argument("--binary", default=os.path.join(ROOT, "build/apps/shellfrac/shellfrac"))
    a = p.parse_args()
    vs = []
    for s in a.velocities:
        lo, hi, st = (list(map(float, s.split(":"))) + [1.0])[:3] if ":" in s else (float(s), float(s), 1.0)
        vs += list(np.arange(lo, hi + 0.5 * st, st))
    nx, ny = map(int, a.cells.lower().split("x"))
    if nx % 2:
        sys.exit("the number of cells along x must be even (centre probe)")
    os.makedirs(a.outdir, exist_ok=True)
    rows = []

    def run(v):
        rows.append(run_one(float(v), nx, ny, a.end_time, os.path.abspath(a.outdir), a.binary, a.alpha1,
                            a.output_interval, a.shear_yield, a.fixture))
        print(f"  V0 = {v:g} m/s: rc {rows[-1]['rc']}, regime {rows[-1].get('regime', '?')}, "
              f"t_act {rows[-1].get('t_act_us', '-')} us", file=sys.stderr)
        return rows[-1].get("regime", "?")

    for v in vs:
        run(v)
    thresholds = {}
    if a.thresholds:
        order = {"I": 1, "II": 2, "III": 3}
        grid = sorted(((r["V0"], r.get("regime", "?")) for r in rows), key=lambda x: x[0])
        for target in (2, 3):  # the lowest V0 whose regime is >= target, between two grid points
            lo = max((v for v, g in grid if order.get(g, 0) < target), default=None)
            hi = min((v for v, g in grid if order.get(g, 0) >= target and (lo is None or v > lo)), default=None)
            if lo is None or hi is None:
                continue
            while hi - lo > a.tol:
                mid = 0.5 * (lo + hi)
                if order.get(run(mid), 0) >= target:
                    hi = mid
                else:
                    lo = mid
            thresholds["I->II" if target == 2 else "II->III"] = (lo, hi)
        rows.sort(key=lambda r: r["V0"])
    keys = [k for k in COLUMNS if any(k in r for r in rows)]
    with open(os.path.join(a.outdir, "sweep.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, keys)
        wr.writeheader()
        wr.writerows(rows)
    fmt = lambda x: f"{x:.4g}" if isinstance(x, float) else str(x)
    print(f"S0 = h sigma_c = {H * SIGC:.4g} N/m; elastic shear at the clamp rho h c_s V0 = S0 at V0 = "
          f"{SIGC / (RHO * np.sqrt(5 / 6 * E / (2 * (1 + NU)) / RHO)):.1f} m/s (kappa = 5/6)\n")
    table = "| " + " | ".join(keys) + " |\n|" + "---|" * len(keys) + "\n"
    table += "".join("| " + " | ".join(fmt(r.get(k, "")) for k in keys) + " |\n" for r in rows)
    print(table)
    for name, (lo, hi) in thresholds.items():
        print(f"threshold {name}: between {lo:.4g} and {hi:.4g} m/s")
    if a.doc:
        with open(a.doc, "w") as f:
            f.write("# Beam blast: regime thresholds (written by tools/beam_blast_sweep.py)\n\n")
            f.write(f"Command: `/usr/bin/python3 tools/beam_blast_sweep.py {' '.join(sys.argv[1:])}`\n\n")
            f.write(f"Mesh {a.cells} cells over the span, end time {a.end_time:g} s, Alpha 1 = {a.alpha1:.6g}, "
                    f"Shear Yield = {'true' if a.shear_yield else 'false'}, fixture columns {a.fixture}. Regimes from "
                    "the crack log: I = no fracture, II = first edges break in an in-plane (tensile) mode, III = they "
                    "break in transverse shear.\n\n")
            for name, (lo, hi) in thresholds.items():
                f.write(f"* **{name}: {lo:.4g}–{hi:.4g} m/s** (impulse {lo * RHO * H:.4g}–{hi * RHO * H:.4g} Pa·s)\n")
            f.write("\n" + table)


if __name__ == "__main__":
    main()
