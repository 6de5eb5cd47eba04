"""Bad scenes from Python: shpb.InputError carrying the command's own one-line message, and
nothing written."""
import copy
import json
import os

import pytest

import shpb
from conftest import SOURCE, run_command, scene_dir


def command_message(path):
    """The command's error line for a scene file, without main's "error: " prefix."""
    code, _, err = run_command("validate", path)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("error: ")
    return lines[0][len("error: "):]


def edits():
    def length(d): d["bars"][2]["length"] = "-5 mm"
    def key(d): d["bars"][0]["velocty"] = "15 m/s"
    def material(d): d["bars"][1]["material"] = "steel-c305"
    def kind(d): d["simulation"]["duration"] = "800 kg"
    def courant(d): d["simulation"]["courant"] = 1.5
    def gauge(d): d["bars"][1]["gauges"][0]["position"] = "3 m"
    return [length, key, material, kind, courant, gauge]


@pytest.mark.parametrize("edit", edits(), ids=lambda e: e.__name__)
def test_a_bad_dict_raises_the_commands_message(edit, tmp_path, classic_json):
    folder = scene_dir(tmp_path, "classic-al6061")
    bad = copy.deepcopy(classic_json)
    edit(bad)
    path = folder / "bad.json"
    path.write_text(json.dumps(bad))
    expected = command_message(path)
    path.unlink()
    before = sorted(os.walk(tmp_path))
    with pytest.raises(shpb.InputError) as e:
        run = shpb.simulate(shpb.Scene.from_dict(bad, file=path))
    assert str(e.value) == expected
    assert isinstance(e.value, ValueError)
    assert sorted(os.walk(tmp_path)) == before  # nothing written


def test_a_good_dict_is_the_scene_file(tmp_path, classic_json):
    folder = scene_dir(tmp_path, "classic-al6061")
    a = shpb.simulate(shpb.Scene.from_dict(classic_json, file=folder / "scene.json"))
    b = shpb.simulate(shpb.Scene.load(SOURCE / "experiments" / "classic-al6061" / "scene.json"))
    assert a.gauges["incident"].tolist() == b.gauges["incident"].tolist()


@pytest.mark.parametrize("value, shown", [
    (float("nan"), "nan"), (float("inf"), "inf"), (-float("inf"), "-inf")])
def test_not_json_is_an_input_error(value, shown, classic_json):
    """A number no JSON file can hold: the reader's one line naming the file, path and value."""
    classic_json["bars"][1]["gauges"][0]["position"] = value
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.from_dict(classic_json, file="lab/scene.json")
    message = str(e.value)
    assert "\n" not in message
    file = os.path.join(os.getcwd(), "lab", "scene.json")  # anchored where the dict was read
    assert message.startswith(f"{file}: bars[1].gauges[0].position: {shown}: ")


def test_a_bad_tolerance_is_the_commands_message(tmp_path):
    scene = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    code, _, err = run_command("simulate", scene, "-o", tmp_path / "out", "--tolerance", "150 %")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.simulate(scene, tolerance="150 %")
    assert "error: " + str(e.value) == err.strip()
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("edit", [
    lambda s: setattr(s.bars[1], "length_m", -1.0),
    lambda s: setattr(s.bars[1], "gap_m", -0.001),
    lambda s: setattr(s.striker, "velocity_m_s", float("nan")),
    lambda s: setattr(s.bars[1], "elements", -5),
    lambda s: setattr(s.bars[1].material, "density_kg_m3", 0.0),
    lambda s: setattr(s.bars[1].material, "poisson_ratio", 0.7),
    lambda s: setattr(s.specimen.material.johnson_cook, "n", 1.5),
    lambda s: setattr(s, "duration_s", -1e-3),
    lambda s: setattr(s, "tolerance", 1.5),
    lambda s: setattr(s, "tolerance", "-1 %"),
    lambda s: setattr(s, "tolerance", float("nan")),
    # Rules between values (model/input_limits.hpp): each value in its range, the pair not. The
    # incident bar cut to 0.5 m left its gauge at 1 m off the bar, and the run went on; a room
    # temperature above melting made the homologous temperature negative.
    lambda s: setattr(s.bars[1], "length_m", 0.5),
    lambda s: setattr(s.specimen.material.johnson_cook, "room_temperature_K", 2000.0),
    lambda s: setattr(s.specimen.material.johnson_cook, "melting_temperature_K", 100.0),
    lambda s: setattr(s.specimen.material.johnson_cook, "initial_temperature_K", 2000.0),
    # The gap is to the next bar: the last bar's was kept and never used (the file refuses it).
    lambda s: setattr(s.bars[-1], "gap_m", 0.01),
], ids=["length", "gap", "velocity", "elements", "density", "poisson", "jc-n", "duration",
        "tolerance-150%", "tolerance-negative", "tolerance-nan", "gauge-off-bar",
        "room-above-melting", "melting-below-room", "test-above-melting", "gap-after-last-bar"])
