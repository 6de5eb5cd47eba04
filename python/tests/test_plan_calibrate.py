"""plan and calibrate from Python: the command's own functions (app/plan.cpp, app/calibrate.cpp),
so the command's folders, warnings and one-line messages."""
import json
import os
import warnings

import numpy as np
import pytest

import shpb
from conftest import SOURCE, columns, read_csv, run_command

CLASSIC = SOURCE / "experiments" / "classic-al6061"
# The cheap search of tests/plan (a free striker velocity, 10 % gauge errors): a fraction of a
# second.
FAST = ("--search-tolerance", "10 %", "--tolerance", "10 %", "--threads", "2", "-q")


def classic_with_plan(folder, velocity_bounds):
    """The classic scene with its striker's velocity free within `velocity_bounds`, its specimen
    material by absolute path (as tests/plan/test_plan.cpp writes it)."""
    scene = json.loads((CLASSIC / "scene.json").read_text(encoding="utf-8"))
    for bar in scene["bars"]:
        if "/" in bar["material"]:
            bar["material"] = os.path.normpath(CLASSIC / bar["material"])
    scene["plan"] = {"striker": {"velocity": list(velocity_bounds)}}
    file = folder / "scene.json"
    file.write_text(json.dumps(scene, indent=2), encoding="utf-8")
    return file


def files_of(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file())


