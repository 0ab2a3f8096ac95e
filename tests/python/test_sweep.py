"""sweep() and switch_points(): arrays, exact values, the command's numbers, threads, the GIL."""
import threading
import time
from fractions import Fraction

import numpy as np
import pytest

import superball
from conftest import PAPER, SCENES, run_cli


def test_linspace_is_the_command_s_range():
    r = superball.linspace(0, 20, 401)
    assert len(r) == 401
    assert r.fractions() == [Fraction(20 * k, 400) for k in range(401)]
    a = np.asarray(r)
    assert a.dtype == np.float64 and a.shape == (401,) and a[-1] == 20.0
    down = superball.linspace("1/3", 0, 4)
    assert down.fractions() == [Fraction(1, 3), Fraction(2, 9), Fraction(1, 9), 0]


def test_arrays_dtypes_and_shapes(paper):
    s = superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 41))
    assert s.values.dtype == np.float64 and s.values.shape == (41,)
    assert s.velocities.dtype == np.float64 and s.velocities.shape == (41, 4)
    assert s.cases.shape == (41,) and s.cases.dtype.kind == "U"
    assert s.case_codes.dtype == np.int32 and s.status_codes.dtype == np.int8
    assert s.ok and list(s.status[:1]) == ["success"] and len(s) == 41
    assert s.case_list == ("2.2", "3.3", "3.2") and s.closed_list == (("3-4",), (), ("2-3",))
    assert all(s.cases[k] == s.case_list[s.case_codes[k]] for k in range(41))
    assert s.closed(0) == ("3-4",) and s.closed(40) == ("2-3",)


def test_long_chains_and_their_cases():
    """More than 64 contacts: the cases are sets of contacts, not bit masks."""
    n = 80
    chain = superball.Scene(bodies=[1] * (n - 1) + [{"mass": "inf", "velocity": 0}], fall_speed=1,
                            K={f"{i}-{i + 1}": 1 + (i % 3) for i in range(1, n)})
    s = superball.sweep(chain, "mass.1", [Fraction(1, 2), 1, 2, 50])
    assert s.velocities.shape == (4, n)
    for k, m in enumerate([Fraction(1, 2), 1, 2, 50]):
        r = superball.solve(chain.with_value("mass.1", m), "double")
        assert s.cases[k] == r.case and s.closed(k) == r.closed_contacts
        np.testing.assert_array_equal(s.velocities[k], r.velocities_after)


def test_every_row_is_the_solve_of_that_value(paper):
    values = [0.5, 3, Fraction(13, 2), "7.25", 19]
    s = superball.sweep(paper, "K.3-4", values)
    for k, v in enumerate(values):
        r = superball.solve(paper.with_value("K.3-4", v), "double")
        np.testing.assert_array_equal(s.velocities[k], r.velocities_after)
        assert s.cases[k] == r.case


def test_the_command_s_csv_row_for_row(paper):
    _, out, _ = run_cli("sweep", PAPER, "--vary", "K.3-4=0:20:21", "--csv")
    rows = [line.split(",") for line in out.strip().splitlines()[1:]]
    s = superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 21))
    assert len(rows) == 21
    for k, row in enumerate(rows):
        assert float(row[0]) == s.values[k]
        np.testing.assert_array_equal(np.array([float(x) for x in row[1:5]]), s.velocities[k])
        assert row[5] == s.cases[k] and row[6] == s.status[k]


def test_ranges_and_ints_are_exact(paper):
    a = superball.sweep(paper, "K.3-4", range(0, 21, 5))
    b = superball.sweep(paper, "K.3-4", np.arange(0, 21, 5))
    c = superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 5))
    np.testing.assert_array_equal(a.velocities, b.velocities)
    np.testing.assert_array_equal(a.velocities, c.velocities)


