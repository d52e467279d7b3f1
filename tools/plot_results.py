#!/usr/bin/python3
"""Plots a shellfrac run at a glance: the deformed, possibly broken structure coloured by an element field (by
default the fragment each element belongs to, else the owning rank), with a title (run, field, time), a legend
for ids and a colour bar for values, beside the energy history and the fracture (or probe) history.

usage: plot_results.py RESULTS.exo [--field F] [--step -1] [--history H.csv | --no-history]
                       [--units auto|SI|mm-t-s|mm-kg-ms|mm-g-ms|in-lbf-s|none] [-o out.png]

RESULTS.exo may be a single file or the base name of a per-rank set RESULTS.exo.<np>.<rank>. The history is
<base>_history.csv beside the results unless --history names another. Ids (fragment_id, rank, block) get one
distinct colour each and a legend; other fields a continuous colour map. Labels carry the units the run declared
(the deck's `Units`, SI by default: s, m, kg, J; none: bare numbers); --units names others. Reads Exodus II through netCDF4 (Debian: python3-netcdf4).
"""
import argparse
import os
import re
import sys

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from shellfrac_tools.exodus import ExodusFile  # noqa: E402
from shellfrac_tools.results_files import ResultsError, rank_files  # noqa: E402
from shellfrac_tools.tables import TableError, pieces_at, read_table  # noqa: E402
from shellfrac_tools.units import SYSTEMS, chosen_units  # noqa: E402

ID_FIELDS = ("fragment_id", "rank", "block")
LEGEND_ENTRIES = 12  # ids listed by name; the rest summed up in one line
ENERGY_COLUMNS = ("kinetic_energy", "strain_energy", "plastic_dissipation", "cohesive_dissipation", "external_work",
                  "reaction_work", "energy_balance_error")
FRACTURE_COLUMNS = (("num_cohesive_edges", "activated edges"), ("num_separated_edges", "separated edges"),
                    ("num_fragments", "pieces"))


def read_piece(path, field, step):
    """Triangles (vertex coordinates, deformed), the element field of one Exodus file (the block index where the
    file has no such field, or no step) and the time of the step (None without steps)."""
    with ExodusFile(path) as ds:
        times = ds.times()
        has_steps = len(times) > 0
        x = ds.coordinates()
        u = ds.displacement(step) if has_steps else None
        if u is not None:
            x = x + u
        tris, values = [], []
        for b, conn in ds.blocks():
            tris.append(x[conn[:, :3]])
            v = ds.element(field, b, step) if has_steps else None
            values.append(v if v is not None else np.full(conn.shape[0], float(b)))
        time = float(times[step]) if has_steps else None
        if not tris:
            return np.zeros((0, 3, 3)), np.zeros(0), time
        return np.concatenate(tris), np.concatenate(values), time


def element_fields(path):
    """The element variables of a results file."""
    with ExodusFile(path) as ds:
        return ds.names("name_elem_var")


def is_id_field(field, values):
    """Whether a field holds ids (one colour per value) rather than a quantity (a colour map)."""
    if field in ID_FIELDS:
        return True
    return len(values) > 0 and np.all(values == np.round(values)) and len(np.unique(values)) <= LEGEND_ENTRIES


def id_colours(values):
    """{id: colour} for the distinct values, in increasing order, from a qualitative palette (tab10, or tab20 beyond
    ten ids; repeated past twenty)."""
    ids = np.unique(values)
    palette = plt.get_cmap("tab10" if len(ids) <= 10 else "tab20")
    return {v: palette(i % palette.N) for i, v in enumerate(ids)}


def fragment_motion(results, time):
    """{fragment id: (mass, speed of its centre of mass)} from <base>_fragments.csv at the frame `time`."""
    try:
        return {i: (m, v) for i, _, m, v in pieces_at(results, time)}
    except TableError as e:
        sys.exit("plot_results: %s" % e)


