"""shellfrac's CSV tables (docs/output.md): `<base>_history.csv`, `<base>_cracks.csv`, `<base>_fragments.csv`, read by
column name as numpy arrays."""
import csv
import os

import numpy as np

from .cli import note


class TableError(Exception):
    """A table that cannot be read; the message names the file (and the line) and what is wrong."""


def read_table(path):
    """{column name: numpy array} of a shellfrac CSV table (a header line, then rows of numbers).

    A last line without its newline is a row still being written (a running or cut run): it is left out, with a
    note. Any other row that is not complete numbers is a TableError naming the file and the line."""
    if not os.path.exists(path):
        raise TableError("missing %s" % path)
    with open(path, newline="") as f:
        text = f.read()
    lines = text.split("\n")
    if lines and lines[-1] != "":
        note("%s ends in a partial line (a run still writing?): left out" % path)
    lines = lines[:-1]
    if not lines:
        raise TableError("%s is empty" % path)
    header = next(csv.reader([lines[0]]))
    body = []
    for number, line in enumerate(lines[1:], start=2):
        try:
            values = [float(v) for v in line.split(",")]
        except ValueError:
            values = None
        if values is None or len(values) != len(header):
            raise TableError("%s: line %d is not %d numbers: '%s'" % (path, number, len(header), line[:80]))
        body.append(values)
    data = np.array(body, dtype=float).reshape(len(body), len(header))
    return {name: data[:, k] for k, name in enumerate(header)}


def column(table, name, path):
    """table[name], or a TableError naming the file and the columns it has."""
    if name not in table:
        raise TableError("%s: no column '%s'; available columns: %s" % (path, name, ", ".join(table)))
    return table[name]


def fragments_path(results):
    """`<base>_fragments.csv` of a results name (`<base>.exo`, a per-rank file `<base>.exo.<np>.<rank>` or `<base>`)."""
    base = results
    if ".exo." in os.path.basename(base):
        base = base[:base.rindex(".exo.")]
    elif base.endswith(".exo"):
        base = base[:-len(".exo")]
    return base + "_fragments.csv"


def pieces_at(results, time):
    """The pieces of the fragment table at the frame `time`, largest first (most elements, then the lower id):
    [(fragment id, elements, mass, speed of the centre of mass)]; [] when the run wrote no fragment table or no
    rows at that time. A TableError for a table that cannot be read."""
    path = fragments_path(results)
    if time is None or not os.path.exists(path):
        return []
    table = read_table(path)
    for name in ("time", "fragment_id", "elements", "mass", "momentum_x", "momentum_y", "momentum_z"):
        column(table, name, path)
    at = np.isclose(table["time"], time, rtol=1e-12, atol=0.0)
    mass = table["mass"][at]
    momentum = np.stack([table["momentum_" + c][at] for c in "xyz"], axis=1)
    speed = np.linalg.norm(momentum, axis=1) / np.where(mass > 0, mass, 1.0)
    pieces = [(int(i), int(n), float(m), float(v))
              for i, n, m, v in zip(table["fragment_id"][at], table["elements"][at], mass, speed)]
    return sorted(pieces, key=lambda p: (-p[1], p[0]))
