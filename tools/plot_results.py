#!/usr/bin/python3
"""Plots a shellfrac run: the deformed DG mesh coloured by an element field (default: owning rank) and,
when the history has more than one row, the energy histories.

usage: plot_results.py RESULTS.exo [--field rank] [--step -1] [--history H.csv] [-o out.png]

RESULTS.exo may be a single file or the base name of a per-rank set RESULTS.exo.<np>.<rank>.
Reads Exodus II through netCDF4 (Debian: python3-netcdf4).
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from shellfrac_tools.exodus import ExodusFile  # noqa: E402
from shellfrac_tools.results_files import ResultsError, rank_files  # noqa: E402
from shellfrac_tools.tables import TableError, read_table  # noqa: E402


def read_piece(path, field, step):
    """Triangles (vertex coordinates, deformed) and the element field of one Exodus file (the block index where the
    file has no such field, or no step)."""
    with ExodusFile(path) as ds:
        has_steps = len(ds.times()) > 0
        x = ds.coordinates()
        u = ds.displacement(step) if has_steps else None
        if u is not None:
            x = x + u
        tris, values = [], []
        for b, conn in ds.blocks():
            tris.append(x[conn[:, :3]])
            v = ds.element(field, b, step) if has_steps else None
            values.append(v if v is not None else np.full(conn.shape[0], float(b)))
        if not tris:
            return np.zeros((0, 3, 3)), np.zeros(0)
        return np.concatenate(tris), np.concatenate(values)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("--field", default="rank", help="element variable used for colour (default: rank)")
    ap.add_argument("--step", type=int, default=-1, help="time step index (default: last)")
    ap.add_argument("--history", help="history CSV to plot beside the mesh")
    ap.add_argument("-o", "--output", help="PNG file (default: RESULTS with .png)")
    a = ap.parse_args()

    try:
        files = rank_files(a.results)
    except ResultsError as e:
        sys.exit("plot_results: %s" % e)
    pieces = [read_piece(f, a.field, a.step) for f in files]
    tris = np.concatenate([p[0] for p in pieces])
    vals = np.concatenate([p[1] for p in pieces])

    hist = {}
    if a.history and os.path.exists(a.history):
        try:
            hist = read_table(a.history)
        except TableError as e:
            sys.exit("plot_results: %s" % e)
    with_history = len(hist.get("time", [])) > 1
    fig = plt.figure(figsize=(12 if with_history else 8, 5))
    flat = np.ptp(tris[:, :, 2]) <= 1e-12 * max(np.ptp(tris[:, :, 0]), np.ptp(tris[:, :, 1]), 1e-300)
    cmap = plt.get_cmap("tab20" if a.field == "rank" else "viridis")
    norm = plt.Normalize(vals.min(), vals.max() if vals.max() > vals.min() else vals.min() + 1)
    if flat:
        ax = fig.add_subplot(1, 2 if with_history else 1, 1)
        pc = PolyCollection(tris[:, :, :2], array=vals, cmap=cmap, norm=norm, edgecolors="k", linewidths=0.05)
        ax.add_collection(pc)
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    else:
        ax = fig.add_subplot(1, 2 if with_history else 1, 1, projection="3d")
        pc = Poly3DCollection(tris, cmap=cmap, norm=norm, edgecolors="k", linewidths=0.05)
        pc.set_array(vals)
        ax.add_collection3d(pc)
        lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
        c, r = (lo + hi) / 2, (hi - lo).max() / 2
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(c[2] - r, c[2] + r)
    fig.colorbar(pc, ax=ax, label=a.field, shrink=0.7)
    ax.set_title("%s: %d elements, %d file(s)" % (os.path.basename(a.results), len(tris), len(files)))
    if with_history:
        t = hist["time"]
        probes = [c for c in hist if c.endswith("_displ_z")]
        hx = fig.add_subplot(2 if probes else 1, 2, 2)
        for col in ("kinetic_energy", "strain_energy", "penalty_energy", "plastic_dissipation",
                    "energy_balance_error"):
            if col in hist and (col != "plastic_dissipation" or np.any(hist[col] != 0)):
                hx.plot(t, hist[col], label=col)
        hx.set_xlabel("time")
        hx.set_ylabel("energy")
        hx.legend(fontsize="small")
        if probes:
            px = fig.add_subplot(2, 2, 4)
            for col in probes:
                px.plot(t, hist[col], label=col)
            px.set_xlabel("time")
            px.set_ylabel("mean displacement z")
            px.legend(fontsize="small")
    out = a.output or os.path.splitext(a.results)[0] + ".png"
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print("plot_results: wrote", out)


if __name__ == "__main__":
    main()
