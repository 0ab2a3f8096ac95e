"""audit(), verify(), explore(): plain data that says what the command says; the docstrings and the stubs."""
import ast
import pathlib
from fractions import Fraction

import numpy as np
import pytest

import superball
from conftest import cli_json, run_cli


def test_verify_agrees_with_the_command():
    kw = dict(case="1", alphas=2, epsilons=["1/100", "1/10000"], samples=150, boundary_pairs=4, seed=3)
    v = superball.verify(**kw, threads=2)
    j = cli_json("verify", "--case", "1", "--alphas", "2", "--epsilons", "1/100,1/10000", "--samples", 150, "--boundary-pairs", 4,
                 "--seed", 3, "--json", "--quiet")
    assert v.data == j and v.exact_agrees
    assert v.epsilons.dtype == np.float64 and v.epsilons.tolist() == [0.01, 0.0001]
    assert v.points.dtype == np.int64 and (v.points >= 150).all()
    assert (v.exact_agreement == 1).all()
    assert ((0 <= v.asymptotic_agreement) & (v.asymptotic_agreement <= 1)).all()
    # the same run on one thread: the same result
    assert superball.verify(**kw, threads=1).data == v.data
    assert "exact agree" in str(v)


def test_verify_every_case_and_errors():
    every = superball.verify(all=True, alphas=2, epsilons=["1/100"], samples=20, boundary_pairs=1)
    assert len(every) == 8 and all(v.exact_agrees for v in every)
    for kwargs, what in ((dict(epsilons=["2"]), "epsilons must be in \\(0, 1\\), got 2"), (dict(epsilons=["x"]), "epsilons: 'x'"),
                         (dict(samples=0), "samples"), (dict(boundary_pairs=-1), "boundary_pairs"), (dict(threads=-2), "threads")):
        with pytest.raises(ValueError, match=what):
            superball.verify(case="1", alphas=2, **kwargs)


def test_explore_finds_a_witness_that_an_exact_solve_confirms():
    e = superball.explore(case="1", alphas=3, starts=4, evaluations=300)
    assert e.reach == "yes" and e.ratio > 1
    assert e.data == cli_json("explore", "--case", "1", "--alphas", "3", "--starts", 4, "--evaluations", 300, "--json")
    r = superball.solve(e.scene, "exact")
    assert r.case == "1" and r.superball
    assert r.velocities_after_exact[0] / e.witness["a"] == e.ratio
    assert all(isinstance(x, Fraction) for x in e.witness.values())


def test_explore_proves_the_clash_of_alpha1_alpha6():
    e = superball.explore(case="1", alphas=[1, 6], starts=4, evaluations=200)
    assert e.reach == "no (proved)" and e.data["clash"]
    assert e.reach == cli_json("explore", "--case", "1", "--alphas", "1,6", "--starts", 4, "--evaluations", 200, "--json")["reach"]
    with pytest.raises(ValueError, match="starts"):
        superball.explore(case="1", alphas=2, starts=0)
    with pytest.raises(ValueError, match="give a case"):
        superball.explore(alphas=2)


def test_audit_small():
    a = superball.audit(samples=200)
    j = cli_json("audit", "--samples", 200, "--json")
    assert a.data == j
    verdicts = {c["verdict"] for c in a.conditions}
    assert verdicts == {"identical to the exact condition", "identical at the asymptotic order", "different"}
    witnesses = 0
    for c in a.conditions:  # a different condition comes with a point where it disagrees with the exact solution
        if c["verdict"] == "different" and "witness" in c:
            witnesses += 1
            w = c["witness"]
            assert w["printed_holds"] != w["exact_solution_holds"] and w["derived_exact_holds"] == w["exact_solution_holds"]
    assert witnesses > 0
    assert all(isinstance(c["supported"], bool) for c in a.claims)
    with pytest.raises(ValueError, match="epsilon"):
        superball.audit(epsilon=2)


def test_docstrings_carry_the_maths():
    assert "w = q + Nλ" in superball.solve.__doc__
    assert "(ZᵀAZ)V" in superball.derive.__doc__
    assert "A W = diag(m) U⁻" in superball.__doc__
    for name in superball.__all__:
        obj = getattr(superball, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__) > 40, name


def test_the_stubs_name_every_public_symbol():
    stub = pathlib.Path(superball.__file__).with_name("__init__.pyi")
    assert pathlib.Path(superball.__file__).with_name("py.typed").exists()
    tree = ast.parse(stub.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    assert set(superball.__all__) <= names, set(superball.__all__) - names
    # and the functions' parameters are the module's
    import inspect
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name in superball.__all__:
            stub_params = [a.arg for a in node.args.args + node.args.kwonlyargs]
            assert stub_params == list(inspect.signature(getattr(superball, node.name)).parameters), node.name


def test_version_is_the_command_s():
    assert run_cli("--version")[1].strip() == f"superball {superball.__version__}"


def test_explore_every_pattern():
    told = []
    t = superball.explore(all_patterns=True, starts=1, evaluations=10, progress=lambda *a: told.append(a))
    # its progress is over the 64 cells, each of 1 × 10 evaluations and one step for the rest
    assert {x[0] for x in told} == {"cells"} and told[-1] == ("cells", 64 * 11, 64 * 11)
    # each cell is explore() of its pattern and case (the command's --all-patterns JSON is the same library call)
    cell = t.data["rows"][2]["cells"][0]
    assert cell == superball.explore(case="1", alphas=3, starts=1, evaluations=10).data
    assert t.reach.shape == (len(t.patterns), len(t.cases)) == (8, 8)
    assert t.patterns[0] == "alpha1" and t.patterns[-1] == "alpha1,alpha6" and t.cases[0] == "1"
    assert t.reach[t.patterns.index("alpha1,alpha6"), t.cases.index("1")] == "no (proved)"  # §4.1's remark, proved
    assert "| " in str(t)
