"""Shared fixtures of the Python module's tests.

ctest runs them with PYTHONPATH pointing at the module to test (the build
tree's, or an installed prefix's) and SUPERBALL_EXE at the `superball`
command built from the same sources, whose output the module must match.
"""
import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("SUPERBALL_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE_DIR / "cases" / "scenes"
BAD = SOURCE_DIR / "tests" / "data" / "bad"
PAPER = SCENES / "paper-4.4-alpha2.toml"


@pytest.fixture(scope="session")
def paper_path():
    return PAPER


@pytest.fixture(scope="session")
def paper():
    import superball

    return superball.Scene.load(PAPER)


def cli_path():
    exe = os.environ.get("SUPERBALL_EXE")
    if not exe:
        pytest.skip("SUPERBALL_EXE is not set (ctest sets it to the built command)")
    return exe


def run_cli(*args, check=True):
    """The command's (exit code, stdout, stderr)."""
    p = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True, timeout=120)
    if check and p.returncode not in (0, 1):
        raise AssertionError(f"superball {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_json(*args):
    return json.loads(run_cli(*args)[1])
