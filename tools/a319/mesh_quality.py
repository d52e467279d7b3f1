#!/usr/bin/python3
"""Triangle quality and connectivity of a Gmsh msh 4.1 (ASCII) surface mesh.

    /usr/bin/python3 tools/a319/mesh_quality.py MESH.msh [--smallest N] [--surfaces] [--parts] [--json]

Reads the nodes and the triangles (element type 2, TRI3, or 9, TRI6: the corner nodes are used) and prints
the number of triangles, the total area, the distribution of the smallest triangle height 2A / (longest edge)
(min, 0.1 %, 1 %, median, max), the shortest edge, the edge counts (edges with 1, 2 and more than 2
triangles: boundary, manifold and non-manifold; and manifold edges whose two triangles run through them the
same way, i.e. inconsistently oriented), the connected components, and the N smallest elements with their
centroids. --surfaces adds one row per surface entity (triangles, area, bounding box). --parts sorts the
surfaces of the A319 skin into fuselage, wings, horizontal tail and fin by their bounding boxes (see PARTS).
Lengths are in the mesh's units. Needs numpy (Debian's /usr/bin/python3 with python3-numpy).
"""
import argparse
import json
import sys

import numpy as np


def read_msh41(path):
    """Returns (node tags, coordinates, triangles as node tags (n, 3), element tags, surface entity tags)."""
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    n = len(lines)
    i = 0
    fmt = None
    node_tags, node_xyz = [], []
    tris, tri_tags, tri_ent = [], [], []
    while i < n:
        line = lines[i].strip()
        if line == "$MeshFormat":
            fmt = lines[i + 1].split()
            if not fmt[0].startswith("4.1"):
                sys.exit(f"mesh_quality.py: {path}: msh version {fmt[0]}, expected 4.1")
            if fmt[1] != "0":
                sys.exit(f"mesh_quality.py: {path}: binary msh; save it as ASCII (-format msh41)")
            i += 2
        elif line == "$Nodes":
            n_blocks = int(lines[i + 1].split()[0])
            i += 2
            for _ in range(n_blocks):
                _, _, parametric, count = (int(v) for v in lines[i].split())
                i += 1
                if count == 0:
                    continue
                tags = np.array(" ".join(lines[i:i + count]).split(), dtype=np.int64)
                i += count
                xyz = np.array(" ".join(lines[i:i + count]).split(), dtype=np.float64).reshape(count, -1)
                i += count
                node_tags.append(tags)
                node_xyz.append(xyz[:, :3])
        elif line == "$Elements":
            n_blocks = int(lines[i + 1].split()[0])
            i += 2
            for _ in range(n_blocks):
                dim, ent, etype, count = (int(v) for v in lines[i].split())
                i += 1
                if etype in (2, 9) and count:
                    a = np.array(" ".join(lines[i:i + count]).split(), dtype=np.int64).reshape(count, -1)
                    tri_tags.append(a[:, 0])
                    tris.append(a[:, 1:4])
                    tri_ent.append(np.full(count, ent, dtype=np.int64))
                i += count
        else:
            i += 1
    if fmt is None:
        sys.exit(f"mesh_quality.py: {path}: no $MeshFormat section (not a Gmsh msh file?)")
    if not tris:
        sys.exit(f"mesh_quality.py: {path}: no triangles (element types 2 or 9)")
    tags = np.concatenate(node_tags)
    xyz = np.concatenate(node_xyz)
    return tags, xyz, np.concatenate(tris), np.concatenate(tri_tags), np.concatenate(tri_ent)


# The A319 skin (x aft from the nose, y to starboard, z up; metres): the fuselage stays within |y| < 2.1 and
# z < 2.0; a surface reaching beyond |y| = 2.2 is a wing (x < 25) or the horizontal tail (x > 25), one
# reaching above z = 2.2 is the fin.
PARTS = ("fuselage", "wings", "horizontal tail", "fin")


def part_of(bbox_min, bbox_max, unit):
    """The part of a surface from its bounding box; unit = metres per mesh unit."""
    lo = [v * unit for v in bbox_min]
    hi = [v * unit for v in bbox_max]
    if hi[2] > 2.2:
        return "fin"
    if max(abs(lo[1]), abs(hi[1])) > 2.2:
        return "horizontal tail" if lo[0] > 25.0 else "wings"
    return "fuselage"


