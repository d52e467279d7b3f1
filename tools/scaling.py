#!/usr/bin/python3
"""The scaling study of paper §6.4 (Fig. 19) with shellfrac_bench: time per explicit step against the number of
processors (cores = ranks x threads), weak and strong, over every (ranks x threads) layout up to --max-cores; and
the size study: time per element-step (by phase) and memory per element against the number of elements, on one
layout.

usage: scaling.py [--max-cores N] [--bench BUILD/bench/shellfrac_bench] [--mpiexec mpiexec] [--steps 100]
                  [--warmup 5] [--repeats 3] [--study weak strong size] [--strong-sizes 16000 64000 256000]
                  [--sizes 16000 64000 256000 686440] [--size-ranks 2]
                  [-o scaling]                       (writes scaling.csv, one row per run, and scaling.png)

The problem is the paper's cantilever strip (xml/cantilever_200x40.xml: 10 m x 2 m, 200 x 40 grid cells of two
TRI6 each, 16 000 elements). Weak study: 16 000 elements per core; P = 4^k cores get the strip refined k times
(200 2^k x 40 2^k cells, as the paper's uniform refinement x4 per processors x4) and P = 2 x 4^k cores get it
refined k times and doubled along the length. Strong study: 16 000, 64 000 and 256 000 elements (200 x 40,
400 x 80, 800 x 160) on every P. Size study (not run unless asked): the strip of 5 w x w cells (10 w^2 elements:
--sizes, each 10 w^2) on --size-ranks ranks x 1 thread; per size the median µs per element-step of the run and
of each phase, the model's bytes per element and the peak resident memory of all ranks per element. P runs over the powers of 2 up to --max-cores (default: the cores of this
machine); each P over every layout ranks x threads = P (ranks and threads powers of 2; threads only when the
benchmark was built with Kokkos OpenMP: tools/build-trilinos.sh, README "for threads"). Each run is repeated
--repeats times and the median wall time per step is plotted; the CSV holds every run with its phases.
Open MPI: set the launcher's flags with --mpiexec-flags (tools/mpi-env.sh sets the root and oversubscribe
variables; `--bind-to none` keeps ranks from sharing a core with another rank's threads).
"""
import argparse
import csv
import math
import os
import re
import statistics
import subprocess
import tempfile

from shellfrac_tools.cli import fail

HERE = os.path.dirname(os.path.abspath(__file__))
PROJECT = os.path.dirname(HERE)
BASE_CELLS = (200, 40)
PHASES = ("element_kernel", "interface_kernel", "gather", "communication", "update")


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--max-cores", type=int, default=os.cpu_count() or 1)
    p.add_argument("--bench", default=os.path.join(PROJECT, "build", "bench", "shellfrac_bench"))
    p.add_argument("--mpiexec", default="mpiexec")
    p.add_argument("--mpiexec-flags", default="--bind-to none", help="extra launcher flags (one string)")
    p.add_argument("--steps", type=int, default=100)
    p.add_argument("--warmup", type=int, default=5)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--study", nargs="+", default=["weak", "strong"], choices=["weak", "strong", "size"])
    p.add_argument("--strong-sizes", type=int, nargs="+", default=[16000, 64000, 256000])
    p.add_argument("--sizes", type=int, nargs="+", default=[16000, 64000, 256000, 686440])
    p.add_argument("--size-ranks", type=int, default=2)
    p.add_argument("--deck", default=os.path.join(PROJECT, "xml", "cantilever_200x40.xml"))
    p.add_argument("-o", "--output", default="scaling", help="output base: BASE.csv and BASE.png")
    p.add_argument("--replot", metavar="CSV", help="no runs: redraw BASE.png and the table from a CSV of this tool")
    a = p.parse_args()
    if a.replot:
        return a
    if a.max_cores < 1 or a.steps < 1 or a.repeats < 1 or a.warmup < 0:
        fail("--max-cores, --steps and --repeats must be positive, --warmup non-negative")
    if not os.access(a.bench, os.X_OK):
        fail("no benchmark executable %s (build it: cmake --build BUILD --target shellfrac_bench)" % a.bench)
    if not os.path.isfile(a.deck):
        fail("no deck %s" % a.deck)
    for n in a.strong_sizes:
        cells = n // 2
        k = round(math.log(cells / (BASE_CELLS[0] * BASE_CELLS[1]), 4))
        if k < 0 or BASE_CELLS[0] * BASE_CELLS[1] * 4 ** k * 2 != n:
            fail("--strong-sizes must be 16000 x 4^k elements (got %d)" % n)
    for n in a.sizes:
        if cells_for_strip(n) is None:
            fail("--sizes must be 10 w^2 elements, the strip of 5 w x w cells (got %d)" % n)
    return a


