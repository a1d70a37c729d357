#!/usr/bin/env python3
"""Tags the appendicular artery in an appendectomy mesh (Gmsh msh2 ASCII), in place: the
mesoappendix's tets (physical group 2) whose centroid lies within RADIUS of the artery's course
become physical group 4, "artery".

Why a tag rather than a solid of its own: the artery is a vessel of about 2 mm inside a 2.5 mm
fold, thinner than the fold's tets; tagging the fold's tets along its course gives the metrics a
group to follow (a cut through it bleeds unless a clip holds it) without slivers round a tube.

The course (tools/assets/appendectomy.geo's frame, metres): the artery enters the fold at its
root beside the cecum and runs about 3 mm inside the fold's free edge towards the appendix's
tip, as the appendicular artery runs in the free edge of the mesoappendix.

usage: tag_artery.py FILE.msh
"""
import sys

RADIUS = 0.0018  # m
COURSE = [(0.0100, -0.0262, 0.0), (0.0352, -0.0372, 0.0), (0.0660, -0.0450, 0.0)]  # m
MESO, ARTERY = 2, 4


def distance_to_segment(p, a, b):
    ab = [b[k] - a[k] for k in range(3)]
    ap = [p[k] - a[k] for k in range(3)]
    t = sum(x * y for x, y in zip(ab, ap)) / sum(x * x for x in ab)
    t = max(0.0, min(1.0, t))
    return sum((a[k] + t * ab[k] - p[k]) ** 2 for k in range(3)) ** 0.5


def distance_to_course(p):
    return min(distance_to_segment(p, COURSE[i], COURSE[i + 1]) for i in range(len(COURSE) - 1))


def tag(path):
    lines = open(path).read().split("\n")
    ni = lines.index("$Nodes")
    nodes = {}
    for line in lines[ni + 2:ni + 2 + int(lines[ni + 1])]:
        f = line.split()
        nodes[int(f[0])] = tuple(float(x) for x in f[1:4])
    ei = lines.index("$Elements")
    tagged = 0
    for i in range(ei + 2, ei + 2 + int(lines[ei + 1])):
        f = lines[i].split()
        if f[1] != "4" or int(f[3]) != MESO:
            continue
        corners = [nodes[int(v)] for v in f[-4:]]
        centroid = tuple(sum(c[k] for c in corners) / 4 for k in range(3))
        if distance_to_course(centroid) <= RADIUS:
            f[3] = str(ARTERY)
            lines[i] = " ".join(f)
            tagged += 1
    if tagged == 0:
        sys.exit(f"tag_artery: {path}: no mesoappendix tet lies on the artery's course")
    pi = lines.index("$PhysicalNames")
    names = [l for l in lines[pi + 2:pi + 2 + int(lines[pi + 1])] if not l.startswith(f"3 {ARTERY} ")]
    names.append(f'3 {ARTERY} "artery"')
    lines[pi + 1:pi + 2 + int(lines[pi + 1])] = [str(len(names))] + names
    open(path, "w").write("\n".join(lines))
    print(f"tag_artery: {path}: {tagged} tets tagged \"artery\"")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for arg in sys.argv[1:]:
        tag(arg)
