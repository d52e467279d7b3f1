#!/usr/bin/python3
"""Summarises the fracture of a shellfrac run over time: crack length, cohesive and separated edges, fragments,
and the fragment mass distribution at a chosen output time.

usage: fracture_summary.py BASE [--time T] [--min-elements 1] [-o BASE_fracture.png] [--csv BASE_fracture.csv]

BASE is the run's output base name (`<base>_history.csv`, `<base>_cracks.csv`, `<base>_fragments.csv` and the
Exodus results `<base>.exo` or the per-rank set `<base>.exo.<np>.<rank>`). The crack length is the length of the
edges that have activated (a cohesive zone or a separated edge), measured on the reference mid-surface along
each edge's quadratic curve; the Exodus results give the elements' nodes, so any mesh works (also refined ones).
The pieces are all the connected parts of the structure, as the history's num_fragments counts them; the fragment
statistics leave out the main piece (the one of most elements, the structure the fragments come from; in a
shear-off that may be the flying part). Writes a PNG with
four panels and a CSV, one row per output time, and prints the table at the chosen time (default: the last).
Reads Exodus II through netCDF4 (Debian: python3-netcdf4).
"""
import argparse
import csv
import os

import numpy as np

from shellfrac_tools.cli import fail
from shellfrac_tools.exodus import ExodusFile
from shellfrac_tools.results_files import ResultsError, rank_files
from shellfrac_tools.tables import TableError, read_table


def read_csv(path):
    """The table's columns by name (shellfrac_tools.tables.read_table: a partial last line is left out with a note);
    any other problem stops the script, naming the file and the line."""
    try:
        return read_table(path)
    except TableError as e:
        fail(str(e))


def exodus_files(base):
    try:
        return rank_files(base + ".exo")
    except ResultsError as e:
        fail(str(e))


def element_nodes(files):
    """Reference coordinates of every element's nodes: {element id (1-based): (nodes, 3) array}."""
    nodes = {}
    for path in files:
        with ExodusFile(path) as ds:
            x, ids, start = ds.coordinates(), ds.element_ids(), 0
            for _, conn in ds.blocks():
                for e, c in zip(ids[start:start + len(conn)], conn):
                    nodes[int(e)] = x[c]
                start += len(conn)
    return nodes


def edge_length(a, b):
    """Length of the edge shared by two elements (vertex and mid-side nodes of P2 triangles, or P1)."""
    verts_a, verts_b = a[:3], b[:3]
    scale = np.max(np.ptp(np.vstack([verts_a, verts_b]), axis=0))
    shared = [i for i in range(3) if np.min(np.linalg.norm(verts_b - verts_a[i], axis=1)) <= 1e-9 * scale]
    if len(shared) != 2:
        return None
    i, j = shared
    if len(a) < 6:
        return float(np.linalg.norm(a[i] - a[j]))
    mid = a[{(0, 1): 3, (1, 2): 4, (0, 2): 5}[(i, j)]]  # Exodus TRI6: mid-side nodes of edges 01, 12, 20
    # the quadratic curve x(s) = a_i N0 + a_j N1 + mid N2, s in [0, 1]: 3-point Gauss on |x'(s)|
    total = 0.0
    for s, w in ((0.5 - 0.5 * np.sqrt(0.6), 5 / 18), (0.5, 8 / 18), (0.5 + 0.5 * np.sqrt(0.6), 5 / 18)):
        d = a[i] * (4 * s - 3) + a[j] * (4 * s - 1) + mid * (4 - 8 * s)
        total += w * np.linalg.norm(d)
    return float(total)


