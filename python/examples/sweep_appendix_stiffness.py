#!/usr/bin/env python3
"""Sweep the appendix's Young's modulus over five values, run the transection for each from
Python, and plot the grasper's peak force and the tets the cut created (a PNG).

    PYTHONPATH=build/release/python python3 python/examples/sweep_appendix_stiffness.py \
        --out sweep.png

Each run is the scripted transection (config/transection.toml): the grasper lifts the appendix,
the scissors cut it. Only the appendix's material changes (organ.0.material.appendix.young).
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

import serosa  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
YOUNG_PA = [7.5e3, 1.5e4, 3.0e4, 6.0e4, 1.2e5]  # the scene's 3.0e4 in the middle


def run(scene, young, steps):
    sim = serosa.Simulation(str(scene), overrides={"organ.0.material.appendix.young": young},
                            steps=steps)
    sim.step(steps if steps is not None else sim.report()["steps"])
    report = sim.report()
    return {
        "young_pa": young,
        "peak_force_n": report["metrics"]["force_max_n"]["grasper"],
        "tets_created": report["cutting"]["tets_added"],
        "steps": sim.steps,
    }


def plot(rows, out):
    young = [r["young_pa"] / 1e3 for r in rows]
    fig, (force, tets) = plt.subplots(1, 2, figsize=(9, 3.6))
    force.plot(young, [r["peak_force_n"] for r in rows], "o-")
    force.set_xscale("log")
    force.set_xlabel("appendix Young's modulus, kPa")
    force.set_ylabel("grasper peak force, N")
    tets.plot(young, [r["tets_created"] for r in rows], "s-", color="tab:red")
    tets.set_xscale("log")
    tets.set_xlabel("appendix Young's modulus, kPa")
    tets.set_ylabel("tets created by the cut")
    fig.suptitle("Transection against appendix stiffness")
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", type=pathlib.Path, default=ROOT / "config" / "transection.toml")
    ap.add_argument("--out", type=pathlib.Path, default=pathlib.Path("sweep_appendix.png"))
    ap.add_argument("--steps", type=int, default=None, help="steps per run (default: the scene's)")
    args = ap.parse_args()
    rows = [run(args.scene, y, args.steps) for y in YOUNG_PA]
    print(f"{'E, kPa':>8} {'peak force, N':>14} {'tets created':>13}")
    for r in rows:
        print(f"{r['young_pa'] / 1e3:8.1f} {r['peak_force_n']:14.4f} {r['tets_created']:13d}")
    plot(rows, args.out)
    print(f"plot: {args.out}")


if __name__ == "__main__":
    main()
