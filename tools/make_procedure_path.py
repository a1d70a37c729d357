#!/usr/bin/env python3
"""Writes the default scene's scripted appendectomy, an expert's (config/paths/
appendectomy_procedure.csv) and a novice's (appendectomy_procedure_novice.csv: every motion 1.5
times slower, and the clip applier closed 12 mm above the fold, so the clip falls away and the
hook then divides an unsecured artery), and prints each instrument's trocar for
config/appendectomy.toml. With --stapler it writes the stapler variant instead
(appendectomy_stapler.csv, for config/appendectomy_stapler.toml): the same exposure, clip and
fold division, then a linear cutter-stapler secures and divides the base in one fire in place of
the endoloop and the scissors.

Each instrument pivots about its trocar: every row's orientation points the shaft (local +z) from
the trocar through the row's tip, rolled so the jaws open towards a chosen direction (local +x,
engine/tool_geometry.h). Instruments come in and go out along their shaft. Frame and anatomy:
config/appendectomy.toml, docs/procedure.md. Times in s, positions in m, jaw angles in rad.

usage: make_procedure_path.py [--stapler] [FOLDER]     (default: config/paths)
"""
import math
import os
import sys

END = 9.4  # s: the expert's path's length (the scene's headless.steps x dt)
NOVICE_SLOWER = 1.5  # the novice's times over the expert's


def sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def add(a, b, s=1.0):
    return [a[k] + s * b[k] for k in range(3)]


