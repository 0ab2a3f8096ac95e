"""One rule, one message: the same bad option value refused by the command and
by the Python module, with the same line.

Every rule on an option lives in the library type it belongs to (its check()
or its parse_…() function); the command and the module only translate their
arguments, so the command's stderr line after "superball: " is exactly the
InputError's message.  The library names an option by its bare name, as a
Python keyword spells it (the command's --name without its dashes, "-" as "_").
"""
import pytest

import superball

from conftest import PAPER, cli_path, run_cli

VERIFY = ("verify", "--case", "1", "--alphas", "2")
AUDIT = ("audit",)
EXPLORE = ("explore", "--case", "1", "--alphas", "2")
SOLVE = ("solve", PAPER)
SWEEP = ("sweep", PAPER, "--vary", "K.3-4=0:20:5")
TWO_BALLS = PAPER.parent / "drop-two-balls.toml"
DROP = ("drop", TWO_BALLS)


def scene():
    return superball.Scene.load(PAPER)


def two_balls():
    return superball.Scene.load(TWO_BALLS)


def verify(**kw):
    return superball.verify(**{"case": "1", "alphas": 2, **kw})


def explore(**kw):
    return superball.explore(**{"case": "1", "alphas": 2, **kw})


def sweep(**kw):
    return superball.sweep(scene(), "K.3-4", superball.linspace(0, 20, 5), **kw)


