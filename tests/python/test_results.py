"""Every result: exact U⁻ and U₁⁺/a, short reprs and HTML views, progress and Ctrl-C, wrong types as InputError."""
import _thread
from fractions import Fraction

import numpy as np
import pytest

import superball

A = Fraction(313209, 100000)  # the paper scene's fall speed


def test_exact_before_and_ratio(paper):
    exact = superball.solve(paper, "exact")
    assert exact.velocities_before_exact == [-A, -A, -A, 0]
    assert exact.ratio == exact.velocities_after_exact[0] / A and isinstance(exact.ratio, Fraction) and exact.ratio > 1
    double = superball.solve(paper, "double")
    assert double.velocities_before_exact == [-A, -A, -A, 0]  # U⁻ is the scene's, whatever the arithmetic
    assert isinstance(double.ratio, float) and double.ratio == pytest.approx(float(exact.ratio), rel=1e-13)
    # a = sqrt(2 g h) irrational: no exact U⁻ for the falling bodies, the ratio in float
    h = superball.solve(superball.Scene(bodies=[1, {"mass": "inf", "velocity": 0}], drop_height=1, K={"1-2": 1}), "exact")
    assert h.velocities_before_exact == [None, 0] and isinstance(h.ratio, float)


def test_sweep_ratio_repr_html_and_switch_points(paper):
    s = superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 401), progress=False)
    np.testing.assert_array_equal(s.ratio, s.velocities[:, 0] / float(A))
    r = repr(s)
    assert "\n" not in r and len(r) < 200 and "401 values" in r and "array" not in r
    assert "<table>" in s._repr_html_() and "2.2" in s._repr_html_()
    points = s.switch_points()
    assert [(p.case_below, p.case_above) for p in points] == [("2.2", "3.3"), ("3.3", "3.2")]
    assert points == superball.switch_points(paper, "K.3-4", superball.linspace(0, 20, 401))
    fall = superball.sweep(paper, "fall_speed", [1, 2, "5/2"], progress=False)
    for k, a in enumerate([1, 2, 2.5]):
        assert fall.ratio[k] == pytest.approx(superball.solve(paper.with_value("fall_speed", a), "double").ratio, rel=1e-15)


def test_sweep_and_verify_progress_and_ctrl_c(paper):
    seen = []
    superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 140001), progress=lambda *a: seen.append(a))
    assert seen == [("values", 0, 140001), ("values", 65536, 140001), ("values", 131072, 140001), ("values", 140001, 140001)]

    def interrupt(phase, done, total):
        if done == 65536:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 140001), progress=interrupt)
    told = []
    superball.verify(case="1", alphas=2, epsilons=["1/100"], samples=30, boundary_pairs=2, progress=lambda *a: told.append(a))
    assert told[0][:2] == ("drawn points", 0) and told[-1][0] == "boundaries" and told[-1][1] == told[-1][2]


@pytest.mark.parametrize("call", [
    lambda p: superball.solve("paper.toml"),
    lambda p: superball.solve(p, precision=3),
    lambda p: superball.solve(p, rtol="0.1"),
    lambda p: superball.sweep(p, "K.3-4", [1, 2], threads="2"),
    lambda p: superball.sweep(p, 34, [1, 2]),
    lambda p: superball.switch_points(p, "K.3-4", [1, 2], bits=1.5),
    lambda p: superball.sweep(p, "K.3-4", [1, 2], progress="yes"),
    lambda p: superball.audit(samples="many"),
    lambda p: superball.verify(case="1", alphas=2, samples=None),
])
def test_wrong_types_are_input_errors(paper, call):
    with pytest.raises(superball.InputError) as e:
        call(paper)
    assert "\n" not in str(e.value)


def test_checks_have_short_reprs_and_html():
    a = superball.audit(samples=50)
    v = superball.verify(case="1", alphas=2, epsilons=["1/100"], samples=30, boundary_pairs=2)
    e = superball.explore(case="1", alphas=2, starts=4, evaluations=200)
    t = superball.explore(all_patterns=True, starts=1, evaluations=10)
    for result, words in ((a, "printed conditions"), (v, "case 1"), (e, "reach yes"), (t, "patterns x")):
        r = repr(result)
        assert "\n" not in r and len(r) < 200 and words in r, r
        assert result._repr_html_().startswith("<div>")
    assert str(v) in v._repr_html_().replace("&gt;", ">").replace("&lt;", "<").replace("&quot;", '"').replace("&#x27;", "'").replace("&amp;", "&")


def test_sweep_marks_values_where_m_is_not_psd(paper):
    """alpha.2 from -110 to 0: M is PSD only from about -102.47 on; the others are marked, not a failed sweep."""
    s = superball.sweep(paper, "alpha.2", superball.linspace(-110, 0, 111), progress=False)
    assert s.psd.dtype == np.bool_ and s.psd.sum() == 103 and not s.psd[:8].any() and s.psd[8:].all()  # -102 … 0
    assert np.isnan(s.velocities[:8]).all() and np.isnan(s.ratio[:8]).all() and (s.cases[:8] == "").all()
    assert (s.case_codes[:8] == -1).all() and (s.status[:8] == "").all() and s.closed(0) == () and not s.ok
    for k in (0, 7):  # solve() refuses those values, naming M
        with pytest.raises(superball.InputError, match="not positive semi-definite"):
            superball.solve(paper.with_value("alpha.2", -110 + k), "double")
    for k in (8, 60, 110):
        r = superball.solve(paper.with_value("alpha.2", -110 + k), "double")
        np.testing.assert_array_equal(s.velocities[k], r.velocities_after)
        assert s.cases[k] == r.case
    with pytest.raises(superball.InputError, match="M is not positive semi-definite at any value of the sweep"):
        superball.sweep(paper, "alpha.2", [-200, -150], progress=False)
