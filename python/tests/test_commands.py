"""compare, dispersion, study and fit from Python: the command's own function, so the command's
files."""
import gc
import json
import os
import shutil

import numpy as np
import pytest

import shpb
from conftest import SOURCE, columns, read_csv, run_command


def test_dispersion_is_the_commands_table(tmp_path):
    code, _, err = run_command("dispersion", "--poisson", "0.3", "--points", "41",
                               "--radius", "0.01", "--c0", "5000", "-o", tmp_path / "d.csv")
    assert code == 0, err
    expected = read_csv(tmp_path / "d.csv")
    got = columns(shpb.dispersion(poisson=0.3, points=41, radius_m=0.01, c0_m_s=5000))
    assert list(got) == list(expected)
    for name in expected:
        assert np.array_equal(got[name], expected[name]), name


def test_a_bad_dispersion_option_is_the_commands_message(tmp_path):
    code, _, err = run_command("dispersion", "--poisson", "0.29", "--radius", "0.01", "-o", tmp_path / "d.csv")
    assert code == 2
    try:
        shpb.dispersion(radius_m=0.01)
    except shpb.InputError as e:
        assert "error: " + str(e) == err.strip()
    else:
        raise AssertionError("no InputError")


def test_compare_saves_the_commands_folder(tmp_path):
    scene = SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json"
    assert run_command("compare", scene, "-o", tmp_path / "cmd", "--quiet")[0] == 0
    result = shpb.compare(scene)
    assert result.exit_code == 0
    result.save(tmp_path / "py")
    for name in same_folder(tmp_path / "cmd", tmp_path / "py", result, timing=()):
        if name.endswith(".csv"):
            assert (tmp_path / "cmd" / name).read_bytes() == (tmp_path / "py" / name).read_bytes()


def test_a_compare_run_from_the_scenes_folder_saves_beside_it(tmp_path, monkeypatch):
    # A lab's run from the scene's folder, by relative names: the command writes its folder there;
    # result.save refused it, a channel read from the measurement's file having been declared as
    # an empty path, "." in Python: the current folder, an input.
    folder = tmp_path / "lanl"
    shutil.copytree(SOURCE / "experiments" / "lanl-cu-ofe-273k", folder)
    monkeypatch.chdir(folder)
    assert run_command("compare", "scene.json", "-o", "cmd", "--quiet")[0] == 0
    result = shpb.compare("scene.json")
    result.save("py")
    same_folder(folder / "cmd", folder / "py", result, timing=())


def test_compare_takes_the_striker_velocity_as_the_option_does(tmp_path):
    # --striker-velocity takes a velocity with its unit ("15 m/s"); compare(striker_velocity=...)
    # took a number only: the option's text was a TypeError.
    scene = SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json"
    assert run_command("compare", scene, "-o", tmp_path / "cmd", "--quiet",
                       "--striker-velocity", "15 m/s")[0] == 0
    result = shpb.compare(scene, striker_velocity="15 m/s")
    assert result.summary["striker_velocity_m_s"] == 15
    result.save(tmp_path / "py")
    same_folder(tmp_path / "cmd", tmp_path / "py", result, timing=())
    code, _, err = run_command("compare", scene, "-o", tmp_path / "bad", "--striker-velocity",
                               "15 kg")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.compare(scene, striker_velocity="15 kg")
    assert "error: " + str(e.value) == err.strip()


def same_folder(cmd, py, result, timing=("wall_time",)):
    """The command's folder and result.save's hold the same files; their CSV tables are equal
    column by column apart from measured times (a column whose name holds a `timing` word, and
    the Pareto front over wall time, which is read from them)."""
    names = sorted(p.name for p in cmd.iterdir())
    assert names == sorted(p.name for p in py.iterdir())
    for name in (n for n in names if n.endswith(".csv")):
        expected = read_csv(cmd / name)
        got = columns(result.tables[name[:-4]])
        assert list(got) == list(expected), name
        for column in expected:
            if any(word in column for word in timing):
                continue
            np.testing.assert_array_equal(np.asarray(got[column]), np.asarray(expected[column]),
                                          err_msg=f"{name}: {column}")
    return names


def test_study_is_the_commands_sweep(tmp_path):
    # Accuracy against cost on the striker on a bar (exact reference): every method and step.
    scene = SOURCE / "experiments" / "striker-on-bar" / "scene.json"
    assert run_command("study", scene, "-o", tmp_path / "cmd", "--quiet")[0] == 0
    result = shpb.study(scene)
    assert result.exit_code == 0
    result.save(tmp_path / "py")
    assert "pareto.csv" in same_folder(tmp_path / "cmd", tmp_path / "py", result)


