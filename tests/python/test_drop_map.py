"""superball.sweep() and superball.map() of a drop scene (a [drop] table):
the same numbers, labels and ends as ``superball sweep`` and ``superball map``
of that scene, bit for bit, and each value the drop of its own scene."""
import csv
import io

import numpy as np
import pytest

import superball

from conftest import SCENES, run_cli

TWO_BALLS = SCENES / "drop-two-balls.toml"
THREE_BALLS = SCENES / "drop-three-balls.toml"


def out(*args):
    """The command's standard output, after a run that exits 0."""
    code, text, err = run_cli(*args)
    assert code == 0, err
    return text


def rows(text):
    return list(csv.reader(io.StringIO(text)))


@pytest.mark.parametrize("precision", ["double", "long-double"])
def test_a_drop_sweep_gives_the_command_s_numbers_and_each_value_s_drop(precision):
    scene = superball.Scene.load(THREE_BALLS)
    r = superball.sweep(scene, "gap.1", superball.linspace(0, "0.004", 5), precision=precision, threads=2)
    assert isinstance(r, superball.DropSweepResult) and len(r) == 5 and r.ok
    table = rows(out("sweep", THREE_BALLS, "--vary", "gap.1=0:0.004:5", "--csv", "--precision", precision))
    assert table[0] == ["gap.1", "top_apex_ratio", "events", "end", "label"]
    for k, row in enumerate(table[1:]):
        assert float(row[1]) == r.ratio[k]
        assert int(row[2]) == r.events[k] and row[3] == r.end[k] and row[4] == r.labels[k]
        # The value written into the scene, dropped on its own.
        d = superball.drop(scene.with_value("gap.1", row[0]), precision)
        assert d.top_apex_ratio == r.ratio[k]
    assert r.labels[0] != r.labels[1]


def test_a_drop_map_gives_the_command_s_grid():
    scene = superball.Scene.load(TWO_BALLS)
    m = superball.map(scene, "gap.1=0:0.01:3", ("mass.1", "1/1000", "1/2", 3), threads=2)
    assert isinstance(m, superball.DropMapResult) and m.shape == (3, 3)
    table = rows(out("map", TWO_BALLS, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1/1000:1/2:3", "--csv"))
    assert table[0] == ["gap.1", "mass.1", "top_apex_ratio", "events", "end", "label"]
    for k, row in enumerate(table[1:]):
        j, i = divmod(k, 3)
        assert float(row[2]) == m.ratio[j, i] and int(row[3]) == m.events[j, i]
        assert row[4] == m.end[j, i] and row[5] == m.labels[j, i]
    assert str(m) == out("map", TWO_BALLS, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1/1000:1/2:3")
    assert m.labels[0, 0] == "2-3:{1-2}" and np.all(m.labels[:, 0] != m.labels[:, 1])
    assert "none bisected" in m.boundaries


def test_a_drop_scene_s_keys_hold_its_gaps_and_each_can_be_set():
    scene = superball.Scene.load(THREE_BALLS)
    assert scene.keys[-2:] == ["gap.1", "gap.2"]
    for key in scene.keys:
        assert scene.with_value(key, "1/2").keys == scene.keys
    assert "gap.1" not in superball.Scene.load(SCENES / "paper-4.4-alpha2.toml").keys


@pytest.mark.parametrize("call, message", [
    (lambda s: superball.sweep(s, "gap.1", [0, 1], checkpoint="unused"), "no checkpoint"),
    (lambda s: superball.map(s, "gap.1=0:1:3", "mass.1=1:2:3", overlay=True), "overlay: "),
    (lambda s: superball.map(s, "gap.1=0:1:3", "mass.1=1:2:3", precision="quad"), "quad"),
    (lambda s: superball.sweep(s, "gap.1", [-1, 0]), "gap.1 = -1"),
    (lambda s: superball.sweep(s, "gap.2", [0, 1]), "body 2's is drop_height"),
    (lambda s: superball.switch_points(s, "gap.1", [0, 1]), "has a [drop] table"),
])
def test_what_a_drop_map_or_sweep_cannot_do_is_refused(call, message, tmp_path):
    with pytest.raises(superball.InputError) as e:
        call(superball.Scene.load(TWO_BALLS))
    assert message in str(e.value)
    assert not (tmp_path / "unused").exists()
