"""checkpoint=: a folder kept by the library of the command's --checkpoint (same files, same checks, same messages);
the result is the same with it, without it, and interrupted then resumed."""
import os
import re

import numpy as np
import pytest

import superball
from conftest import PAPER, run_cli

# Three tasks of sweep() (blocks of 2**16 values), the last one short.
VALUES = superball.linspace(0, 20, 2 * 65536 + 1000)
X, Y = "K.3-4=0:20:9", "alpha.2=-110:0:9"


def same_sweep(a, b):
    assert np.array_equal(a.values, b.values)
    assert np.array_equal(a.velocities, b.velocities, equal_nan=True)
    assert np.array_equal(a.case_codes, b.case_codes) and a.case_list == b.case_list and a.closed_list == b.closed_list
    assert np.array_equal(a.status_codes, b.status_codes) and np.array_equal(a.psd, b.psd)


def same_map(a, b):
    for name in ("cases", "superball", "psd"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.ratio, b.ratio, equal_nan=True)
    assert a.case_list == b.case_list and a.boundary_points == b.boundary_points
    assert a.curves == b.curves
    for c, d in zip(a.curves, b.curves):
        assert np.array_equal(c.points, d.points)


def tasks(folder):
    """The finished task files: a worker stopped by an interrupt may leave a task-N.tmpXXXXXX write cut short, which the next run removes."""
    return sorted(f for f in os.listdir(folder) if re.fullmatch(r"task-[0-9]{8}", f))


@pytest.fixture(scope="module")
def plain(paper):
    return superball.sweep(paper, "K.3-4", VALUES, progress=False)


def test_sweep_with_a_checkpoint_is_the_same_and_keeps_every_block(paper, plain, tmp_path):
    kept = superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=tmp_path / "c")
    same_sweep(kept, plain)
    assert tasks(tmp_path / "c") == ["task-00000000", "task-00000001", "task-00000002"]
    with open(tmp_path / "c" / "run") as f:
        assert f.readline() == "superball checkpoint 2\n"
    again = superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=str(tmp_path / "c"))  # all read back
    same_sweep(again, plain)


def test_sweep_interrupted_then_resumed_computes_only_the_missing_blocks(paper, plain, tmp_path):
    folder = tmp_path / "c"

    def stop(phase, done, total):
        if done >= 65536:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.sweep(paper, "K.3-4", VALUES, progress=stop, checkpoint=folder)
    assert tasks(folder) == ["task-00000000"]
    told = []
    resumed = superball.sweep(paper, "K.3-4", VALUES, progress=lambda *a: told.append(a), checkpoint=folder)
    same_sweep(resumed, plain)
    assert told[0] == ("values", 65536, len(VALUES))  # block 0 read back, not solved again
    assert told[-1] == ("values", len(VALUES), len(VALUES))


def test_a_tampered_task_file_is_said_removed_and_computed_again(paper, plain, tmp_path):
    folder = tmp_path / "c"
    superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=folder)
    path = folder / "task-00000001"
    text = path.read_bytes()
    at = text.index(b"\n") + 5
    path.write_bytes(text[:at] + (b"7" if text[at:at + 1] != b"7" else b"8") + text[at + 1:])
    with pytest.warns(UserWarning) as said:
        again = superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=folder)
    messages = [str(w.message) for w in said]
    assert messages == [f"--checkpoint {folder}: task-00000001: task 1: fails its checksum (changed or damaged since it was written); "
                        "task 1 computed again"]
    same_sweep(again, plain)
    assert path.read_bytes() == text  # written again, whole


@pytest.mark.parametrize("kind", ["fifo", "symlink"])
def test_a_fifo_or_a_link_in_place_of_a_task_file_is_not_read(paper, plain, tmp_path, kind):
    folder = tmp_path / "c"
    superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=folder)
    path = folder / "task-00000002"
    kept = path.read_bytes()
    os.rename(path, tmp_path / "elsewhere")
    if kind == "fifo":
        os.mkfifo(path)
        said = "a FIFO, not a regular file: not read"
    else:
        os.symlink(tmp_path / "elsewhere", path)
        said = "a symbolic link, not read"
    with pytest.warns(UserWarning, match=re.escape(f"--checkpoint {folder}: task-00000002: {said}; task 2 computed again")):
        again = superball.sweep(paper, "K.3-4", VALUES, progress=False, checkpoint=folder)
    same_sweep(again, plain)
    assert not os.path.islink(path) and path.read_bytes() == kept


