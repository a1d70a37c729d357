#!/usr/bin/env python3
"""A trainee's hands on the mouse and keyboard, under Xvfb: starts `serosa run SCENE` and does one
task with xdotool drags and keys only, aiming as a person does by what the window draws (the
window's view log gives where it drew each instrument, the guide and the organs, in its pixels and
depth along the view), then ends the session and checks its report.

  trainee_mouse.py SEROSA SCENE OUT_DIR transection       transect the appendix with the scissors
  trainee_mouse.py SEROSA SCENE OUT_DIR grasp_and_lift    grasp the appendix and lift it (expose)
  trainee_mouse.py SEROSA SCENE OUT_DIR keep_moving       circle the active instrument for 20 s:
                                                          the session must not read as idle

Each move is closed-loop: look (the newest frame), move the hand part of the way, look again.
"""
import json
import math
import os
import subprocess
import sys
import time

SEROSA, SCENE, OUT, TASK = sys.argv[1:5]
os.makedirs(OUT, exist_ok=True)
REPORT = os.path.join(OUT, "report.json")
LOG = os.path.join(OUT, "view.jsonl")
STEP_M = 0.003  # one W/S press into or out of the picture, m (app/pointer_control.h)


def say(*a):
    print("[trainee]", *a, flush=True)


def xdo(*args):
    subprocess.run(["xdotool", *map(str, args)], check=True)


def frames_drawn():
    try:
        with open(LOG, "rb") as f:
            return f.read().count(b"\n")
    except FileNotFoundError:
        return 0


def look():
    """The newest frame the window drew."""
    with open(LOG, "rb") as f:
        lines = f.read().splitlines()
    return json.loads(lines[-1])


def wait_frames(n=2, at_least_s=0.0, limit_s=30.0):
    start = time.time()
    goal = frames_drawn() + n
    while frames_drawn() < goal or time.time() - start < at_least_s:
        if time.time() - start > limit_s:
            raise SystemExit("trainee_mouse.py: the window stopped drawing")
        time.sleep(0.03)


def tool(frame, name):
    for t in frame["tools"]:
        if t.get("tool") == name:
            return t
    raise SystemExit(f"trainee_mouse.py: {name} is not drawn")


def key(k, hold_s=0.0):
    if hold_s > 0.0:
        xdo("keydown", k)
        time.sleep(hold_s)
        xdo("keyup", k)
    else:
        xdo("key", k)
    wait_frames(2, 0.15)


def set_jaws(want_open, what):
    """Taps J, as a trainee does, until the overlay shows the active instrument's jaws open (or
    closed); says so when a tap did not do what it should."""
    for tap in range(3):
        key("j")
        wait_frames(3, 0.6)
        h = look()["hands"][look()["active_hand"]]
        if (h["jaw_rad"] > 0.5 * h["jaw_max_rad"]) == want_open:
            return
        say(f"{what}: after tap {tap + 1} the overlay shows the jaws at {h['jaw_rad']:.2f} of "
            f"{h['jaw_max_rad']:.2f} rad")
    raise SystemExit(f"trainee_mouse.py: J did not {'open' if want_open else 'close'} the jaws")


def drag(dx, dy):
    """A drag with the left button from the middle of the picture, in moves of 25 px at most."""
    xdo("mousemove", "--window", window, 640, 360)
    xdo("mousedown", 1)
    n = max(1, int(math.ceil(max(abs(dx), abs(dy)) / 25.0)))
    done_x = done_y = 0
    for i in range(1, n + 1):
        x, y = round(dx * i / n), round(dy * i / n)
        xdo("mousemove_relative", "--", x - done_x, y - done_y)
        done_x, done_y = x, y
    xdo("mouseup", 1)
    wait_frames(3, 0.3)


def px(p):
    return p["px"]


def aim(name, target_of, within_px=3.0, within_m=0.0015, tries=40):
    """Brings the middle of `name`'s jaws onto the target, in the picture and in depth."""
    gain = 0.6  # picture px per drag px; learnt from each move
    for _ in range(tries):
        f = look()
        t = tool(f, name)
        target = target_of(f)
        mid = t["jaw_mid"]
        ex = target["px"][0] - mid["px"][0]
        ey = target["px"][1] - mid["px"][1]
        dz = target["depth_m"] - mid["depth_m"]
        if math.hypot(ex, ey) < within_px and abs(dz) < within_m:
            say(f"{name} on target: {ex:+.1f} {ey:+.1f} px, {1e3 * dz:+.1f} mm deep")
            return True
        if abs(dz) >= within_m:
            # W and S move the tip 3 mm into and out of the picture.
            presses = max(-6, min(6, round(dz / STEP_M)))
            if presses != 0:
                for _ in range(abs(presses)):
                    key("w" if presses > 0 else "s")
                continue
        before = mid["px"]
        mx, my = ex / gain, ey / gain
        scale = min(1.0, 250.0 / max(1e-9, math.hypot(mx, my)))
        drag(round(mx * scale), round(my * scale))
        after = tool(look(), name)["jaw_mid"]["px"]
        moved = math.hypot(after[0] - before[0], after[1] - before[1])
        asked = math.hypot(mx * scale, my * scale)
        if asked > 10 and moved > 1:
            gain = min(3.0, max(0.1, moved / asked))
    say(f"{name} not on target after {tries} tries")
    return False


def line_angle(a, b):
    return math.atan2(b[1] - a[1], b[0] - a[0])