def powers_of_two(limit):
    p = 1
    while p <= limit:
        yield p
        p *= 2


def cells_for_weak(cores):
    """Grid cells for 16 000 elements per core: refined k times (x4) and doubled along the length if needed."""
    k = int(math.log(cores, 4) + 1e-9)
    doubled = cores // 4 ** k  # 1 or 2
    return BASE_CELLS[0] * 2 ** k * doubled, BASE_CELLS[1] * 2 ** k


def cells_for_strip(elements):
    """The strip of 5 w x w cells with `elements` = 10 w^2 TRI6 elements (the 200 x 40 strip's aspect), or None."""
    w = round(math.sqrt(elements / 10))
    return (5 * w, w) if 10 * w * w == elements else None


def cells_for_size(elements):
    k = round(math.log(elements // 2 / (BASE_CELLS[0] * BASE_CELLS[1]), 4))
    return BASE_CELLS[0] * 2 ** k, BASE_CELLS[1] * 2 ** k


def write_deck(template, cells, folder):
    text = template
    for name, value in (("Elements Along Length", cells[0]), ("Elements Along Width", cells[1])):
        text, n = re.subn(r'(<Parameter name="%s" type="int" value=")\d+"' % name, r"\g<1>%d" % value + '"', text)
        if n != 1:
            fail("the deck has no single '%s' parameter" % name)
    path = os.path.join(folder, "strip_%dx%d.xml" % cells)
    with open(path, "w") as f:
        f.write(text)
    return path


def run_bench(a, deck, ranks, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="false")
    cmd = [a.mpiexec, "-np", str(ranks)] + a.mpiexec_flags.split() + \
        [a.bench, deck, "--steps", str(a.steps), "--warmup", str(a.warmup)]
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        fail("%s failed (exit %d):\n%s%s" % (" ".join(cmd), r.returncode, r.stdout, r.stderr))
    values = dict(re.findall(r"^(\w+)=([0-9.eE+-]+)", r.stdout, re.M))
    elements = re.search(r"(\d+) elements", r.stdout)
    if "total_us_per_element_step" not in values or not elements:
        fail("unexpected output of %s:\n%s" % (" ".join(cmd), r.stdout))
    values = {k: float(v) for k, v in values.items()}
    values["elements"] = int(elements.group(1))
    values["threads_seen"] = int(values.get("threads", 1))
    return values


def bench_threads(a, folder, template):
    """How many threads the benchmark uses when given 2 (1 on a Kokkos Serial build)."""
    deck = write_deck(template, (20, 4), folder)
    return run_bench(a, deck, 1, 2)["threads_seen"]


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail("%s has no rows" % path)
    for row in rows:
        for k in row:
            if k in ("elements", "cores", "ranks", "threads", "repeat"):
                row[k] = int(row[k])
            elif k != "study":
                row[k] = float(row[k])
    return rows


def main():
    a = parse()
    if a.replot:
        report(read_rows(a.replot), a.output, None)
        print("scaling.py: wrote the figures of %s" % a.output)
        return
    template = open(a.deck).read()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        threaded = bench_threads(a, folder, template) > 1
        layouts = [(p, r, p // r) for p in powers_of_two(a.max_cores) for r in powers_of_two(p)
                   if threaded or r == p]
        plan = []
        if "weak" in a.study:
            plan += [("weak", cells_for_weak(p), p, r, t) for p, r, t in layouts]
        if "strong" in a.study:
            plan += [("strong", cells_for_size(n), p, r, t) for n in a.strong_sizes for p, r, t in layouts]
        if "size" in a.study:
            plan += [("size", cells_for_strip(n), a.size_ranks, a.size_ranks, 1) for n in a.sizes]
        print("scaling.py: %d layouts (%s), %d runs x %d repeats, %d steps each; threads %s"
              % (len(layouts), ", ".join("%dx%d" % (r, t) for _, r, t in layouts), len(plan), a.repeats, a.steps,
                 "available" if threaded else "not built (Kokkos Serial): ranks only"), flush=True)
        decks = {cells: write_deck(template, cells, folder) for _, cells, _, _, _ in plan}
        # the repeats go round the whole plan, so that a slow spell of the machine hits every layout alike
        for rep in range(a.repeats):
            for study, cells, p, r, t in plan:
                deck = decks[cells]
                v = run_bench(a, deck, r, t)
                seconds = v["total_us_per_element_step"] * v["elements"] * 1e-6
                row = {"study": study, "elements": v["elements"], "cores": p, "ranks": r, "threads": t,
                       "repeat": rep + 1, "seconds_per_step": seconds,
                       "us_per_element_step": v["total_us_per_element_step"]}
                row.update({ph: v.get(ph + "_us_per_element_step", float("nan")) for ph in PHASES})
                row["bytes_per_element"] = v.get("bytes_per_element", float("nan"))
                row["peak_bytes_per_element"] = v.get("peak_resident_bytes_per_element", float("nan"))
                rows.append(row)
                print("  %-6s %7d elements  %2d cores = %d ranks x %d threads  %.4g s per step"
                      % (study, v["elements"], p, r, t, seconds), flush=True)
    tmp = a.output + ".csv.part"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for row in rows:
            w.writerow({k: ("%.6g" % x if isinstance(x, float) else x) for k, x in row.items()})
    os.replace(tmp, a.output + ".csv")
    report(rows, a.output, a.steps)
    print("scaling.py: wrote %s.csv and %s.png" % (a.output, a.output))


def report(rows, output, steps):
    """The tables and the figures: BASE.png for the weak and strong studies, BASE_size.png for the size study."""
    scaling = [r for r in rows if r["study"] != "size"]
    if scaling:
        summary = summarise(scaling)
        print_table(summary)
        plot(summary, output + ".png", steps)
    sizes = [r for r in rows if r["study"] == "size"]
    if sizes:
        summary = summarise_sizes(sizes)
        print_size_table(summary)
        plot_sizes(summary, output + "_size.png", steps)


def summarise(rows):
    """Median seconds per step per (study, elements or per-core size, cores, ranks, threads), with efficiencies."""
    groups = {}
    for row in rows:
        key = (row["study"], row["elements"] if row["study"] == "strong" else 0, row["cores"], row["ranks"],
               row["threads"])
        groups.setdefault(key, []).append(row)
    summary = []
    for key, g in sorted(groups.items()):
        study, size, cores, ranks, threads = key
        entry = {"study": study, "size": size, "elements": g[0]["elements"], "cores": cores, "ranks": ranks,
                 "threads": threads, "seconds": statistics.median(r["seconds_per_step"] for r in g),
                 "low": min(r["seconds_per_step"] for r in g), "high": max(r["seconds_per_step"] for r in g),
                 "runs": len(g)}
        for ph in PHASES:
            entry[ph] = statistics.median(r[ph] for r in g)
        summary.append(entry)
    for e in summary:
        base = [b for b in summary if b["study"] == e["study"] and b["size"] == e["size"] and b["cores"] == 1]
        t1 = base[0]["seconds"] if base else float("nan")
        e["efficiency"] = t1 / e["seconds"] if e["study"] == "weak" else t1 / (e["cores"] * e["seconds"])
    return summary


def summarise_sizes(rows):
    """Per size: the medians of the run's and each phase's µs per element-step, and of the memory per element."""
    groups = {}
    for row in rows:
        groups.setdefault(row["elements"], []).append(row)
    summary = []
    for elements, g in sorted(groups.items()):
        entry = {"elements": elements, "ranks": g[0]["ranks"], "runs": len(g)}
        for k in ("us_per_element_step",) + PHASES + ("bytes_per_element", "peak_bytes_per_element"):
            entry[k] = statistics.median(r.get(k, float("nan")) for r in g)
        entry["low"] = min(r["us_per_element_step"] for r in g)
        entry["high"] = max(r["us_per_element_step"] for r in g)
        summary.append(entry)
    return summary


def print_size_table(summary):
    print("| elements | ranks | µs per element-step (median) | min - max | element | interface | gather | "
          "communication | update | model kB per element | peak kB per element | runs |")
    print("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for e in summary:
        print("| %d | %d | %.3f | %.3f - %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %d |"
              % (e["elements"], e["ranks"], e["us_per_element_step"], e["low"], e["high"], e["element_kernel"],
                 e["interface_kernel"], e["gather"], e["communication"], e["update"], e["bytes_per_element"] / 1024,
                 e["peak_bytes_per_element"] / 1024, e["runs"]))


def plot_sizes(summary, path, steps):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    elements = [e["elements"] for e in summary]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4))
    left.plot(elements, [e["us_per_element_step"] for e in summary], "o-", color="k", label="whole step")
    for c, ph in enumerate(PHASES):
        left.plot(elements, [e[ph] for e in summary], "s--", color="C%d" % c, mfc="none", label=ph.replace("_", " "))
    left.set_ylabel("µs per element-step (median)")
    left.set_ylim(0, 1.45 * max(e["us_per_element_step"] for e in summary))
    left.set_title("time, %d ranks" % summary[0]["ranks"] + (" (%d steps)" % steps if steps else ""))
    right.plot(elements, [e["peak_bytes_per_element"] / 1024 for e in summary], "o-", color="k",
               label="peak resident memory of all ranks")
    right.plot(elements, [e["bytes_per_element"] / 1024 for e in summary], "s--", color="C0", mfc="none",
               label="state, model and force buffers")
    right.set_ylabel("kB per element (1 kB = 1024 B)")
    right.set_ylim(bottom=0)
    right.set_title("memory, %d ranks" % summary[0]["ranks"])
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_xlabel("elements")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="upper center" if ax is left else "lower left", ncol=3 if ax is left else 1)
    fig.tight_layout()
    tmp = path + ".part.png"
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, path)