def analyse(path, n_smallest):
    tags, xyz, tri_nodes, tri_tags, tri_ent = read_msh41(path)
    # Node tags to dense indices.
    order = np.argsort(tags)
    stags = tags[order]
    pos = np.searchsorted(stags, tri_nodes)
    if np.any(pos >= len(stags)) or np.any(stags[np.minimum(pos, len(stags) - 1)] != tri_nodes):
        sys.exit(f"mesh_quality.py: {path}: a triangle refers to a missing node")
    t = order[pos]                                   # (n, 3) dense node indices
    p0, p1, p2 = xyz[t[:, 0]], xyz[t[:, 1]], xyz[t[:, 2]]
    e = np.stack([np.linalg.norm(p2 - p1, axis=1),
                  np.linalg.norm(p0 - p2, axis=1),
                  np.linalg.norm(p1 - p0, axis=1)], axis=1)
    area = 0.5 * np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)
    longest = e.max(axis=1)
    height = np.where(longest > 0, 2.0 * area / np.where(longest > 0, longest, 1.0), 0.0)
    centroid = (p0 + p1 + p2) / 3.0

    # Edges: (a, b) with a < b, and the direction each triangle runs through it.
    a = np.concatenate([t[:, 0], t[:, 1], t[:, 2]])
    b = np.concatenate([t[:, 1], t[:, 2], t[:, 0]])
    forward = a < b
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo.astype(np.int64) * (len(xyz) + 1) + hi
    uniq, inv, counts = np.unique(key, return_inverse=True, return_counts=True)
    n_edges = len(uniq)
    boundary = int(np.sum(counts == 1))
    manifold = int(np.sum(counts == 2))
    nonmanifold = int(np.sum(counts > 2))
    fwd_per_edge = np.bincount(inv, weights=forward.astype(np.float64), minlength=n_edges)
    inconsistent = int(np.sum((counts == 2) & (fwd_per_edge != 1)))
    degenerate = int(np.sum(t[:, 0] == t[:, 1]) + np.sum(t[:, 1] == t[:, 2]) + np.sum(t[:, 2] == t[:, 0]))

    # Connected components of the triangles through shared edges (union-find on edge ids).
    n_tri = len(t)
    tri_of_slot = np.tile(np.arange(n_tri), 3)
    parent = np.arange(n_tri)
    first = np.full(n_edges, -1, dtype=np.int64)
    # Link each triangle to the first triangle of each of its edges, then compress until stable.
    order_e = np.argsort(inv, kind="stable")
    inv_sorted = inv[order_e]
    starts = np.r_[0, np.flatnonzero(np.diff(inv_sorted)) + 1]
    first[inv_sorted[starts]] = tri_of_slot[order_e[starts]]
    u, v = tri_of_slot, first[inv]
    while True:
        pu, pv = parent[u], parent[v]
        m = np.minimum(pu, pv)
        changed = np.any(pu != pv)
        np.minimum.at(parent, pu, m)
        np.minimum.at(parent, pv, m)
        parent = parent[parent]
        while True:
            nxt = parent[parent]
            if np.array_equal(nxt, parent):
                break
            parent = nxt
        if not changed:
            break
    components = int(len(np.unique(parent)))

    q = lambda x: float(np.quantile(height, x))
    smallest = np.argsort(height)[:n_smallest]
    surfaces = []
    extent = float(np.max(xyz.max(axis=0) - xyz.min(axis=0)))
    unit = 1e-3 if extent > 1000.0 else 1.0          # millimetres or metres
    for ent in np.unique(tri_ent):
        m = tri_ent == ent
        used = np.unique(t[m])
        lo_b, hi_b = xyz[used].min(axis=0), xyz[used].max(axis=0)
        surfaces.append({"surface": int(ent), "triangles": int(m.sum()), "area": float(area[m].sum()),
                         "min_height": float(height[m].min()),
                         "bbox_min": lo_b.tolist(), "bbox_max": hi_b.tolist(),
                         "part": part_of(lo_b, hi_b, unit)})
    parts = {name: {"surfaces": sum(1 for x in surfaces if x["part"] == name),
                    "triangles": sum(x["triangles"] for x in surfaces if x["part"] == name),
                    "area": sum(x["area"] for x in surfaces if x["part"] == name)} for name in PARTS}
    return {
        "file": path,
        "nodes": int(len(xyz)),
        "triangles": int(n_tri),
        "area": float(area.sum()),
        "bbox_min": xyz.min(axis=0).tolist(),
        "bbox_max": xyz.max(axis=0).tolist(),
        "height": {"min": float(height.min()), "p0.1": q(0.001), "p1": q(0.01), "median": q(0.5),
                   "max": float(height.max())},
        "shortest_edge": float(e.min()),
        "longest_edge": float(e.max()),
        "edges": {"total": n_edges, "boundary (1 triangle)": boundary, "manifold (2)": manifold,
                  "non-manifold (>2)": nonmanifold, "inconsistently oriented (2)": inconsistent},
        "degenerate_triangles": degenerate,
        "components": components,
        "smallest": [{"element": int(tri_tags[k]), "surface": int(tri_ent[k]), "height": float(height[k]),
                      "shortest_edge": float(e[k].min()), "centroid": centroid[k].tolist()}
                     for k in smallest],
        "surfaces": surfaces,
        "parts": parts,
        "unit": "mm" if unit == 1e-3 else "m",
    }


