"""Every error path: bad input is a ValueError (superball.InputError) with the command's one line, never a crash."""
import pytest

import superball
from conftest import BAD, PAPER, run_cli


def one_line(e):
    text = str(e.value)
    assert "\n" not in text and text
    return text


@pytest.mark.parametrize("name", ["negative-mass.toml", "M-not-psd-alpha.toml", "contact-opening.toml", "not-toml.toml",
                                  "key-with-control-characters.toml", "invalid-utf8.toml", "nesting-too-deep.toml", "empty.toml"])
def test_bad_scene_files_say_what_the_command_says(name):
    path = BAD / name
    with pytest.raises(ValueError) as e:
        superball.solve(superball.Scene.load(path), "exact")
    assert isinstance(e.value, superball.InputError) and isinstance(e.value, superball.Error)
    code, _, err = run_cli("solve", path, "--precision", "exact", check=False)
    assert code == 2 and err == f"superball: {one_line(e)}\n"


def test_missing_file_and_folder(tmp_path):
    for path in (tmp_path / "none.toml", tmp_path):
        with pytest.raises(ValueError) as e:
            superball.Scene.load(path)
        assert one_line(e) == run_cli("solve", path, check=False)[2].removeprefix("superball: ").rstrip("\n")


def test_keywords_and_dicts():
    # the loader's message, without the place in a TOML text the user never wrote
    for build, message in ((lambda: superball.Scene(bodies=[1, -1], fall_speed=1), "<scene>: body[2].mass: must be > 0 (got -1)"),
                           (lambda: superball.Scene.from_dict({"bodies": [1, 2], "fall_speed": "x"}), "<dict>: fall_speed: 'x' is not a number"),
                           (lambda: superball.Scene(bodies=[1, 2], fall_speed=1, K={"1-3": 1}, title="Two: 1-3"),
                            "Two: 1-3: dissipation.K.1-3: pair 1-3 is outside bodies 1..2")):
        with pytest.raises(ValueError) as e:
            build()
        assert one_line(e) == message
    with pytest.raises(ValueError, match="unknown key 'bodys'"):
        superball.Scene.from_dict({"bodys": [1, 2]})
    with pytest.raises(ValueError, match="^<dict>: body: no \\[\\[body\\]\\] tables: a scene needs at least 2 bodies"):
        superball.Scene.from_dict({})
    with pytest.raises(ValueError, match="^<scene>: body\\[1\\].mass: must be a number or a fraction string"):
        superball.Scene(bodies=[True, 1], fall_speed=1)
    with pytest.raises(ValueError, match="^<scene>: body\\[1\\].speed: unknown key \\(expected one of: gap, mass, velocity\\)"):
        superball.Scene(bodies=[{"mass": 1, "speed": 2}, 1], fall_speed=1)
    with pytest.raises(ValueError, match="not positive semi-definite"):
        superball.solve(superball.Scene(bodies=[1, 2, 3, 4], fall_speed=1, K={"1-2": 1, "1-4": 1}, alpha={2: 5}))


def test_with_value(paper):
    with pytest.raises(ValueError) as e:
        paper.with_value("g", -1)
    assert one_line(e) == f"{PAPER}: g = -1: g: must be > 0 (got -1)"
    for key, value, what in (("K.9-9", 1, "is not a pair"), ("mass.1", "x", "mass.1 = 'x'"), ("nosuch", 1, "nosuch")):
        with pytest.raises(ValueError, match=what):
            paper.with_value(key, value)


def test_solve_options(paper):
    for kwargs, what in (({"precision": "digits:3"}, "digits"), ({"precision": "float"}, "float"),
                         ({"precision": "double", "rtol": 1e-3}, "rtol is the certified error"),
                         ({"rtol": 2}, "rtol must be a number from 0 to 1"), ({"rtol": float("nan")}, "rtol must be")):
        with pytest.raises(ValueError, match=what) as e:
            superball.solve(paper, **kwargs)
        one_line(e)
    with pytest.raises(superball.InputError, match="^solve: expected a superball.Scene, got str$"):
        superball.solve("cases/scenes/paper-4.4-alpha2.toml")


def test_sweep_refuses_an_inadmissible_range_as_the_command_does(paper):
    with pytest.raises(ValueError) as e:
        superball.sweep(paper, "g", [-1, 0, 1])
    code, _, err = run_cli("sweep", PAPER, "--vary", "g=-1:1:3", check=False)
    assert code == 2 and err == f"superball: {one_line(e)}\n"