def test_an_edit_outside_the_scene_files_range_is_refused(edit):
    # A value no scene file could hold is refused when it is set, and the scene keeps its value.
    scene = shpb.Scene.load(SOURCE / "experiments" / "classic-al6061" / "scene.json")
    before = shpb.simulate(scene).gauges["incident"].tolist()
    with pytest.raises(shpb.InputError):
        edit(scene)
    assert shpb.simulate(scene).gauges["incident"].tolist() == before


@pytest.mark.parametrize("experiment, edit, message", [
    # A viscoelastic material has no youngs_modulus of its own (its instantaneous modulus is
    # E_inf + its arms'): PMMA set to 1 GPa meshed its specimen for a 1 GPa wave speed while the
    # law stayed at 5.7 GPa, and the run blew up (engineering strain 13.3 in an element).
    ("lanl-pmma13-mini-kolsky", lambda s: setattr(s.specimen.material, "youngs_modulus_Pa", 1e9),
     "material.youngs_modulus_Pa: 1000000000.0: material "),
    # A bilinear law hardens below its elastic modulus (the reader's tangent_modulus < E): a
    # tangent modulus of 80 GPa on a 70 GPa metal, or the metal's modulus cut below its 2 GPa
    # tangent, ran with no word.
    ("tension-bonded",
     lambda s: setattr(s.specimen.material.bilinear, "tangent_modulus_Pa", 80e9),
     "bilinear.tangent_modulus_Pa: 8e+10: must be >= 0 and < youngs_modulus (7e+10 Pa)"),
    ("tension-bonded", lambda s: setattr(s.specimen.material, "youngs_modulus_Pa", 1e9),
     "material.youngs_modulus_Pa: 1e+09: bilinear.tangent_modulus_Pa 2e+09 must be >= 0 and < "
     "youngs_modulus (1e+09 Pa)"),
], ids=["viscoelastic-modulus", "tangent-above-modulus", "modulus-below-tangent"])
def test_a_modulus_no_material_file_could_hold_is_refused(experiment, edit, message):
    scene = shpb.Scene.load(SOURCE / "experiments" / experiment / "scene.json")
    material = scene.specimen.material
    before = repr(material), repr(material.bilinear)
    with pytest.raises(shpb.InputError) as e:
        edit(scene)
    assert str(e.value).startswith("scene edit: " + message)
    assert (repr(material), repr(material.bilinear)) == before


def test_adiabatic_heating_is_a_boolean_and_needs_a_specific_heat(classic_json):
    # A material that is not adiabatic need not give its specific heat (docs/scene-format.md);
    # adiabatic set True on one ran with a specific heat of 900 J/(kg K) no file had given, and
    # a text or a number was pybind11's RuntimeError "Unable to cast".
    material = json.loads((SOURCE / "specimens" / "al6061-t6.json").read_text())
    material["adiabatic"] = False
    del material["specific_heat"]
    classic_json["materials"]["cold"] = material
    classic_json["bars"][2]["material"] = "cold"
    scene = shpb.Scene.from_dict(classic_json, file=SOURCE / "experiments" / "classic-al6061" /
                                 "scene.json")
    jc = scene.specimen.material.johnson_cook
    for value in ["no", 1]:
        with pytest.raises(TypeError, match="johnson_cook.adiabatic: "):
            jc.adiabatic = value
    with pytest.raises(shpb.InputError, match="needs the material's specific heat"):
        jc.adiabatic = True
    assert jc.adiabatic is False
    jc.specific_heat_J_kgK = 885
    jc.adiabatic = True
    assert jc.adiabatic is True


