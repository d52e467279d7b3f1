"""The files of a shellfrac Exodus result, as the program writes them: one file, or the per-rank set
<path>.<np>.<rank> (np and rank zero-padded to the same width). Names are taken literally (no glob patterns), and a
set must be complete: a missing rank file, or files of two sets (two rank counts), is an error, never a silent gap.
"""
import os
import re


class ResultsError(Exception):
    """A result that cannot be read as one data set; the message names the path and what is wrong."""


def rank_files(path):
    """[path] if it is a regular file, else the files of the complete per-rank set path.<np>.<rank> in rank order."""
    if os.path.isfile(path):
        return [path]
    directory, base = os.path.split(path)
    pattern = re.compile(re.escape(base) + r"\.([0-9]+)\.([0-9]+)$")
    sets = {}
    for name in os.listdir(directory or "."):
        m = pattern.match(name)
        if m and len(m.group(1)) == len(m.group(2)) and str(int(m.group(1))) == m.group(1) and int(m.group(1)) > 1:
            sets.setdefault(int(m.group(1)), {})[int(m.group(2))] = os.path.join(directory, name)
    if not sets:
        raise ResultsError("%s: no such results file, and no per-rank set %s.<np>.<rank>" % (path, path))
    if len(sets) > 1:
        raise ResultsError("%s: several per-rank sets are present (np = %s); remove the stale files"
                           % (path, ", ".join(str(n) for n in sorted(sets))))
    np_, ranks = next(iter(sets.items()))
    missing = [r for r in range(np_) if r not in ranks]
    if missing:
        width = len(str(np_))
        raise ResultsError("%s: the per-rank set for np = %d is incomplete: %s.%d.%0*d is missing"
                           % (path, np_, path, np_, width, missing[0]))
    return [ranks[r] for r in range(np_)]
