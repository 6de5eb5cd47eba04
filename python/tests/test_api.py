"""What a notebook meets of the module's surface (docs/python.md, Reference): the names it shows,
results only the functions make, and the scene values and options of the command it may set, each
as the scene file or the command line gives it."""
import json

import numpy as np
import pytest

import shpb
from conftest import SOURCE, run_command, scene_dir

CLASSIC = SOURCE / "experiments" / "classic-al6061" / "scene.json"
PMMA = SOURCE / "experiments" / "lanl-pmma13-mini-kolsky" / "scene.json"
LANL = SOURCE / "experiments" / "lanl-cu-ofe-273k" / "scene.json"


def test_dir_shows_the_api_only():
    # os, shutil and tempfile were imported under their own names: shpb.os was a public name.
    public = {n for n in dir(shpb) if not n.startswith("_")}
    assert public == set(shpb.__all__), sorted(public ^ set(shpb.__all__))


@pytest.mark.parametrize("cls, function", [(shpb.SimulationResult, "simulate"),
                                           (shpb.ProcessResult, "process"),
                                           (shpb.BarCheckResult, "process"),
                                           (shpb.PlanResult, "plan")])
def test_a_result_is_made_by_its_function_not_by_hand(cls, function):
    # SimulationResult(None) was an object whose every attribute raised AttributeError.
    with pytest.raises(TypeError, match=f"what shpb.{function}\\(\\) returns"):
        cls(None)


def gauges_of(scene):
    return {k: np.asarray(v) for k, v in shpb.simulate(scene).arrays("gauges").items()}


def same_run(edited, from_file):
    a, b = gauges_of(edited), gauges_of(from_file)
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def test_radial_inertia_is_the_scene_files_inertia(classic_json):
    # A Johnson-Cook specimen: the closed form of its radial inertia (docs/methods.md §8.2).
    edited = shpb.Scene.load(CLASSIC)
    assert edited.specimen.inertia is False
    edited.specimen.inertia = True
    classic_json["bars"][2]["inertia"] = True
    same_run(edited, shpb.Scene.from_dict(classic_json, file=str(CLASSIC)))


def test_radial_inertia_is_refused_where_the_file_refuses_it(tmp_path):
    # The reader's rule, one function for both (radial_inertia_problem): the same words. Bar 1 is
    # elastic, bar 0 too (and not squeezed).
    folder = scene_dir(tmp_path, "classic-al6061")
    for bar in (0, 1):
        scene = shpb.Scene.load(CLASSIC)
        with pytest.raises(shpb.InputError) as edit:
            scene.bars[bar].inertia = True
        assert scene.bars[bar].inertia is False  # unchanged
        d = json.loads(CLASSIC.read_text())
        d["bars"][bar]["inertia"] = True
        (folder / "scene.json").write_text(json.dumps(d))
        code, _, err = run_command("validate", folder / "scene.json")
        assert code == 2
        constraint = str(edit.value).split("scene edit: bar.inertia: True: ", 1)[1]
        assert err.strip() == f"error: {folder / 'scene.json'}: bars[{bar}].inertia: true: {constraint}"
    with pytest.raises(TypeError, match="bar.inertia: 1: expected True or False"):
        shpb.Scene.load(CLASSIC).specimen.inertia = 1


def test_a_bar_diameter_is_the_files(classic_json):
    edited = shpb.Scene.load(CLASSIC)
    edited.specimen.diameter_m = 0.008
    assert edited.specimen.area_m2 == pytest.approx(np.pi * 0.008**2 / 4, rel=1e-15)
    classic_json["bars"][2]["diameter"] = "8 mm"
    a = gauges_of(edited)
    b = gauges_of(shpb.Scene.from_dict(classic_json, file=str(CLASSIC)))
    # The area scaled by (d/d0)^2 against pi d^2/4: equal to a few ulps, and so the runs.
    for k in a:
        np.testing.assert_allclose(a[k], b[k], rtol=1e-9, atol=1e-9 * np.abs(b[k]).max(), err_msg=k)
    with pytest.raises(shpb.InputError, match="bar.diameter_m: 0: must be > 0"):
        edited.specimen.diameter_m = 0


def test_a_johnson_cook_strain_rate_filter_is_the_files():
    edited = shpb.Scene.load(CLASSIC)
    jc = edited.specimen.material.johnson_cook
    assert jc.strain_rate_filter_s is None  # the default: half the specimen's transit
    jc.strain_rate_filter_s = 0  # off
    d = json.loads(CLASSIC.read_text())
    specimen = json.loads((SOURCE / "specimens" / "al6061-t6.json").read_text())
    specimen["strain_rate_filter"] = "0 s"
    d["bars"][2]["material"] = specimen
    same_run(edited, shpb.Scene.from_dict(d, file=str(CLASSIC)))
    jc.strain_rate_filter_s = None
    same_run(edited, shpb.Scene.load(CLASSIC))
    with pytest.raises(shpb.InputError, match="strain_rate_filter_s: -1e-06: must be >= 0"):
        jc.strain_rate_filter_s = -1e-6
    with pytest.raises(shpb.InputError, match="applies only to a johnson-cook material"):
        edited.bars[1].material.johnson_cook.strain_rate_filter_s = 0


def test_a_viscoelastic_laws_moduli_are_the_files():
    edited = shpb.Scene.load(PMMA)
    v = edited.specimen.material.viscoelastic
    assert v.long_term_modulus_Pa == 3.0e9
    assert v.arms == [{"modulus_Pa": 1.5e9, "relaxation_time_s": 1e-3},
                      {"modulus_Pa": 1.2e9, "relaxation_time_s": pytest.approx(20e-6, rel=1e-15)}]
    v.set_arm(1, modulus_Pa=2.4e9, relaxation_time_s=40e-6)
    v.long_term_modulus_Pa = 2.5e9
    # E0 = E_inf + sum of the arms' moduli, as the reader derives it.
    assert edited.specimen.material.youngs_modulus_Pa == 2.5e9 + 1.5e9 + 2.4e9
    d = json.loads(PMMA.read_text())
    material = json.loads((SOURCE / "specimens" / "pmma.json").read_text())
    material["long_term_modulus"] = "2.5 GPa"
    material["arms"][1] = {"modulus": "2.4 GPa", "relaxation_time": "40 us"}
    d["bars"][2]["material"] = material
    same_run(edited, shpb.Scene.from_dict(d, file=str(PMMA)))
    with pytest.raises(shpb.InputError, match="has 2 arms: expected an index below that"):
        v.set_arm(2, modulus_Pa=1e9)
    with pytest.raises(shpb.InputError, match="relaxation_time_s: 0: must be > 0"):
        v.set_arm(0, modulus_Pa=1e9, relaxation_time_s=0)
    assert v.arms[0]["modulus_Pa"] == 1.5e9  # a refused edit changes nothing
    with pytest.raises(shpb.InputError, match="applies only to a viscoelastic material"):
        edited.bars[1].material.viscoelastic.long_term_modulus_Pa = 1e9


def test_process_threads_are_the_commands(tmp_path):
    # The draws do not depend on the threads that run them (one seed, one draw per index).
    one = shpb.process(LANL, draws=20, threads=1).summary["uncertainty"]["figures"]
    two = shpb.process(LANL, draws=20, threads=2).summary["uncertainty"]["figures"]
    assert one == two
    with pytest.raises(shpb.InputError) as e:
        shpb.process(LANL, draws=20, threads=-1)
    code, _, err = run_command("process", LANL, "-o", tmp_path / "out", "--threads", "-1")
    assert code == 2 and err.strip() == f"error: {e.value}"