def test_sweep_and_switch_point_arguments(paper):
    cases = [
        (lambda: superball.sweep(paper, "K.3-4", []), "no value"),
        (lambda: superball.sweep(paper, "K.3-4", [[1, 2]]), "one-dimensional"),
        (lambda: superball.sweep(paper, "K.3-4", [1.0, float("nan")]), "not a finite number"),
        (lambda: superball.sweep(paper, "K.3-4", ["1/0"]), "values: '1/0'"),
        (lambda: superball.sweep(paper, "K.3-4", [1], precision="nope"), "nope"),
        (lambda: superball.sweep(paper, "K.3-4", [1], threads=-1), "threads"),
        (lambda: superball.sweep(paper, "K.1-2-3", [1]), "K.1-2-3"),
        (lambda: superball.linspace(0, 1, 1), "steps must be at least 2"),
        (lambda: superball.linspace(1, 1, 5), "equal"),
        (lambda: superball.switch_points(paper, "K.3-4", [1]), "at least two values"),
        (lambda: superball.switch_points(paper, "K.3-4", [1, 2], bits=0), "bits"),
        (lambda: superball.switch_points(paper, "K.1-4", superball.linspace(-1e9, 0, 3)), "K.1-4"),
    ]
    for call, what in cases:
        with pytest.raises(ValueError, match=what) as e:
            call()
        one_line(e)


def test_derive_options():
    cases = [
        (dict(case="9"), "9"),
        (dict(case="1", alphas="x"), "alphas: 'x'"),
        (dict(case="1", alphas=8), "8"),
        (dict(case="1", alphas=2, obstacle="soft"), "obstacle"),
        (dict(case="1", alphas=2, order=-1), "order"),
        (dict(alphas=2), "give a case"),
        (dict(closed="2-3", bodies=1), "n = 1: the symbolic derivation takes 2 to 21 bodies"),
        (dict(closed="1-3", bodies=3), "1-3"),
        (dict(case="1", alphas=2, scaling="zz=1"), "zz"),
        (dict(closed="none", bodies=21, pairs="near"), "holds about .* this machine has"),
    ]
    for kwargs, what in cases:
        with pytest.raises(ValueError, match=what) as e:
            superball.derive(**kwargs)
        one_line(e)


def test_one_parameter_under_its_spellings(paper):
    # Issue 25: K.03-4 is K.3-4, coupling.1-4/1-2 is alpha.2 (4 bodies), mass.01 is mass.1.
    for a, b, value in (("K.03-4", "K.3-4", 12), ("coupling.1-4/1-2", "alpha.2", -90), ("coupling.1-2/1-4", "alpha.2", -90),
                        ("mass.01", "mass.1", "1/100")):
        assert paper.with_value(a, value).to_toml() == paper.with_value(b, value).to_toml()
    one = superball.sweep(paper, "coupling.1-4/01-2", [-100, -50])
    other = superball.sweep(paper, "alpha.2", [-100, -50])
    assert (one.velocities == other.velocities).all() and list(one.cases) == list(other.cases)


def test_range_ends_past_64_bits_as_a_scene_takes_them(paper):
    r = superball.sweep(paper, "K.1-4", ["1e18", "10000000000000000000"], precision="exact")
    assert list(r.status) == ["success", "success"]


def test_body_count_and_box_are_refused_as_the_command_does():
    with pytest.raises(ValueError) as e:
        superball.derive(closed="none", bodies=64, pairs="near")
    code, _, err = run_cli("derive", "--bodies", "64", "--pairs", "near", "--closed", "none", check=False)
    assert code == 2 and err == f"superball: {one_line(e)}\n"
    with pytest.raises(ValueError) as e:
        superball.explore(case="1", alphas=3, box=(5, 1))
    code, _, err = run_cli("explore", "--alphas", "3", "--case", "1", "--box", "5:1", check=False)
    assert code == 2 and err == f"superball: {one_line(e)}\n"
    # A box to the ends of double is searched.
    assert superball.explore(case="1", alphas=2, box=(1e-300, 1e300), starts=4).reach == "yes"


def test_error_is_the_base_of_input_error():
    assert issubclass(superball.InputError, superball.Error) and issubclass(superball.InputError, ValueError)
    assert not issubclass(superball.Error, ValueError)


@pytest.mark.parametrize("scaling, message", [
    ("m1=1000000000000,K14=-1000000000000", "sampling needs orders in epsilon from -4000 to 4000 (m1 has order 1000000000000)"),
    ("m1=3000,K14=-1", "eps = 1/100 to the order 3000 of the scaling is below 1e-3998: the points would hold numbers no scene holds "
                       "(use a larger eps or smaller orders)"),
])
def test_verify_refuses_scaling_orders_it_cannot_sample(scaling, message):
    # an order of 10^12 ended in "internal error: Not a 32-bit integer" (a CLN conversion)
    with pytest.raises(ValueError) as e:
        superball.verify(case="1", alphas=2, scaling=scaling, samples=10)
    assert one_line(e) == message
    code, _, err = run_cli("verify", "--case", "1", "--alphas", "2", "--scaling", scaling, "--samples", "10", check=False)
    assert code == 2 and err == f"superball: {message}\n"
