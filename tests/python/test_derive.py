"""derive(): the symbolic case against the command's JSON and against exact solves."""
import json
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest

import superball
from conftest import cli_json


@pytest.fixture(scope="module")
def case1():
    return superball.derive(case="1", alphas=2)


def test_matches_the_command_s_json(case1):
    j = cli_json("derive", "--case", "1", "--alphas", "2", "--format", "json")
    assert case1.data == j
    assert case1.case == "1" and case1.closed_contacts == ("2-3", "3-4")
    assert [c.about for c in case1.conditions] == [c["about"] for c in j["conditions"]]


def test_condition_fields(case1):
    s = case1.condition("U1 > a")
    assert s.kind == "superball"
    assert s.text == "−α₂ > 2m₁ + K₁₂ + K₁₃"
    assert s.exact == "-2*m1 - K12 - K13 - alpha2 > 0"
    assert s.asymptotic_text == "−α₂ > K₁₂ + K₁₃"
    assert s._repr_latex_().startswith("$") and "\\alpha" in s.latex
    assert str(s) == s.text
    kinds = {c.kind for c in case1.conditions}
    assert kinds == {"superball", "evolution", "contact", "psd"}
    with pytest.raises(KeyError):
        case1.condition("nothing")


def test_velocities_and_reactions(case1):
    assert case1.velocities_text[0] == "a(K₁₄ + α₂ − m₁)/(m₁ + K₁₂ + K₁₃ + K₁₄ + 2α₂)"
    assert case1.velocities_text[3] == "0"  # the fixed obstacle
    assert case1.reactions_text[0] == "0" and case1.reactions_text[1] != "0"  # 1-2 open, 2-3 closed
    assert len(case1.velocities_latex) == 4 and len(case1.reactions_latex) == 3
    assert "\\begin{aligned}" in case1._repr_latex_()
    assert case1.report.startswith("case 1") or "case 1" in case1.report


def test_to_sympy_is_the_same_condition(case1):
    import sympy

    s = case1.condition("U1 > a").to_sympy()
    assert isinstance(s, sympy.StrictGreaterThan)
    m1, K12, K13, alpha2 = sympy.symbols("m1 K12 K13 alpha2")
    names = {str(x): x for x in s.free_symbols}
    assert sympy.simplify(s.lhs - s.rhs - (-2 * names["m1"] - names["K12"] - names["K13"] - names["alpha2"])) == 0
    assert isinstance(case1.condition("2-3").to_sympy(), sympy.GreaterThan)
    assert case1.condition("U1 > a").to_sympy(asymptotic=True).free_symbols == {names["K12"], names["K13"], names["alpha2"]}


def test_sympy_is_imported_only_when_asked():
    code = "import sys, superball; superball.derive(case='1', alphas=2); print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def point(rng):
    """A random point of the paper's regime with M positive semi-definite (α₂² < K₁₂K₁₄)."""
    v = {f"m{i}": Fraction(int(rng.integers(1, 2000)), 100) for i in (1, 2, 3)}
    v["m1"] /= 100
    for p in ("12", "13", "23", "24", "34"):
        v[f"K{p}"] = Fraction(int(rng.integers(1, 2000)), 100)
    v["K14"] = Fraction(int(rng.integers(100, 100000)), 10)
    bound = int((v["K12"] * v["K14"]) ** 0.5 * 0.99)
    v["alpha2"] = -Fraction(int(rng.integers(0, max(bound, 1))))
    v["a"] = Fraction(int(rng.integers(1, 500)), 100)
    return v


def scene_at(v):
    return superball.Scene(bodies=[v["m1"], v["m2"], v["m3"], {"mass": "inf", "velocity": 0}], fall_speed=v["a"],
                           K={f"{p[0]}-{p[1]}": v[f"K{p}"] for p in ("12", "13", "14", "23", "24", "34")}, alpha={2: v["alpha2"]})


def test_exact_conditions_decide_the_exact_solution(case1):
    """At random points: the case's exact conditions hold iff the exact solve is case 1, the superball
    condition then holds iff U₁⁺ > a, and the derived U₁⁺ is the solver's, exactly."""
    import sympy

    rng = np.random.default_rng(3)
    names = {s["name"]: sympy.Symbol(s["name"], positive=s["positive"]) if s["positive"] else sympy.Symbol(s["name"], real=True)
             for s in case1.data["symbols"]}
    case_conditions = [c.to_sympy() for c in case1.conditions if c.kind in ("evolution", "contact")]
    superball_condition = case1.condition("U1 > a").to_sympy()
    u1 = case1.velocity_sympy(1)
    seen = {True: 0, False: 0}
    for _ in range(40):
        v = point(rng)
        at = {names[k]: sympy.Rational(x.numerator, x.denominator) for k, x in v.items() if k in names}
        holds = all(bool(c.subs(at)) for c in case_conditions)
        r = superball.solve(scene_at(v), "exact")
        assert holds == (r.case == "1"), v
        seen[holds] += 1
        if holds:
            exact_u1 = u1.subs(at)
            assert Fraction(int(sympy.numer(exact_u1)), int(sympy.denom(exact_u1))) == r.velocities_after_exact[0]
            assert bool(superball_condition.subs(at)) == (r.velocities_after_exact[0] > v["a"]) == r.superball
    assert seen[True] >= 3 and seen[False] >= 3  # both sides were reached


def test_all_cases_and_other_patterns():
    every = superball.derive(all=True, alphas=[1, 6])
    assert isinstance(every, list) and len(every) == 8
    assert sorted(d.case for d in every) == sorted(["0", "1", "2.1", "2.2", "3.1", "3.2", "3.3", "3.4"])
    chain = superball.derive(bodies=5, pairs="near2", coupling="near2", closed=["2-3", "4-5"])
    assert chain.closed_contacts == ("2-3", "4-5") and len(chain.velocities) == 5
    j = cli_json("derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--closed", "2-3,4-5", "--format", "json")
    assert chain.data == j
    finite = superball.derive(case="3.2", alphas=5, obstacle="finite", scaling={"m1": 1, "m4": -1, "K14": -1}, order=1)
    assert finite.data["obstacle"] == "finite" and all(c.data["orders_kept"] == 2 for c in finite.conditions if c.kind != "psd")
