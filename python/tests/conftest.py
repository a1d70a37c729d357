"""Shared fixtures: the repository, the serosa executable CTest built, and its scenes."""
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("SEROSA_SOURCE", pathlib.Path(__file__).resolve().parents[2]))
TRANSECTION = SOURCE / "config" / "transection.toml"


@pytest.fixture(scope="session")
def serosa_exe():
    exe = os.environ.get("SEROSA_EXE")
    if not exe:
        pytest.fail("SEROSA_EXE is not set (CTest sets it to the serosa executable)")
    return pathlib.Path(exe)


@pytest.fixture(scope="session")
def source():
    return SOURCE


def run_headless(exe, *args):
    """`serosa headless ... --json`: the report on stdout, as text."""
    out = subprocess.run([str(exe), "headless", *map(str, args), "--json"],
                         capture_output=True, text=True, check=True)
    return out.stdout
