"""gaps_to_zero(): the command's numbers (superball drop --gaps-to-zero --json) and text, the limit of the gapped
drops against the simultaneous collision, and bad input refused with the command's line."""
import numpy as np
import pytest

import superball
from conftest import SCENES, cli_json, run_cli

TWO = SCENES / "drop-two-balls.toml"
PAPER_STACK = SCENES / "drop-paper-4.4.toml"


@pytest.mark.parametrize("path,decades", [(TWO, 8), (PAPER_STACK, 3)])
def test_the_command_s_json_and_text(path, decades):
    g = superball.gaps_to_zero(superball.Scene.load(path), decades=decades)
    j = cli_json("drop", path, "--gaps-to-zero", "--decades", str(decades), "--json")
    assert g.to_dict() == j
    assert str(g) == run_cli("drop", path, "--gaps-to-zero", "--decades", str(decades))[1]
    assert g.velocities.shape == (decades + 1, len(g.simultaneous.velocities)) and g.scales[0] == 1 and g.scales[-1] == pytest.approx(10.0 ** -decades)
    assert g.simultaneous.scale == 0 and g.simultaneous.deviation == 0
    assert "GapLimit" in repr(g) and "<pre>" in g._repr_html_()


def test_two_balls_tend_to_three_times_the_landing_speed_not_to_the_simultaneous_collision():
    g = superball.gaps_to_zero(superball.Scene.load(TWO))
    a = g.landing_speed
    assert a == pytest.approx(np.sqrt(2 * 9.81 * 1), rel=1e-12)
    # m1/m2 = 1e-3: the light ball leaves at (3 - 4 m1/m2 + ...) a after the two binary collisions
    assert g.steps[-1].collisions == ("2-3 {}", "1-2 {}")
    assert g.velocities[-1, 0] / a == pytest.approx(2.996, abs=1e-3)
    # Fremond's collision of the touching stack keeps them together (case {1-2}), both at about a
    assert g.simultaneous.collisions == ("1-3 {1-2}",)
    assert g.simultaneous.velocities[0] == pytest.approx(g.simultaneous.velocities[1], rel=1e-9)
    assert not g.converges and g.deviations[-1] == pytest.approx(2, abs=1e-2)


@pytest.mark.parametrize("decades", [0, -1, 13])
def test_decades_out_of_range_are_refused_as_the_command_does(decades):
    code, _, err = run_cli("drop", TWO, "--gaps-to-zero", "--decades", str(decades), check=False)
    assert code == 2
    with pytest.raises(superball.InputError) as e:
        superball.gaps_to_zero(superball.Scene.load(TWO), decades=decades)
    assert err.strip() == "superball: " + str(e.value) == f"superball: decades must be a whole number from 1 to 12, got {decades}"


def test_a_scene_without_gaps_is_refused_as_the_command_does():
    path = SCENES / "drop-one-ball.toml"
    code, _, err = run_cli("drop", path, "--gaps-to-zero", check=False)
    assert code == 2
    with pytest.raises(superball.InputError) as e:
        superball.gaps_to_zero(superball.Scene.load(path))
    assert err.strip() == "superball: " + str(e.value)
    assert "no body has a gap > 0" in str(e.value)
    with pytest.raises(superball.InputError, match="decades: expected an int"):
        superball.gaps_to_zero(superball.Scene.load(TWO), decades=2.5)
