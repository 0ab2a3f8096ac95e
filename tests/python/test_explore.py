"""explore(): progress and Ctrl-C, from Python and from the command; the result does not depend on them."""
import os
import signal
import subprocess
import tempfile
import time

import pytest

import superball
from conftest import cli_path


def test_progress_counts_the_steps_and_changes_nothing():
    for case, reach in (("1", "yes"), ("0", "no (proved)")):  # a witness; the proofs
        told = []
        kw = dict(case=case, alphas=2, starts=4, evaluations=300)
        e = superball.explore(**kw, progress=lambda *a: told.append(a))
        quiet = superball.explore(**kw, progress=False)
        assert e.reach == reach
        assert e.data == quiet.data and e.text == quiet.text
        planned = 4 * 300 + 1  # the evaluations of the local searches, then the confirmation and the proofs
        assert {t[0] for t in told} == {f"case {case}"} and {t[2] for t in told} == {planned}
        assert [t[1] for t in told] == sorted(t[1] for t in told)
        assert len(told) >= 5 and told[-1][1] == planned and all(t[1] < planned for t in told[:-1])


def test_a_progress_that_raises_keyboard_interrupt_stops_it_at_once():
    told = []

    def interrupt(phase, done, total):
        told.append(done)
        raise KeyboardInterrupt

    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        superball.explore(case="1", alphas=2, evaluations=1000000, progress=interrupt)  # minutes without the interrupt
    assert time.monotonic() - start < 5
    assert told == [1024]
    # the module still works after it
    assert superball.explore(case="1", alphas=2, starts=2, evaluations=100, progress=False).reach == "yes"


def test_progress_must_be_callable():
    with pytest.raises(superball.InputError, match="progress: expected a callable"):
        superball.explore(case="1", alphas=2, progress="yes")


def test_the_command_stops_on_ctrl_c_writing_nothing():
    """`superball explore` with a budget of minutes: Ctrl-C gives exit 130, one line, no output file."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "explore.txt")
        p = subprocess.Popen([cli_path(), "explore", "--alphas", "2", "--all", "--evaluations", "1000000", "-o", out, "--out", folder],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(0.5)
        start = time.monotonic()
        p.send_signal(signal.SIGINT)
        stdout, stderr = p.communicate(timeout=60)
        assert time.monotonic() - start < 5, "the interrupt waited for the search"
        assert p.returncode == 130
        assert stdout == ""
        assert stderr == "superball: explore: interrupted (Ctrl-C): stopped before the end, nothing written\n"
        assert os.listdir(folder) == []