def test_fit_is_the_commands_fit(tmp_path):
    # The LANL copper campaign: the fitted material equals the command's, parameter by parameter.
    campaign = SOURCE / "experiments" / "lanl-cu-ofe-273k" / "campaign.json"
    # Without the bootstrap's refits (their own tests: tests/fit): the fit itself, in seconds.
    assert run_command("fit", campaign, "-o", tmp_path / "cmd", "--quiet", "--bootstrap", "0")[0] == 0
    result = shpb.fit(campaign, bootstrap=0)
    assert result.exit_code == 0
    result.save(tmp_path / "py")
    same_folder(tmp_path / "cmd", tmp_path / "py", result)
    # fit.json is the fitted material file: the same parameters, to the last digit.
    assert result.json["fit"] == json.loads((tmp_path / "cmd" / "fit.json").read_text())


def test_a_monte_carlo_study_is_the_commands(tmp_path):
    # The planned test's uncertainty: the scene values of distributions.json drawn and simulated,
    # bands on the gauges and the curve; two draws are enough to compare the files.
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    distributions = SOURCE / "experiments" / "classic-al6061" / "distributions.json"
    assert run_command("study", scene, "-o", tmp_path / "cmd", "--quiet", "--sweep", "monte-carlo",
                       "--distributions", distributions, "--draws", "2", "--seed", "7")[0] == 0
    result = shpb.study(scene, sweep="monte-carlo", distributions=distributions, draws=2, seed=7)
    assert result.exit_code == 0
    result.save(tmp_path / "py")
    assert "draws.csv" in same_folder(tmp_path / "cmd", tmp_path / "py", result)


def test_save_refuses_a_folder_holding_an_input_as_the_command_does(tmp_path):
    # A fit started from a previous fit.json (the documented way to refine one), saved over that
    # fit's folder: the command refuses it (exit 2), result.save replaced the folder and so
    # deleted the starting material.
    lanl = SOURCE / "experiments" / "lanl-cu-ofe-273k"
    first = tmp_path / "first"
    fast = ("--max-iterations", "1", "--bootstrap", "0", "--quiet")
    assert run_command("fit", lanl / "campaign.json", "-o", first, *fast)[0] == 0
    campaign = json.loads((lanl / "campaign.json").read_text(encoding="utf-8"))
    campaign["material"] = str(first / "fit.json")
    campaign["tests"][0]["scene"] = str(lanl / "scene.json")
    again = tmp_path / "again.json"
    again.write_text(json.dumps(campaign), encoding="utf-8")
    before = {p.name: p.read_bytes() for p in first.iterdir()}
    code, _, err = run_command("fit", again, "-o", first, *fast)
    assert code == 2 and "input" in err
    result = shpb.fit(again, max_iterations=1, bootstrap=0)
    try:
        result.save(first)
    except shpb.InputError as e:
        assert "error: " + str(e) == err.strip()
    else:
        raise AssertionError("saved over the folder holding the starting material")
    assert {p.name: p.read_bytes() for p in first.iterdir()} == before


