#!/usr/bin/env python3
"""Structured tetrahedral beam for validation and convergence studies.

Box [0, L] x [-W/2, W/2] x [-H/2, H/2] (m), L = 0.1, W = H = 0.01: the beam
runs along +x, its fixed end is the face x = 0, its axis is the x axis.
Each of the nx*ny*nz cubes is split into 6 tets (Kuhn/Freudenthal split: one
tet per permutation of the axes, all sharing the cube diagonal from its lowest
to its highest corner). Every cube is split the same way, so neighbouring
cubes agree on their shared face diagonals and the mesh is conforming.
Every tet (a,b,c,d) has (b-a).((c-a)x(d-a)) > 0. Physical volume 1 "beam".
The same block of another size, at another place and with another name (the
transfer drill's bead): --size L W H --corner X Y Z (its lowest corner, m)
--name NAME; without --corner the block spans [0, L] x [-W/2, W/2] x [-H/2, H/2].

usage: make_beam.py NX NY NZ OUT.msh [--size L W H] [--corner X Y Z] [--name NAME]
"""
import argparse
import itertools
import sys


def coord(i, n, lo, size):
    # i*size/n computed directly (no accumulation)
    # rounded to 1e-12 m so that grid coordinates print cleanly (0.03, not 0.030000000000000006)
    return round(lo + size * i / n, 12) + 0.0


def main(argv):
    ap = argparse.ArgumentParser(usage=__doc__)
    ap.add_argument("n", type=int, nargs=3)
    ap.add_argument("out")
    ap.add_argument("--size", type=float, nargs=3, default=[0.1, 0.01, 0.01])
    ap.add_argument("--corner", type=float, nargs=3)
    ap.add_argument("--name", default="beam")
    opt = ap.parse_args(argv)
    nx, ny, nz = opt.n
    out = opt.out
    L, W, H = opt.size
    x0, y0, z0 = opt.corner if opt.corner else (0.0, -W / 2, -H / 2)

    def nid(i, j, k):
        return 1 + i + (nx + 1) * (j + (ny + 1) * k)

    xs = [coord(i, nx, x0, L) for i in range(nx + 1)]
    ys = [coord(j, ny, y0, W) for j in range(ny + 1)]
    zs = [coord(k, nz, z0, H) for k in range(nz + 1)]

    # the 6 Kuhn tets of the unit cube as corner offsets, oriented positively
    pattern = []
    for perm in itertools.permutations(range(3)):
        c = [0, 0, 0]
        corners = [tuple(c)]
        for ax in perm:
            c[ax] += 1
            corners.append(tuple(c))
        a, b, cc, d = corners
        u = [b[t] - a[t] for t in range(3)]
        v = [cc[t] - a[t] for t in range(3)]
        w = [d[t] - a[t] for t in range(3)]
        det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
               + u[2] * (v[0] * w[1] - v[1] * w[0]))
        if det < 0:
            corners[2], corners[3] = corners[3], corners[2]
        pattern.append(corners)

    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat",
             "$PhysicalNames", "1", '3 1 "%s"' % opt.name, "$EndPhysicalNames"]
    nn = (nx + 1) * (ny + 1) * (nz + 1)
    lines += ["$Nodes", str(nn)]
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                lines.append("%d %r %r %r" % (nid(i, j, k), xs[i], ys[j], zs[k]))
    lines.append("$EndNodes")
    ne = 6 * nx * ny * nz
    lines += ["$Elements", str(ne)]
    e = 0
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                for corners in pattern:
                    e += 1
                    ids = [nid(i + c[0], j + c[1], k + c[2]) for c in corners]
                    lines.append("%d 4 2 1 1 %d %d %d %d" % (e, ids[0], ids[1], ids[2], ids[3]))
    lines.append("$EndElements")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s: %d nodes, %d tets" % (out, nn, ne))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
