"""Results cross from C++ into Python as objects (dicts, lists, Fractions, arrays), never as JSON text."""
import json
from fractions import Fraction

import pytest

import superball
from conftest import PAPER, cli_json


@pytest.fixture
def no_json_text(monkeypatch):
    """json.loads and json.dumps refuse while the test runs: a result decoded from text fails it."""
    def refuse(*args, **kwargs):
        raise AssertionError("a result went through JSON text")

    monkeypatch.setattr(json, "loads", refuse)
    monkeypatch.setattr(json, "dumps", refuse)


def test_solve_s_dict(paper, no_json_text):
    d = superball.solve(paper, "exact").to_dict()
    assert isinstance(d, dict) and d["case"] == "3.3" and isinstance(d["velocities_after"], list)


def test_audit_verify_explore(no_json_text):
    a = superball.audit(samples=50)
    assert isinstance(a.data, dict) and a.conditions and a.claims
    v = superball.verify(case="1", alphas=2, epsilons=["1/100"], samples=30, boundary_pairs=2)
    assert isinstance(v.data, dict) and v.data["case"] == "1" and v.exact_agrees
    e = superball.explore(case="1", alphas=2, starts=4, evaluations=200)
    assert e.reach == "yes" and isinstance(e.ratio, Fraction) and e.ratio > 1
    assert isinstance(e.scene, superball.Scene) and superball.solve(e.scene, "exact").superball


def test_the_same_values_as_the_command(paper):
    assert superball.solve(paper, "exact").to_dict() == cli_json("solve", PAPER, "--precision", "exact", "--json")
    assert superball.audit(samples=50, seed=3).data == cli_json("audit", "--samples", "50", "--seed", "3", "--json")
