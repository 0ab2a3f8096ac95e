"""derive() and derive_all(): the symbolic cases against the command's JSON and against exact solves;
conditions evaluated exactly and over NumPy; the worker processes, their progress and Ctrl-C."""
import inspect
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from fractions import Fraction

import numpy as np
import pytest

import superball
from conftest import cli_json, cli_path


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
    with pytest.raises(superball.InputError, match="no condition about 'nothing' in case 1 .*'U1 > a', '1-2'"):
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
    every = superball.derive_all(alphas=[1, 6])
    assert isinstance(every, list) and len(every) == 8
    assert sorted(d.case for d in every) == sorted(["0", "1", "2.1", "2.2", "3.1", "3.2", "3.3", "3.4"])
    chain = superball.derive(bodies=5, pairs="near2", coupling="near2", closed=["2-3", "4-5"])
    assert chain.closed_contacts == ("2-3", "4-5") and len(chain.velocities) == 5
    j = cli_json("derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--closed", "2-3,4-5", "--format", "json")
    assert chain.data == j
    finite = superball.derive(case="3.2", alphas=5, obstacle="finite", scaling={"m1": 1, "m4": -1, "K14": -1}, order=1)
    assert finite.data["obstacle"] == "finite" and all(c.data["orders_kept"] == 2 for c in finite.conditions if c.kind != "psd")


def test_one_function_per_return_shape():
    # derive() is one case, derive_all() a list; no parameter shadows a built-in.
    for f in (superball.derive, superball.derive_all):
        assert not {"all", "no_limit"} & set(inspect.signature(f).parameters)
    with pytest.raises(superball.InputError, match="give a case .*derive_all"):
        superball.derive(alphas=2)
    assert isinstance(superball.derive(closed="none", alphas=2), superball.Derivation)
    assert "derive_all" in superball.__all__ and "derive" in superball.__all__


@pytest.fixture(scope="module")
def chain5():
    """Every case of 5 bodies, near2 with couplings (long cases written through their elimination), in 3 workers."""
    steps = []
    every = superball.derive_all(bodies=5, pairs="near2", coupling="near2", jobs=3, progress=lambda done, total: steps.append((done, total)))
    return every, steps


def test_derive_all_equals_the_command_whatever_the_workers(chain5):
    every, steps = chain5
    assert steps == [(k, 16) for k in range(17)]
    j = cli_json("derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--all", "--format", "json")
    assert [d.data for d in every] == j
    one = superball.derive_all(bodies=5, pairs="near2", coupling="near2", jobs=1, progress=False)
    assert [d.data for d in one] == j
    # The compact JSON has the conditions on M in its first case only; every Derivation shows them.
    assert not any(c["kind"] == "psd" for c in j[1]["conditions"])
    psd = [c.about for c in every[0].conditions if c.kind == "psd"]
    assert psd and all([c.about for c in d.conditions if c.kind == "psd"] == psd for d in every)
    expanded = superball.derive(bodies=5, pairs="near2", coupling="near2", closed="none", expanded=True)
    assert expanded.data == cli_json("derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--closed", "none", "--format",
                                     "json", "--expanded")
    with pytest.raises(superball.InputError, match="jobs"):
        superball.derive_all(alphas=2, jobs=-1)
    with pytest.raises(superball.InputError, match="progress"):
        superball.derive_all(alphas=2, progress="yes")


def random_values(d, rng):
    """Random exact values of a derivation's symbols: masses, K's and a in (0, 10], couplings small and negative
    (M diagonally dominant, so positive semi-definite)."""
    v = {}
    for s in d.data["symbols"]:
        if s["kind"] == "coupling":
            v[s["name"]] = -Fraction(int(rng.integers(0, 100)), 1000)
        else:
            v[s["name"]] = Fraction(int(rng.integers(1, 1000)), 100)
    return v


def test_evaluate_is_exact(case1):
    rng = np.random.default_rng(5)
    s = case1.condition("U1 > a")
    for _ in range(10):
        v = random_values(case1, rng)
        assert s.evaluate(v) == -2 * v["m1"] - v["K12"] - v["K13"] - v["alpha2"]
        assert s.evaluate(v, asymptotic=True) == -v["K12"] - v["K13"] - v["alpha2"]
    # Numbers as a scene file reads them; a float exactly as the double it is.
    v = {"m1": "1/100", "K12": 3, "K13": 0.5, "alpha2": Fraction(-10)}
    assert s.evaluate(v) == Fraction(648, 100)
    with pytest.raises(superball.InputError, match="'x' is not a symbol of this derivation"):
        s.evaluate({**v, "x": 1})
    with pytest.raises(superball.InputError, match="no value for K13"):
        s.evaluate({"m1": 1, "K12": 1, "alpha2": 1})
    with pytest.raises(superball.InputError, match="m1"):
        s.evaluate({**v, "m1": "one"})


