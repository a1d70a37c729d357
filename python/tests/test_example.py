"""The example for engineers runs, writes its plot, and its physics holds: with the grasper's
path prescribed, a stiffer appendix pulls back harder."""
import pathlib
import subprocess
import sys

from conftest import SOURCE

EXAMPLE = SOURCE / "python" / "examples" / "sweep_appendix_stiffness.py"


def test_the_stiffness_sweep_plots_a_rising_grasper_force(tmp_path):
    out = tmp_path / "sweep.png"
    run = subprocess.run([sys.executable, str(EXAMPLE), "--out", str(out)],
                         capture_output=True, text=True, check=True)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = [line.split() for line in run.stdout.splitlines()[1:6]]
    young = [float(r[0]) for r in rows]
    force = [float(r[1]) for r in rows]
    created = [int(r[2]) for r in rows]
    assert young == sorted(young) and len(set(young)) == 5
    assert all(b > a for a, b in zip(force, force[1:])), force
    assert all(c > 0 for c in created)  # every run transected the appendix
    assert pathlib.Path(str(out)).stat().st_size > 10_000
