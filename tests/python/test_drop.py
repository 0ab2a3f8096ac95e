"""drop(): the command's numbers (superball drop --json) and text, the physics of a drop, scenes with gaps from
keywords, and bad input as the command says it."""
import json
import math

import numpy as np
import pytest

import superball
from conftest import PAPER, SCENES, cli_json, run_cli

TWO = SCENES / "drop-two-balls.toml"
PAPER_STACK = SCENES / "drop-paper-4.4.toml"


@pytest.mark.parametrize("path", [TWO, PAPER_STACK])
def test_the_command_s_json_and_text(path):
    r = superball.drop(superball.Scene.load(path))
    j = cli_json("drop", path, "--json")
    assert r.to_dict() == j
    assert str(r) == run_cli("drop", path)[1]
    assert len(r.events) == len(j["events"]) > 0 and r.velocities_after.shape == (len(r.events), len(j["masses"]))
    for e, c in zip(r.events, j["events"]):
        assert e.time == c["time"] and list(e.velocities_after) == c["velocities_after"] and e.case == c["case"]
    np.testing.assert_array_equal(r.times, [c["time"] for c in j["events"]])
    assert (r.end, r.top_apex_ratio) == (j["end"], j["top_apex_ratio"])
    assert "DropResult" in repr(r) and len(repr(r)) < 300 and "<pre>" in r._repr_html_()


def test_physics_of_the_two_ball_drop():
    r = superball.drop(superball.Scene.load(TWO))
    assert np.all(np.diff(r.times) >= 0)
    for e in r.events:
        assert e.kinetic_energy_after <= e.kinetic_energy_before * (1 + 1e-12)
        if e.bodies[1] < len(r.masses):  # the fixed floor not in the cluster: momentum conserved
            assert e.momentum_after == pytest.approx(e.momentum_before, rel=1e-9)
    assert 8.9 < r.top_apex_ratio < 9.0  # the light ball over the heavy one: nearly 9 h
    assert r.apexes[0].height == pytest.approx(r.top_apex_ratio * r.release_heights[0], rel=1e-12)


def test_a_ball_on_the_floor_from_keywords_rests_at_the_sum_of_its_bounces():
    s = superball.Scene(bodies=[1, "inf"], drop_height=1, K={"1-2": 9}, drop={"until": 10})
    assert s.drop and not superball.Scene(bodies=[1, "inf"], drop_height=1, K={"1-2": 9}).drop
    r = superball.drop(s)
    e, h, g = 0.8, 1.0, 9.81  # e = (K - m)/(K + m)
    assert [x.body for x in r.rest] == [1] and r.rest[0].accumulation and r.rest[0].ratio == pytest.approx(e, rel=1e-12)
    assert r.rest[0].time == pytest.approx(math.sqrt(2 * h / g) * (1 + e) / (1 - e), rel=1e-9)
    for k, v in enumerate(r.velocities_after[:, 0]):
        assert v * v / (2 * g) == pytest.approx(e ** (2 * (k + 1)) * h, rel=1e-9)
    # The same scene with gaps from keywords is the file's.
    two = superball.Scene(bodies=[{"mass": 0.001, "gap": 0.001}, 1, "inf"], drop_height=1, K={"1-2": 1e6, "2-3": 1e6}, drop=True)
    assert superball.drop(two).to_dict()["events"] == superball.drop(superball.Scene.load(TWO)).to_dict()["events"]


@pytest.mark.parametrize("precision, code, end", [("digits:20", 0, "apex"), ("exact", 1, "inexact")])
def test_digits_and_exact_drops_are_the_command_s(precision, code, end):
    # digits:20 runs the whole drop; exact goes as far as every event's time is rational (exit 1 there).
    r = superball.drop(superball.Scene.load(TWO), precision)
    got, out, err = run_cli("drop", TWO, "--precision", precision, "--json", check=False)
    assert (got, err) == (code, "")
    assert r.to_dict() == json.loads(out)
    assert (r.precision, r.end) == (precision, end)
    d = superball.drop(superball.Scene.load(TWO))
    for e, f in zip(r.events, d.events):  # the events double has, to the rounding of its stiff re-solves (K/m = 1e9)
        np.testing.assert_allclose(e.velocities_after, f.velocities_after, rtol=1e-9)


