#!/usr/bin/python3
"""Plots one column of one or more shellfrac history CSVs against time, one curve per file.

usage: plot_history.py H1.csv [H2.csv ...] --column centre_displ_z [--label L ...]
                       [--time-scale 1e3 --time-unit ms] [--ylabel Y] [--title T] -o out.png

Exits with status 1 (naming the file and listing its columns) if a file lacks the column.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


from shellfrac_tools.tables import TableError, column, read_table  # noqa: E402


def plot_histories(paths, col, out, labels=None, time_scale=1.0, time_unit="s", ylabel=None, title=None):
    """Plots column col of each CSV in paths against time*time_scale into out. Raises TableError."""
    labels = list(labels or [])
    if len(labels) > len(paths):
        raise ValueError(f"{len(labels)} labels for {len(paths)} files")
    labels += [os.path.basename(p) for p in paths[len(labels):]]
    series = []
    for p in paths:
        h = read_table(p)
        series.append((column(h, "time", p), column(h, col, p)))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (t, y), lab in zip(series, labels):
        ax.plot(t * time_scale, y, label=lab)
    ax.set_xlabel(f"time [{time_unit}]")
    ax.set_ylabel(ylabel or col)
    if title:
        ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", nargs="+", help="history CSV files")
    ap.add_argument("--column", required=True, help="column to plot, e.g. centre_displ_z")
    ap.add_argument("--label", nargs="+", default=[], help="one legend label per file (default: file names)")
    ap.add_argument("--time-scale", type=float, default=1.0, help="factor applied to time (e.g. 1e3)")
    ap.add_argument("--time-unit", default="s", help="unit shown on the time axis (e.g. ms)")
    ap.add_argument("--ylabel", help="y-axis label (default: the column name)")
    ap.add_argument("--title")
    ap.add_argument("-o", "--output", required=True, help="output image, e.g. out.png")
    a = ap.parse_args()
    try:
        plot_histories(a.csv, a.column, a.output, a.label, a.time_scale, a.time_unit, a.ylabel, a.title)
    except (TableError, ValueError, OSError) as e:
        print(f"plot_history.py: error: {e}", file=sys.stderr)
        return 1
    print(f"wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