def without_times(value):
    """A summary.json without its measured times (wall_time_s, run_time_s)."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if not k.endswith("time_s")}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def test_plan_saves_the_commands_folder(tmp_path):
    scene = classic_with_plan(tmp_path, ("2 m/s", "40 m/s"))
    code, _, err = run_command("plan", scene, "--rate", "2000 1/s", "-o", tmp_path / "cmd", *FAST)
    assert code == 0, err
    # The options as numbers or as the command's text.
    result = shpb.plan(scene, rate=2000, search_tolerance=0.1, tolerance="10 %", threads=2)
    result.save(tmp_path / "py")
    cmd, py = tmp_path / "cmd", tmp_path / "py"
    assert files_of(cmd) == files_of(py)
    for name in files_of(cmd):
        if name.endswith("summary.json"):  # measured times aside, the same summary
            assert without_times(json.loads((cmd / name).read_text())) == \
                without_times(json.loads((py / name).read_text())), name
        elif not name.startswith(".shpb-output"):  # the marker holds the summaries' digests
            assert (cmd / name).read_bytes() == (py / name).read_bytes(), name
    # The planned scene.json names the specimen's material from the folder it is written in.
    assert (py / "scene.json").read_text() == (cmd / "scene.json").read_text()
    # The tables are the CSV files, column by column.
    for name in ("path", "loading"):
        expected, got = read_csv(cmd / f"{name}.csv"), columns(result.tables[name])
        assert list(got) == list(expected), name
        for column in expected:
            np.testing.assert_array_equal(got[column], expected[column], err_msg=column)
    assert without_times(result.summary) == without_times(json.loads((cmd / "summary.json").read_text()))
    assert result.warnings == result.summary["warnings"]


def test_a_bad_plan_is_the_commands_message(tmp_path):
    scene = classic_with_plan(tmp_path, ("2 m/s", "40 m/s"))
    for option, keyword in ((("--rate", "0"), {"rate": 0}),
                            (("--rate", "2000", "--strain", "1.5"), {"rate": 2000, "strain": 1.5}),
                            (("--rate", "2000", "--tolerance", "150 %"), {"rate": 2000, "tolerance": 1.5}),
                            (("--rate", "2 m/s"), {"rate": "2 m/s"})):
        code, _, err = run_command("plan", scene, *option, "-o", tmp_path / "out")
        assert code == 2, err
        with pytest.raises(shpb.InputError) as e:
            shpb.plan(scene, **keyword)
        assert "error: " + str(e.value) == err.strip()
    # No set-up within the bounds: the command's exit 3, nothing written.
    slow = classic_with_plan(tmp_path, ("2 m/s", "5 m/s"))
    code, _, err = run_command("plan", slow, "--rate", "20000 1/s", "-o", tmp_path / "out", *FAST)
    assert code == 3 and "plan.striker.velocity" in err
    with pytest.raises(shpb.NumericalError) as e:
        shpb.plan(os.fspath(slow), rate="20000 1/s", search_tolerance="10 %", tolerance="10 %",
                  threads=2)
    assert "error: " + str(e.value) == err.strip()
    assert not (tmp_path / "out").exists()


C0, DT, SAMPLES, PEAK = 1.007 * 5000, 0.2e-6, 6500, 1e-3  # tests/fit/test_calibration.cpp's lab


def write_shots(folder):
    """A bars-apart and a bars-together shot of steel bars as tests/fit/test_calibration.cpp
    writes them (the incident gauge 12 mm off, the transmitter channel 1.5 % gain, 0.8 us late),
    the pulses moved without dispersion (numpy alone): the Poisson ratios then run to their
    bound and the solver stops at its iteration limit, a warning to carry."""
    t = np.arange(SAMPLES) * DT
    rng = np.random.default_rng(1)

    def pulse(delay):  # 10 us raised-cosine ramps around a 100 us plateau, from 20 us
        s = t - 20e-6 - delay
        v = np.where((s > 0) & (s < 10e-6), 0.5 * (1 - np.cos(np.pi * s / 10e-6)), 0.0)
        v = np.where((s >= 10e-6) & (s <= 110e-6), 1.0, v)
        v = np.where((s > 110e-6) & (s < 120e-6),
                     0.5 * (1 + np.cos(np.pi * (s - 110e-6) / 10e-6)), v)
        return -PEAK * v

    def record(ways, gain=1.0, delay=0.0):
        return gain * sum(sign * pulse(d / C0 + delay) for sign, d in ways) + \
            rng.normal(0, 0.003 * PEAK, SAMPLES)

    def write_csv(name, channels):
        np.savetxt(folder / name, np.column_stack([t, *channels.values()]), delimiter=",",
                   header=",".join(["time_s", *channels]), comments="", fmt="%.10g")

    xi, li, lt, xt = 1.012, 2.0, 1.5, 0.5
    write_csv("apart.csv", {"inc": record([(1, xi), (-1, 2 * li - xi), (1, 2 * li + xi),
                                           (-1, 4 * li - xi)])})
    write_csv("together.csv", {"inc": record([(1, xi)]),
                               "tr": record([(1, li + xt), (-1, li + 2 * lt - xt),
                                             (1, li + 2 * lt + xt)], 1.015, 0.8e-6)})

    def bar(name, length, gauge=None, position=None):
        b = {"name": name, "material": "steel", "length": f"{length} m", "diameter": "25 mm"}
        if gauge:
            b["gauges"] = [{"name": gauge, "position": f"{position} m"}]
        return b

    def scene(together, csv):
        bars = [bar("striker", 0.25), bar("incident", li, "inc", 1.0)]
        channels = [{"gauge": "inc", "column": "inc", "unit": "strain"}]
        if together:
            bars.append(bar("transmitter", lt, "tr", xt))
            channels.append({"gauge": "tr", "column": "tr", "unit": "strain"})
        return {"materials": {"steel": {"model": "elastic", "density": "7850 kg/m3",
                                        "youngs_modulus": "196.25 GPa", "poisson_ratio": 0.29}},
                "bars": bars, "measurement": {"file": csv, "channels": channels}}

    for name, together in (("apart", False), ("together", True)):
        (folder / f"{name}.json").write_text(json.dumps(scene(together, f"{name}.csv")))


def test_calibrate_saves_the_commands_folder(tmp_path, monkeypatch):
    # Run from the shots' folder with relative names, as a lab does; saved under it (a channel
    # read from its measurement's file was declared as an empty path, "." in Python: the current
    # folder, refused as an input).
    monkeypatch.chdir(tmp_path)
    write_shots(tmp_path)
    code, _, err = run_command("calibrate", "apart.json", "together.json", "-o", "cmd", "-q")
    assert code == 0, err
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = shpb.calibrate(["apart.json", "together.json"], threads=2)
    result.save("py")
    assert files_of(tmp_path / "cmd") == files_of(tmp_path / "py")
    for name in files_of(tmp_path / "cmd"):  # no measured time in calibrate's files
        assert (tmp_path / "cmd" / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    assert result.json["calibration"] == json.loads((tmp_path / "cmd" / "calibration.json").read_text())
    expected = read_csv(tmp_path / "cmd" / "shot-2.csv")
    got = columns(result.tables["shot-2"])
    assert list(got) == list(expected)
    for column in expected:
        np.testing.assert_array_equal(got[column], expected[column], err_msg=column)
    # Every warning the command prints, as a ShpbWarning and in result.warnings.
    printed = [line[len("warning: "):] for line in err.splitlines() if line.startswith("warning: ")]
    assert printed and result.warnings == printed
    assert [str(w.message) for w in caught if w.category is shpb.ShpbWarning] == printed


def test_a_bad_calibration_shot_is_the_commands_message(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_shots(tmp_path)
    # A scene with a specimen is a test, not a calibration shot.
    test = json.loads((tmp_path / "together.json").read_text())
    test["specimen"] = "transmitter"
    (tmp_path / "test.json").write_text(json.dumps(test))
    for scenes, threads in ((["test.json"], 0), (["apart.json"], -1)):
        code, _, err = run_command("calibrate", *scenes, "--threads", threads, "-o", "out")
        assert code == 2, err
        with pytest.raises(shpb.InputError) as e:
            shpb.calibrate(scenes, threads=threads)
        assert "error: " + str(e.value) == err.strip()
    assert not (tmp_path / "out").exists()


def test_calibrate_of_no_shot_is_the_commands_line_not_an_abort(tmp_path):
    # shpb.calibrate([]) reached the solver with nothing to fit, which aborted the interpreter (a
    # notebook's kernel died); the command refused it in its option parser. Both now say one line.
    import subprocess
    import sys
    code, _, err = run_command("calibrate", "-o", tmp_path / "cmd")
    assert code == 2
    p = subprocess.run([sys.executable, "-c",
                        "import shpb\ntry:\n    shpb.calibrate([])\nexcept shpb.InputError as e:"
                        "\n    print('error: ' + str(e))"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.strip() == err.strip()
    assert not (tmp_path / "cmd").exists()


def test_calibrate_of_scenes_names_their_files(tmp_path):
    # The shots as Scenes, one edited (its striker's length, which the fit does not read): calibration.json's
    # provenance and the warnings name their files, not the temporary copies they ran from.
    write_shots(tmp_path)
    apart, together = (shpb.Scene.load(tmp_path / f"{n}.json") for n in ("apart", "together"))
    together.bars[0].length_m = 0.3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", shpb.ShpbWarning)  # the fit's own, said by the test above
        result = shpb.calibrate([apart, together], threads=2)
    shots = result.json["calibration"]["provenance"]["shots"]
    assert [s["scene"] for s in shots] == [str(tmp_path / "apart.json"),
                                           f"{tmp_path / 'together.json'} (edited in Python)"]
    assert not any("/shpb-calibrate-" in w for w in result.warnings)


def test_plan_of_a_scene_names_its_file(tmp_path):
    # An edited Scene (its name) planned: summary.json names its file, as read back and as saved.
    file = classic_with_plan(tmp_path, ("2 m/s", "40 m/s"))
    scene = shpb.Scene.load(file)
    scene.name = "edited"
    result = shpb.plan(scene, rate=2000, search_tolerance=0.1, tolerance=0.1, threads=2)
    assert result.summary["scene"] == f"{file} (edited in Python)"
    result.save(tmp_path / "py")
    saved = json.loads((tmp_path / "py" / "summary.json").read_text())
    assert saved["scene"] == f"{file} (edited in Python)"
