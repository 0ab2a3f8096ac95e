"""map(): the command's numbers (superball map --json) on a grid, exact brackets, the figure, progress and Ctrl-C."""
import _thread
import math
from fractions import Fraction

import numpy as np
import pytest

import superball
from conftest import PAPER, cli_json, run_cli

X, Y = "K.3-4=0:20:21", "alpha.2=-110:0:21"


@pytest.fixture(scope="module")
def paper_map(paper):
    return superball.map(paper, X, Y, progress=False)


def test_the_command_s_json_point_for_point(paper_map):
    j = cli_json("map", PAPER, "--x", X, "--y", Y, "--json")
    m = paper_map
    assert m.shape == (21, 21) and m.cases.shape == (21, 21) and m.ratio.dtype == np.float64
    assert m.superball.dtype == np.bool_ and m.psd.dtype == np.bool_
    assert (m.x.key, m.x.start, m.x.stop, m.x.steps) == (j["x"]["key"], Fraction(j["x"]["from"]), Fraction(j["x"]["to"]), j["x"]["steps"])
    assert (m.y.key, m.y.start, m.y.stop, m.y.steps) == (j["y"]["key"], Fraction(j["y"]["from"]), Fraction(j["y"]["to"]), j["y"]["steps"])
    assert len(j["points"]) == 441
    for p in j["points"]:
        i, k = p["i"], p["j"]
        assert m.x.values[i] == p["x"] and m.y.values[k] == p["y"]
        assert m.psd[k, i] == p["psd"]
        if not p["psd"]:
            assert m.cases[k, i] == "" and math.isnan(m.ratio[k, i]) and not m.superball[k, i] and m.case_codes[k, i] == -1
            continue
        assert m.cases[k, i] == p["case"] and list(m.closed_list[m.case_codes[k, i]]) == p["closed"]
        assert m.superball[k, i] == p["superball"]
        assert m.ratio[k, i] == p["U1_over_a"]  # bit for bit
        assert superball.STATUSES[m.status_codes[k, i]] == p["status"]
    assert len(m.boundary_points) == len(j["boundaries"]) > 0
    for b, c in zip(m.boundary_points, j["boundaries"]):
        assert (b.along, b.i, b.j, b.x, b.y, b.width) == (c["along"], c["i"], c["j"], c["x"], c["y"], c["bracket_width"])
        assert isinstance(b.low, Fraction) and (b.low, b.high) == (Fraction(c["low"]), Fraction(c["high"])) and b.low < b.high
        # the command's JSON says "psd" only where M is not PSD; Python says it always
        assert [{k: v for k, v in side.items() if k != "psd" or not v} for side in (b.below, b.above)] == [c["below"], c["above"]]
    assert len(m.curves) == len(j["curves"]) > 0
    for a, c in zip(m.curves, j["curves"]):
        assert (a.kind, list(a.cases), a.closed, a.boundaries) == (c["kind"], c.get("cases", []), c["closed"], c["boundaries"])
        np.testing.assert_array_equal(a.points, np.array(c["points"], dtype=float).reshape(-1, 2))
        assert a.brackets == [(m.boundary_points[k].low, m.boundary_points[k].high) for k in a.boundaries]
    assert str(m) == run_cli("map", PAPER, "--x", X, "--y", Y)[1]  # the command's summary


def test_every_point_is_the_solve_of_its_scene(paper, paper_map):
    """A few points against solve() of the scene with both values set: the case, U1+/a and the verdict."""
    m = paper_map
    xs, ys = m.x.fractions(), m.y.fractions()
    for i, k in ((0, 20), (7, 10), (14, 3), (20, 20)):
        r = superball.solve(paper.with_value("K.3-4", xs[i]).with_value("alpha.2", ys[k]), "double")
        assert m.psd[k, i] and m.cases[k, i] == r.case and m.superball[k, i] == r.superball
        assert m.ratio[k, i] == pytest.approx(r.velocities_after[0] / abs(r.velocities_before[0]), rel=1e-14)


def test_boundaries_separate_what_they_say(paper):
    """Each bracket's ends, solved exactly, are in the regions the boundary point names."""
    m = superball.map(paper, "K.3-4=0:20:5", "alpha.2=-90:0:5", progress=False)
    assert m.boundary_points
    for b in m.boundary_points[:6]:
        other = m.y.fractions()[b.j] if b.along_x else m.x.fractions()[b.i]
        keys = (m.x.key, m.y.key) if b.along_x else (m.y.key, m.x.key)
        for end, side in ((b.low, b.below), (b.high, b.above)):
            r = superball.solve(paper.with_value(keys[0], end).with_value(keys[1], other), "exact")
            assert side["psd"] and r.case == side["case"] and r.superball == side["superball"]


def test_tuple_axes_threads_and_precision(paper, paper_map):
    a = superball.map(paper, ("K.3-4", 0, 20, 21), ("alpha.2", -110, 0, 21), threads=1, progress=False)
    np.testing.assert_array_equal(a.ratio, paper_map.ratio)
    assert [b.low for b in a.boundary_points] == [b.low for b in paper_map.boundary_points]
    e = superball.map(paper, "K.3-4=0:20:3", "alpha.2=-90:0:3", precision="exact", progress=False)
    assert e.precision == "exact" and e.psd.all()


def test_reprs_are_short(paper_map):
    r = repr(paper_map)
    assert "\n" not in r and len(r) < 300 and "21 x 21" in r and "superball" in r
    h = paper_map._repr_html_()
    assert "<table>" in h and "case" in h and len(h) < 5000