def id_legend(field, values, colours, motion, units):
    """Legend handles: one per id with its element count (and a piece's mass and speed), the largest first; ids
    beyond LEGEND_ENTRIES in one line."""
    ids, counts = np.unique(values, return_counts=True)
    order = np.argsort(-counts, kind="stable")
    name = {"fragment_id": "piece", "rank": "rank", "block": "block"}.get(field, field)

    def label(i):
        text = "%s %d: %d elements" % (name, ids[i], counts[i])
        if field == "fragment_id" and int(ids[i]) in motion:
            m, v = motion[int(ids[i])]
            text += ", %.3g%s at %.3g%s" % (m, suffix(units.mass), v, suffix(units.speed))
        return text

    handles = [Patch(color=colours[ids[i]], label=label(i)) for i in order[:LEGEND_ENTRIES]]
    if len(ids) > LEGEND_ENTRIES:
        rest = order[LEGEND_ENTRIES:]
        handles.append(Patch(color="0.8", label="... %d more (%d elements)" % (len(rest), counts[rest].sum())))
    return handles


def time_text(t, units):
    """A time for a title: in the largest time unit it reaches (SI: s, ms or us), a bare number without units."""
    if t is None:
        return "no time step"
    if not units:
        return "t = %.4g" % t
    scales = units.time_scales()
    for scale, unit in scales:
        if abs(t) >= scale or unit == scales[-1][1]:
            return "t = %.4g %s" % (t / scale, unit)


def time_axis(times, units):
    """(scaled times, axis label): the largest time unit the run's end reaches (SI: ms or us for short runs)."""
    end = float(np.max(np.abs(times))) if len(times) else 0.0
    if not units:
        return times, "time"
    scales = units.time_scales()
    for scale, unit in scales:
        if end >= scale or unit == scales[-1][1]:
            return times / scale, "time [%s]" % unit


def unit(text):
    """An axis label's unit: " [m]", or nothing without declared units."""
    return " [%s]" % text if text else ""


def suffix(text):
    """A value's unit in a legend: " kg", or nothing without declared units."""
    return " " + text if text else ""


def frame_3d(ax, tris):
    """A 3-D axis framed on the model: the box of the deformed mesh, true proportions, thin directions widened to a
    tenth of the largest so that a plate's deflection stays visible."""
    pts = tris.reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    span = np.maximum(hi - lo, 0.1 * max(np.max(hi - lo), 1e-300))
    centre = (lo + hi) / 2
    for setter, c, s in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre, span):
        setter(c - s / 2, c + s / 2)
    ax.set_box_aspect(span)
    ax.view_init(elev=14, azim=-72)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(matplotlib.ticker.MaxNLocator(4))


def draw_mesh(fig, position, tris, vals, field, units, motion):
    """The deformed mesh in its panel, coloured by the field: ids with a legend, values with a colour bar."""
    flat = np.ptp(tris[:, :, 2]) <= 1e-12 * max(np.ptp(tris[:, :, 0]), np.ptp(tris[:, :, 1]), 1e-300)
    ids = is_id_field(field, vals)
    if ids:
        colours = id_colours(vals)
        face = [colours[v] for v in vals]
    if flat:
        ax = fig.add_subplot(*position)
        pc = PolyCollection(tris[:, :, :2], edgecolors="k", linewidths=0.05)
        ax.add_collection(pc)
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_xlabel("x" + unit(units.length))
        ax.set_ylabel("y" + unit(units.length))
    else:
        ax = fig.add_subplot(*position, projection="3d")
        pc = Poly3DCollection(tris, edgecolors="k", linewidths=0.05)
        ax.add_collection3d(pc)
        frame_3d(ax, tris)
        for label, axis in zip("xyz", (ax.set_xlabel, ax.set_ylabel, ax.set_zlabel)):
            axis(label + unit(units.length))
    if ids:
        pc.set_facecolor(face)
        ax.legend(handles=id_legend(field, vals, colours, motion, units), fontsize="small", loc="upper left",
                  bbox_to_anchor=(0.0, 1.0), framealpha=0.8)
    else:
        pc.set_array(vals)
        pc.set_cmap("viridis")
        pc.set_clim(vals.min(), vals.max() if vals.max() > vals.min() else vals.min() + 1)
        fig.colorbar(pc, ax=ax, label=field, shrink=0.7)
    return ax


