"""Scenes: loading, construction from a dict or keywords, with_value, TOML round trip."""
from fractions import Fraction

import pytest

import superball
from conftest import BAD, PAPER, SCENES

PAPER_KW = dict(bodies=[0.001, 10, 15, {"mass": 5e6, "velocity": 0}], fall_speed=3.13209,
                K={"1-2": 7, "1-3": 7, "1-4": 1500, "2-3": 10, "2-4": 13, "3-4": 10}, alpha={2: -100})


def test_load_reads_the_file(paper):
    assert paper.bodies == 4
    assert paper.origin == str(PAPER)
    assert "Paper 4.4" in paper.title
    # exact masses: 0.001 is 1/1000, not the nearest double
    assert paper.masses == [Fraction(1, 1000), 10, 15, 5000000]


def test_load_accepts_path_objects_and_every_paper_scene():
    for path in sorted(SCENES.glob("*.toml")):
        s = superball.Scene.load(path)
        assert s.bodies >= 2


def test_keywords_and_dict_give_the_file_s_scene(paper):
    by_keywords = superball.Scene(**PAPER_KW)
    by_dict = superball.Scene.from_dict(PAPER_KW)
    exact = superball.solve(paper, "exact").velocities_after_exact
    assert superball.solve(by_keywords, "exact").velocities_after_exact == exact
    assert superball.solve(by_dict, "exact").velocities_after_exact == exact


def test_numbers_are_exact_in_every_spelling():
    a = superball.Scene(bodies=["1/3", Fraction(2, 3), 0.5, {"mass": float("inf")}], fall_speed=1, K={"1-2": 1, "2-3": 1, "3-4": 1})
    assert a.masses[:3] == [Fraction(1, 3), Fraction(2, 3), Fraction(1, 2)]
    assert a.masses[3] == float("inf")


def test_couplings_in_both_spellings_are_the_same_entry():
    base = dict(bodies=[1, 2, 3, 4], fall_speed=1, K={"1-2": 5, "1-3": 5, "2-4": 5, "3-4": 5, "2-3": 5})
    one = superball.Scene(**base, coupling=[("1-3", "2-4", 2)])
    two = superball.Scene.from_dict(dict(base, coupling=[{"pairs": ["1-3", "2-4"], "value": 2}]))
    assert one.to_toml() == two.to_toml()


def test_with_value_changes_only_that_parameter(paper):
    changed = paper.with_value("K.3-4", 7)
    assert '"3-4" = 10' in paper.to_toml() and '"3-4" = 7' in changed.to_toml()  # the original is unchanged
    assert superball.solve(paper, "exact").velocities_after_exact != superball.solve(changed, "exact").velocities_after_exact
    assert superball.solve(changed, "exact").velocities_after_exact == \
        superball.solve(superball.Scene.from_toml(paper.to_toml().replace('"3-4" = 10', '"3-4" = 7')), "exact").velocities_after_exact
    assert changed.with_value("K.3-4", 10).to_toml() == paper.to_toml()


def test_with_value_accepts_fractions_and_strings(paper):
    a = paper.with_value("mass.1", Fraction(1, 1000))
    b = paper.with_value("mass.1", "1e-3")
    assert a.masses == b.masses == paper.masses


def test_toml_round_trip(paper):
    again = superball.Scene.from_toml(paper.to_toml("a comment\non two lines"), "again")
    assert again.origin == "again"
    assert again.masses == paper.masses
    assert superball.solve(again, "exact").velocities_after_exact == superball.solve(paper, "exact").velocities_after_exact


def test_repr_names_the_scene(paper):
    r = repr(paper)
    assert "paper-4.4-alpha2.toml" in r and "4 bodies" in r and "fall_speed=3.13209" in r and "\n" not in r


def test_flight_table():
    s = superball.Scene(bodies=[1, {"mass": "inf"}], fall_speed=2, K={"1-2": 1}, flight={"duration": 1})
    assert "[flight]" in s.to_toml()


def test_a_scene_shows_its_matrix_and_keys(paper):
    for s in (paper, superball.Scene(**PAPER_KW)):
        assert s.K == {"1-2": 7, "1-3": 7, "1-4": 1500, "2-3": 10, "2-4": 13, "3-4": 10}
        assert s.alpha == {2: -100} and s.couplings == {}
        assert s.fall_speed == Fraction(313209, 100000) and s.drop_height is None and s.g == Fraction(981, 100)
        assert s.velocities == [None, None, None, 0]
        assert s.keys == ["K.1-2", "K.1-3", "K.1-4", "K.2-3", "K.2-4", "K.3-4", "alpha.2", "mass.1", "mass.2", "mass.3", "mass.4",
                          "velocity.4", "fall_speed"]
        for key in s.keys:  # every key is one with_value() takes, and names the value the scene holds
            assert s.with_value(key, 1).keys == s.keys
    html = paper._repr_html_()
    assert "<table>" in html and "α<sub>2</sub> = -100" in html and "K<sub>34</sub> = 10" in html
    chain = superball.Scene(bodies=[1, 2, {"mass": "inf"}], drop_height="1/2", K={"1-2": 1},
                            coupling=[("1-2", "2-3", "1/3"), {"pairs": "1-3/2-3", "value": 0}])
    assert chain.couplings == {"1-2/2-3": Fraction(1, 3), "1-3/2-3": 0} and chain.alpha == {}
    assert chain.keys == ["K.1-2", "coupling.1-2/2-3", "coupling.1-3/2-3", "mass.1", "mass.2", "drop_height", "g"]
    assert chain.masses[2] == float("inf") and chain.drop_height == Fraction(1, 2)


def test_a_scene_from_a_dict_is_not_written_as_text(monkeypatch):
    """The scene is built in C++ from the dict (Scene.from_value): no TOML text is made or parsed."""
    import superball._superball as ext

    def refuse(*args, **kwargs):
        raise AssertionError("a scene went through TOML text")

    monkeypatch.setattr(ext.Scene, "parse", refuse)
    assert superball.Scene(**PAPER_KW).bodies == 4
    assert superball.Scene.from_dict(PAPER_KW).K["3-4"] == 10
