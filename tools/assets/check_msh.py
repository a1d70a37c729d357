#!/usr/bin/env python3
"""Check a Gmsh 2.2 ASCII tetrahedral mesh (no numpy needed).

Reports node and tet counts, bounding box (m), volume per physical group
(with names from $PhysicalNames), min/max signed tet volume with the
convention V = (b-a).((c-a)x(d-a))/6 for tet (a,b,c,d), min and mean
mean-ratio quality (1 = regular tet, 0 = flat), conformity (no face shared
by more than two tets, faces between groups), unreferenced nodes and
whether node ids run 1..N.

Exit status 1 if any tet has V <= 0, a face is shared by more than two tets,
or the file is not a valid msh2 tet mesh.

usage: check_msh.py FILE.msh [FILE.msh ...] [--min-quality Q]
"""
import sys


def parse_msh2(path):
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    nodes = {}
    tets = []          # (phys, n0, n1, n2, n3)
    names = {}
    other = 0
    fmt = None
    n = len(lines)
    while i < n:
        s = lines[i].strip()
        if s == "$MeshFormat":
            fmt = lines[i + 1].split()
            if not fmt[0].startswith("2.2") or fmt[1] != "0":
                raise ValueError("%s: not Gmsh 2.2 ASCII (format %s)" % (path, " ".join(fmt)))
            i += 2
        elif s == "$PhysicalNames":
            k = int(lines[i + 1])
            for j in range(k):
                parts = lines[i + 2 + j].split(None, 2)
                names[(int(parts[0]), int(parts[1]))] = parts[2].strip().strip('"')
            i += 2 + k
        elif s == "$Nodes":
            k = int(lines[i + 1])
            for j in range(k):
                p = lines[i + 2 + j].split()
                nodes[int(p[0])] = (float(p[1]), float(p[2]), float(p[3]))
            i += 2 + k
        elif s == "$Elements":
            k = int(lines[i + 1])
            for j in range(k):
                p = [int(t) for t in lines[i + 2 + j].split()]
                etype, ntags = p[1], p[2]
                if etype == 4:
                    phys = p[3] if ntags > 0 else 0
                    tets.append((phys,) + tuple(p[3 + ntags:3 + ntags + 4]))
                else:
                    other += 1
            i += 2 + k
        else:
            i += 1
    if fmt is None:
        raise ValueError("%s: no $MeshFormat" % path)
    return nodes, tets, names, other


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def check(path, min_quality=None):
    nodes, tets, names, other = parse_msh2(path)
    ok = True
    vol = {}
    count = {}
    vmin = float("inf")
    vmax = 0.0
    qmin = float("inf")
    qsum = 0.0
    nbad = 0
    used = set()
    faces = {}
    for t in tets:
        g = t[0]
        a, b, c, d = (nodes[k] for k in t[1:])
        used.update(t[1:])
        u, v, w = sub(b, a), sub(c, a), sub(d, a)
        cx = (v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0])
        V = (u[0] * cx[0] + u[1] * cx[1] + u[2] * cx[2]) / 6.0
        if V <= 0:
            nbad += 1
        vmin = min(vmin, V)
        vmax = max(vmax, V)
        vol[g] = vol.get(g, 0.0) + V
        count[g] = count.get(g, 0) + 1
        P = (a, b, c, d)
        l2 = 0.0
        for i in range(4):
            for j in range(i + 1, 4):
                e = sub(P[i], P[j])
                l2 += e[0] * e[0] + e[1] * e[1] + e[2] * e[2]
        q = 12.0 * (3.0 * abs(V)) ** (2.0 / 3.0) / l2 if l2 > 0 else 0.0
        if V <= 0:
            q = -q
        qmin = min(qmin, q)
        qsum += q
        n = t[1:]
        for f in ((n[1], n[2], n[3]), (n[0], n[2], n[3]), (n[0], n[1], n[3]), (n[0], n[1], n[2])):
            key = tuple(sorted(f))
            faces.setdefault(key, []).append(g)
    over = sum(1 for v in faces.values() if len(v) > 2)
    boundary = sum(1 for v in faces.values() if len(v) == 1)
    iface = {}
    for v in faces.values():
        if len(v) == 2 and v[0] != v[1]:
            k = tuple(sorted(v))
            iface[k] = iface.get(k, 0) + 1
    xs = [nodes[k] for k in used]
    lo = [min(p[i] for p in xs) for i in range(3)]
    hi = [max(p[i] for p in xs) for i in range(3)]
    print("file: %s" % path)
    contiguous = sorted(nodes) == list(range(1, len(nodes) + 1))
    print("  nodes %d (ids %s, unreferenced %d), tets %d, other elements %d"
          % (len(nodes), "1..N" if contiguous else "NOT contiguous", len(nodes) - len(used),
             len(tets), other))
    print("  bbox min (%.5f, %.5f, %.5f) max (%.5f, %.5f, %.5f) m"
          % (lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]))
    total = 0.0
    for g in sorted(vol):
        total += vol[g]
        print("  group %d %-13s tets %6d volume %.6e m^3"
              % (g, '"%s"' % names.get((3, g), "?"), count[g], vol[g]))
    print("  total volume %.6e m^3" % total)
    print("  signed volume min %.3e max %.3e m^3, non-positive %d" % (vmin, vmax, nbad))
    print("  mean-ratio quality min %.4f mean %.4f" % (qmin, qsum / max(1, len(tets))))
    print("  faces: boundary %d, shared by >2 tets %d, between groups %s"
          % (boundary, over, ", ".join("%d-%d: %d" % (k[0], k[1], c) for k, c in sorted(iface.items())) or "none"))
    missing = [g for g in vol if (3, g) not in names]
    if nbad or over or not tets or missing:
        ok = False
    if min_quality is not None and qmin < min_quality:
        print("  quality below %.3f" % min_quality)
        ok = False
    print("  result: %s" % ("OK" if ok else "FAIL"))
    return ok


def main(argv):
    files = []
    mq = None
    it = iter(argv)
    for a in it:
        if a == "--min-quality":
            mq = float(next(it))
        else:
            files.append(a)
    if not files:
        print(__doc__)
        return 2
    ok = True
    for f in files:
        try:
            ok = check(f, mq) and ok
        except (ValueError, KeyError, IndexError) as e:
            print("file: %s\n  error: %s\n  result: FAIL" % (f, e))
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