def test_a_folder_of_another_run_is_refused(paper, tmp_path):
    folder = tmp_path / "c"
    few = superball.linspace(0, 20, 11)
    superball.sweep(paper, "K.3-4", few, progress=False, checkpoint=folder)
    for other in (dict(precision="long-double"), dict(key="K.2-3"), dict(values=superball.linspace(0, 20, 12))):
        args = dict(key="K.3-4", values=few)
        args.update(other)
        with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder}: holds run ") + ".*give another folder$"):
            superball.sweep(paper, progress=False, checkpoint=folder, **args)
    # The same run whatever the spelling of the key, and the scene by its content, not its name.
    again = superball.sweep(superball.Scene.from_toml(paper.to_toml(), "elsewhere"), "K.03-4", few, progress=False, checkpoint=folder)
    assert np.array_equal(again.velocities, superball.sweep(paper, "K.3-4", few, progress=False).velocities)


def test_a_folder_of_the_command_is_refused_with_the_command_s_message(paper, tmp_path):
    folder = tmp_path / "c"
    run_cli("sweep", PAPER, "--vary", "K.3-4=0:20:11", "--checkpoint", folder)
    with pytest.raises(superball.InputError) as python:
        superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 11), progress=False, checkpoint=folder)
    m = re.fullmatch(r"--checkpoint (.*): holds run ([0-9a-f]{16}) \(superball sweep (.*)\), and this command is run ([0-9a-f]{16}) "
                     r"\(superball sweep (.*)\); give another folder", str(python.value))
    assert m and m.group(1) == str(folder) and m.group(2) != m.group(4), str(python.value)
    # The command refuses Python's folder the same way.
    superball.sweep(paper, "K.3-4", superball.linspace(0, 20, 11), progress=False, checkpoint=tmp_path / "p")
    code, out, err = run_cli("sweep", PAPER, "--vary", "K.3-4=0:20:11", "--checkpoint", tmp_path / "p", check=False)
    assert code == 2 and out == ""
    assert re.fullmatch(r"superball: --checkpoint .*: holds run [0-9a-f]{16} \(superball sweep --key=K.3-4 --precision=double --scene --values\), "
                        r"and this command is run [0-9a-f]{16} \(superball sweep .*\); give another folder\n", err), err


def test_checkpoint_must_name_a_folder(paper):
    for bad in ("", 3, b"folder"):
        with pytest.raises(superball.InputError, match="sweep: checkpoint: expected a folder"):
            superball.sweep(paper, "K.3-4", [1.0], checkpoint=bad)


def test_map_with_a_checkpoint_is_the_same_interrupted_then_resumed(paper, tmp_path):
    plain = superball.map(paper, X, Y, progress=False)
    folder = tmp_path / "m"

    def stop(phase, done, total):
        if phase == "boundaries" and done >= 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.map(paper, X, Y, progress=stop, checkpoint=folder)
    assert sorted(os.listdir(folder)) == ["boundaries", "points"]
    points, boundaries = tasks(folder / "points"), tasks(folder / "boundaries")
    assert len(points) > 3 and len(boundaries) == 3
    told = []
    resumed = superball.map(paper, X, Y, progress=lambda *a: told.append(a), checkpoint=folder)
    same_map(resumed, plain)
    assert told[0] == ("points", len(points), len(points))  # every point read back
    assert ("boundaries", 3, told[-1][2]) in told and ("boundaries", 0, told[-1][2]) not in told
    same_map(superball.map(paper, X, Y, progress=False, checkpoint=folder), plain)
    with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder / 'points'}: holds run ")):
        superball.map(paper, X, "alpha.2=-110:0:10", progress=False, checkpoint=folder)