def test_evaluate_through_the_elimination_has_the_sign_of_the_expanded_condition(chain5):
    every, _ = chain5
    rng = np.random.default_rng(7)
    compact = every[0]  # {}: every contact open, the longest case
    expanded = superball.derive(bodies=5, pairs="near2", coupling="near2", closed="none", expanded=True)
    assert compact.definitions and compact.velocities[0] == "V1" and expanded.velocities[0] != "V1"
    through = [c for c in compact.conditions if c.exact is None]
    assert len(through) >= 5
    for _ in range(5):
        v = random_values(compact, rng)
        for c in through:
            e = expanded.conditions[compact.conditions.index(c)]
            assert e.about == c.about and e.exact is not None
            value, reference = c.evaluate(v), e.evaluate(v)
            assert (value > 0) == (reference > 0) and (value == 0) == (reference == 0), c.about


def test_lambdify_is_numpy_without_sympy(case1, chain5):
    rng = np.random.default_rng(11)
    for c in list(case1.conditions) + list(chain5[0][0].conditions):
        f = c.lambdify()
        points = [random_values(chain5[0][0] if c in chain5[0][0].conditions else case1, rng) for _ in range(6)]
        arrays = {name: np.array([float(p[name]) for p in points]) for name in f.parameters}
        got = f(**arrays)
        assert got.shape == (6,) and got.dtype == np.float64
        want = np.array([float(c.evaluate({k: p[k] for k in f.parameters})) for p in points])
        np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-12 * max(1.0, float(np.abs(want).max())))
    code = ("import sys, superball; c = superball.derive(case='1', alphas=2).condition('U1 > a'); "
            "print(c.lambdify()(m1=0.01, K12=3.0, K13=0.5, alpha2=-10.0), c.evaluate({'m1': 1, 'K12': 1, 'K13': 1, 'alpha2': -9}), "
            "'sympy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["6.48", "5", "False"]


def test_short_reprs_and_html(case1, chain5):
    for d in (case1, chain5[0][0]):
        assert len(repr(d)) < 120 and repr(d).startswith("<Derivation case ")
        assert "<table>" in d._repr_html_()
        for c in d.conditions:
            assert len(repr(c)) < 160 and "<table>" in c._repr_html_()
    assert repr(case1) == "<Derivation case 1 {2-3,3-4}: 4 bodies, 11 conditions, actual depends>"
    assert repr(case1.condition("U1 > a")) == "<Condition superball U1 > a: −α₂ > 2m₁ + K₁₂ + K₁₃ (depends)>"


SEVEN = dict(bodies=7, pairs="near2", coupling="near2")


def test_keyboard_interrupt_stops_the_workers():
    """Ctrl-C during derive_all() of 7 bodies (about 20 s): KeyboardInterrupt at once, no worker left."""
    code = ("import os, sys, superball\n"
            "try:\n"
            "    superball.derive_all(bodies=7, pairs='near2', coupling='near2', progress=lambda d, t: print('step', d, flush=True))\n"
            "except KeyboardInterrupt:\n"
            "    try:\n"
            "        os.waitpid(-1, os.WNOHANG); print('a worker is left')\n"
            "    except ChildProcessError:\n"
            "        print('interrupted, no worker left')\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "step 0"
    time.sleep(0.5)
    start = time.monotonic()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    assert time.monotonic() - start < 10, "the interrupt waited for the cases"
    assert out.strip().splitlines()[-1] == "interrupted, no worker left", (out, err)


def test_the_command_stops_on_ctrl_c_writing_nothing():
    """`superball derive` of 7 bodies: the estimate first, then Ctrl-C: exit 130, one line, no output file left."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "d7.json")
        p = subprocess.Popen([cli_path(), "derive", "--bodies", "7", "--pairs", "near2", "--coupling", "near2", "--all", "--format", "json",
                              "-o", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        estimate = p.stderr.readline()
        assert estimate.startswith("derive: deriving every case of 7 bodies, a pattern of width 3: about "), estimate
        assert " on one core, " in estimate and "available" in estimate
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        rest = p.communicate(timeout=60)[1]
        assert p.returncode == 130
        assert rest == "superball: derive: interrupted (Ctrl-C): stopped before the end, nothing written\n"
        assert os.listdir(folder) == []
