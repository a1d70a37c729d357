#!/usr/bin/env python3
"""Writes the grasp-and-transfer drill's scripted paths, an expert's (config/paths/transfer.csv)
and a novice's (transfer_novice.csv: every motion 1.6 times slower, and the left grasper lets go
before the right one has closed, so the bead falls to the board and the right grasper sets down
nothing), and prints each grasper's trocar for config/transfer.toml.

The drill (config/transfer.toml, docs/assessment.md): a soft bead lies on the board on the left;
the left grasper picks it up by its left half and lifts it, the right grasper takes its right
half in the air, the left lets go, and the right sets the bead down on the target on the right
and lets go. Each grasper pivots about its trocar (make_procedure_path.Tool); its jaws open
across the bead (along y). Frame: metres, the board is z = 0, gravity along -z.

usage: make_transfer_path.py [FOLDER]     (default: config/paths)
"""
import os
import sys

from make_procedure_path import Tool, write

END = 4.6  # s: the expert's path's length (the scene's headless.steps x dt)
NOVICE_SLOWER = 1.6
OPEN = 1.0  # rad: the jaws' opening to take the bead (6 mm wide)
# The bead: x in [-31, -19] mm, y in [-3, 3] mm, z in [0, 6] mm; the target, on the right.
# Positions are the jaws' tips (a row's tip, engine/tool_geometry.h): the jaws, 15 mm long,
# reach from above the bead down past it, so their wedge spans the bead's whole height.
PICK = [-0.0270, 0.0, 0.0010]    # the left tip by the bead's left half, 1 mm over the board
LIFTED = [-0.0050, 0.0, 0.0210]  # the left tip, the bead lifted 20 mm for the hand-off
TAKE = [0.0015, 0.0, 0.0185]     # the right tip by the lifted bead's right half
PLACE = [0.0285, 0.0, 0.0020]    # the right tip with the bead's centre over the target


def drill(novice=False):
    k = NOVICE_SLOWER if novice else 1.0
    left = Tool("left-grasper", PICK, [0.30, 0.0, -0.95], [0.0, 1.0, 0.0], slower=k)
    right = Tool("right-grasper", TAKE, [-0.30, 0.0, -0.95], [0.0, 1.0, 0.0], slower=k)
    above = lambda p, dz: [p[0], p[1], p[2] + dz]
    # Each waits in view, over its work (the drill is in the endoscope's view from the start).
    ready = {left: above(PICK, 0.030), right: above(TAKE, 0.015)}
    for tool in (left, right):
        tool.at(0.0, ready[tool])

    # pick up with the left grasper
    left.at(0.2, ready[left], OPEN)
    left.at(0.7, above(PICK, 0.012), OPEN)
    left.at(1.0, PICK, OPEN)
    left.at(1.2, PICK, 0.0)
    left.at(1.7, LIFTED, 0.0)
    # the right grasper takes the bead's other half in the air; the left lets go
    right.at(1.2, ready[right], OPEN)
    right.at(1.8, above(TAKE, 0.012), OPEN)
    right.at(2.1, TAKE, OPEN)
    if novice:  # lets go too soon: the bead falls before the right jaws close
        left.at(2.0, LIFTED, 0.0)
        left.at(2.1, LIFTED, OPEN)
    else:
        left.at(2.4, LIFTED, 0.0)
        left.at(2.5, LIFTED, OPEN)
    right.at(2.3, TAKE, 0.0)
    left.at(2.9, ready[left], OPEN)
    left.at(3.1, ready[left], 0.0)
    # set it down on the target and let go
    right.at(2.6, TAKE, 0.0)
    right.at(3.3, PLACE, 0.0)
    right.at(3.5, PLACE, OPEN)
    right.at(3.9, above(PLACE, 0.015), OPEN)
    right.at(4.3, above(PLACE, 0.030), 0.0)
    for tool in (left, right):
        _, tip, jaw, _, roll = tool.rows[-1]
        tool.at(END, tip, jaw, 0, roll)
    return [left, right]


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "config/paths")
    scope = ([0.0, -0.0150, 0.1000], [0.0, 0.0, 1.0, 0.0])  # above the board, looking down
    tools = drill()
    write(os.path.join(folder, "transfer.csv"), tools, END, scope)
    write(os.path.join(folder, "transfer_novice.csv"), drill(novice=True), END * NOVICE_SLOWER,
          scope)
    for tool in tools:
        print(f"{tool.name}: trocar = [{tool.trocar[0]:.4f}, {tool.trocar[1]:.4f}, {tool.trocar[2]:.4f}]")


if __name__ == "__main__":
    main()