def test_a_sweep_longer_than_a_chunk(paper):
    """The module solves 2^16 values per library call: rows across the seam are the solves of their values."""
    values = superball.linspace(0, 20, 140001)
    s = superball.sweep(paper, "K.3-4", values)
    exact = values.fractions()
    for k in (0, 65535, 65536, 65537, 131072, 140000):
        r = superball.solve(paper.with_value("K.3-4", exact[k]), "double")
        np.testing.assert_array_equal(s.velocities[k], r.velocities_after)
        assert s.cases[k] == r.case
    assert s.case_list == ("2.2", "3.3", "3.2")


def test_a_sweep_through_the_psd_bound_marks_the_values_where_m_is_not_psd(paper):
    """Issue 26: alpha.2 from -110 to 0 crosses M's PSD bound (about -102.47): the values where M is not PSD
    are marked, exactly where the exact PSD test of each value's scene says so, and every other value is
    solved bit for bit as a sweep of those values alone; the command's sweep refuses the range."""
    values = superball.linspace(-110, 0, 111)
    s = superball.sweep(paper, "alpha.2", values)
    fractions = values.fractions()

    def psd_at(v):
        try:
            superball.solve(paper.with_value("alpha.2", v), "double")
            return True
        except superball.InputError as e:
            assert "M is not positive semi-definite" in str(e)
            return False

    assert s.psd.dtype == np.bool_ and s.psd.tolist() == [psd_at(v) for v in fractions]
    assert 0 < int(np.sum(s.psd)) < len(s)
    off = ~s.psd
    assert np.isnan(s.velocities[off]).all() and (s.cases[off] == "").all()
    assert (s.case_codes[off] == -1).all() and (s.status_codes[off] == -1).all() and s.closed(0) == ()
    only = superball.sweep(paper, "alpha.2", [v for v, ok in zip(fractions, s.psd) if ok])
    assert only.psd.all()
    assert s.velocities[s.psd].tobytes() == only.velocities.tobytes()
    assert s.cases[s.psd].tolist() == only.cases.tolist()
    assert s.status_codes[s.psd].tobytes() == only.status_codes.tobytes()
    assert s.values.tobytes() == np.asarray(values).tobytes()
    code, out, err = run_cli("sweep", PAPER, "--vary", "alpha.2=-110:0:111", check=False)
    assert code == 2 and out == "" and err.count("\n") == 1 and "alpha.2 = -110: dissipation: M is not positive semi-definite" in err
    # a range where M is PSD nowhere: nothing to solve
    with pytest.raises(superball.InputError, match=r"M is not positive semi-definite at any value of the sweep \(alpha.2 from -300 to -200\)"):
        superball.sweep(paper, "alpha.2", superball.linspace(-300, -200, 5))


def test_result_does_not_depend_on_threads(paper):
    r = superball.linspace(0, 20, 2001)
    one, two = superball.sweep(paper, "K.3-4", r, threads=1), superball.sweep(paper, "K.3-4", r, threads=2)
    np.testing.assert_array_equal(one.velocities, two.velocities)
    np.testing.assert_array_equal(one.cases, two.cases)


def test_numpy_arrays_are_taken_exactly(paper):
    x = np.array([0.1, 6.0, 12.0])
    s = superball.sweep(paper, "K.3-4", x)
    np.testing.assert_array_equal(s.values, x)
    # 0.1 the double, not 1/10: the row is the solve of Fraction(0.1)
    r = superball.solve(paper.with_value("K.3-4", str(Fraction(0.1))), "double")
    np.testing.assert_array_equal(s.velocities[0], r.velocities_after)


def test_momentum_along_the_sweep(paper):
    s = superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 101))
    m = np.array([float(x) for x in paper.masses])
    p_before = superball.solve(paper, "double").momentum_before
    np.testing.assert_allclose(s.velocities @ m, p_before, rtol=1e-9)


