#!/usr/bin/env python3
"""Reorders a Gmsh msh2 (ASCII) mesh for memory locality, in place: nodes along a Morton (Z-order)
curve of their position, elements by the Morton code of their centroid, both renumbered 1..n.

Why: gmsh's Delaunay output lists a node's tets all over the file (box_19k: the tets around a node
span a median 78 % of the element list), so per-node loops of the FEM step (fem/block_system.h
fill, the SpMV) miss the cache on every tet they touch. Sorted, the step of the 19k box runs about
2x faster (docs/BENCHMARKS.md "FEM"). Geometry, tags and element types are unchanged.

usage: reorder_msh.py FILE.msh [FILE.msh ...]
"""
import sys


def morton(ix, iy, iz):
    code = 0
    for b in range(21):
        code |= ((ix >> b) & 1) << (3 * b) | ((iy >> b) & 1) << (3 * b + 1) | ((iz >> b) & 1) << (3 * b + 2)
    return code


def reorder(path):
    lines = open(path).read().split("\n")
    ni = lines.index("$Nodes")
    nn = int(lines[ni + 1])
    nodes, text = {}, {}
    for line in lines[ni + 2:ni + 2 + nn]:
        f = line.split()
        nodes[int(f[0])] = (float(f[1]), float(f[2]), float(f[3]))
        text[int(f[0])] = " ".join(f[1:])  # coordinates exactly as written
    ei = lines.index("$Elements")
    ne = int(lines[ei + 1])
    elems = [line.split() for line in lines[ei + 2:ei + 2 + ne]]
    lo = [min(p[k] for p in nodes.values()) for k in range(3)]
    hi = [max(p[k] for p in nodes.values()) for k in range(3)]
    span = max(h - l for h, l in zip(hi, lo)) or 1.0

    def key(p):
        q = [int((p[k] - lo[k]) / span * ((1 << 21) - 1)) for k in range(3)]
        return morton(*q)

    order = sorted(nodes, key=lambda i: (key(nodes[i]), i))
    new_id = {old: k + 1 for k, old in enumerate(order)}

    def centroid(e):
        ntags = int(e[2])
        vs = [nodes[int(v)] for v in e[3 + ntags:]]
        return tuple(sum(v[k] for v in vs) / len(vs) for k in range(3))

    elems.sort(key=lambda e: (key(centroid(e)), int(e[0])))
    out = lines[:ni + 2]
    out += ["%d %s" % (k + 1, text[old]) for k, old in enumerate(order)]
    out += lines[ni + 2 + nn:ei + 2]
    for k, e in enumerate(elems):
        ntags = int(e[2])
        head = e[1:3 + ntags]
        verts = [str(new_id[int(v)]) for v in e[3 + ntags:]]
        out.append(" ".join([str(k + 1)] + head + verts))
    out += lines[ei + 2 + ne:]
    open(path, "w").write("\n".join(out))


if __name__ == "__main__":
    for p in sys.argv[1:]:
        reorder(p)
