"""serosa.Simulation against the command line and the physics: the same bits as
`serosa headless`, numpy shapes, a cut that conserves rest volume, snapshots, tools."""
import json

import numpy as np
import pytest

import serosa
from conftest import TRANSECTION, run_headless


@pytest.fixture(scope="module")
def stepped():
    sim = serosa.Simulation(str(TRANSECTION))
    sim.step(120)
    return sim


def test_stepping_equals_headless_bit_for_bit(stepped, serosa_exe, tmp_path):
    exported = tmp_path / "headless.vtu"
    report = json.loads(run_headless(serosa_exe, TRANSECTION, "--steps", 120,
                                     "--export-final", exported))
    assert stepped.steps == 120 and report["steps_taken"] == 120
    assert stepped.state_hash == report["state_hash"]
    ours = tmp_path / "python.vtu"
    stepped.export(str(ours))
    assert ours.read_bytes() == exported.read_bytes()  # positions, to the file's last digit
    assert stepped.report()["state_hash"] == report["state_hash"]


def test_arrays_have_documented_shapes_and_types(stepped):
    n = stepped.positions.shape[0]
    m = stepped.tets.shape[0]
    for a in (stepped.positions, stepped.rest_positions, stepped.velocities):
        assert a.shape == (n, 3) and a.dtype == np.float64
    assert stepped.tets.shape == (m, 4) and stepped.tets.dtype == np.int32
    assert stepped.groups.shape == (m,) and stepped.groups.dtype == np.int32
    assert stepped.tets.min() >= 0 and stepped.tets.max() < n
    assert set(np.unique(stepped.groups)) <= set(stepped.group_names)
    assert stepped.time == pytest.approx(120 * stepped.dt)
    # Copies: writing to one changes nothing in the simulation.
    p = stepped.positions
    p[:] = 0.0
    assert np.abs(stepped.positions).max() > 0.0
    # Rest volume is the sum of the tets' signed volumes.
    x = stepped.rest_positions[stepped.tets]
    v = np.einsum("ij,ij->i", np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), x[:, 3] - x[:, 0])
    assert stepped.rest_volume == pytest.approx(v.sum() / 6.0, rel=1e-12)


def appendix_polygon(sim):
    """A square across the appendix's long axis, through its middle, larger than it."""
    rest = sim.rest_positions[np.unique(sim.tets[sim.groups == 1])]
    lo, hi = rest.min(axis=0), rest.max(axis=0)
    axis = int(np.argmax(hi - lo))
    mid = 0.5 * (lo + hi)
    u, w = [k for k in range(3) if k != axis]
    corners = []
    for du, dw in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        p = mid.copy()
        p[u] += du * 0.05
        p[w] += dw * 0.05
        corners.append(p)
    return np.array(corners)


def test_cut_adds_tets_and_conserves_rest_volume(tmp_path):
    sim = serosa.Simulation(str(TRANSECTION))
    sim.step(2)
    before_volume, before_tets = sim.rest_volume, sim.tets.shape[0]
    done = sim.cut(appendix_polygon(sim))
    assert done["cuts"] == 1 and done["tets_crossed"] > 0
    assert done["tets_added"] > done["tets_crossed"]
    assert sim.tets.shape[0] == before_tets - done["tets_removed"] + done["tets_added"]
    assert sim.rest_volume == pytest.approx(before_volume, rel=1e-12)
    assert 0.0 < done["min_quality"] <= 1.0
    assert sim.report()["cutting"]["tets_added"] == done["tets_added"]
    sim.step(5)  # the FEM takes the new tets
    assert np.isfinite(sim.positions).all()
    out = tmp_path / "cut.msh"
    sim.export(str(out))
    check = serosa.check_mesh(str(out))
    assert check["valid"], check["problems"]
    assert check["overshared_faces"] == 0
    assert check["volume_m3"] == pytest.approx(before_volume, rel=1e-9)


def test_restored_snapshot_goes_on_bit_for_bit():
    sim = serosa.Simulation(str(TRANSECTION))
    sim.step(30)
    snap = sim.snapshot()
    sim.step(40)
    first = (sim.state_hash, sim.positions)
    sim.restore(snap)
    assert sim.steps == 30
    sim.step(40)
    assert sim.state_hash == first[0]
    assert np.array_equal(sim.positions, first[1])
    # Across a cut: the snapshot waits for the step after the one that cut.
    done = sim.cut(appendix_polygon(sim))
    assert done["cuts"] == 1
    with pytest.raises(RuntimeError, match="cut is in flight"):
        sim.snapshot()
    sim.step()
    snap = sim.snapshot()
    sim.step(25)
    after_cut = sim.state_hash
    other = serosa.Simulation(str(TRANSECTION))
    other.restore(snap)
    other.step(25)
    assert other.state_hash == after_cut


def test_a_python_tool_takes_the_pose_it_is_given():
    sim = serosa.Simulation(str(TRANSECTION), overrides={"tool.0.device": "python"})
    assert sim.tool("grasper")["device"] == "python"
    sim.set_tool("grasper", position=(0.01, 0.05, 0.06), orientation=(0.0, 0.0, 0.0, 2.0), jaw=0.4)
    sim.step()
    t = sim.tool("grasper")
    assert t["position"] == pytest.approx((0.01, 0.05, 0.06))
    assert t["orientation"] == pytest.approx((0.0, 0.0, 0.0, 1.0))  # normalised
    assert t["jaw"] == pytest.approx(0.4)
    sim.set_tool("grasper", jaw=0.0)  # what is not given stays
    sim.step()
    t = sim.tool("grasper")
    assert t["jaw"] == 0.0 and t["position"] == pytest.approx((0.01, 0.05, 0.06))
    # Two runs given the same poses are the same run.
    again = serosa.Simulation(str(TRANSECTION), overrides={"tool.0.device": "python"})
    again.set_tool("grasper", position=(0.01, 0.05, 0.06), orientation=(0, 0, 0, 1), jaw=0.4)
    again.step()
    again.set_tool("grasper", jaw=0.0)
    again.step()
    assert again.state_hash == sim.state_hash


def test_overrides_reach_the_scene():
    soft = serosa.Simulation(str(TRANSECTION), overrides={"solver.tolerance": 1e-5})
    assert soft.report()["solver"]["tolerance"] == pytest.approx(1e-5)
    assert soft.report()["provenance"]["overrides"]