def test_a_result_removes_its_own_temporary_folder_and_nothing_else(tmp_path):
    # A FolderResult read from a folder of the user's (its parent holding other files) removes
    # nothing when collected; the temporary folder compare ran into goes with its result.
    user = tmp_path / "results"
    (user / "x").mkdir(parents=True)
    (user / "keep.txt").write_text("the user's", encoding="utf-8")
    (user / "x" / "summary.json").write_text("{}", encoding="utf-8")
    result = shpb.FolderResult("compare", str(user / "x"), 0)
    assert result.summary == {}
    del result
    gc.collect()
    assert (user / "keep.txt").is_file() and (user / "x" / "summary.json").is_file()
    result = shpb.compare(SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json")
    temporary = result._folder
    assert result.tables and os.path.isdir(temporary)
    del result
    gc.collect()
    assert not os.path.exists(os.path.dirname(temporary))


def printed_warnings(err):
    """The `warning: ` lines a command printed on stderr, without that prefix."""
    return [line[len("warning: "):] for line in err.splitlines() if line.startswith("warning: ")]


@pytest.mark.parametrize("command", ["compare", "fit", "simulate", "process"])
def test_every_warning_the_command_prints_reaches_a_notebook(command, tmp_path, capfd):
    # A notebook shows Python's warnings under the cell, not the library's stderr: compare's and
    # fit's warnings went there alone (compare: a striker velocity 2x the one the record shows;
    # fit: a solver stopped after one iteration, residuals 13x the noise), and a FolderResult
    # had no warnings. Each is now a shpb.ShpbWarning, in result.warnings, in the command's words.
    lanl = SOURCE / "experiments" / "lanl-cu-ofe-273k"
    if command == "compare":
        args, call = (lanl / "scene.json", "--striker-velocity", "40 m/s"), lambda: shpb.compare(
            lanl / "scene.json", striker_velocity="40 m/s")
    elif command == "fit":
        args, call = (lanl / "campaign.json", "--max-iterations", "1", "--bootstrap", "0"), \
            lambda: shpb.fit(lanl / "campaign.json", max_iterations=1, bootstrap=0)
    elif command == "process":  # a record rounded in time, at an implausible strain scale
        epoxy = SOURCE / "experiments" / "epoxy-resin-sample01" / "scene.json"
        args, call = (epoxy,), lambda: shpb.process(epoxy)
    else:  # a scene whose striker rests: "no bar has a velocity"
        scene = json.loads((SOURCE / "experiments" / "classic-al6061" / "scene.json").read_text())
        scene["bars"][0]["velocity"] = 0
        path = tmp_path / "experiments" / "still" / "scene.json"
        path.parent.mkdir(parents=True)
        path.write_text(json.dumps(scene), encoding="utf-8")
        (tmp_path / "specimens").symlink_to(SOURCE / "specimens")
        args, call = (path,), lambda: shpb.simulate(path)
    code, _, err = run_command(command, *args, "-o", tmp_path / "cmd")
    assert code == 0, err
    expected = printed_warnings(err)
    assert expected
    capfd.readouterr()
    with pytest.warns(shpb.ShpbWarning) as caught:
        result = call()
    assert result.warnings == expected
    assert [str(w.message) for w in caught] == expected
    assert all(w.filename == __file__ for w in caught)  # at the caller's line
    assert "warning" not in capfd.readouterr().err  # said once, not also on the process's stderr


def test_a_study_result_has_the_summarys_warnings(tmp_path):
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    distributions = SOURCE / "experiments" / "classic-al6061" / "distributions.json"
    result = shpb.study(scene, sweep="monte-carlo", distributions=distributions, draws=2, seed=7)
    assert result.warnings == result.summary["warnings"]


def test_a_study_planned_run_in_shards_and_merged_is_the_commands(tmp_path):
    # The striker's velocity drawn twice (three runs with the nominal one) on the striker on a
    # bar: planned, run in two shards and merged from Python, against the command's steps on
    # the same plan (a plan's runs are fixed when it is written: the merged tables are equal).
    scene = SOURCE / "experiments" / "striker-on-bar" / "scene.json"
    (tmp_path / "d.json").write_text('{"values": {"striker.velocity": {"normal": "2 %"}}}')
    planned = shpb.study(scene, sweep="monte-carlo", distributions=tmp_path / "d.json", draws=2,
                         plan=tmp_path / "plan")
    assert planned.json["plan"]["scene"] == str(scene)
    parts = [shpb.study(run=tmp_path / "plan", shard=f"{k}/2") for k in range(2)]
    # Every run exactly once over the two parts: runs 0 and 2 in 0/2, run 1 in 1/2.
    assert [len(p["results"]) for p in parts] == [2, 1]
    merged = shpb.study(merge=tmp_path / "plan")
    assert merged.exit_code == 0 and (tmp_path / "plan" / "result" / "draws.csv").is_file()
    for k in range(2):
        assert run_command("study", "--run", tmp_path / "plan", "--shard", f"{k}/2", "-q")[0] == 0
    code, _, err = run_command("study", "--merge", tmp_path / "plan", "-o", tmp_path / "cmd", "-q")
    assert code == 0, err
    merged.save(tmp_path / "py")
    assert "draws.csv" in same_folder(tmp_path / "cmd", tmp_path / "py", merged)
    # save(dir) refuses the plan's folder, which the merge read, as the command refuses -o there.
    with pytest.raises(shpb.InputError, match="input"):
        merged.save(tmp_path / "plan")


@pytest.mark.parametrize("call, words", [
    # A plan names its scene's file, which the runs read again: a Scene is saved first.
    (lambda t: shpb.study(shpb.Scene.load(SOURCE / "experiments" / "striker-on-bar" / "scene.json"),
                          plan=t / "p"), "scene.save(path)"),
    (lambda t: shpb.study(run=t / "p", shard=3), '"K/N"'),
    (lambda t: shpb.study(SOURCE / "experiments" / "striker-on-bar" / "scene.json",
                          output=t / "o"), "merge"),
    (lambda t: shpb.report(shpb.dispersion(points=3)), "expected a path"),
], ids=["scene-of-a-plan", "shard-3", "output-without-merge", "report-of-a-table"])
def test_a_wrong_type_of_a_step_is_one_line(call, words, tmp_path):
    with pytest.raises(TypeError) as e:
        call(tmp_path)
    assert "\n" not in str(e.value) and words in str(e.value)


def test_a_bad_step_is_the_commands_line(tmp_path):
    args = ["study", "--merge", tmp_path / "nowhere", "--sweep", "pareto"]
    code, _, err = run_command(*args)
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.study(merge=tmp_path / "nowhere", sweep="pareto")
    assert "error: " + str(e.value) == err.strip()


def test_report_draws_a_saved_folder_as_the_command_does(tmp_path):
    # The report of a saved simulation: the page and its figures, as `shpb report` writes them;
    # a folder holding no output is the command's line (exit 2) as an InputError.
    shpb.simulate(SOURCE / "experiments" / "striker-on-bar" / "scene.json").save(tmp_path / "run")
    page = shpb.report(tmp_path / "run")
    assert page == str(tmp_path / "run" / "report.html") and os.path.isfile(page)
    assert any(p.suffix == ".png" for p in (tmp_path / "run" / "figures").iterdir())
    (tmp_path / "empty").mkdir()
    code, _, err = run_command("report", tmp_path / "empty")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.report(tmp_path / "empty")
    assert "error: " + str(e.value) == err.strip()
