"""Scene.save and Scene.to_dict: an edited scene written as a scene file reads back as the same
scene and runs as it does; the commands that read a scene file take an edited Scene; validate; a
wrong type is a one-line TypeError."""
import filecmp
import json

import numpy as np
import pytest

import shpb
from conftest import SOURCE, read_csv, run_command, scene_dir

CLASSIC = SOURCE / "experiments" / "classic-al6061" / "scene.json"


def edited_classic():
    scene = shpb.Scene.load(CLASSIC)
    scene.striker.velocity_m_s = 12.0
    scene.bar("incident").material.youngs_modulus_Pa = 190e9  # a material shared by three bars
    scene.bar("specimen").material.johnson_cook.A_Pa = 290e6  # a material file's
    scene.bar("specimen").length_m = 0.006
    scene.duration_s = 9e-4
    return scene


def model(scene):
    """Every value of the scene the module shows, by attribute."""
    out = {"name": scene.name, "tolerance": scene.tolerance, "duration_s": scene.duration_s}
    for b in scene.bars:
        m = b.material
        out[b.name] = (b.length_m, b.area_m2, b.diameter_m, b.velocity_m_s, b.elements, b.gap_m,
                       b.inertia, b.gauges, m.model, m.density_kg_m3, m.youngs_modulus_Pa,
                       m.poisson_ratio, m.bilinear.yield_stress_Pa,
                       m.bilinear.tangent_modulus_Pa,
                       [getattr(m.johnson_cook, k) for k in dir(m.johnson_cook)
                        if not k.startswith("_")])
    return out


def test_saved_scene_reads_back_and_runs_byte_for_byte(tmp_path):
    scene = edited_classic()
    path = tmp_path / "elsewhere" / "edited.json"  # another folder: its material paths rebased
    scene.save(path)
    back = shpb.Scene.load(path)
    assert model(back) == model(scene)
    assert shpb.Scene.from_dict(scene.to_dict(), file=scene.file).striker.velocity_m_s == 12.0
    # Unedited bars keep their named material; the original file is untouched.
    written = json.loads(path.read_text())
    assert written["bars"][0]["material"] == "steel-c350"
    assert json.loads(CLASSIC.read_text())["bars"][0]["velocity"] == "15 m/s"
    shpb.simulate(scene).save(tmp_path / "python")
    code, _, err = run_command("simulate", path, "-o", tmp_path / "command", "-q")
    assert code == 0, err
    for name in ("gauges.csv", "interfaces.csv", "specimen.csv", "energy.csv", "field.csv"):
        assert filecmp.cmp(tmp_path / "python" / name, tmp_path / "command" / name, shallow=False)


def test_edited_striker_velocity_reaches_the_incident_pulse(tmp_path):
    # A striker on a bar of its own material and section gives the bar sigma = rho c v / 2, a
    # strain v / (2 c): the plateau of the incident gauge in the file's run.
    scene = shpb.Scene.load(CLASSIC)
    scene.striker.velocity_m_s = 9.0
    scene.save(tmp_path / "scene.json")
    code, _, err = run_command("simulate", tmp_path / "scene.json", "-o", tmp_path / "run", "-q")
    assert code == 0, err
    strain = -read_csv(tmp_path / "run" / "gauges.csv")["incident"]
    steel = scene.striker.material
    expected = 9.0 / (2 * steel.wave_speed_m_s)
    plateau = np.median(strain[strain > 0.5 * strain.max()])
    assert plateau == pytest.approx(expected, rel=0.01)  # the 1D model's plateau ripple
    assert shpb.validate(scene)["striker_velocity_m_s"] == 9.0


def test_a_command_reading_a_file_takes_an_edited_scene(tmp_path):
    folder = scene_dir(tmp_path, "lanl-cu-ofe-273k")
    scene = shpb.Scene.load(folder / "scene.json")
    scene.name = "edited in memory"
    run = shpb.compare(scene, dispersion=False)
    scene.save(tmp_path / "saved.json")
    saved = shpb.compare(tmp_path / "saved.json", dispersion=False)
    for name, table in saved.tables.items():
        for column in table:
            a, b = np.asarray(run.tables[name][column]), np.asarray(table[column])
            if a.dtype == object:
                assert list(a) == list(b)
            else:
                assert np.array_equal(a, b, equal_nan=True)
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        p.name for p in (SOURCE / "experiments" / "lanl-cu-ofe-273k").iterdir())


def test_save_replaces_no_file_it_should_not(tmp_path):
    folder = scene_dir(tmp_path, "lanl-cu-ofe-273k")
    scene = shpb.Scene.load(folder / "scene.json")
    record = folder / "data" / "20061201_1148HE_CuOFE_273K.raw"
    before = record.read_bytes()
    for target, overwrite in ((folder / "scene.json", False), (record, True),
                              (folder / "campaign.json", False)):
        with pytest.raises(shpb.InputError) as e:
            scene.save(target, overwrite=overwrite)
        assert "\n" not in str(e.value)
    assert record.read_bytes() == before
    # Files the scene does not read, asked to be replaced: only a scene file is.
    table = tmp_path / "table.csv"
    table.write_text("a,b\n1,2\n")
    material = tmp_path / "material.json"
    material.write_bytes((SOURCE / "specimens" / "al6061-t6.json").read_bytes())
    for target in (table, material):
        before = target.read_bytes()
        with pytest.raises(shpb.InputError, match="is not a scene file"):
            scene.save(target, overwrite=True)
        assert target.read_bytes() == before
    scene.striker.velocity_m_s = 20.0
    scene.save(folder / "scene.json", overwrite=True)  # its own file, asked for
    assert shpb.Scene.load(folder / "scene.json").striker.velocity_m_s == 20.0