def draw_history(fig, hist, units):
    """The energy history (upper right) and the fracture counts, or else the probes' z displacement (lower right)."""
    t, tlabel = time_axis(hist["time"], units)
    hx = fig.add_subplot(2, 2, 2)
    for col in ENERGY_COLUMNS:
        if col in hist and np.any(hist[col] != 0):
            hx.plot(t, hist[col], label=col.replace("_", " "))
    hx.set_xlabel(tlabel)
    hx.set_ylabel("energy" + unit(units.energy))
    hx.set_title("energies", fontsize=10)
    hx.legend(fontsize="small")
    hx.grid(alpha=0.3)
    px = fig.add_subplot(2, 2, 4)
    fracture = [(c, name) for c, name in FRACTURE_COLUMNS if c in hist]
    if fracture and np.any(hist[fracture[0][0]] > 0):
        for col, name in fracture:
            px.step(t, hist[col], where="post", label=name)
        px.set_ylabel("count")
        px.set_title("fracture", fontsize=10)
    else:
        for col in (c for c in hist if c.endswith("_displ_z")):
            name = col[:-len("_displ_z")]
            px.plot(t, hist[col], label=name + (" (History Nodes)" if re.fullmatch(r"node\d+", name) else
                                                " (mean of the set)"))
        px.set_ylabel("displacement z" + unit(units.length))
        px.set_title("probes and nodes", fontsize=10)
    px.set_xlabel(tlabel)
    if px.get_legend_handles_labels()[0]:
        px.legend(fontsize="small")
    px.grid(alpha=0.3)


def history_of(results, named, wanted):
    """The history table to plot: the one named, or <base>_history.csv beside the results; {} if none."""
    if not wanted:
        return {}
    path = named or os.path.splitext(results)[0] + "_history.csv"
    if not os.path.exists(path):
        if named:
            sys.exit("plot_results: %s: no such history file" % named)
        return {}
    try:
        return read_table(path)
    except TableError as e:
        sys.exit("plot_results: %s" % e)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("--field", help="element variable for the colours (default: fragment_id if written, else rank)")
    ap.add_argument("--step", type=int, default=-1, help="output step index (default: the last)")
    ap.add_argument("--history", help="history CSV (default: <base>_history.csv beside the results)")
    ap.add_argument("--no-history", action="store_true", help="the mesh only")
    ap.add_argument("--units", choices=("auto",) + tuple(SYSTEMS), default="auto",
                    help="units of the labels (default: those the run declared, 'Units' of its deck)")
    ap.add_argument("-o", "--output", help="PNG file (default: RESULTS with .png)")
    a = ap.parse_args()
    try:
        files = rank_files(a.results)
        units = chosen_units(a.units, a.results)
    except ResultsError as e:
        sys.exit("plot_results: %s" % e)
    field = a.field or ("fragment_id" if "fragment_id" in element_fields(files[0]) else "rank")
    pieces = [read_piece(f, field, a.step) for f in files]
    tris = np.concatenate([p[0] for p in pieces])
    vals = np.concatenate([p[1] for p in pieces])
    time = pieces[0][2]
    hist = history_of(a.results, a.history, not a.no_history)
    with_history = len(hist.get("time", [])) > 1

    fig = plt.figure(figsize=(15 if with_history else 9, 6.5))
    ax = draw_mesh(fig, (1, 2 if with_history else 1, 1), tris, vals, field, units, fragment_motion(a.results, time))
    run = os.path.basename(a.results)
    run = run[:-4] if run.endswith(".exo") else run
    ax.set_title("%s: %s at %s\n(%d elements, %d file%s; deformed, true scale)"
                 % (run, field, time_text(time, units), len(tris), len(files), "s" if len(files) > 1 else ""),
                 fontsize=10)
    if with_history:
        draw_history(fig, hist, units)
    out = a.output or os.path.splitext(a.results)[0] + ".png"
    fig.tight_layout()
    tmp = out + ".part.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)
    print("plot_results: wrote", out)


if __name__ == "__main__":
    main()