def test_verify_with_a_checkpoint_interrupted_then_resumed_is_the_same(tmp_path):
    kw = dict(all=True, alphas=2, epsilons=["1/100"], samples=20, boundary_pairs=1)
    plain = superball.verify(**kw, progress=False)
    folder = tmp_path / "v"

    def stop(phase, done, total):
        if phase == "cases" and done >= 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.verify(**kw, progress=stop, checkpoint=folder)
    assert tasks(folder) == ["task-00000000", "task-00000001"]
    told = []
    resumed = superball.verify(**kw, progress=lambda *a: told.append(a), checkpoint=folder)
    assert told[0] == ("cases", 2, len(plain))
    assert [(r.data, r.text, r.exact_agrees) for r in resumed] == [(r.data, r.text, r.exact_agrees) for r in plain]
    path = folder / "task-00000000"
    text = path.read_bytes()
    path.write_bytes(text.replace(b"\nA\n", b"\nX\n", 1))  # a record whose checksum no longer holds
    with pytest.warns(UserWarning, match=re.escape(f"--checkpoint {folder}: task-00000000: task 0: fails its checksum")):
        again = superball.verify(**kw, progress=False, checkpoint=folder)
    assert [r.data for r in again] == [r.data for r in plain]
    with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder}: holds run ")):
        superball.verify(**dict(kw, seed=2), progress=False, checkpoint=folder)


def test_a_run_file_that_is_a_link_or_a_fifo_is_refused(paper, tmp_path):
    few = superball.linspace(0, 20, 11)
    for kind in ("symlink", "fifo"):
        folder = tmp_path / kind
        superball.sweep(paper, "K.3-4", few, progress=False, checkpoint=folder)
        run = folder / "run"
        os.rename(run, tmp_path / f"{kind}-run")
        if kind == "fifo":
            os.mkfifo(run)
            said = "a FIFO, not a regular file: not read"
        else:
            os.symlink(tmp_path / f"{kind}-run", run)
            said = "a symbolic link, not read"
        with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder}: its run file: {said}; give another folder")):
            superball.sweep(paper, "K.3-4", few, progress=False, checkpoint=folder)


EXPLORE = dict(alphas=2, all=True, starts=2, evaluations=100)


def explored(results):
    return [(r.case, r.reach, r.ratio, r.witness, None if r.scene is None else r.scene.to_toml(), r.data, r.text) for r in results]


