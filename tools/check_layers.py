#!/usr/bin/python3
"""Checks that every shellfrac include in packages/ goes down the layers of packages/layers.txt.

Usage: check_layers.py [SOURCE_ROOT]   (default: the repository this script is in)
Prints each offending include as `file:line: layer A includes B (allowed: ...)` and exits 1 if there is any;
exits 2 if layers.txt is malformed (an unknown layer, a cycle) or a source file belongs to no layer.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"shellfrac/([a-z_]+)/(?:([a-z_]+)/)?[A-Za-z0-9_.]+"')


def read_layers(path):
    uses = {}
    for n, line in enumerate(path.read_text().splitlines(), 1):
        line = line.split('#', 1)[0].strip()
        if not line:
            continue
        name, _, rest = line.partition(':')
        if not _ or name.strip() in uses:
            sys.exit(f'{path}:{n}: expected `layer: used layers`, each layer once')
        uses[name.strip()] = rest.split()
    for name, used in uses.items():
        for u in used:
            if u not in uses:
                sys.exit(f'{path}: layer {name} uses {u}, which is not a layer')
    allowed = {}

    def closure(name, stack=()):
        if name in stack:
            sys.exit(f'{path}: the layers form a cycle: {" -> ".join(stack + (name,))}')
        if name not in allowed:
            out = {name}
            for u in uses[name]:
                out |= closure(u, stack + (name,))
            allowed[name] = out
        return allowed[name]

    for name in uses:
        closure(name)
    return uses, allowed


def layer_of_header(package, sub, layers):
    if sub and f'{package}/{sub}' in layers:
        return f'{package}/{sub}'
    return package


def layer_of_file(rel, layers):
    """rel: path below packages/<p>/src/shellfrac/, e.g. solver/step/loads.cpp."""
    parts = rel.parts
    if len(parts) > 2:
        room = f'{parts[0]}/{parts[1]}'
        if room in layers:
            return room
        if any(name.startswith(parts[0] + '/') for name in layers):
            return None  # a folder of a package with rooms must be one of its rooms
    return parts[0] if parts[0] in layers else None


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    uses, allowed = read_layers(root / 'packages' / 'layers.txt')
    bad, files = [], 0
    for src in sorted((root / 'packages').glob('*/src/shellfrac')):
        for f in sorted(src.rglob('*')):
            if f.suffix not in ('.hpp', '.cpp', '.h'):
                continue
            files += 1
            layer = layer_of_file(f.relative_to(src), uses)
            if layer is None:
                sys.exit(f'{f}: belongs to no layer of packages/layers.txt')
            for n, line in enumerate(f.read_text().splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                target = layer_of_header(m.group(1), m.group(2), uses)
                if target not in allowed[layer]:
                    bad.append(f'{f.relative_to(root)}:{n}: layer {layer} includes {target} '
                               f'(allowed: {" ".join(sorted(allowed[layer]))})')
    for b in bad:
        print(b)
    print(f'{files} files, {len(uses)} layers, {len(bad)} upward or sideways includes')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
