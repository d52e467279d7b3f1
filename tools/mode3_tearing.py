#!/usr/bin/python3
"""Mode III tearing of a notched 6061-T6 plate (Talamini & Radovitzky 2016 §6.2, Figs. 12-13; docs/mode3_tearing.md).

Runs the decks xml/mode3_tearing_G050.xml, _G075.xml and _G100.xml (Gamma = 0.5, 0.75, 1.0 Y0 h), or reads their
existing histories with --no-run, and computes the normalised clamp force F/(Y0 h b) against Delta/h, where
  F     = clamp_top_reaction_z, the vertical support reaction of the top clamp, signed so that F > 0 resists the
          imposed upward motion (not |.|: that would rectify the vibration of the halves after separation into a
          spurious mean force); --force mean uses (top - bottom)/2, the mean of both clamps (they differ only by the
          plate's net vertical momentum rate),
  Delta = the imposed vertical displacement of one clamp (clamp_top_displ_z; paper Fig. 13: "imposed vertical
          displacement at the clamp"); --delta relative uses the relative displacement of the two clamps (2x),
  b     = 33.1 mm, the original ligament; Y0 h b = 21.18 kN.
Writes DIR/mode3_tearing_F_delta.csv (Delta_over_h, then F_over_Y0hb per Gamma, on a uniform Delta/h grid up to 10),
DIR/mode3_tearing_F_delta.png (force curves and crack length), and prints per Gamma: peak force (and where), the
mean force over Delta/h in [--steady-from, --steady-to] (the paper's steady state), the mean force over the
propagation phase (from the first to the last separated ligament edge) and its Delta/h range, the crack length at
Delta/h = 10 (separated ligament edges x edge length), the cohesive dissipation against Gamma h x crack length, the
energy balance error max |error| / input work, and the wall time; then for the steady-state window: the mean force
and its values at both ends, the crack growth per unit Delta, the tearing resistance R (plastic work + cohesive
dissipation per unit crack area) and how the separated flanks open (the out-of-plane share of the jump, from the
Exodus file).

usage: mode3_tearing.py [--np N] [--jobs J] [--out DIR] [--decks D1.xml ...] [--no-run]
                        [--delta clamp|relative] [--force top|mean] [--steady-from 4 --steady-to 10]
"""
import argparse
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
from shellfrac_tools.exodus import ExodusFile  # noqa: E402
from shellfrac_tools.tables import column, read_table  # noqa: E402

BINARY = os.path.join(ROOT, "build", "apps", "shellfrac", "shellfrac")
MPI_ENV = os.path.join(ROOT, "tools", "mpi-env.sh")
DEFAULT_DECKS = [os.path.join(ROOT, "xml", f"mode3_tearing_G{g}.xml") for g in ("050", "075", "100")]
B_LIGAMENT = 33.1e-3  # original ligament length b [m] (paper footnote 5)
DELTA_MAX = 10.0      # Delta/h range of Fig. 13


def deck_params(deck):
    """Returns h, Y0, Gamma and the mesh path of a deck (the first block and its material)."""
    root = ET.parse(deck).getroot()

    def sub(node, name):
        for c in node:
            if c.tag == "ParameterList" and c.get("name") == name:
                return c
        raise KeyError(f"{deck}: no sublist {name}")

    def par(node, name):
        for c in node:
            if c.tag == "Parameter" and c.get("name") == name:
                return c.get("value")
        raise KeyError(f"{deck}: no parameter {name} in {node.get('name')}")

    block = [c for c in sub(root, "Blocks") if c.tag == "ParameterList"][0]
    mat = sub(sub(root, "Materials"), par(block, "Material"))
    mesh = par(sub(root, "Mesh"), "File")
    return {
        "h": float(par(block, "Thickness")),
        "Y0": float(par(mat, "Yield Stress")),
        "Gamma": float(par(mat, "Fracture Energy")),
        "sigma_c": float(par(mat, "Cohesive Strength")),
        "mesh": os.path.join(os.path.dirname(os.path.abspath(deck)), mesh),
    }


