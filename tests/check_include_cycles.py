#!/usr/bin/env python3
"""Fails when modules of one folder include each other, directly or round a longer loop.

A module is a header and its source (cut_mesh.h + cut_mesh.cpp); module A depends on module B
when either of A's files includes B's header. Within each top folder (engine, fem, cutting, ...,
app, python) the dependencies must form no loop: a loop means neither module can be read,
tested or moved without the other. Usage: check_include_cycles.py ROOT
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([a-z_0-9/]+)\.(?:h|cuh)"', re.M)
FOLDERS = ["engine", "fem", "cutting", "surface", "contact", "haptics", "metrics", "render",
           "recording", "batch", "trainee", "window", "app", "replay", "bench", "python"]


def modules(root, folder):
    """{module: set of modules it includes}, modules named by path without extension."""
    graph = {}
    for dirpath, _, files in os.walk(os.path.join(root, folder)):
        for name in files:
            stem, ext = os.path.splitext(name)
            if ext not in (".h", ".cpp", ".cu", ".cuh"):
                continue
            mod = os.path.relpath(os.path.join(dirpath, stem), root)
            with open(os.path.join(dirpath, name), encoding="utf-8") as f:
                text = f.read()
            deps = graph.setdefault(mod, set())
            for target in INCLUDE.findall(text):
                if target.split("/")[0] == folder and target != mod:
                    deps.add(target)
    return graph


def loops(graph):
    """The strongly connected components with more than one module (Tarjan, iterative)."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    found.append(sorted(comp))
    return found


def main():
    root = sys.argv[1]
    bad = []
    for folder in FOLDERS:
        if os.path.isdir(os.path.join(root, folder)):
            bad += loops(modules(root, folder))
    for comp in bad:
        print("modules that include each other: " + ", ".join(comp))
    if bad:
        return 1
    print("no include loops within a folder")
    return 0


if __name__ == "__main__":
    sys.exit(main())