def align_blades(name, tries=20):
    """Rolls the instrument until its open jaws' tips lie along the guide in the picture: one key
    while the error shrinks, the other once a press made it grow."""
    last_err, k = None, "e"
    for _ in range(tries):
        f = look()
        t = tool(f, name)
        g = f["guide"]
        want = line_angle(px(g[0]), px(g[-1]))
        got = line_angle(px(t["jaw_tips"][0]), px(t["jaw_tips"][1]))
        err = (got - want + math.pi / 2) % math.pi - math.pi / 2
        if abs(err) < math.radians(12):
            say(f"blades along the guide ({math.degrees(err):+.0f} deg)")
            return True
        if last_err is not None and abs(err) > abs(last_err):
            k = "q" if k == "e" else "e"
        key(k)
        last_err = err
    say(f"blades not along the guide after {tries} presses ({math.degrees(err):+.0f} deg)")
    return False


def end_session():
    xdo("keydown", "Escape")
    subprocess.run(["xdotool", "search", "--sync", "--name", "session summary"], check=True,
                   timeout=60, stdout=subprocess.DEVNULL)
    xdo("keyup", "Escape")
    xdo("keydown", "space")
    proc.wait(timeout=120)
    xdo("keyup", "space")


env = dict(os.environ, SEROSA_PROGRESS_DB=os.path.join(OUT, "progress.sqlite"))
proc = subprocess.Popen([SEROSA, "run", SCENE, "--seconds", "400", "--report", REPORT,
                         "--view-log", LOG], env=env)
try:
    window = subprocess.run(["xdotool", "search", "--sync", "--name", "^Serosa"], check=True,
                            timeout=90, capture_output=True, text=True).stdout.split()[0]
    wait_frames(1, 0.0, limit_s=90)
    xdo("windowfocus", "--sync", window)
    first = look()
    while not first["hands"]:  # the solver has not published a frame yet
        wait_frames(1, 0.0, limit_s=60)
        first = look()
    names = [h["tool"] for h in first["hands"]]  # what each hand holds, as the overlay says
    say("hands:", names, "active:", first["active_hand"])
    if TASK == "transection":
        if first["active_hand"] != names.index("scissors"):
            key("Tab")
        assert look()["active_hand"] == names.index("scissors"), "Tab did not give the scissors"
        set_jaws(True, "open the scissors")
        say("scissors open to", round(tool(look(), "scissors")["jaw_rad"], 2), "rad")
        centre = lambda f: {"px": [(f["guide"][0]["px"][i] + f["guide"][-1]["px"][i]) / 2
                                   for i in range(2)],
                            "depth_m": (f["guide"][0]["depth_m"] + f["guide"][-1]["depth_m"]) / 2}
        align_blades("scissors")
        aim("scissors", centre)
        align_blades("scissors")
        aim("scissors", centre)
        for _ in range(4):  # as the overlay says: the appendix (7 mm) wholly between the blades
            in_jaws = tool(look(), "scissors")["tissue_in_jaws_m"]
            say(f"{1e3 * in_jaws:.0f} mm in the jaws")
            if in_jaws >= 0.006:
                break
            key("w")
        key("j")  # close: the blades cut
        wait_frames(5, 1.5)
    elif TASK == "grasp_and_lift":
        if first["active_hand"] != names.index("grasper"):
            key("Tab")
        g = look()["active_hand"]
        for attempt in range(3):  # as a trainee does: closed on nothing, open and try again
            set_jaws(True, "open the grasper")
            aim("grasper", lambda f: f["groups"]["appendix"])
            key("j")  # close on the appendix
            wait_frames(3, 1.0)
            hand = look()["hands"][g]
            say(f"jaws {hand['jaw_rad']:.2f} rad, holding {hand['holding_nodes']} nodes")
            if hand["holding_nodes"] > 0:
                break
        for _ in range(4):
            key("s")  # out of the picture, towards the scope: lifting what it holds
        before = tool(look(), "grasper")["jaw_mid"]["px"]
        drag(0, -120)
        wait_frames(5, 1.0)
        after = tool(look(), "grasper")["jaw_mid"]["px"]
        say(f"lifted: the jaws moved {after[0] - before[0]:+.0f} {after[1] - before[1]:+.0f} px")
    elif TASK == "keep_moving":
        xdo("mousemove", "--window", window, 640, 360)
        xdo("mousedown", 1)
        start, k = time.time(), 0
        while time.time() - start < 20.0:  # a 60 px circle every 2 s, never still
            a, b = 2 * math.pi * k / 40, 2 * math.pi * (k + 1) / 40
            xdo("mousemove_relative", "--", round(60 * (math.cos(b) - math.cos(a))),
                round(60 * (math.sin(b) - math.sin(a))))
            k += 1
            time.sleep(0.05)
        xdo("mouseup", 1)
    else:
        raise SystemExit(f"trainee_mouse.py: unknown task {TASK}")
    end_session()
except BaseException:
    proc.kill()
    raise

with open(REPORT) as f:
    report = json.load(f)
metrics = report.get("assessment", {}).get("metrics", {})
say("report: assessment", json.dumps(metrics)[:2000])
if TASK == "keep_moving":
    m = report["metrics"]
    say(f"idle {m['idle_time_s']:.2f} s of {m['time_s']:.2f} s")
    sys.exit(0 if m["idle_time_s"] < 0.1 * m["time_s"] else 1)
if TASK == "transection":
    pieces = None
    for k, v in (metrics.items() if isinstance(metrics, dict) else []):
        if k == "pieces.appendix":
            pieces = v.get("value", v) if isinstance(v, dict) else v
    say("appendix in", pieces, "pieces;", report.get("cutting", {}).get("strokes"), "strokes")
    sys.exit(0 if pieces == 2 else 1)
else:
    steps = report["metrics"]["procedure"]["steps"]
    say("procedure steps:", json.dumps(steps))
    expose = [s for s in steps if s.get("name") == "expose"] if isinstance(steps, list) else [steps.get("expose")]
    sys.exit(0 if expose and expose[0] and expose[0].get("done") else 1)
