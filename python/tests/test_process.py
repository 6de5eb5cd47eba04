"""shpb.process against `shpb process`: the curve of curve.csv to the bit, the command's folder."""
import json

import numpy as np
import pytest

import shpb
from conftest import SOURCE, columns, read_csv, run_command

MEASURED = ["lanl-cu-ofe-273k", "lanl-pmma13-mini-kolsky", "epoxy-resin-sample01"]


@pytest.mark.parametrize("experiment", MEASURED)
def test_curve_equals_the_commands_curve_csv_bit_for_bit(experiment, tmp_path):
    scene = SOURCE / "experiments" / experiment / "scene.json"
    code, _, err = run_command("process", scene, "-o", tmp_path / "cmd", "--quiet")
    assert code == 0, err
    result = shpb.process(shpb.Scene.load(scene))
    for table in ["curve", "pulses", "raw_signals"]:
        expected = read_csv(tmp_path / "cmd" / f"{table}.csv")
        got = columns(getattr(result, table))
        assert list(got) == list(expected)
        for name in expected:
            assert np.array_equal(got[name], expected[name], equal_nan=True), (table, name)
    assert result.summary == json.loads((tmp_path / "cmd" / "summary.json").read_text())


def test_save_writes_the_commands_folder(tmp_path):
    scene = SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json"
    assert run_command("process", scene, "-o", tmp_path / "cmd", "--quiet")[0] == 0
    shpb.process(scene).save(tmp_path / "py")
    names = sorted(p.name for p in (tmp_path / "cmd").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir())
    for name in names:
        assert (tmp_path / "cmd" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name


def test_simulated_signals_reduce_as_with_signals(tmp_path):
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    assert run_command("simulate", scene, "-o", tmp_path / "sim", "--quiet")[0] == 0
    assert run_command("process", scene, "-o", tmp_path / "cmd", "--quiet",
                       "--signals", tmp_path / "sim" / "gauges.csv")[0] == 0
    result = shpb.process(scene, signals=shpb.simulate(scene))
    expected = read_csv(tmp_path / "cmd" / "curve.csv")
    got = columns(result.curve)
    for name in expected:
        assert np.array_equal(got[name], expected[name]), name


def test_a_scene_without_measurement_is_the_commands_message(tmp_path):
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    code, _, err = run_command("process", scene, "-o", tmp_path / "cmd")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process(scene)
    assert "error: " + str(e.value) == err.strip()


@pytest.mark.parametrize("signals", [False, True], ids=["measurement", "signals"])
def test_a_scene_without_a_specimen_is_the_commands_message(signals, tmp_path):
    # striker-on-bar has no specimen and no measurement: the command refuses it as a bars-together
    # check without signals, and --signals as a test with no specimen. The module gave another
    # line for both.
    scene = SOURCE / "experiments" / "striker-on-bar" / "scene.json"
    gauges = tmp_path / "run" / "gauges.csv"
    extra = []
    if signals:
        assert run_command("simulate", scene, "-o", tmp_path / "run", "--quiet")[0] == 0
        extra = ["--signals", gauges]
    code, _, err = run_command("process", scene, "-o", tmp_path / "cmd", *extra)
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process(scene, signals=gauges if signals else None)
    assert "error: " + str(e.value) == err.strip()


def test_a_simulation_in_memory_is_named_as_such_not_by_a_temporary_file(tmp_path):
    # process(scene, signals=run) reads the run through a temporary gauges.csv, removed when the
    # call returns: summary.json (in memory and saved) and an error's line named that file, which
    # no longer exists.
    scene = shpb.Scene.load(SOURCE / "experiments" / "classic-al6061" / "scene.json")
    shown = f"the SimulationResult of {scene.file} (in memory)"
    result = shpb.process(scene, signals=shpb.simulate(scene))
    assert result.summary["signals"]["file"] == shown
    result.save(tmp_path / "out")
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["signals"]["file"] == shown
    # The epoxy scene gives no striker velocity: its simulated gauges hold no pulse.
    epoxy = shpb.Scene.load(SOURCE / "experiments" / "epoxy-resin-sample01" / "scene.json")
    with pytest.raises(shpb.InputError) as e:
        shpb.process(epoxy, signals=shpb.simulate(epoxy))
    assert str(e.value).startswith(f"the SimulationResult of {epoxy.file} (in memory): column ")


def test_a_scene_loaded_by_a_relative_path_processes_after_a_change_of_folder(tmp_path,
                                                                               monkeypatch):
    # A notebook loads "scene.json" from its folder, then changes folder (os.chdir, %cd): the
    # measured record, read when the scene is processed, is still found beside the scene.
    folder = SOURCE / "experiments" / "lanl-cu-ofe-273k"
    expected = shpb.process(shpb.Scene.load(folder / "scene.json"), draws=2).arrays("curve")
    monkeypatch.chdir(folder)
    scene = shpb.Scene.load("scene.json")
    monkeypatch.chdir(tmp_path)
    got = shpb.process(scene, draws=2).arrays("curve")
    for name in expected:
        assert np.array_equal(got[name], expected[name], equal_nan=True), name