def test_bad_scenes_and_types():
    paper = superball.Scene.load(PAPER)
    with pytest.raises(superball.InputError, match=r"has no \[drop\] table"):
        superball.drop(paper)
    for bad, message in (({"max_events": 0}, "drop.max_events: must be a whole number"), ({"until": -1}, "drop.until"),
                         ({"when": 3}, "unknown key")):
        with pytest.raises(superball.InputError, match=message):
            superball.drop(superball.Scene(bodies=[1, "inf"], drop_height=1, K={"1-2": 9}, drop=bad))
    assert superball.drop(superball.Scene(bodies=[1, "inf"], drop_height=1, K={"1-2": 9}, drop={"distant": True})).to_dict()["distant"]
    with pytest.raises(superball.InputError, match="gap"):
        superball.Scene(bodies=[{"mass": 1, "gap": -1}, 1, "inf"], drop_height=1, K={"1-2": 9, "2-3": 9}, drop=True)
    for call in (lambda: superball.drop(str(TWO)), lambda: superball.drop(superball.Scene.load(TWO), 2)):
        with pytest.raises(superball.InputError):
            call()


def _figure_blocks(path):
    """The blocks of a `--plot` data file: (title, x array, y array) each."""
    blocks = []
    for line in path.read_text().splitlines():
        if line.startswith("# "):
            blocks.append((line[2:], [], []))
        elif line.strip():
            x, y = line.split()
            blocks[-1][1].append(float(x))
            blocks[-1][2].append(float(y))
    return blocks


@pytest.mark.parametrize("path", [SCENES / "drop-one-ball.toml", PAPER_STACK])
def test_the_trajectories_are_the_command_s_figure(path, tmp_path):
    """trajectories() and plot() draw from the library's sampling: the points of `superball drop --plot`."""
    r = superball.drop(superball.Scene.load(path))
    code, _, err = run_cli("drop", path, "--plot", tmp_path, check=False)
    if code == 3 and "gnuplot" in err:
        pytest.skip("no gnuplot")  # the data file is written before gnuplot runs
    blocks = _figure_blocks(tmp_path / "trajectories.dat")
    curves = r.trajectories()
    assert len(curves) == len(r.masses) and [b[0] for b in blocks[:len(curves)]][-1] == "obstacle"
    for (t, z), (_, x, y) in zip(curves, blocks):
        np.testing.assert_allclose(t, x, rtol=1e-15)  # the file has 17 digits
        np.testing.assert_allclose(z, y, rtol=1e-15, atol=1e-300)
        assert t[0] == 0 and t[-1] == r.end_time and np.all(np.diff(t) >= 0)
    for (t, z), h in zip(curves, r.release_heights):
        assert z[0] == h
    # Between events each free body flies a parabola of g: its second differences on equal steps are -g·dt².
    t, z = curves[0]
    first = t <= r.events[0].time
    tt, zz = t[first], z[first]
    np.testing.assert_allclose(zz, r.release_heights[0] + r.release_velocities[0] * tt - r.g * tt ** 2 / 2, atol=1e-12)


def test_plot_draws_every_body_and_marks_the_collisions_and_the_rests():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = superball.drop(superball.Scene(bodies=[1, "inf"], drop_height=1, K={"1-2": 9}, drop={"until": 10}))
    ax = r.plot()
    labels = [line.get_label() for line in ax.lines]
    assert labels == ["body 1", "obstacle", "collisions", "at rest"]
    assert ax.get_xlabel() == "time since the release (s)"
    collisions = ax.lines[2].get_xdata()
    np.testing.assert_array_equal(collisions, r.times)
    rest = ax.lines[3]
    assert list(rest.get_xdata()) == [r.rest[0].time] and list(rest.get_ydata()) == [0]
    # After the rest the ball lies on the floor, to the end of the run.
    t, z = r.trajectories()[0]
    assert np.all(z[t >= r.rest[0].time] == 0) and t[-1] == 10 and len(t) < 2000
    plt.close(ax.figure)