@pytest.mark.parametrize("bar, group, attribute, value, law", [
    ("specimen", "bilinear", "yield_stress_Pa", 300e6, "johnson-cook"),
    ("specimen", "bilinear", "tangent_modulus_Pa", 1e9, "johnson-cook"),
    ("incident", "bilinear", "yield_stress_Pa", 300e6, "elastic"),
    ("incident", "johnson_cook", "A_Pa", 300e6, "elastic"),
    ("incident", "johnson_cook", "adiabatic", False, "elastic"),
], ids=["bilinear-on-jc", "tangent-on-jc", "bilinear-on-elastic", "jc-on-elastic",
        "adiabatic-on-elastic"])
def test_a_parameter_of_another_law_is_refused(bar, group, attribute, value, law):
    # A material is read with the keys of its own law only (docs/scene-format.md): a parameter of
    # another law was kept and never used (a bilinear yield stress set on a Johnson-Cook specimen
    # changed nothing). Refused when set, naming the attribute and the material's law.
    scene = shpb.Scene.load(SOURCE / "experiments" / "classic-al6061" / "scene.json")
    material = scene.bar(bar).material
    assert material.model == law
    with pytest.raises(shpb.InputError) as e:
        setattr(getattr(material, group), attribute, value)
    message = str(e.value)
    assert "\n" not in message
    assert message.startswith(f"scene edit: {group}.{attribute}: ")
    assert f" is {law}: " in message
    # The group of the material's own law is still edited.
    shaper = shpb.Scene.load(SOURCE / "experiments" / "pulse-shaper" / "scene.json")
    bilinear = next(b.material for b in shaper.bars if b.material.model == "bilinear")
    bilinear.bilinear.yield_stress_Pa = 120e6
    assert bilinear.bilinear.yield_stress_Pa == 120e6