# (command line, the same request from Python, the message both give)
CASES = [
    # epsilon in (0, 1): VerifyOptions::check(), AuditOptions::check(); its text by parse_epsilon()
    (VERIFY + ("--epsilons", "0"), lambda: verify(epsilons=[0]), "epsilons must be in (0, 1), got 0"),
    (VERIFY + ("--epsilons", "1"), lambda: verify(epsilons=[1]), "epsilons must be in (0, 1), got 1"),
    (VERIFY + ("--epsilons=-1",), lambda: verify(epsilons=[-1]), "epsilons must be in (0, 1), got -1"),
    (VERIFY + ("--epsilons", "2"), lambda: verify(epsilons=[2]), "epsilons must be in (0, 1), got 2"),
    (VERIFY + ("--epsilons", "1/100,3/2"), lambda: verify(epsilons=["1/100", 1.5]), "epsilons must be in (0, 1), got 3/2"),
    (VERIFY + ("--epsilons", "nan"), lambda: verify(epsilons=[float("nan")]), None),
    (AUDIT + ("--epsilon", "0"), lambda: superball.audit(epsilon=0), "epsilon must be in (0, 1), got 0"),
    (AUDIT + ("--epsilon", "2"), lambda: superball.audit(epsilon=2), "epsilon must be in (0, 1), got 2"),
    (AUDIT + ("--epsilon", "nan"), lambda: superball.audit(epsilon=float("nan")), None),
    # samples, boundary pairs, threads
    (VERIFY + ("--samples", "0"), lambda: verify(samples=0), "samples must be a whole number from 1 to 100000000, got 0"),
    (VERIFY + ("--samples", "-5"), lambda: verify(samples=-5), "samples must be a whole number from 1 to 100000000, got -5"),
    (AUDIT + ("--samples", "0"), lambda: superball.audit(samples=0), "samples must be a whole number from 1 to 10000000, got 0"),
    (VERIFY + ("--boundary-pairs", "-1"), lambda: verify(boundary_pairs=-1),
     "boundary_pairs must be a whole number from 0 to 1000000, got -1"),
    (VERIFY + ("--threads", "-1"), lambda: verify(threads=-1), "threads must be a whole number from 0 (all cores) to 1024, got -1"),
    (SWEEP + ("--threads", "-1"), lambda: sweep(threads=-1), "threads must be a whole number from 0 (all cores) to 1024, got -1"),
    (SWEEP + ("--threads", "5000"), lambda: sweep(threads=5000), "threads must be a whole number from 0 (all cores) to 1024, got 5000"),
    # the selection: SelectionOptions::check(), parse_obstacle(), parse_alphas(), the pattern's parsers
    (VERIFY + ("--obstacle", "middle"), lambda: verify(obstacle="middle"), "obstacle must be infinite or finite, got 'middle'"),
    (VERIFY + ("--order", "21"), lambda: verify(order=21), "order must be a whole number from 0 to 20, got 21"),
    (VERIFY + ("--order=-1",), lambda: verify(order=-1), "order must be a whole number from 0 to 20, got -1"),
    (("verify", "--case", "1", "--alphas", "1,,6"), lambda: superball.verify(case="1", alphas="1,,6"),
     "alphas: '1,,6': an empty item is not an index 1..7 (e.g. 1,6)"),
    (("verify", "--case", "1", "--alphas", "x"), lambda: superball.verify(case="1", alphas="x"),
     "alphas: 'x': 'x' is not an index 1..7 (e.g. 1,6)"),
    (("verify", "--case", "1", "--alphas", "1,8"), lambda: superball.verify(case="1", alphas=[1, 8]),
     "alphas: '1,8': '8' is not an index 1..7 (e.g. 1,6)"),
    (("verify", "--closed", "2-3", "--bodies", "5", "--pairs", "1-9"), lambda: superball.verify(closed="2-3", bodies=5, pairs="1-9"),
     "pairs: '1-9': pair 1-9 is outside bodies 1..5"),
    (("verify", "--closed", "2-3", "--bodies", "5", "--coupling", "1-2"), lambda: superball.verify(closed="2-3", bodies=5, coupling="1-2"),
     "coupling: '1-2': '1-2' is not a coupling of two pairs i-j/k-l"),
    (("verify", "--case", "1", "--closed", "2-3", "--alphas", "2"), lambda: superball.verify(case="1", closed="2-3", alphas=2),
     "case, closed and all each choose the cases: give one of them"),
    (("verify", "--alphas", "2"), lambda: superball.verify(alphas=2), "give a case: case, closed or all"),
    (("explore", "--alphas", "2"), lambda: superball.explore(alphas=2), "give a case: case, closed or all, or all_patterns"),
    (("explore", "--all-patterns", "--case", "1"), lambda: superball.explore(all_patterns=True, case="1"),
     "all_patterns chooses the patterns and cases: drop case, closed, all, alphas, coupling and scene"),
    # scene gives the pattern: SelectionOptions::check() (bodies and pairs given differ from their defaults)
    *[(VERIFY[:3] + ("--scene", PAPER) + args, (lambda kw=kw: superball.verify(case="1", scene=str(PAPER), **kw)),
       "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs")
      for args, kw in ((("--bodies", "4"), {"bodies": 4}), (("--pairs", "all"), {"pairs": "all"}), (("--alphas", "2"), {"alphas": 2}),
                       (("--coupling", "1-2/1-3"), {"coupling": "1-2/1-3"}))],
    (("derive", "--closed", "none", "--scene", PAPER, "--bodies", "5"), lambda: superball.derive(closed="none", scene=str(PAPER), bodies=5),
     "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"),
    (("explore", "--case", "1", "--scene", PAPER, "--alphas", "2"), lambda: superball.explore(case="1", scene=str(PAPER), alphas=2),
     "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"),
    # derive: parse_derive_format(), plan_derivation()'s jobs (numeric::check_threads())
    (("derive", "--case", "1", "--format", "pdf"), None, "format must be text, latex or json, got 'pdf'"),
    (("derive", "--all", "--jobs=-1"), lambda: superball.derive_all(jobs=-1), "jobs must be a whole number from 0 (all cores) to 1024, got -1"),
    (("derive", "--all", "--jobs", "2000"), lambda: superball.derive_all(jobs=2000),
     "jobs must be a whole number from 0 (all cores) to 1024, got 2000"),
    # explore: ExploreOptions::check(), parse_box()
    (EXPLORE + ("--starts", "0"), lambda: explore(starts=0), "starts must be a whole number from 1 to 100000, got 0"),
    (EXPLORE + ("--evaluations", "5"), lambda: explore(evaluations=5), "evaluations must be a whole number from 10 to 10000000, got 5"),
    (EXPLORE + ("--box", "2:1"), lambda: explore(box=(2, 1)), None),
    # solve and sweep: SolvePrecision::parse(), Precision::parse()
    (SOLVE + ("--precision", "double", "--rtol", "1e-3"), lambda: superball.solve(scene(), "double", 1e-3),
     "rtol is the certified error of precision auto; precision double has none"),
    (SOLVE + ("--rtol", "2"), lambda: superball.solve(scene(), rtol=2), "rtol must be a number from 0 to 1, got 2"),
    (SOLVE + ("--rtol", "nan"), lambda: superball.solve(scene(), rtol=float("nan")), "rtol must be a number from 0 to 1, got nan"),
    (SOLVE + ("--precision", "quad"), lambda: superball.solve(scene(), "quad"), None),
    (SOLVE + ("--precision", "digits:3"), lambda: superball.solve(scene(), "digits:3"), None),
    (SWEEP + ("--precision", "quad"), lambda: sweep(precision="quad"), None),
    # map's threads: MapSettings::check() (Python's map had a rule and a message of its own)
    (("map", PAPER, "--x", "K.3-4=0:20:3", "--y", "alpha.2=-110:0:3", "--threads", "-1"),
     lambda: superball.map(scene(), "K.3-4=0:20:3", "alpha.2=-110:0:3", threads=-1, progress=False),
     "threads must be a whole number from 0 (all cores) to 1024, got -1"),
    (("map", PAPER, "--x", "K.3-4=0:20:3", "--y", "alpha.2=-110:0:3", "--threads", "1025"),
     lambda: superball.map(scene(), "K.3-4=0:20:3", "alpha.2=-110:0:3", threads=1025, progress=False),
     "threads must be a whole number from 0 (all cores) to 1024, got 1025"),
    # switch points through M's PSD bound: refused by check_range() (a sweep marks such values instead)
    (("sweep", PAPER, "--vary", "alpha.2=-110:0:12", "--switch-points"),
     lambda: superball.switch_points(scene(), "alpha.2", superball.linspace(-110, 0, 12)), None),
    (("sweep", PAPER, "--vary", "alpha.2=-110:0:12", "--switch-points"),
     lambda: superball.sweep(scene(), "alpha.2", superball.linspace(-110, 0, 12)).switch_points(), None),
    # the drop's arithmetic: numeric::drop(), Precision::parse()
    (DROP + ("--precision", "quad"), lambda: superball.drop(superball.Scene.load(TWO_BALLS), "quad"), None),
    (("drop", PAPER), lambda: superball.drop(scene()), None),
    # maps and sweeps of drops: the loader's checks at the range's ends,
    # drop()'s arithmetic, and what a drop has not (numeric::refuse_drop(), refuse_distributed_drop())
    (("sweep", TWO_BALLS, "--vary", "gap.1=-1:1:3"), lambda: superball.sweep(two_balls(), "gap.1", superball.linspace(-1, 1, 3)), None),
    (("sweep", TWO_BALLS, "--vary", "gap.1=0:1:3", "--precision", "quad"),
     lambda: superball.sweep(two_balls(), "gap.1", superball.linspace(0, 1, 3), precision="quad"), None),
    (("map", TWO_BALLS, "--x", "gap.1=0:1:3", "--y", "drop_height=0:1:3"),
     lambda: superball.map(two_balls(), "gap.1=0:1:3", "drop_height=0:1:3"), None),
    (("sweep", TWO_BALLS, "--vary", "gap.1=0:1:3", "--switch-points"),
     lambda: superball.switch_points(two_balls(), "gap.1", superball.linspace(0, 1, 3)), None),
    (("map", TWO_BALLS, "--x", "gap.1=0:1:3", "--y", "mass.1=1:2:3", "--overlay"),
     lambda: superball.map(two_balls(), "gap.1=0:1:3", "mass.1=1:2:3", overlay=True), None),
    (("map", TWO_BALLS, "--x", "gap.1=0:1:3", "--y", "mass.1=1:2:3", "--checkpoint", "unused-drop-map"),
     lambda: superball.map(two_balls(), "gap.1=0:1:3", "mass.1=1:2:3", checkpoint="unused-drop-map"), None),
    (("sweep", TWO_BALLS, "--vary", "gap.1=0:1:3", "--checkpoint", "unused-drop-sweep"),
     lambda: superball.sweep(two_balls(), "gap.1", superball.linspace(0, 1, 3), checkpoint="unused-drop-sweep"), None),
]


