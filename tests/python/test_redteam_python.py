"""The red team's pass on the Python surfaces: map(), scenes from dicts and
keywords, Condition.evaluate()/lambdify(), derive_all(jobs=, progress=) and
the reprs, fed what a hostile user feeds them (extremes first, the same
thing spelled two ways, wrong types, huge values, control bytes).

Each case asserts the honest behaviour: an InputError of one line naming the
field, a clean refusal by a rule of the library, or the right answer.  The
cases marked "was:" failed before their fix (tests/redteam/README.md, class
Python).  The whole file runs in a few seconds.
"""
import decimal
import subprocess
import sys
import time
from fractions import Fraction

import numpy as np
import pytest

import superball

from conftest import PAPER, run_cli

X, Y = "K.3-4=0:20:3", "alpha.2=-110:0:3"
STEPS = "STEPS must be a whole number from 2 to 10000"
THREADS = "threads must be a whole number from 0 (all cores) to 1024, got "


def refused(call, *parts):
    """call() raises one InputError line holding every one of parts; its text."""
    with pytest.raises(superball.InputError) as e:
        call()
    text = str(e.value)
    assert "\n" not in text and "\0" not in text, text
    for p in parts:
        assert p in text, text
    return text


def scene(**kw):
    return superball.Scene(**{"bodies": [1, 2], "fall_speed": 1, **kw})


# ---------------------------------------------------------------------------
# map(): axes, precision, threads, progress, plot


@pytest.mark.parametrize("steps", ["0", "1", "-1", "1000000000", "1e3", "3.0", "99999999999999999999999"])
def test_map_steps_out_of_range_are_refused(paper, steps):
    refused(lambda: superball.map(paper, f"K.3-4=0:20:{steps}", Y, progress=False), f"x K.3-4=0:20:{steps}: {STEPS}")


def test_map_two_steps_is_the_smallest_grid(paper):
    r = superball.map(paper, "K.3-4=0:20:2", Y, progress=False)
    assert r.shape == (3, 2) and list(r.x.values) == [0.0, 20.0]


def test_map_of_a_million_by_a_million_is_refused_at_once(paper):
    t = time.monotonic()
    refused(lambda: superball.map(paper, "K.3-4=0:20:1000000", "alpha.2=-110:0:1000000", progress=False), STEPS)
    assert time.monotonic() - t < 1