def dot(a, b):
    return sum(a[k] * b[k] for k in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def quaternion(side, pin, forward):
    """(w, x, y, z) of the rotation whose columns are side, pin, forward."""
    m = [[side[r], pin[r], forward[r]] for r in range(3)]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        return [0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0.0] * 4
    q[0] = (m[k][j] - m[j][k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (m[j][i] + m[i][j]) / s
    q[1 + k] = (m[k][i] + m[i][k]) / s
    return q


class Tool:
    """An instrument through its trocar: rows of (time, tip, jaw, buttons)."""

    def __init__(self, name, work, forward, side_hint, reach=0.15, slower=1.0):
        self.name = name
        self.slower = slower
        self.forward = unit(forward)
        self.trocar = add(work, self.forward, -reach)
        self.side_hint = side_hint
        self.rows = []
        self.hands = [(0.0, "port")]  # (time, hand): who holds it from then on

    def frame(self, tip, roll=None):
        f = unit(sub(tip, self.trocar))
        hint = roll or self.side_hint
        s = unit(add(hint, f, -dot(hint, f)))
        return s, cross(f, s), f

    def at(self, t, tip, jaw=0.0, buttons=0, roll=None):
        """A row: the tip (m) at time t (s); roll: where the jaws open (else the tool's way)."""
        self.rows.append((t * self.slower, list(tip), jaw, buttons, roll))

    def held(self, t, hand):
        """From time t (s) `hand` (left, right) holds it, or it waits in its port (port)."""
        self.hands.append((t * self.slower, hand))

    def hand_at(self, t):
        return [h for s, h in self.hands if s <= t][-1]

    def rows_with_hands(self):
        """The rows, with a row added where the hand changes between two, and each row's hand."""
        rows = list(self.rows)
        times = {r[0] for r in rows}
        for s, _ in self.hands:
            if s in times or s <= rows[0][0] or s >= rows[-1][0]:
                continue
            b = next(k for k, r in enumerate(rows) if r[0] > s)
            (ta, pa, ja, ba, ra), (tb, pb, jb, _, _) = rows[b - 1], rows[b]
            u = (s - ta) / (tb - ta)
            rows.insert(b, (s, [pa[i] + u * (pb[i] - pa[i]) for i in range(3)],
                            ja + u * (jb - ja), ba, ra))
        return [r + (self.hand_at(r[0]),) for r in rows]

    def parked(self, depth=0.05):
        """Tip `depth` in from the trocar along the working line: out of the way and of view."""
        return add(self.trocar, self.forward, depth)


def staple_base(stapler, x_knife):
    """The stapler's part: its jaws opened wide come down the shaft round the appendix's base, the
    knife's plane across the appendix at x = x_knife (the jaws' pin along +x), the appendix's axis
    20 mm beyond the hinge, where the jaws are 12 mm apart; they close (the stapler fires: two
    staple lines, the knife between them), stay closed while the staples press, open a little to
    let go (less than the arming angle, engine/stapler.h, so closing them to leave fires nothing)
    and leave."""
    st = stapler
    axis = [x_knife, -0.0240, 0.0]
    tip = add(axis, st.forward, -(0.020 - 0.015))  # the hinge 15 mm behind the tip
    st.at(6.0, st.parked(), 0.0)
    st.at(6.2, st.parked(), 0.6)
    st.at(6.6, add(tip, st.forward, -0.012), 0.6)
    st.at(6.9, tip, 0.6)
    st.at(7.2, tip, 0.0)
    st.at(7.6, tip, 0.0)
    st.at(7.8, tip, 0.15)
    st.at(8.1, add(tip, st.forward, -0.012), 0.15)
    st.at(8.5, st.parked(), 0.0)


def procedure(novice=False, stapler=False):
    # Where the anatomy is (rest, m): the appendix's axis runs along +x at y = -0.022, z = 0 from
    # the cecum wall (x = 0.017) to x = 0.040, then down along (1, -1, 0)/sqrt(2) to its tip near
    # (0.080, -0.057, 0); the fold hangs below it in z = 0 with its free edge from (0.004, -0.027)
    # to (0.034, -0.040) to (0.0725, -0.0496); the artery runs 3 mm inside that edge.
    d = unit([1.0, -1.0, 0.0])
    x_loop, x_transect, x_divide = 0.0265, 0.030, 0.029

    k = NOVICE_SLOWER if novice else 1.0
    grasper = Tool("grasper", [0.0700, -0.0470, 0.0], [-0.10, -0.35, -0.93], d, slower=k)
    clip = Tool("clip-applier", [0.0200, -0.0300, -0.0040], [0.10, 0.25, -0.96], [0.40, 0.92, 0.0],
                slower=k)
    hook = Tool("hook", [x_divide, -0.0300, 0.0], [0.0, -0.35, -0.94], [0.0, 1.0, 0.0], slower=k)
    loop = Tool("endoloop", [x_loop, -0.0330, 0.0], [-1.0, 0.0, -0.10], [0.0, 1.0, 0.0], slower=k)
    cut = [x_transect, -0.02280, -0.00572]
    scissors = Tool("scissors", cut, [0.0, 0.30, -0.95], [0.0, 1.0, 0.0], slower=k)
    tools = [grasper, clip, hook, loop, scissors]
    # the stapler comes in as the scissors do, its knife 0.5 mm short of where they cut: in the
    # strip the hook freed from the fold, clear of the hook's first cut at x_divide
    x_knife = 0.0295
    stapler_tool = Tool("stapler", [x_knife, -0.0240, 0.0], [0.0, 0.30, -0.95], [0.0, 1.0, 0.0])
    if stapler:
        tools = [grasper, clip, hook, stapler_tool]
    for tool in tools:
        tool.at(0.0, tool.parked())
    # Two hands: the left holds the grasper throughout; the right takes the clip applier, the
    # hook, the endoloop and the scissors in turn, each exchange as the last one leaves its work.
    # With the stapler the right hand takes it after the hook, in place of the endoloop and the
    # scissors.
    grasper.held(0.0, "left")
    last = ((stapler_tool, 6.0, None),) if stapler else ((loop, 6.0, 7.1), (scissors, 7.1, None))
    for tool, start, end in ((clip, 2.0, 3.6), (hook, 3.6, 6.0)) + last:
        tool.held(start, "right")
        if end is not None:
            tool.held(end, "port")

    # expose: take the appendix 14 mm from its tip and lift it 15 mm towards the wall above
    g = grasper
    take = [0.0700, -0.0470, 0.0]
    g.at(0.3, g.parked(), 1.0)
    g.at(0.9, add(take, [0, 0, 0.010]), 1.0)
    g.at(1.2, take, 1.0)
    g.at(1.4, take, 0.0)
    lifted = add(take, [0, 0, 0.015])
    g.at(2.0, lifted, 0.0)

    # clip the artery near its root: jaws across it, the fold between them
    c = clip
    at_artery = [0.0200, -0.0305, -0.0010]
    c.at(2.0, c.parked(), 0.0)
    c.at(2.3, c.parked(), 0.7)
    c.at(2.8, add(at_artery, [0, 0, 0.012]), 0.7)
    closed_at = add(at_artery, [0, 0, 0.012 if novice else -0.008])  # the novice's is short
    c.at(3.1, closed_at, 0.7)
    c.at(3.3, closed_at, 0.0)
    c.at(3.5, add(at_artery, [0, 0, 0.012]), 0.0)
    c.at(3.9, c.parked(), 0.0)

    # divide the fold beyond the clip, in two presses of the pedal. First across the fold: the
    # crook (along +y) goes down past the free edge, along under the fold to the appendix and up
    # into the appendix's wall (one stroke: the rectangle it spans, in the plane x = x_divide).
    # Then the fold is freed from the appendix's base between the two cuts: the crook (along +x,
    # from x_divide - 1 mm to x_divide + 2 mm, across where the scissors will cut) goes down through the fold just under the
    # appendix. So the fold and the appendix part where the scissors will cut, and the specimen
    # keeps no fold joined to the stump.
    h = hook
    y_edge, y_app, y_under = -0.0460, -0.0270, -0.0268
    z_lo, z_hi = -0.0080, 0.0080
    h.at(3.6, h.parked())
    h.at(4.1, [x_divide, y_edge, z_hi])
    h.at(4.2, [x_divide, y_edge, z_hi], 0.0, 2)
    h.at(4.5, [x_divide, y_edge, z_lo], 0.0, 2)
    h.at(5.0, [x_divide, y_app, z_lo], 0.0, 2)
    h.at(5.3, [x_divide, y_app, z_hi], 0.0, 2)
    h.at(5.35, [x_divide, y_app, z_hi])
    under = [x_divide - 0.0010, y_under, z_hi]
    h.at(5.6, under, 0.0, 0, roll=[1.0, 0.0, 0.0])
    h.at(5.65, under, 0.0, 2, roll=[1.0, 0.0, 0.0])
    h.at(5.95, add(under, [0, 0, z_lo - z_hi]), 0.0, 2, roll=[1.0, 0.0, 0.0])
    h.at(6.0, add(under, [0, 0, z_lo - z_hi]), 0.0, 0, roll=[1.0, 0.0, 0.0])
    h.at(6.4, h.parked(), 0.0, 0, roll=[1.0, 0.0, 0.0])

    if stapler:
        staple_base(stapler_tool, x_knife)
        return finish(grasper, lifted, tools)

    # secure the base: the open ring slid up to the base, round the appendix, then cinched
    lp = loop
    # the pusher's tip; the ring's centre is 10 mm along +y from it, 0.5 mm below the
    # appendix's axis. The ring's plane is nearly upright so it keeps clear of the cecum.
    ring_tip = [x_loop, -0.0330, 0.0]
    lp.at(6.0, lp.parked(), 0.0)
    lp.at(6.2, lp.parked(), 0.6)
    lp.at(6.6, add(ring_tip, [0.010, 0, 0.004]), 0.6)
    lp.at(6.8, ring_tip, 0.6)
    lp.at(6.95, ring_tip, 0.0)
    lp.at(7.3, lp.parked(0.1), 0.0)

    # transect between the loop and the specimen: the blades open wide, their tips 6 mm beyond
    # the lifted appendix's axis (9 mm from the hinge, where the blades are 12 mm apart) and their
    # plane 0.8 mm off it towards the cecum, so the whole appendix lies between them however the
    # fold held it up (with the tips 1 mm deeper and on the axis, a path perturbed by 0.5 mm left
    # the appendix joined in 5 runs of 8; so, 1 in 8)
    s = scissors
    s.at(7.1, s.parked(), 0.0)
    s.at(7.3, s.parked(), 1.2)
    s.at(7.7, add(cut, s.forward, -0.012), 1.2)
    s.at(8.0, cut, 1.2)
    s.at(8.3, cut, 0.0)
    s.at(8.6, s.parked(), 0.0)

    return finish(grasper, lifted, tools)


def finish(grasper, lifted, tools):
    """extract: carry the freed appendix away, towards the port it will leave by"""
    g = grasper
    g.at(8.6, lifted, 0.0)
    g.at(9.2, add(lifted, [0.045, -0.010, 0.015]), 0.0)
    g.at(END, add(lifted, [0.045, -0.010, 0.015]), 0.0)
    for tool in tools:
        if tool is not grasper:
            _, tip, jaw, _, roll = tool.rows[-1]
            tool.at(END, tip, jaw, 0, roll)
    return tools


# the endoscope stays put over the field, looking down (-z) from the umbilicus: (tip, quaternion)
SCOPE = ([0.0450, -0.0320, 0.0600], [0.0, 0.0, 1.0, 0.0])


def write(path, tools, end, scope=SCOPE):
    rows = []
    for tool in tools:
        for t, tip, jaw, buttons, roll, hand in tool.rows_with_hands():
            q = quaternion(*tool.frame(tip, roll))
            rows.append((t, tool.name, tip, q, jaw, buttons, hand))
    rows.append((0.0, "endoscope", scope[0], scope[1], 0.0, 0, ""))
    rows.append((end, "endoscope", scope[0], scope[1], 0.0, 0, ""))
    rows.sort(key=lambda r: (r[0], r[1]))
    with open(path, "w") as f:
        f.write("t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons,hand\n")
        for t, name, p, q, jaw, buttons, hand in rows:
            f.write(f"{t:.3f},{name},{p[0]:.5f},{p[1]:.5f},{p[2]:.5f},"
                    f"{q[0]:.6f},{q[1]:.6f},{q[2]:.6f},{q[3]:.6f},{jaw:.2f},{buttons},{hand}\n")


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    args = sys.argv[1:]
    stapler = "--stapler" in args
    args = [a for a in args if a != "--stapler"]
    folder = args[0] if args else os.path.join(root, "config/paths")
    if stapler:
        tools = procedure(stapler=True)
        write(os.path.join(folder, "appendectomy_stapler.csv"), tools, END)
    else:
        tools = procedure()
        write(os.path.join(folder, "appendectomy_procedure.csv"), tools, END)
        write(os.path.join(folder, "appendectomy_procedure_novice.csv"), procedure(novice=True),
              END * NOVICE_SLOWER)
    for tool in tools:
        print(f"{tool.name}: trocar = [{tool.trocar[0]:.4f}, {tool.trocar[1]:.4f}, {tool.trocar[2]:.4f}]")


if __name__ == "__main__":
    main()