@pytest.mark.parametrize("args, call, message", CASES, ids=[" ".join(map(str, c[0][1:] if c[0][0] != "solve" and c[0][0] != "sweep"
                                                                              else c[0][2:])) or c[0][0] for c in CASES])
def test_the_command_and_the_module_refuse_with_the_same_line(args, call, message):
    cli_path()
    code, out, err = run_cli(*args, check=False)
    assert code == 2 and out == "", f"superball {' '.join(map(str, args))}: exit {code}: {err}"
    assert err.startswith("superball: ") and err.endswith("\n") and err.count("\n") == 1, err
    if call is None:  # the command only (Python's derive returns objects: it has no format)
        assert err == f"superball: {message}\n"
        return
    with pytest.raises(superball.InputError) as e:
        call()
    assert str(e.value) == err[len("superball: "):-1]
    if message is not None:
        assert str(e.value) == message


# Bad drop scenes (the red team's): refused by the scene loader (cases/) or by numeric::drop() (a datum outside
# the arithmetic's window), the same line from `superball drop FILE` and from superball.drop(Scene.load(FILE)).
_DROP_BODIES = ('[[body]]\nmass = 0.001\n{top}[[body]]\nmass = 1\n{middle}[[body]]\nmass = "inf"\n{bottom}'
                '[dissipation]\nK = {{ "1-2" = 1e3, "2-3" = 1e3 }}\n[drop]\n{drop}')
