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


def bars_together(folder):
    """Two 20 mm steel bars pushed together, gauges 0.5 m into the first and 1.0 m into the
    second (2 m apart, c0 = 5000 m/s: 400 µs), no specimen. The far record is the near one
    delayed by exactly those 400 µs (4000 samples): a plain time shift reproduces it."""
    dt, samples, delay = 1e-7, 12000, 4000
    def trapezoid(i):  # a 100 µs pulse from 50 µs, 5 µs fronts, -1e-3
        t = i * dt * 1e6
        return -1e-3 * max(0.0, min(1.0, (t - 50) / 5, (155 - t) / 5))
    rows = ["time_s,near,far"] + [f"{i * dt!r},{trapezoid(i)!r},{trapezoid(i - delay)!r}"
                                  for i in range(samples)]
    (folder / "signals.csv").write_text("\n".join(rows) + "\n", encoding="utf-8")
    steel = {"model": "elastic", "density": 8000, "youngs_modulus": "200 GPa",
             "poisson_ratio": 0.29}
    scene = {"bars": [{"name": "a", "material": "steel", "length": "1.5 m", "diameter": "20 mm",
                       "gauges": [{"name": "near", "position": "0.5 m"}]},
                      {"name": "b", "material": "steel", "length": "1.5 m", "diameter": "20 mm",
                       "gauges": [{"name": "far", "position": "1.0 m"}]}],
             "materials": {"steel": steel},
             "measurement": {"file": "signals.csv", "time": {"column": "time_s", "unit": "s"},
                             "channels": [{"gauge": "near", "column": "near", "unit": "strain"},
                                          {"gauge": "far", "column": "far", "unit": "strain"}]}}
    path = folder / "scene.json"
    path.write_text(json.dumps(scene), encoding="utf-8")
    return path


def test_the_bars_together_check_is_the_commands(tmp_path):
    # `shpb process` of a scene without a specimen checks the bars together; process() raised
    # "name the specimen bar to reduce a test" for it. It returns the check now, the command's
    # folder byte for byte, and the delayed record is reproduced by the delay.
    scene = bars_together(tmp_path)
    code, _, err = run_command("process", scene, "-o", tmp_path / "cmd", "--quiet")
    assert code == 0, err
    result = shpb.process(scene)
    assert isinstance(result, shpb.BarCheckResult)
    assert result.summary["distance_m"] == pytest.approx(2.0)
    # A pure delay of a whole number of samples: what is left is round-off.
    rounding = 1e-12
    assert result.summary["rms_of_peak"]["time_shift"] < rounding
    pulses = result.arrays("pulses")
    assert np.allclose(pulses["far_time_shift"], pulses["far_measured"], rtol=0, atol=1e-15)
    result.save(tmp_path / "py")
    for name in ("pulses.csv", "summary.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cmd" / name).read_bytes()
    assert result.warnings == result.summary["warnings"]


@pytest.mark.parametrize("name", ["nope", "save", "scene", "summary"])
def test_arrays_of_a_name_that_is_no_table_is_a_key_error(name):
    # arrays(name) was getattr on the library's object: "nope" an AttributeError naming the
    # private class _Processing, "save" a bound method, "scene" a Scene, none of them columns.
    result = shpb.process(SOURCE / "experiments" / "lanl-pmma13-mini-kolsky" / "scene.json")
    with pytest.raises(KeyError, match="expected one of the tables curve, pulses, raw_signals"):
        result.arrays(name)
    assert set(result.arrays("curve")) == set(result.curve.columns)