def curve_edges(msh, name):
    """Number and mean length of the line elements of the physical curve `name` in an ASCII Gmsh 4.1 file, and the
    smallest x of their vertices (for the ligament: the notch tip)."""
    lines = open(msh).read().split("\n")
    i = lines.index("$PhysicalNames")
    tag = None
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        d, t, nm = ln.split(maxsplit=2)
        if int(d) == 1 and nm.strip('"') == name:
            tag = int(t)
    if tag is None:
        raise KeyError(f"{msh}: no physical curve {name}")
    i = lines.index("$Entities")
    npt, ncv = map(int, lines[i + 1].split()[:2])
    curves = set()
    for ln in lines[i + 2 + npt:i + 2 + npt + ncv]:
        v = ln.split()
        nphys = int(v[7])
        if tag in map(int, v[8:8 + nphys]):
            curves.add(int(v[0]))
    i = lines.index("$Nodes")
    nb = int(lines[i + 1].split()[0])
    k, xyz = i + 2, {}
    for _ in range(nb):
        n = int(lines[k].split()[3])
        tags = [int(t) for t in lines[k + 1:k + 1 + n]]
        for j, t in enumerate(tags):
            xyz[t] = np.array(lines[k + 1 + n + j].split(), float)
        k += 1 + 2 * n
    i = lines.index("$Elements")
    nb = int(lines[i + 1].split()[0])
    k, lengths, xmin = i + 2, [], np.inf
    for _ in range(nb):
        dim, ent, _typ, n = map(int, lines[k].split())
        if dim == 1 and ent in curves:
            for ln in lines[k + 1:k + 1 + n]:
                v = list(map(int, ln.split()))
                lengths.append(np.linalg.norm(xyz[v[2]] - xyz[v[1]]))
                xmin = min(xmin, xyz[v[1]][0], xyz[v[2]][0])
        k += 1 + n
    return len(lengths), float(np.mean(lengths)), float(xmin)


def run_deck(deck, out, np_):
    """Starts shellfrac on deck in out; returns the Popen (stdout and stderr to out/<name>.log)."""
    name = os.path.splitext(os.path.basename(deck))[0]
    log = open(os.path.join(out, f"{name}.log"), "w")
    launcher = f"mpiexec --oversubscribe -np {np_} " if np_ > 1 else ""
    cmd = f"source '{MPI_ENV}' && {launcher}'{BINARY}' '{os.path.abspath(deck)}'"
    return subprocess.Popen(["bash", "-c", cmd], cwd=out, stdout=log, stderr=subprocess.STDOUT)


def run_all(decks, out, np_, jobs):
    """Runs the decks, at most `jobs` at a time; writes out/<name>_wall.txt with each wall time [s]."""
    pending, running = list(decks), []
    while pending or running:
        while pending and len(running) < jobs:
            d = pending.pop(0)
            print(f"running {os.path.basename(d)} on {np_} rank(s) in {out}", flush=True)
            running.append((d, run_deck(d, out, np_), time.time()))
        time.sleep(1.0)
        for item in list(running):
            d, p, t0 = item
            if p.poll() is not None:
                running.remove(item)
                name = os.path.splitext(os.path.basename(d))[0]
                wall = time.time() - t0
                if p.returncode != 0:
                    raise RuntimeError(f"{d} failed (exit {p.returncode}); see {out}/{name}.log")
                with open(os.path.join(out, f"{name}_wall.txt"), "w") as f:
                    f.write(f"{wall:.1f}\n")
                print(f"  {name}: {wall:.0f} s", flush=True)


def flank_jumps(exo, x_tip, h, delta_of_t, delta_at):
    """Opening of the crack flanks at the Exodus frame nearest to Delta/h = delta_at: for every ligament vertex
    (y = 0, x >= x_tip) the displacement jump between the copies of the elements above (y > 0) and below; returns
    (Delta/h of the frame, x [m], jump [m] as an (n, 3) array), or None when the file has no displacements."""
    with ExodusFile(exo) as d:
        t = d.times()
        if len(t) == 0:
            return None
        fr = int(np.argmin(np.abs(delta_of_t(t) / h - delta_at)))
        u = d.displacement(fr)
        if u is None:
            return None
        xyz = d.coordinates()
        conn = d.blocks()[0][1]
    above, below = {}, {}
    tol = 1e-9 * max(1.0, float(np.abs(xyz).max()))
    for c in conn:
        side = above if xyz[c, 1].mean() > 0 else below
        for n in c:
            if abs(xyz[n, 1]) <= tol and xyz[n, 0] >= x_tip - tol:
                side.setdefault(round(xyz[n, 0] / tol), n)
    keys = sorted(set(above) & set(below))
    x = np.array([xyz[above[k], 0] for k in keys])
    jump = np.array([u[above[k]] - u[below[k]] for k in keys])
    return delta_of_t(t[fr]) / h, x, jump