def pieces_at(fragments, t, min_elements):
    """The fragment table at output time t: masses, the index of the main piece (most elements), and which
    of the others count as fragments (at least min_elements elements)."""
    sel = fragments["time"] == t
    masses, counts = fragments["mass"][sel], fragments["elements"][sel]
    main_piece = int(np.argmax(counts))
    keep = counts >= min_elements
    keep[main_piece] = False
    return masses, main_piece, keep


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("base")
    p.add_argument("--time", type=float, help="output time of the fragment table (nearest; default: the last)")
    p.add_argument("--min-elements", type=int, default=1, help="smallest fragment counted (elements)")
    p.add_argument("--time-unit", default="ms", choices=("s", "ms", "us"))
    p.add_argument("-o", "--output", help="PNG (default BASE_fracture.png)")
    p.add_argument("--csv", help="CSV (default BASE_fracture.csv)")
    a = p.parse_args()
    if a.time is not None and not np.isfinite(a.time):
        fail("--time %s is not a finite time" % a.time)
    base = a.base
    png = a.output or base + "_fracture.png"
    out_csv = a.csv or base + "_fracture.csv"
    history = read_csv(base + "_history.csv")
    cracks = read_csv(base + "_cracks.csv")
    fragments = read_csv(base + "_fragments.csv")
    for name, table in (("history", history), ("cracks", cracks), ("fragments", fragments)):
        if len(next(iter(table.values()))) == 0 and name != "cracks":
            fail("%s_%s.csv has no rows" % (base, name))

    nodes = element_nodes(exodus_files(base))
    lengths = []
    for em, ep in zip(cracks["element_minus"], cracks["element_plus"]):
        a_nodes, b_nodes = nodes.get(int(em)), nodes.get(int(ep))
        length = edge_length(a_nodes, b_nodes) if a_nodes is not None and b_nodes is not None else None
        if length is None:
            fail("elements %d and %d of the crack log share no edge in the Exodus results" % (em, ep))
        lengths.append(length)
    lengths = np.array(lengths)
    crack_time = cracks["time"]

    frame_times = np.unique(fragments["time"])
    rows = []
    for t in frame_times:
        masses, main_piece, keep = pieces_at(fragments, t, a.min_elements)
        h = np.argmin(np.abs(history["time"] - t))
        rows.append({
            "time": t,
            "pieces": int(len(masses)),
            "crack_length": float(np.sum(lengths[crack_time <= t * (1 + 1e-12)])),
            "cohesive_edges": int(history["num_cohesive_edges"][h]),
            "separated_edges": int(history["num_separated_edges"][h]),
            "fragments": int(np.sum(keep)),
            "fragment_mass": float(np.sum(masses[keep])),
            "largest_fragment_mass": float(np.max(masses[keep])) if keep.any() else 0.0,
            "main_piece_mass": float(masses[main_piece]),
        })
    tmp = out_csv + ".part"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.10g" % v if isinstance(v, float) else v) for k, v in r.items()})
    os.replace(tmp, out_csv)

    t_pick = frame_times[-1] if a.time is None else frame_times[np.argmin(np.abs(frame_times - a.time))]
    masses, _, keep = pieces_at(fragments, t_pick, a.min_elements)
    scale = {"s": 1.0, "ms": 1e3, "us": 1e6}[a.time_unit]
    row = rows[int(np.argmin(np.abs(frame_times - t_pick)))]
    print("t = %g %s: crack length %.4g, %d cohesive and %d separated edges, %d pieces (the history's "
          "num_fragments): the main piece (the one of most elements) of mass %.6g and %d fragments (of >= %d "
          "elements) of mass %.4g in all (largest %.4g)"
          % (t_pick * scale, a.time_unit, row["crack_length"], row["cohesive_edges"], row["separated_edges"],
             row["pieces"], row["main_piece_mass"], row["fragments"], a.min_elements, row["fragment_mass"],
             row["largest_fragment_mass"]))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    order = np.argsort(crack_time, kind="stable")
    t_end = history["time"][-1] * scale
    ax[0, 0].step(np.concatenate([[0.0], crack_time[order] * scale, [t_end]]),
                  np.concatenate([[0.0], np.cumsum(lengths[order]), [np.sum(lengths)]]), where="post", color="C3")
    ax[0, 0].set_xlabel("time [%s]" % a.time_unit)
    ax[0, 0].set_ylabel("crack length of the activated edges (mesh units)")
    ax[0, 0].grid(alpha=0.3)
    ax[0, 1].plot(history["time"] * scale, history["num_cohesive_edges"], label="activated edges")
    ax[0, 1].plot(history["time"] * scale, history["num_separated_edges"], label="separated edges")
    ax[0, 1].set_xlabel("time [%s]" % a.time_unit)
    ax[0, 1].set_ylabel("edges")
    ax[0, 1].legend()
    ax[0, 1].grid(alpha=0.3)
    ax[1, 0].step([r["time"] * scale for r in rows], [r["fragments"] for r in rows], where="post", color="C2")
    ax[1, 0].set_xlabel("time [%s]" % a.time_unit)
    ax[1, 0].set_ylabel("fragments (without the main piece)")
    ax[1, 0].grid(alpha=0.3)
    if keep.any():
        m = masses[keep]
        bins = np.logspace(np.log10(m.min()) - 0.05, np.log10(m.max()) + 0.05, min(25, max(5, len(m) // 3)))
        ax[1, 1].hist(m, bins=bins, color="C0", edgecolor="k")
        ax[1, 1].set_xscale("log")
    ax[1, 1].set_xlabel("fragment mass")
    ax[1, 1].set_ylabel("fragments")
    ax[1, 1].set_title("t = %g %s: %d fragments" % (t_pick * scale, a.time_unit, int(keep.sum())), fontsize=10)
    ax[1, 1].grid(alpha=0.3)
    for axis in (ax[0, 0], ax[0, 1], ax[1, 0]):
        axis.set_xlim(0.0, t_end)
    fig.suptitle(os.path.basename(base))
    fig.tight_layout()
    tmp = png + ".part.png"
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, png)
    print("fracture_summary.py: wrote %s and %s" % (png, out_csv))


if __name__ == "__main__":
    main()