@pytest.mark.parametrize("call", [
    lambda: shpb.Scene.load(123),
    lambda: shpb.Scene.from_dict({}, file=5),
    lambda: shpb.Scene.load(CLASSIC).save(7),
    lambda: shpb.Scene.load(CLASSIC).save("x.json", overwrite="yes"),
    lambda: shpb.simulate(123),
    lambda: shpb.simulate(CLASSIC, contact=1),
    lambda: shpb.simulate(CLASSIC, full_model="no"),
    lambda: shpb.validate([CLASSIC]),
    lambda: shpb.study(CLASSIC, sweep=2),
    lambda: shpb.fit(shpb.Scene.load(CLASSIC)),
    lambda: shpb.simulate(CLASSIC).save(1),
    lambda: shpb.process(CLASSIC, signals=2.0),
])
def test_a_wrong_type_is_one_line_naming_what_was_given(call):
    with pytest.raises(TypeError) as e:
        call()
    text = str(e.value)
    assert "\n" not in text and "expected" in text and "incompatible" not in text


def test_every_relative_path_is_rebased_into_a_new_folder(tmp_path):
    # The plan's shaper material and the specimen's are files beside the repository's scene; the
    # file is written two folders down a folder that does not exist yet.
    scene = shpb.Scene.load(SOURCE / "experiments" / "plan-al6061" / "scene.json")
    scene.bar("specimen").material.johnson_cook.B_Pa = 120e6
    path = tmp_path / "new" / "folder" / "scene.json"
    scene.save(path)
    back = shpb.Scene.load(path)
    assert model(back) == model(scene)
    shaper = json.loads(path.read_text())["plan"]["shaper"]["material"]
    assert (path.parent / shaper).resolve() == SOURCE / "specimens" / "pulse-shaper-copper.json"


def test_an_edit_the_calibration_replaces_is_refused(tmp_path, classic_json):
    # A calibration sets the incident bar's modulus to rho c^2 whenever the file is read: an edit
    # of it cannot be written, and nothing is.
    wave_speed, density = 5000.0, 8080.0
    (tmp_path / "calibration.json").write_text(json.dumps({
        "format": "shpb calibration 1", "reference_gauge": "incident", "absolute_gain": False,
        "bars": [{"bar": "incident", "wave_speed_m_s": {"value": wave_speed, "sd": None},
                  "poisson_ratio": {"value": 0.3, "sd": None}, "density_kg_m3": density,
                  "youngs_modulus_Pa": density * wave_speed ** 2}],
        "gauges": [{"gauge": "incident", "bar": "incident", "position_m": {"value": 1.0, "sd": None},
                    "gain": {"value": 1.0, "sd": None}, "delay_s": {"value": 0.0, "sd": None}}]}))
    classic_json["calibration"] = "calibration.json"
    classic_json["bars"][2]["material"] = str(SOURCE / "specimens" / "al6061-t6.json")
    scene = shpb.Scene.from_dict(classic_json, file=tmp_path / "scene.json")
    assert scene.bar("incident").material.youngs_modulus_Pa == density * wave_speed ** 2
    scene.striker.velocity_m_s = 10.0  # a value the calibration leaves alone
    scene.save(tmp_path / "out" / "kept.json")
    assert shpb.Scene.load(tmp_path / "out" / "kept.json").striker.velocity_m_s == 10.0
    scene.bar("incident").material.youngs_modulus_Pa = 190e9
    with pytest.raises(shpb.InputError, match=r"bars\[1\].material: .*calibration"):
        scene.save(tmp_path / "refused" / "scene.json")
    assert not (tmp_path / "refused").exists()
    # A command that reads its scene from a file refuses it too, naming the scene, not the
    # temporary file it was being written to.
    with pytest.raises(shpb.InputError) as e:
        shpb.compare(scene)
    assert str(e.value).startswith(f"{tmp_path / 'scene.json'} (edited in Python): bars[1].material: ")


def test_save_keeps_the_files_own_text_where_nothing_was_edited(tmp_path):
    # The classic scene saved beside its file with the striker's velocity edited is the file's
    # own text with "15 m/s" alone replaced (before, the whole file was re-indented).
    folder = scene_dir(tmp_path, "classic-al6061")
    original = (folder / "scene.json").read_text(encoding="utf-8")
    assert original.count('"velocity": "15 m/s"') == 1
    scene = shpb.Scene.load(folder / "scene.json")
    scene.striker.velocity_m_s = 12.0
    scene.save(folder / "edited.json")
    assert (folder / "edited.json").read_text(encoding="utf-8") == original.replace(
        '"velocity": "15 m/s"', '"velocity": "12 m/s"')
    # An edited value is the shortest text of its double, its exponent plain: "1.9e11 Pa", read
    # back as 190 GPa (before, "1.9e+11 Pa").
    scene.bar("specimen").material.youngs_modulus_Pa = 190e9
    scene.save(folder / "modulus.json")
    text = (folder / "modulus.json").read_text(encoding="utf-8")
    assert '"youngs_modulus": "1.9e11 Pa"' in text and "e+" not in text
    assert shpb.Scene.load(folder / "modulus.json").bar("specimen").material.youngs_modulus_Pa == 190e9