def test_explore_with_a_checkpoint_interrupted_then_resumed_is_the_same(tmp_path):
    plain = superball.explore(**EXPLORE, progress=False)
    folder = tmp_path / "e"

    def stop(phase, done, total):
        if phase == "cases" and done >= 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.explore(**EXPLORE, progress=stop, checkpoint=folder)
    assert tasks(folder) == ["task-00000000", "task-00000001", "task-00000002"]
    first = {f: os.stat(folder / f).st_mtime_ns for f in tasks(folder)}
    told = []
    resumed = superball.explore(**EXPLORE, progress=lambda *a: told.append(a), checkpoint=folder)
    assert told[0] == ("cases", 3, len(plain))  # three cases read back, not explored again
    assert [t for t in told if t[0] == "cases"] == [("cases", k, len(plain)) for k in range(3, len(plain) + 1)]
    assert {f: os.stat(folder / f).st_mtime_ns for f in tasks(folder)[:3]} == first
    assert explored(resumed) == explored(plain)
    assert any(r.scene is not None for r in resumed)  # a witness scene read back from its task file
    # A task edited by hand (its checksum no longer holds): said, explored again, the same.
    path = folder / "task-00000001"
    text = path.read_bytes()
    path.write_bytes(text.replace(b'"reach"', b'"REACH"', 1))
    with pytest.warns(UserWarning) as said:
        again = superball.explore(**EXPLORE, progress=False, checkpoint=folder)
    assert [str(w.message) for w in said] == [f"--checkpoint {folder}: task-00000001: task 1: fails its checksum (changed or damaged since it was "
                                              "written); task 1 computed again"]
    assert explored(again) == explored(plain) and path.read_bytes() == text
    # A task cut short: said, explored again.
    path.write_bytes(text[:len(text) // 2])
    with pytest.warns(UserWarning, match=re.escape(f"--checkpoint {folder}: task-00000001: cut short in task 1 (") + r".* left\); task 1 computed again$"):
        superball.explore(**EXPLORE, progress=False, checkpoint=folder)
    # Another search is another run.
    with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder}: holds run ") + ".*give another folder$"):
        superball.explore(**dict(EXPLORE, seed=2), progress=False, checkpoint=folder)


def test_explore_all_patterns_with_a_checkpoint_keeps_each_cell(tmp_path):
    kw = dict(all_patterns=True, starts=1, evaluations=10)
    plain = superball.explore(**kw, progress=False)
    kept = superball.explore(**kw, progress=False, checkpoint=tmp_path / "t")
    assert len(tasks(tmp_path / "t")) == plain.reach.size == 64
    again = superball.explore(**kw, progress=False, checkpoint=tmp_path / "t")
    for t in (kept, again):
        assert t.data == plain.data and t.text == plain.text and np.array_equal(t.reach, plain.reach)


def derived(results):
    return [(d.case, d.velocities_text, d.report, d.data) for d in results]


@pytest.mark.parametrize("jobs", [1, 2])
def test_derive_all_with_a_checkpoint_interrupted_then_resumed_derives_only_the_missing_cases(tmp_path, jobs):
    kw = dict(bodies=5, pairs="near2", coupling="near2", jobs=jobs)
    plain = superball.derive_all(**kw, progress=False)
    folder = tmp_path / "d"

    def stop(done, total):
        if done >= 5:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.derive_all(**kw, progress=stop, checkpoint=folder)
    kept = tasks(folder)
    assert kept[:5] == [f"task-0000000{k}" for k in range(5)] and len(kept) < len(plain)
    first = {f: os.stat(folder / f).st_mtime_ns for f in kept}
    told = []
    resumed = superball.derive_all(**kw, progress=lambda *a: told.append(a), checkpoint=folder)
    assert told == [(k, len(plain)) for k in range(len(kept), len(plain) + 1)]  # the cases kept read back, not derived again
    assert {f: os.stat(folder / f).st_mtime_ns for f in kept} == first
    assert derived(resumed) == derived(plain)
    assert tasks(folder) == [f"task-{k:08d}" for k in range(len(plain))]


def test_derive_all_checkpoint_checks_its_folder(tmp_path):
    kw = dict(alphas=2, jobs=1, progress=False)
    plain = superball.derive_all(**kw)
    folder = tmp_path / "d"
    superball.derive_all(**kw, checkpoint=folder)
    path = folder / "task-00000003"
    text = path.read_bytes()
    path.write_bytes(text.replace(b"velocities", b"VELOCITIES", 1))
    with pytest.warns(UserWarning) as said:
        again = superball.derive_all(**kw, checkpoint=folder)
    assert [str(w.message) for w in said] == [f"--checkpoint {folder}: task-00000003: task 3: fails its checksum (changed or damaged since it was "
                                              "written); task 3 computed again"]
    assert derived(again) == derived(plain) and path.read_bytes() == text
    for kind in ("fifo", "symlink"):
        os.rename(path, tmp_path / "elsewhere")
        if kind == "fifo":
            os.mkfifo(path)
            said = "a FIFO, not a regular file: not read"
        else:
            os.symlink(tmp_path / "elsewhere", path)
            said = "a symbolic link, not read"
        with pytest.warns(UserWarning, match=re.escape(f"--checkpoint {folder}: task-00000003: {said}; task 3 computed again")):
            assert derived(superball.derive_all(**kw, checkpoint=folder)) == derived(plain)
        assert not os.path.islink(path) and path.read_bytes() == text
        os.remove(tmp_path / "elsewhere")
    with pytest.raises(superball.InputError, match=re.escape(f"--checkpoint {folder}: holds run ") + ".*give another folder$"):
        superball.derive_all(**dict(kw, expanded=True), checkpoint=folder)
    with pytest.raises(superball.InputError, match="derive_all: checkpoint: expected a folder"):
        superball.derive_all(**kw, checkpoint=3)


def test_a_map_folder_is_one_run_for_the_command_and_the_module(paper, tmp_path):
    """map names its run the same way from both fronts (numeric::Axis::text(), the scene's content, the precision):
    a folder made by the command is finished by the module and the reverse, with the same results."""
    plain = superball.map(paper, X, Y, progress=False)
    reference = run_cli("map", PAPER, "--x", X, "--y", Y, "--json")[1]
    # Made by the command (the axes spelled otherwise: one run), read back whole by the module.
    folder = tmp_path / "from-command"
    code, out, err = run_cli("map", PAPER, "--x", "K.03-4=0.0:20:9", "--y", "alpha.2=-110:0:9", "--json", "--checkpoint", folder)
    assert code == 0 and out == reference and err == ""
    told = []
    same_map(superball.map(paper, X, Y, progress=lambda *a: told.append(a), checkpoint=folder), plain)
    points = len(tasks(folder / "points"))
    assert told[0] == ("points", points, points)  # nothing solved again
    # Made by the module, interrupted in its bisections, finished by the command.
    folder = tmp_path / "from-module"

    def stop(phase, done, total):
        if phase == "boundaries" and done >= 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        superball.map(paper, X, Y, progress=stop, checkpoint=folder)
    code, out, err = run_cli("map", PAPER, "--x", X, "--y", Y, "--json", "--checkpoint", folder)
    assert code == 0 and out == reference
    assert err.splitlines()[:2] == [f"superball: --checkpoint {folder / 'points'}: {points} of {points} tasks done already, 0 to compute",
                                    f"superball: --checkpoint {folder / 'boundaries'}: 3 of {len(tasks(folder / 'boundaries'))} tasks done already, "
                                    f"{len(tasks(folder / 'boundaries')) - 3} to compute"]
    # Both fronts check the other's files the same way, with the same words.
    path = folder / "points" / "task-00000000"
    text = path.read_bytes()
    path.write_bytes(text[:-2])
    code, out, err = run_cli("map", PAPER, "--x", X, "--y", Y, "--json", "--checkpoint", folder)
    said = err.splitlines()[0].removeprefix("superball: ")
    assert code == 0 and out == reference
    assert re.fullmatch(re.escape(f"--checkpoint {folder / 'points'}: task-00000000: cut short in task 0 (") + r".* left\); task 0 computed again", said)
    path.write_bytes(text[:-2])
    with pytest.warns(UserWarning) as warned:
        same_map(superball.map(paper, X, Y, progress=False, checkpoint=folder), plain)
    assert [str(w.message) for w in warned] == [said]
    # Another map is another run, refused by both with one message.
    code, out, err = run_cli("map", PAPER, "--x", X, "--y", "alpha.2=-110:0:10", "--json", "--checkpoint", folder, check=False)
    with pytest.raises(superball.InputError) as python:
        superball.map(paper, X, "alpha.2=-110:0:10", progress=False, checkpoint=folder)
    assert code == 2 and out == "" and err == f"superball: {python.value}\n"
    assert str(python.value).startswith(f"--checkpoint {folder / 'points'}: holds run ")


def test_derive_all_in_two_stages_with_a_checkpoint_is_the_one_process_derivation(tmp_path):
    # A finite obstacle at 5 bodies: with several workers {} and the four cases of one closed contact are derived
    # in two stages (symbolic::prepare_todo()), also when each case is kept in a checkpoint folder.
    kw = dict(bodies=5, pairs="near2", coupling="near2", obstacle="finite", progress=False)
    one = superball.derive_all(**kw, jobs=1)
    folder = tmp_path / "d"
    assert derived(superball.derive_all(**kw, jobs=2, checkpoint=folder)) == derived(one)
    assert tasks(folder) == [f"task-{k:08d}" for k in range(len(one))]
    assert derived(superball.derive_all(**kw, jobs=2, checkpoint=folder)) == derived(one)  # read back