@pytest.mark.parametrize("call, option", [
    (lambda: shpb.study(SOURCE / "experiments" / "striker-on-bar" / "scene.json",
                        sweep="stability", refine=0), "--refine"),
    (lambda: shpb.study(SOURCE / "experiments" / "striker-on-bar" / "scene.json",
                        sweep="stability", refine=65), "--refine"),
    (lambda: shpb.process(SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json", draws=1),
     "--draws"),
    # 0 draws is no Monte Carlo: refused as the command refuses --draws 0 (it was read as "not
    # given" and ran the default 200 draws).
    (lambda: shpb.study(SOURCE / "experiments" / "striker-on-bar" / "scene.json",
                        sweep="monte-carlo", distributions=SOURCE / "experiments" / "classic-al6061"
                        / "distributions.json", draws=0), "--draws"),
    (lambda: shpb.dispersion(max_a_over_lambda=0), "--max-a-over-lambda"),
    (lambda: shpb.dispersion(points=1000001), "--points"),
    # A list is the table: a size given with it was ignored.
    (lambda: shpb.dispersion(a_over_lambda=[0.1], points=5), "--points"),
    # --threads is a whole number >= 0 (0: all cores); -1 was taken as all cores, or ignored.
    (lambda: shpb.simulate(SOURCE / "experiments" / "striker-on-bar" / "scene.json", threads=-1),
     "--threads"),
    (lambda: shpb.study(SOURCE / "experiments" / "striker-on-bar" / "scene.json",
                        sweep="stability", threads=-1), "--threads"),
], ids=["refine-0", "refine-65", "draws-1", "study-draws-0", "max-a-over-lambda-0", "points-1000001",
        "list-and-points",
        "simulate-threads--1", "study-threads--1"])
def test_an_option_outside_the_commands_range_is_an_input_error(call, option):
    # The range the command's option parser gives the option holds from Python too: refused before
    # any work, in one line naming the option (not a run of a grid of 0, a MemoryError, a
    # "0 of 1 draws failed" or a table of zeros).
    with pytest.raises(shpb.InputError) as e:
        call()
    message = str(e.value)
    assert "\n" not in message
    assert message.startswith(option + ": ")


CLASSIC = SOURCE / "experiments" / "classic-al6061" / "scene.json"
LANL = SOURCE / "experiments" / "lanl-cu-ofe-273k"
BAR = SOURCE / "experiments" / "striker-on-bar" / "scene.json"


@pytest.mark.parametrize("args, call", [
    (["simulate", BAR, "--courant", "0.9x"], lambda: shpb.simulate(BAR, courant="0.9x")),
    (["simulate", BAR, "--contact", "bonded"], lambda: shpb.simulate(BAR, contact="bonded")),
    (["simulate", BAR, "--stepping", "implicit"], lambda: shpb.simulate(BAR, stepping="implicit")),
    (["simulate", BAR, "--tolerance", "one"], lambda: shpb.simulate(BAR, tolerance="one")),
    (["simulate", BAR, "--threads", "-1"], lambda: shpb.simulate(BAR, threads=-1)),
    (["study", BAR, "--sweep", "grid"], lambda: shpb.study(BAR, sweep="grid")),
    (["study", BAR, "--refine", "0", "--sweep", "stability"],
     lambda: shpb.study(BAR, sweep="stability", refine=0)),
    (["process", LANL / "scene.json", "--draws", "1"],
     lambda: shpb.process(LANL / "scene.json", draws=1)),
    # The option before the scene's own error (no measurement), as the command reports it.
    (["process", CLASSIC, "--draws", "1"], lambda: shpb.process(CLASSIC, draws=1)),
    (["fit", LANL / "campaign.json", "--relative-step", "1"],
     lambda: shpb.fit(LANL / "campaign.json", relative_step=1)),
    (["fit", LANL / "campaign.json", "--max-iterations", "0"],
     lambda: shpb.fit(LANL / "campaign.json", max_iterations=0)),
    (["dispersion", "--poisson", "0.29", "--points", "1"], lambda: shpb.dispersion(points=1)),
], ids=["courant", "contact", "stepping", "tolerance", "threads", "sweep", "refine", "draws",
        "draws-before-the-scene", "relative-step", "max-iterations", "points"])
def test_an_options_error_is_the_commands_line_word_for_word(args, call, tmp_path):
    # Where the command's parser checked an option (CLI11), the module checked it again in other
    # words ("--draws: Value 1 not in range 2 to 10000000 (see shpb --help)" against "--draws: 1:
    # expected 2 to 10000000"; "contact: ..." against "--contact: bonded not in {...}"), and
    # process(draws=1) of a scene without measurement named the measurement where the command
    # named --draws. One check now, the library's, which both call first.
    output = [] if args[0] == "dispersion" else ["-o", tmp_path / "out"]
    code, _, err = run_command(*args, *output)
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        call()
    assert err.strip() == "error: " + str(e.value)


def test_a_courant_number_as_text_is_read_as_the_command_reads_it(tmp_path):
    # --courant 0.9 is text on the command line; courant="0.9" was a TypeError.
    as_text = shpb.simulate(BAR, courant="0.9").arrays("gauges")
    as_number = shpb.simulate(BAR, courant=0.9).arrays("gauges")
    for name in as_number:
        assert (as_text[name] == as_number[name]).all(), name
    assert run_command("simulate", BAR, "--courant", "90 %", "-o", tmp_path / "cmd")[0] == 0
    command = json.loads((tmp_path / "cmd" / "summary.json").read_text(encoding="utf-8"))
    python = shpb.simulate(BAR, courant="90 %").summary
    assert [b["courant"] for b in python["bars"]] == [b["courant"] for b in command["bars"]]