def g(x):
    return f"{x:.4g}"


def print_report(r, show_surfaces, show_parts):
    h = r["height"]
    print(f"{r['file']}")
    rows = [("triangles", f"{r['triangles']}"), ("nodes", f"{r['nodes']}"), ("total area", g(r["area"])),
            ("bounding box", "(" + ", ".join(g(v) for v in r["bbox_min"]) + ") - ("
             + ", ".join(g(v) for v in r["bbox_max"]) + ")"),
            ("height min", g(h["min"])), ("height 0.1 %", g(h["p0.1"])), ("height 1 %", g(h["p1"])),
            ("height median", g(h["median"])), ("height max", g(h["max"])),
            ("height min / median", g(h["min"] / h["median"])),
            ("shortest edge", g(r["shortest_edge"])), ("longest edge", g(r["longest_edge"]))]
    rows += [(f"edges {k}", f"{v}") for k, v in r["edges"].items()]
    rows += [("degenerate triangles", f"{r['degenerate_triangles']}"),
             ("connected components", f"{r['components']}")]
    w = max(len(k) for k, _ in rows)
    print(f"| {'quantity'.ljust(w)} | value |")
    print(f"|{'-' * (w + 2)}|-------|")
    for k, v in rows:
        print(f"| {k.ljust(w)} | {v} |")
    print()
    print(f"{len(r['smallest'])} smallest triangles (height 2A / longest edge):")
    print("| element | surface | height | shortest edge | centroid |")
    print("|---|---|---|---|---|")
    for s in r["smallest"]:
        c = ", ".join(g(v) for v in s["centroid"])
        print(f"| {s['element']} | {s['surface']} | {g(s['height'])} | {g(s['shortest_edge'])} | ({c}) |")
    if show_surfaces:
        print()
        print("| surface | part | triangles | area | min height | x min | x max | y min | y max | z min | z max |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for s in r["surfaces"]:
            lo, hi = s["bbox_min"], s["bbox_max"]
            print(f"| {s['surface']} | {s['part']} | {s['triangles']} | {g(s['area'])} | {g(s['min_height'])} | "
                  f"{g(lo[0])} | {g(hi[0])} | {g(lo[1])} | {g(hi[1])} | {g(lo[2])} | {g(hi[2])} |")
    if show_parts:
        print()
        print(f"parts of the A319 skin (by surface bounding box; mesh in {r['unit']}):")
        print("| part | surfaces | triangles | share | area |")
        print("|---|---|---|---|---|")
        for name, p in r["parts"].items():
            print(f"| {name} | {p['surfaces']} | {p['triangles']} | {100.0 * p['triangles'] / r['triangles']:.1f} % "
                  f"| {g(p['area'])} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", help="Gmsh msh 4.1 ASCII file")
    ap.add_argument("--smallest", type=int, default=10, help="how many of the smallest triangles to list")
    ap.add_argument("--surfaces", action="store_true", help="one row per surface entity")
    ap.add_argument("--parts", action="store_true", help="triangles of the fuselage, wings and tail (A319)")
    ap.add_argument("--json", action="store_true", help="print the measures as JSON instead of tables")
    args = ap.parse_args()
    try:
        r = analyse(args.mesh, args.smallest)
    except OSError as exc:
        sys.exit(f"mesh_quality.py: {exc}")
    if args.json:
        if not args.surfaces:
            del r["surfaces"]
        if not args.parts:
            del r["parts"]
        json.dump(r, sys.stdout, indent=1)
        print()
    else:
        print_report(r, args.surfaces, args.parts)


if __name__ == "__main__":
    main()