BAD_DROPS = [
    ("drop_height = 1\n", {"drop": 'until = "soon"\n'}, 'drop.until: must be "apex" or a time in seconds > 0 (got "soon")'),
    ("drop_height = 1\n", {"drop": "until = 0\n"}, "drop.until: must be"),
    ("drop_height = 1\n", {"drop": "until = nan\n"}, "drop.until: must be a finite number (got nan)"),
    ("drop_height = 1\n", {"drop": "max_events = 1e3\n"}, "drop.max_events: must be a whole number from 1 to 1000000 (got a float)"),
    ("drop_height = 1\n", {"drop": "max_events = 1000000000000\n"}, "(got 1000000000000)"),
    ("drop_height = 1\n", {"top": "gap = -0.5\n"}, "body[1].gap: must be >= 0 m (got -0.5)"),
    ("drop_height = 1\n", {"top": "gap = inf\n"}, "body[1].gap: must be a finite number (got inf)"),
    ("drop_height = 1\n", {"top": 'gap = "x"\n'}, "body[1].gap: 'x' is not a number"),
    ("drop_height = 1\n", {"bottom": "gap = 0.1\n"}, "body[3].gap: the bottom body has no body below it"),
    ("drop_height = 1\n", {"middle": "gap = 0.1\n"}, "body[2].gap: body 2's distance to the bottom body is drop_height, not a gap"),
    ("drop_height = 0\n", {}, "drop_height: a drop onto a fixed obstacle needs drop_height > 0"),
    ("drop_height = -1\n", {}, "drop_height: must be >= 0 (got -1)"),
    ("drop_height = 1\ng = 0\n", {}, "g: must be > 0 (got 0)"),
    ("drop_height = 1\n", {"top": "gap = 1e308\n"}, "body[1].gap = 1e308 is outside what a drop in double computes with"),
    ("drop_height = 1\n", {"top": 'gap = "1e-400"\n'}, "body[1].gap = 1e-400 is outside what a drop in double computes with"),
    ("drop_height = 1e300\n", {}, "drop_height = 1e300 is outside what a drop in double computes with"),
    ("drop_height = 1\n", {"middle": "velocity = 1e200\n"}, "body[2].velocity = 1e200 is outside"),
    ("drop_height = 1\n", {"drop": "until = 1e300\n"}, "drop.until = 1e300 is outside"),
]


@pytest.mark.parametrize("root, parts, message", BAD_DROPS, ids=[m[:40] for _, _, m in BAD_DROPS])
def test_a_bad_drop_scene_is_refused_with_the_same_line(root, parts, message, tmp_path):
    path = tmp_path / "bad-drop.toml"
    path.write_text(root + _DROP_BODIES.format(**{"top": "", "middle": "", "bottom": "", "drop": "", **parts}))
    code, out, err = run_cli("drop", path, "--plot", tmp_path, check=False)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith(f"superball: {path}:"), err
    assert message in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad-drop.toml"]  # nothing of the figure written
    with pytest.raises(superball.InputError) as e:
        superball.drop(superball.Scene.load(path))
    assert str(e.value) == err[len("superball: "):-1]