def analyse(deck, out, delta_kind, force_kind, steady):
    name = os.path.splitext(os.path.basename(deck))[0]
    prm = deck_params(deck)
    path = os.path.join(out, f"{name}_history.csv")
    hist = read_table(path)
    h, y0 = prm["h"], prm["Y0"]
    norm = y0 * h * B_LIGAMENT
    t = column(hist, "time", path)
    dtop = column(hist, "clamp_top_displ_z", path)
    dbot = column(hist, "clamp_bottom_displ_z", path)
    delta = (dtop - dbot) if delta_kind == "relative" else dtop
    ftop = column(hist, "clamp_top_reaction_z", path)
    fbot = column(hist, "clamp_bottom_reaction_z", path)
    force = 0.5 * (ftop - fbot) if force_kind == "mean" else ftop
    fn, dn = force / norm, delta / h
    nlig, le, x_tip = curve_edges(prm["mesh"], "ligament")
    nsep = column(hist, "num_separated_edges", path)
    ncoh = column(hist, "num_cohesive_edges", path)
    win = (dn >= steady[0]) & (dn <= steady[1])
    crack = nsep * le
    upto = dn <= DELTA_MAX + 1e-9
    ipk = int(np.argmax(np.where(upto, fn, -np.inf)))
    wr = column(hist, "reaction_work", path)
    err = column(hist, "energy_balance_error", path)
    dcoh = column(hist, "cohesive_dissipation", path)
    wall_file = os.path.join(out, f"{name}_wall.txt")
    wall = float(open(wall_file).read()) if os.path.exists(wall_file) else float("nan")
    # the first crossing of Delta/h = 10 (or the last row): crack length at the end of the Fig. 13 range
    iend = int(np.argmax(dn >= DELTA_MAX)) if dn[-1] >= DELTA_MAX else len(dn) - 1
    # propagation phase: from the first separated edge to the last one (or the end of the Fig. 13 range)
    isep = int(np.argmax(nsep > 0)) if nsep[iend] > 0 else None
    ilast = int(np.argmax(nsep >= nsep[iend])) if isep is not None else None
    prop = fn[isep:ilast + 1] if isep is not None else np.array([])
    # the steady-state window: crack growth per Delta (least squares) and the dissipation per unit crack advance
    # (plastic work + cohesive dissipation) / (h x advance), i.e. the tearing resistance R of the window
    wp = column(hist, "plastic_dissipation", path)
    iw = np.nonzero(win & (dn <= DELTA_MAX + 1e-9))[0]
    grow, resist = float("nan"), float("nan")
    if iw.size > 1:
        grow = float(np.polyfit(dn[iw] * h, crack[iw], 1)[0])
        da = crack[iw[-1]] - crack[iw[0]]
        if da > 0:
            resist = ((wp[iw[-1]] + dcoh[iw[-1]]) - (wp[iw[0]] + dcoh[iw[0]])) / (h * da)
    # how the separated flanks open: the out-of-plane (z) share of the jump where it exceeds 2 Gamma / sigma_c
    # (the opening at complete separation), at the end of the Fig. 13 range
    mode3 = float("nan")
    exo = os.path.join(out, f"{name}.exo")
    if os.path.exists(exo):
        fj = flank_jumps(exo, x_tip, h, lambda tt: np.interp(tt, t, delta), DELTA_MAX)
        if fj is not None:
            _, _, jump = fj
            mag = np.linalg.norm(jump, axis=1)
            sep = mag >= 2.0 * prm["Gamma"] / prm["sigma_c"]
            if sep.any():
                mode3 = float(np.mean(np.abs(jump[sep, 2]) / mag[sep]))
    return {
        "name": name, "Gamma": prm["Gamma"], "Gamma_rel": prm["Gamma"] / (y0 * h), "h": h,
        "t": t, "delta_h": dn, "F": fn, "ncoh": ncoh, "nsep": nsep, "edge": le, "nlig": nlig,
        "peak": fn[ipk], "peak_at": dn[ipk],
        "steady": float(np.mean(fn[win])) if win.any() else float("nan"),
        "steady_std": float(np.std(fn[win])) if win.any() else float("nan"),
        "steady_first": fn[iw[0]] if iw.size else float("nan"), "steady_last": fn[iw[-1]] if iw.size else float("nan"),
        "growth": grow, "resistance": resist, "mode3_share": mode3, "Y0h": y0 * h,
        "crack_end": nsep[iend] * le, "cohesive_end": ncoh[iend] * le, "nsep_end": int(nsep[iend]),
        "delta_end": dn[iend], "first_sep_at": dn[isep] if isep is not None else float("nan"),
        "last_sep_at": dn[ilast] if isep is not None else float("nan"),
        "prop": float(np.mean(prop)) if prop.size else float("nan"),
        "prop_speed": (nsep[ilast] - nsep[isep]) * le / max(t[ilast] - t[isep], 1e-300) if isep is not None
        else float("nan"),
        "Dcoh": dcoh[iend], "Dcoh_expected_min": prm["Gamma"] * h * nsep[iend] * le,
        "err_rel": float(np.max(np.abs(err[:iend + 1])) / max(wr[iend], 1e-300)), "Wr": wr[iend],
        "Wp": column(hist, "plastic_dissipation", path)[iend],
        "K": column(hist, "kinetic_energy", path)[iend],
        "wall": wall, "t_end": t[-1],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run (default 1)")
    ap.add_argument("--jobs", type=int, default=1, help="runs at the same time (default 1)")
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "mode3_tearing"), help="results directory")
    ap.add_argument("--decks", nargs="+", default=DEFAULT_DECKS)
    ap.add_argument("--no-run", action="store_true", help="read existing histories in --out")
    ap.add_argument("--delta", choices=("clamp", "relative"), default="clamp",
                    help="Delta = displacement of one clamp (default) or the relative displacement of the clamps")
    ap.add_argument("--force", choices=("top", "mean"), default="top",
                    help="F = top clamp reaction (default) or the mean of both clamps' reactions")
    ap.add_argument("--steady-from", type=float, default=4.0, help="start of the steady-state window in Delta/h")
    ap.add_argument("--steady-to", type=float, default=10.0, help="end of the steady-state window in Delta/h")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if not a.no_run:
        run_all(a.decks, a.out, a.np, a.jobs)
    res = [analyse(d, a.out, a.delta, a.force, (a.steady_from, a.steady_to)) for d in a.decks]

    grid = np.round(np.arange(0.0, DELTA_MAX + 1e-9, 0.01), 2)
    cols = [grid]
    header = ["Delta_over_h"]
    for r in res:
        cols.append(np.interp(grid, r["delta_h"], r["F"], right=np.nan))
        header.append(f"F_over_Y0hb_Gamma{r['Gamma_rel']:.2f}Y0h")
    csv = os.path.join(a.out, "mode3_tearing_F_delta.csv")
    np.savetxt(csv, np.column_stack(cols), delimiter=",", header=",".join(header), comments="", fmt="%.6g")

    dlabel = r"$\Delta/h$ (one clamp)" if a.delta == "clamp" else r"$\Delta/h$ (relative, both clamps)"
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7, 7.5), sharex=True, gridspec_kw={"height_ratios": [3, 2]})
    for r in res:
        sel = r["delta_h"] <= DELTA_MAX + 1e-9
        lab = rf"$\Gamma$ = {r['Gamma_rel']:.2f} $Y_0 h$"
        ax.plot(r["delta_h"][sel], r["F"][sel], lw=1.0, label=lab)
        col = ax.lines[-1].get_color()
        ax2.plot(r["delta_h"][sel], r["nsep"][sel] * r["edge"] * 1e3, color=col, label=lab)
        ax2.plot(r["delta_h"][sel], r["ncoh"][sel] * r["edge"] * 1e3, ls=":", color=col)
    ax.axvspan(a.steady_from, a.steady_to, color="0.92", zorder=0, label="steady-state window")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_ylabel(r"$F/(Y_0 h b)$")
    ax.set_xlim(0, DELTA_MAX)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    k = 2.0 if a.delta == "clamp" else 0.5
    top = ax.secondary_xaxis("top", functions=(lambda x: k * x, lambda x: x / k))
    top.set_xlabel(r"relative clamp displacement / h" if a.delta == "clamp" else r"one clamp's displacement / h")
    ax.set_title("Mode III tearing, 6061-T6, h = 2 mm, b = 33.1 mm (Talamini & Radovitzky 2016 Fig. 13)",
                 fontsize=9)
    ax2.plot([], [], "k-", label="separated")
    ax2.plot([], [], "k:", label="activated (cohesive or separated)")
    ax2.axhline(B_LIGAMENT * 1e3, color="k", lw=0.8, ls="--")
    ax2.set_ylabel("crack length [mm]")
    ax2.set_xlabel(dlabel)
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    png = os.path.join(a.out, "mode3_tearing_F_delta.png")
    fig.savefig(png, dpi=150)
    plt.close(fig)

    fdesc = "top clamp reaction_z" if a.force == "top" else "(top - bottom clamp reaction_z)/2"
    print(f"F = {fdesc} (> 0 resists the imposed motion), Delta = "
          f"{'one clamp' if a.delta == 'clamp' else 'relative'} displacement, Y0 h b = "
          f"{res[0]['h'] * B_LIGAMENT * 320e6 / 1e3:.2f} kN (Y0 = 320 MPa)")
    print(f"{'deck':<20}{'G/Y0h':>6}{'peak':>8}{'at D/h':>7}{'steady':>8}{'(std)':>7}{'prop':>8}{'D/h from':>9}"
          f"{'to':>6}{'v m/s':>7}{'crack':>7}{'Dcoh/Gha':>9}{'err/W':>9}{'W_in J':>8}{'Wp J':>7}{'wall s':>7}")
    for r in res:
        ratio = r["Dcoh"] / r["Dcoh_expected_min"] if r["Dcoh_expected_min"] > 0 else float("nan")
        print(f"{r['name']:<20}{r['Gamma_rel']:>6.2f}{r['peak']:>8.4f}{r['peak_at']:>7.2f}{r['steady']:>8.4f}"
              f"{r['steady_std']:>7.4f}{r['prop']:>8.4f}{r['first_sep_at']:>9.2f}{r['last_sep_at']:>6.2f}"
              f"{r['prop_speed']:>7.0f}{r['crack_end'] * 1e3:>6.1f}m{ratio:>9.3f}{r['err_rel']:>9.2e}"
              f"{r['Wr']:>8.2f}{r['Wp']:>7.2f}{r['wall']:>7.0f}")
    print(f"steady = mean (std) of F/(Y0 h b) over Delta/h in [{a.steady_from:g}, {a.steady_to:g}]; prop = mean over "
          f"the propagation phase, from the first to the last separated ligament edge (Delta/h from .. to), v = mean "
          f"crack speed in it; crack = separated edges x edge length ({res[0]['edge'] * 1e3:.4f} mm, "
          f"{res[0]['nlig']} edges) at Delta/h = {res[0]['delta_end']:.2f}; Dcoh/Gha = cohesive dissipation / "
          f"(Gamma h crack), > 1 by partly opened edges; err/W = max |energy_balance_error| / reaction work W_in; "
          f"Wp = plastic work")
    print(f"\nsteady-state window Delta/h in [{a.steady_from:g}, {a.steady_to:g}]:")
    print(f"{'deck':<28}{'G/Y0h':>6}{'mean F':>8}{'(std)':>7}{'F first':>8}{'F last':>8}{'da/dDelta':>10}"
          f"{'R/(Y0h)':>9}{'R/Gamma':>8}{'z share':>8}")
    for r in res:
        print(f"{r['name']:<28}{r['Gamma_rel']:>6.2f}{r['steady']:>8.4f}{r['steady_std']:>7.4f}"
              f"{r['steady_first']:>8.4f}{r['steady_last']:>8.4f}{r['growth']:>10.2f}"
              f"{r['resistance'] / r['Y0h']:>9.3f}{r['resistance'] / r['Gamma']:>8.2f}{r['mode3_share']:>8.2f}")
    print("mean F (std) = F/(Y0 h b) over the window, F first/last = at its ends; da/dDelta = crack growth per "
          "unit Delta (least squares); R = (plastic work + cohesive dissipation) / (h x crack advance) in the window, "
          "the tearing resistance; z share = mean |jump_z| / |jump| of the crack flanks where the jump exceeds "
          "2 Gamma / sigma_c (complete separation), at Delta/h = 10 (1 = pure out-of-plane sliding, mode III)")
    print(f"wrote {csv}\nwrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