def print_table(summary):
    print("| study | elements | cores | ranks x threads | s per step (median) | min - max | runs | efficiency | "
          "communication µs/el-step |")
    print("|---|---:|---:|---|---:|---|---:|---:|---:|")
    for e in summary:
        print("| %s | %d | %d | %d x %d | %.4g | %.4g - %.4g | %d | %.2f | %.3f |"
              % (e["study"], e["elements"], e["cores"], e["ranks"], e["threads"], e["seconds"], e["low"], e["high"],
                 e["runs"], e["efficiency"], e["communication"]))


def plot(summary, path, steps):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import ticker
    studies = sorted({e["study"] for e in summary}, key=lambda s: s != "weak")
    fig, axes = plt.subplots(1, len(studies), figsize=(5.5 * len(studies), 4.4), squeeze=False)
    markers = {1: "o", 2: "s", 4: "^", 8: "D", 16: "v", 32: "P", 64: "X"}
    for ax, study in zip(axes[0], studies):
        entries = [e for e in summary if e["study"] == study]
        sizes = sorted({e["size"] for e in entries})
        for c, size in enumerate(sizes):
            mine = [e for e in entries if e["size"] == size]
            cores = sorted({e["cores"] for e in mine})
            best = [min((e for e in mine if e["cores"] == p), key=lambda e: e["seconds"]) for p in cores]
            label = "16 000 elements per core" if study == "weak" else "{:,} elements".format(size).replace(",", " ")
            ax.plot(cores, [e["seconds"] for e in best], "-", color="C%d" % c, label=label)
            t1 = [e for e in mine if e["cores"] == 1]
            if t1:
                ideal = [t1[0]["seconds"] if study == "weak" else t1[0]["seconds"] / p for p in cores]
                ax.plot(cores, ideal, ":", color="C%d" % c, alpha=0.8)
            for e in mine:
                ax.plot(e["cores"], e["seconds"], markers.get(e["threads"], "o"), color="C%d" % c, mfc="none")
        for t, m in sorted(markers.items()):
            if any(e["threads"] == t for e in entries):
                ax.plot([], [], m, color="k", mfc="none", label="%d thread%s per rank" % (t, "s" if t > 1 else ""))
        ax.plot([], [], ":", color="k", label="ideal")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        all_cores = sorted({e["cores"] for e in entries})
        ax.set_xticks(all_cores)
        ax.xaxis.set_major_formatter(ticker.ScalarFormatter())
        ax.xaxis.set_minor_locator(ticker.NullLocator())
        ax.yaxis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(ticker.FormatStrFormatter("%.3g"))
        seconds = [e["seconds"] for e in entries]
        within_a_decade = max(seconds) < 10 * min(seconds)
        ax.yaxis.set_minor_formatter(ticker.FormatStrFormatter("%.3g") if within_a_decade else ticker.NullFormatter())
        ax.set_xlabel("cores (ranks x threads)")
        ax.set_ylabel("wall time per step [s]")
        ax.set_title("%s scaling" % study + (" (%d steps)" % steps if steps else ""))
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = path + ".part.png"
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, path)


if __name__ == "__main__":
    main()