def test_progress_is_told_of_each_task(paper):
    seen = []
    superball.map(paper, X, Y, progress=lambda phase, done, total: seen.append((phase, done, total)))
    phases = [p for p, _, _ in seen]
    assert phases[0] == "points" and phases[-1] == "boundaries"
    for phase in ("points", "boundaries"):
        told = [(d, t) for p, d, t in seen if p == phase]
        assert [d for d, _ in told] == list(range(told[0][1] + 1)) and told[-1][0] == told[-1][1] > 0


def test_ctrl_c_stops_a_map(paper):
    """SIGINT (as Ctrl-C) during the computation: KeyboardInterrupt, and the module still works after it."""
    def interrupt(phase, done, total):
        if done == 1:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        superball.map(paper, X, Y, progress=interrupt)
    def stop(phase, done, total):
        if phase == "boundaries":
            raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        superball.map(paper, X, Y, progress=stop)
    assert superball.map(paper, "K.3-4=0:20:3", "alpha.2=-90:0:3", progress=False).psd.all()


@pytest.mark.parametrize("x, y, message", [
    ("K.3-4=0:20", "alpha.2=-110:0:21", "x K.3-4=0:20: the range needs FROM:TO:STEPS"),
    ("K.3-4=0:20:1", "alpha.2=-110:0:21", "x K.3-4=0:20:1: STEPS must be a whole number from 2 to 10000"),
    ("K.9-9=0:20:3", "alpha.2=-110:0:21", None),
    ("K.3-4=0:20:3", "K.03-4=0:5:3", None),
])
def test_bad_axes_say_what_the_library_says(paper, x, y, message):
    with pytest.raises(superball.InputError) as e:
        superball.map(paper, x, y, progress=False)
    text = str(e.value)
    assert "\n" not in text
    if message:
        assert text.startswith(message)
    code, _, err = run_cli("map", PAPER, "--x", x, "--y", y, check=False)
    assert code == 2
    # the command names its options --x/--y, Python its arguments x/y
    def same(t):
        return t.replace("--x ", "x ").replace("--y ", "y ")

    assert same(err.removeprefix("superball: ").rstrip("\n")) == same(text)


def test_wrong_types_are_input_errors(paper):
    for call in (lambda: superball.map("paper.toml", X, Y), lambda: superball.map(paper, 3, Y), lambda: superball.map(paper, X, Y, threads="2"),
                 lambda: superball.map(paper, X, Y, progress=3), lambda: superball.map(paper, X, Y, overlay="yes"),
                 lambda: superball.map(paper, X, Y, overlay=1)):
        with pytest.raises(superball.InputError):
            call()


def test_plot(paper_map):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = paper_map.plot()
    assert ax.get_xlabel() == "K.3-4" and ax.get_ylabel() == "alpha.2"
    assert len(ax.images) == 1 and len(ax.lines) == len(paper_map.curves)
    plt.close(ax.figure)


def test_the_overlay_is_the_command_s(paper):
    """map(overlay=True): the derived conditions' zeros and their matches, as `superball map --overlay --json`."""
    m = superball.map(paper, X, Y, progress=False, overlay=True)
    j = cli_json("map", PAPER, "--x", X, "--y", Y, "--overlay", "--json")["overlay"]
    o = m.overlay
    assert o is not None and superball.map(paper, X, Y, progress=False).overlay is None
    assert (list(o.cases), o.conditions, o.agrees) == (j["cases"], j["conditions"], j["agrees"])
    assert (o.largest_distance_in_steps, o.largest_allowed_in_steps) == (j["largest_distance_in_steps"], j["largest_allowed_in_steps"])
    assert len(o.zeros) == len(j["zeros"]) > 0 and len(o.matches) == len(j["matches"]) > 0
    for z, c in zip(o.zeros, j["zeros"]):
        assert isinstance(z.low, Fraction) and z.low < z.high and (z.low, z.high) == (Fraction(c["low"]), Fraction(c["high"]))
        assert (z.case, z.condition, z.along, z.x, z.y, z.holds_low, z.next_to_case) == (
            c["case"], c["condition"], c["along"], c["x"], c["y"], c["holds_low"], c["next_to_case"])
    for a, c in zip(o.matches, j["matches"]):
        assert (a.boundary, a.found, a.zero, a.distance, a.allowed, a.agrees) == (
            c["boundary"], c["found"], c.get("zero"), c.get("distance"), c.get("allowed"), c["agrees"])
    # Every boundary point between solved points has a derived zero on its segment within the allowed distance.
    assert o.agrees and all(a.agrees for a in o.matches)
    for a in o.matches:
        b, z = m.boundary_points[a.boundary], o.zeros[a.zero]
        assert z.along == b.along and abs((z.low + z.high) / 2 - (b.low + b.high) / 2) <= (z.high - z.low) + (b.high - b.low)
    text = run_cli("map", PAPER, "--x", X, "--y", Y, "--overlay")[1]
    assert str(m) == text and str(o) in text and "overlay" in repr(m) and "agree" in repr(o)
    assert "<pre>" in m._repr_html_()
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = m.plot()  # the curves, then the derived zeros next to their case as dots
    assert len(ax.lines) == len(m.curves) + 1
    assert len(ax.lines[-1].get_xdata()) == sum(z.next_to_case for z in o.zeros) > 0
    plt.close(ax.figure)