def test_switch_points_bracket_a_change_of_the_exact_case(paper):
    points = superball.switch_points(paper, "K.3-4", superball.linspace(0, 20, 401))
    assert [(p.case_below, p.case_above) for p in points] == [("2.2", "3.3"), ("3.3", "3.2")]
    for p in points:
        assert p.low < p.high and p.high - p.low < Fraction(1, 2**60)
        assert superball.solve(paper.with_value("K.3-4", p.low), "exact").case == p.case_below
        assert superball.solve(paper.with_value("K.3-4", p.high), "exact").case == p.case_above
    assert points[0].closed_below == ("3-4",) and points[0].closed_above == ()
    # chained, in increasing value
    assert points[0].case_above == points[1].case_below and points[0].value < points[1].value


def test_switch_points_equal_the_command_s(paper):
    _, out, _ = run_cli("sweep", PAPER, "--vary", "K.3-4=20:0:41", "--switch-points", "--csv")
    rows = [line.split(",") for line in out.strip().splitlines()[1:]]
    points = superball.switch_points(paper, "K.3-4", superball.linspace(0, 20, 41))
    assert [(p.text, p.case_below, p.case_above) for p in points] == [(r[0], r[2], r[3]) for r in rows]


def test_switch_points_from_an_array_and_descending(paper):
    up = superball.switch_points(paper, "K.3-4", np.linspace(0, 20, 41))
    down = superball.switch_points(paper, "K.3-4", np.linspace(20, 0, 41))
    assert [p.text for p in up] == [p.text for p in down]
    with pytest.raises(ValueError, match="strictly increasing or strictly decreasing"):
        superball.switch_points(paper, "K.3-4", [0, 10, 5])


def _turns_during(call):
    """Run ``call`` in a thread; the main thread's loop turns in the middle half of the call.

    A call that holds the GIL stops the main thread from its start to its
    end, so there are none; one that releases it leaves the main thread
    running (thousands), unless the machine stops it for that whole time.
    """
    span = {}

    def run():
        span["start"] = time.perf_counter()
        span["result"] = call()
        span["end"] = time.perf_counter()

    t = threading.Thread(target=run)
    stamps = []
    t.start()
    while t.is_alive():
        stamps.append(time.perf_counter())
    t.join()
    quarter = (span["end"] - span["start"]) / 4
    middle = [s for s in stamps if span["start"] + quarter < s < span["end"] - quarter]
    return len(middle), span["end"] - span["start"], span["result"]


def test_sweep_releases_the_gil(paper):
    values = superball.linspace(0, 20, 100000)
    turns, duration, r = _turns_during(lambda: superball.sweep(paper, "K.3-4", values, threads=1))
    assert r.velocities.shape == (100000, 4) and duration > 0.05  # long enough to tell
    assert turns >= 10, (turns, duration)


def test_switch_points_release_the_gil(paper):
    # Each value's case is found first (a certified double solve each): 10^5 values take long enough to tell.
    values = superball.linspace(0, 20, 100001)
    turns, duration, r = _turns_during(lambda: superball.switch_points(paper, "K.3-4", values, threads=1))
    assert len(r) == 2 and duration > 0.05
    assert turns >= 10, (turns, duration)


def test_solve_releases_the_gil():
    n = 400  # one solve of 0.1-0.5 s: a chain in CLN floats of 10000 digits
    chain = superball.Scene(bodies=[1 + i % 5 for i in range(n - 1)] + [{"mass": "inf", "velocity": 0}], fall_speed=1,
                            K={f"{i}-{i + 1}": 1 + i % 7 for i in range(1, n)})
    turns, duration, r = _turns_during(lambda: superball.solve(chain, "digits:10000"))
    assert r.status == "success" and duration > 0.05
    assert turns >= 10, (turns, duration)


def test_two_threads_sweeping_the_same_values(paper):
    """Calls without the GIL on the same exact values take turns (CLN objects are not thread-safe): same results."""
    values = superball.linspace(0, 20, 20001)
    alone = superball.sweep(paper, "K.3-4", values, threads=1)
    out = [None] * 4

    def run(k):
        out[k] = superball.sweep(paper, "K.3-4", values, threads=1) if k % 2 == 0 else np.asarray(values)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in (0, 2):
        np.testing.assert_array_equal(out[k].velocities, alone.velocities)
    np.testing.assert_array_equal(out[1], alone.values)
