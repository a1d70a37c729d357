"""Bad input raises serosa.InputError (a ValueError) naming the file, key and line; misuse
raises the Python error that fits. Never a crash."""
import numpy as np
import pytest

import serosa
from conftest import TRANSECTION


def test_a_missing_scene_names_the_file(tmp_path):
    missing = tmp_path / "nope.toml"
    with pytest.raises(serosa.InputError) as e:
        serosa.Simulation(str(missing))
    assert str(missing) in str(e.value) and e.value.file == str(missing)
    assert isinstance(e.value, ValueError)


def test_a_broken_scene_names_the_file_and_line(tmp_path, source):
    # A copy of the transection whose paths point back into the repository, one value broken.
    text = (TRANSECTION.read_text()
            .replace('"../assets/', f'"{source}/assets/')
            .replace("script:paths/", f"script:{source}/config/paths/")
            .replace("poisson = 0.45", "poisson = \"soft\"", 1))
    scene = tmp_path / "broken.toml"
    scene.write_text(text)
    with pytest.raises(serosa.InputError) as e:
        serosa.Simulation(str(scene))
    line = 1 + text.splitlines().index(
        next(s for s in text.splitlines() if s.startswith("poisson = \"soft\"")))
    assert e.value.line == line and "poisson" in str(e.value)
    assert str(scene) in str(e.value) and e.value.file == str(scene)


def test_a_wrong_override_names_the_key():
    with pytest.raises(serosa.InputError, match="solver.tolerence"):
        serosa.Simulation(str(TRANSECTION), overrides={"solver.tolerence": 1e-4})
    with pytest.raises(ValueError, match="solver.tolerance"):
        serosa.Simulation(str(TRANSECTION), overrides={"solver.tolerance": object()})


def test_tools_and_cuts_refuse_what_they_cannot_do():
    sim = serosa.Simulation(str(TRANSECTION))
    with pytest.raises(KeyError, match="no tool 'forceps'"):
        sim.tool("forceps")
    with pytest.raises(ValueError, match="not driven from Python"):
        sim.set_tool("scissors", jaw=0.2)
    with pytest.raises(ValueError):
        sim.cut([(0.0, 0.0, 0.0), (0.01, 0.0, 0.0)])  # two points
    with pytest.raises(ValueError):
        sim.cut([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 1e-3)])  # not planar
    with pytest.raises(ValueError, match="not 3"):
        sim.cut([(0, 0), (1, 0), (1, 1)])
    with pytest.raises(ValueError):
        sim.step(-1)
    with pytest.raises(serosa.InputError):
        sim.restore(b"not a snapshot")
    assert sim.steps == 0  # nothing above changed the run
    sim.step()
    assert np.isfinite(sim.positions).all()


def test_meshes_load_and_check(source, tmp_path):
    mesh = serosa.load_mesh(str(source / "assets" / "appendectomy_coarse.msh"))
    assert mesh["rest_positions"].shape[1] == 3 and mesh["tets"].shape[1] == 4
    assert mesh["groups"].shape == (mesh["tets"].shape[0],)
    check = serosa.check_mesh(str(source / "assets" / "appendectomy_coarse.msh"))
    assert check["valid"] and check["tets"] == mesh["tets"].shape[0]
    broken = tmp_path / "broken.msh"
    broken.write_text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n")
    with pytest.raises(serosa.InputError) as e:
        serosa.load_mesh(str(broken))
    assert str(broken) in str(e.value)