def test_map_larger_than_memory_is_refused_by_the_library_estimate():
    # In a process whose address space is limited to 4 GB (ulimit -v): a 10000 x 10000 map's arrays
    # (about 20 GB by the estimate, 13 GB measured) are refused at once, before any point is solved.
    code = ("import resource, sys, time\n"
            "resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))\n"
            "import superball\n"
            f"paper = superball.Scene.load({str(PAPER)!r})\n"
            "t = time.monotonic()\n"
            "try:\n"
            "    superball.map(paper, 'K.3-4=0:20:10000', 'alpha.2=-110:0:10000', progress=False)\n"
            "except superball.InputError as e:\n"
            "    print(e, time.monotonic() - t)\n"
            "    sys.exit(2)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2, done.stderr
    text, seconds = done.stdout.rsplit(" ", 1)
    assert "\n" not in text.strip() and "a 10000 x 10000 grid holds about" in text and "(ulimit -v)" in text and "use a coarser grid" in text, text
    assert float(seconds) < 1


@pytest.mark.parametrize("x, parts", [
    ("K.3-4=5:5:3", ["FROM and TO are equal"]),
    ("K.3-4=nan:1:3", ["'nan' is not a number"]),
    ("K.3-4=0:inf:3", ["'inf' is not a number"]),
    ("K.3-4=0:1e100000:3", ["exponent out of range"]),
    ("K.3-4=0:1e1000000000:3", ["exponent out of range"]),
    ("", ["x : no '='"]),
    ("K.3-4=0:20", ["the range needs FROM:TO:STEPS"]),
    ("mass.9=1:2:3", ["'mass.9': body must be 1..4"]),
    ("K.4-3=0:20:3", ["'4-3' is not a pair i-j"]),
    ("alpha.2=0:1:3", ["--x alpha.2 and --y alpha.2 name the same parameter (alpha.2)"]),
    ("alpha.02=0:1:3", ["--x alpha.02 and --y alpha.2 name the same parameter (alpha.2)"]),  # two spellings of one key
    # was: the message stopped at the NUL ("x K.3-4=0:20:")
    ("K.3-4=0:20:\x003", ["x K.3-4=0:20:\\03: " + STEPS, "e.g. K.3-4=0:20:401)"]),
    ("K.3\x00-4=0:20:3", ["'K.3\\0-4': '3\\0-4' is not a pair i-j"]),
])
def test_map_bad_axes_are_one_line_naming_the_axis(paper, x, parts):
    refused(lambda: superball.map(paper, x, Y, progress=False), *parts)


def test_map_extreme_but_valid_axes_are_solved(paper):
    r = superball.map(paper, "K.3-4=20:0:3", Y, progress=False)  # reversed
    assert list(r.x.values) == [20.0, 10.0, 0.0] and r.x.start == 20
    r = superball.map(paper, "K.3-4=1e400:1e401:3", Y, progress=False)
    assert r.x.start == 10**400 and r.psd.any()


def test_map_axis_end_longer_than_python_writes_as_text(paper):
    # was: ValueError (Python refuses decimal text of more than 4300 digits) when the result crossed into Python
    r = superball.map(paper, "K.3-4=0:" + "9" * 5000 + ":3", Y, progress=False)
    assert r.x.stop == 10**5000 - 1 and r.x.fractions()[1] == Fraction(10**5000 - 1, 2)


@pytest.mark.parametrize("precision, part", [
    ("digits:0", "'digits:0': N in digits:N must be a whole number from 10 to 10000"),
    ("digits:-1", "'digits:-1': N in digits:N must be"),
    ("digits:1000000000", "'digits:1000000000': N in digits:N must be"),
    ("digits:", "'digits:': N in digits:N must be"),
    ("auto", "unknown precision 'auto'"),
    (" double", "unknown precision ' double'"),
    ("dou\x00ble", "unknown precision 'dou\\0ble' (expected double, long-double, digits:N or exact)"),  # was: cut at the NUL
])
def test_map_bad_precisions(paper, precision, part):
    refused(lambda: superball.map(paper, X, Y, precision=precision, progress=False), part)


@pytest.mark.parametrize("threads", [-1, 1025, 5000])
def test_map_threads_out_of_range_say_the_library_rule(paper, threads):
    # was: -1 gave Python's own "map: threads must be >= 0 …"
    assert refused(lambda: superball.map(paper, X, Y, threads=threads, progress=False)) == THREADS + str(threads)


@pytest.mark.parametrize("threads", [2**31, 2**70])
def test_map_threads_past_a_c_int_are_refused_before_they_cross(paper, threads):
    # was: 2**31 a TypeError of pybind11
    assert refused(lambda: superball.map(paper, X, Y, threads=threads, progress=False)) == \
        f"threads: {threads} is out of range (from -2147483648 to 2147483647)"


def test_map_threads_of_other_types(paper):
    assert superball.map(paper, X, Y, threads=np.int64(1), progress=False).shape == (3, 3)  # was: refused
    for threads in ("2", 1.5, True):
        refused(lambda: superball.map(paper, X, Y, threads=threads, progress=False), "threads: expected an int")


def test_map_gives_the_same_answer_on_every_thread_count(paper):
    a = superball.map(paper, X, Y, threads=1, progress=False)
    b = superball.map(paper, X, Y, threads=None, progress=False)
    assert np.array_equal(a.ratio, b.ratio, equal_nan=True) and np.array_equal(a.case_codes, b.case_codes)


@pytest.mark.parametrize("exception", [RuntimeError("boom"), KeyboardInterrupt(), SystemExit(3)])
def test_map_progress_that_raises_stops_the_call_with_its_exception(paper, exception):
    def progress(phase, done, total):
        raise exception

    with pytest.raises(type(exception)):
        superball.map(paper, X, Y, progress=progress)
    assert superball.map(paper, X, Y, progress=False).shape == (3, 3)  # nothing left behind


def test_map_plot_without_matplotlib_says_what_it_needs(paper, monkeypatch):
    r = superball.map(paper, X, Y, progress=False)
    for name in ("matplotlib", "matplotlib.colors", "matplotlib.patches", "matplotlib.pyplot"):
        monkeypatch.setitem(sys.modules, name, None)
    with pytest.raises(ImportError, match=r"MapResult.plot\(\) needs matplotlib"):  # was: the bare ImportError of the import
        r.plot()


def test_map_plot_of_a_grid_without_boundary(paper):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    r = superball.map(paper, "K.3-4=0:1:2", "alpha.2=-1:0:2", progress=False)
    assert not r.boundary_points and not r.curves
    assert r.plot().get_xlabel() == "K.3-4"


def test_map_where_m_is_nowhere_psd_is_refused(paper):
    refused(lambda: superball.map(paper, "K.3-4=0:1:2", "alpha.2=-1000:-900:2", progress=False), "not positive semi-definite at any point")


# ---------------------------------------------------------------------------
# Scenes from dicts and keywords


@pytest.mark.parametrize("kw, parts", [
    ({"bodies": {"mass": 1}}, ["Scene: bodies: expected a list of masses"]),
    ({"bodies": "12"}, ["Scene: bodies: expected a list of masses"]),
    ({"bodies": {1, 2}}, ["Scene: bodies: expected a list of masses"]),  # was: accepted, in the set's order
    ({"bodies": []}, ["body: must be an array of tables"]),
    ({"bodies": [1]}, ["body: a scene needs at least 2 bodies (got 1)"]),
    ({"bodies": [[1, 2], 3]}, ["body[1].mass: must be a number"]),
    ({"bodies": [None, 1]}, ["body[1].mass: expected a number, a string, a list or a dict, got None"]),
    ({"bodies": [True, 1]}, ["body[1].mass: must be a number or a fraction string", "(got a boolean)"]),
    ({"bodies": [b"1", 1]}, ["body[1].mass: expected a number", "got b'1' (bytes)"]),
    ({"bodies": [np.bool_(True), 1]}, ["body[1].mass: expected a number", "(numpy.bool_)"]),
    ({"bodies": [1j, 1]}, ["<scene>: body[1].mass: expected a number", "got 1j (complex)"]),  # was: "number: …", no field
    ({"bodies": [decimal.Decimal("nan"), 1]}, ["<scene>: body[1].mass:", "Decimal('NaN')"]),  # was: no field
    ({"bodies": [10**5000, 1]}, ["<scene>: body[1].mass: a number of more digits than Python writes as text"]),  # was: ValueError
    ({"bodies": [Fraction(10**5000, 3), 1]}, ["<scene>: body[1].mass: a number of more digits"]),  # was: ValueError
    ({"bodies": [float("nan"), 1]}, ["body[1].mass: 'nan' is not a number"]),
    ({"bodies": [float("-inf"), 1]}, ["body[1].mass: '-inf' is not a number"]),
    ({"bodies": [float("inf"), 1]}, ["body[1].mass: only the bottom body may have infinite mass"]),
    ({"bodies": ["1e999999999", 1]}, ["body[1].mass: '1e999999999' has an exponent out of range"]),
    ({"bodies": ["1\x002", 1]}, ["body[1].mass: '1\\02' is not a number (unexpected '\\0')"]),  # was: "body[1].mass: '1"
    ({"bodies": ["1\x1b[31m", 1]}, ["'1\\e[31m' is not a number"]),
    ({"bodies": [{"mass": 1, "colour": 2}, 1]}, ["body[1].colour: unknown key (expected one of: gap, mass, velocity)"]),
    ({"bodies": [{1: 1}, 1]}, ["body[1].1: unknown key"]),
    ({"K": [("1-2", 7)]}, ["dissipation.K: must be a table"]),
    ({"K": {"2-1": 7}}, ["dissipation.K.2-1: '2-1' needs 1 <= i < j"]),
    ({"K": {"1\u20132": 7}}, ["dissipation.K.1\u20132: '1\u20132' is not of the form i-j"]),
    ({"K": {"1-2": 7, "01-2": 8}}, ["the entry of M for (1-2, 1-2) is given twice"]),
    ({"K": {"1-2": None}}, ["dissipation.K.1-2: expected a number"]),
    ({"coupling": {"pairs": ["1-2", "1-3"], "value": 1}}, ["dissipation.coupling: must be an array of tables"]),
    ({"fall_speed": True}, ["fall_speed: must be a number", "(got a boolean)"]),
    ({"drop_height": 1}, ["fall_speed: give drop_height or fall_speed, not both"]),
    ({"flight": "yes"}, ["flight: must be a table"]),
    ({"flight": {"duration": -1}}, ["flight.duration: must be > 0 seconds (got -1)"]),
])
def test_bad_scene_keywords_name_the_field(kw, parts):
    refused(lambda: scene(**kw), *parts)


def test_two_spellings_of_one_alpha_are_given_twice():
    # was: {2: -1, "2": -5} kept -5 without a word
    refused(lambda: superball.Scene(bodies=[1, 2, 3, 4], fall_speed=1, alpha={2: -1, "2": -5}), "dissipation.alpha.2: given twice")


@pytest.mark.parametrize("bodies", [lambda: [1] * 1_000_000, lambda: (1 for _ in range(1_000_000))])
def test_a_million_bodies_are_refused_before_they_are_read(bodies):
    # was: 43 s (each body converted twice) before the count was checked
    b = bodies()
    t = time.monotonic()
    refused(lambda: superball.Scene(bodies=b, fall_speed=1), "<scene>: body: at most 100000 bodies (got 1000000)")
    assert time.monotonic() - t < 2


def test_a_list_longer_than_any_scene_array_is_refused_by_its_length():
    c = [("1-2", "1-3", 1)] * 200_000
    refused(lambda: superball.Scene.from_dict({"bodies": [1, 2, 3], "fall_speed": 1, "coupling": c}),
            "<dict>: dissipation.coupling: at most 100000 items (got 200000)")


def test_deep_nesting_is_refused_naming_the_field():
    deep = 1
    for _ in range(100_000):
        deep = [deep]
    refused(lambda: scene(bodies=[deep, 1]), "body[1].mass[1]", "nest deeper than 16 levels")
    flight = {}
    for _ in range(100_000):
        flight = {"a": flight}
    refused(lambda: scene(flight=flight), "flight.a.a.a", "nest deeper than 16 levels")


@pytest.mark.parametrize("d, part", [
    ([1, 2], "Scene.from_dict: expected a dict, got list"),
    ({"bodies": [1, 2], "fall_speed": 1, "mass": 3}, "Scene.from_dict: unknown key 'mass'"),
    ({"body": [{"mass": 1}, {"mass": 2}], "fall_speed": 1}, "Scene.from_dict: unknown key 'body'"),
    ({"b\u00f6dies": [1, 2]}, "Scene.from_dict: unknown key 'b\u00f6dies'"),
])
def test_from_dict_refusals(d, part):
    refused(lambda: superball.Scene.from_dict(d), part)


def test_numpy_and_exact_values_are_read_exactly():
    s = scene(bodies=[np.float64(0.001), np.int64(3)], K={"1-2": Fraction(1, 3)}, fall_speed="1e400")
    assert s.masses == [Fraction(1, 1000), 3] and s.K == {"1-2": Fraction(1, 3)} and s.fall_speed == 10**400
    s = scene(bodies=np.array([1.5, 2.0]))
    assert s.masses == [Fraction(3, 2), 2]


def test_a_title_with_control_bytes_stays_one_line_in_messages():
    refused(lambda: scene(bodies=[-1, 1], title="a\nb\x00c"), "a\\nb\\0c: body[1].mass: must be > 0 (got -1)")


def test_with_value_of_a_fraction_longer_than_python_writes_as_text(paper):
    refused(lambda: paper.with_value("K.3-4", Fraction(10**5000, 3)), "K.3-4: a number of more digits than Python writes as text")


def test_a_nul_in_a_scene_file_is_the_same_line_from_both_fronts(tmp_path):
    # was: both fronts stopped the line at the NUL ("nul.toml:3:8: body[1].mass: '1")
    path = tmp_path / "nul.toml"
    path.write_text('fall_speed = 1\n[[body]]\nmass = "1\\u00002"\n[[body]]\nmass = 1\n')
    message = f"{path}:3:8: body[1].mass: '1\\02' is not a number (unexpected '\\0')"
    assert refused(lambda: superball.Scene.load(path)) == message
    code, out, err = run_cli("solve", path, check=False)
    assert (code, out, err) == (2, "", f"superball: {message}\n")


# ---------------------------------------------------------------------------
# Condition.evaluate() and lambdify(); derive_all(jobs=, progress=)


@pytest.fixture(scope="module")
def condition():
    return superball.derive(case="1", alphas=2, progress=False).condition("U1 > a")  # −α₂ > 2m₁ + K₁₂ + K₁₃


def values(**kw):
    return {"m1": 1, "K12": 1, "K13": 1, "alpha2": 1, **kw}


def test_evaluate_is_exact(condition):
    assert condition.evaluate(values()) == -5
    assert condition.evaluate(values(m1="1/3")) == Fraction(-11, 3)
    assert condition.evaluate(values(m1="0.001", alpha2=Fraction(-10**4000))) == 10**4000 - 2 - Fraction(2, 1000)
    assert condition.evaluate(values(m1=np.float64(0.5))) == -4


@pytest.mark.parametrize("given, parts", [
    ({}, ["evaluate: the condition: no value for ", "alpha2", "m1", "K12", "K13"]),
    (values(zz=1), ["evaluate: 'zz' is not a symbol of this derivation"]),
    (values(m1=True), ["evaluate: m1: expected a number, got True"]),
    (values(m1="abc"), ["evaluate: m1: 'abc' is not a number"]),
    (values(m1=float("nan")), ["evaluate: m1: nan is not a number"]),
    (values(m1=float("inf")), ["evaluate: m1: inf is not a number"]),  # was: OverflowError
    (values(m1="1e999999999"), ["evaluate: m1: '1e999999999' is not a number", "exponent out of range"]),  # was: did not end
    (values(m1=10**5000), ["evaluate: m1: an int of more than"]),  # was: ValueError
    (values(m1=1j), ["evaluate: m1: 1j is not a number"]),
    ([1, 2], ["evaluate: values: expected a dict"]),  # was: AttributeError
    (None, ["evaluate: values: expected a dict"]),
])
def test_evaluate_refusals(condition, given, parts):
    t = time.monotonic()
    refused(lambda: condition.evaluate(given), *parts)
    assert time.monotonic() - t < 1


def test_lambdify_over_arrays_and_at_zero(condition):
    f = condition.lambdify()
    assert f.parameters == ("m1", "K12", "K13", "alpha2")
    assert list(f(np.ones(3), 1.0, 1.0, np.array([1.0, -10.0, -1e300]))) == [-5.0, 6.0, 1e300 - 3]
    assert f(0.0, 0.0, 0.0, 0.0) == 0


@pytest.mark.parametrize("jobs, message", [(-1, "jobs must be a whole number from 0 (all cores) to 1024, got -1"),
                                           (10**6, "jobs must be a whole number from 0 (all cores) to 1024, got 1000000"),
                                           (2**40, "jobs: 1099511627776 is out of range"),
                                           (True, "jobs: expected an int"), (1.5, "jobs: expected an int"), ("2", "jobs: expected an int")])
def test_derive_all_refuses_bad_jobs(jobs, message):
    # was: 2**40 a TypeError of pybind11
    refused(lambda: superball.derive_all(alphas=2, jobs=jobs, progress=False), message)


def test_derive_all_jobs_do_not_change_the_answer():
    assert [d.case for d in superball.derive_all(alphas=2, jobs=1, progress=False)] == \
        [d.case for d in superball.derive_all(alphas=2, jobs=0, progress=False)]


@pytest.mark.parametrize("call", [lambda: superball.verify(case="1", alphas=2, samples=2**31, progress=False),
                                  lambda: superball.verify(case="1", alphas=2, seed=2**70, progress=False),
                                  lambda: superball.explore(case="1", alphas=2, starts=2**31, progress=False),
                                  lambda: superball.derive(case="1", alphas=2, bodies=2**31)])
def test_an_int_too_large_for_the_library_is_an_input_error(call):
    # was: pybind11's TypeError ("Unable to cast Python instance to C++ type")
    refused(call, "is out of range")


@pytest.mark.parametrize("exception", [RuntimeError("boom"), KeyboardInterrupt()])
def test_derive_all_progress_that_raises_stops_the_call_with_its_exception(exception):
    def progress(done, total):
        raise exception

    with pytest.raises(type(exception)):
        superball.derive_all(alphas=2, progress=progress)
    assert len(superball.derive_all(alphas=2, progress=False)) == 8


# ---------------------------------------------------------------------------
# Reprs and HTML of results with a hostile title


def test_html_of_every_result_escapes_the_scene_title():
    hostile = "<script>alert(1)</script>&\"'"
    text = PAPER.read_text().replace('title = "', 'title = "' + hostile.replace('"', '\\"'), 1)
    s = superball.Scene.from_toml(text, origin=hostile)
    assert s.title.startswith(hostile)
    for result in (s, superball.solve(s), superball.map(s, X, Y, progress=False), superball.sweep(s, "K.3-4", [1, 2, 3], progress=False)):
        html = result._repr_html_()
        assert "<script>" not in html and "&lt;script&gt;" in html or type(result).__name__ == "SweepResult", type(result)
        assert "\n" not in repr(result)
