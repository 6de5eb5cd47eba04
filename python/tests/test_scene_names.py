"""A shpb.Scene given to a command that reads its scene from a file (compare, calibrate, a
campaign, plan) runs from a temporary copy: its outputs, warnings and errors name the scene as the
user knows it, its own file (said to be edited when it was), never the temporary copy, which is
gone with the result."""
import os

import pytest

import shpb
from conftest import SOURCE, scene_dir

EXPERIMENTS = SOURCE / "experiments"


def texts_of(folder):
    """Every file under `folder` as text, by its path relative to it."""
    return {str(p.relative_to(folder)): p.read_text(encoding="utf-8")
            for p in folder.rglob("*") if p.is_file() and p.name != ".shpb-output"}


def temporary_names(result, folder):
    """Where the saved folder or the warnings name a file under the system's temporary folder
    (the tests' own tmp_path lies elsewhere only if TMPDIR says so: it is excluded)."""
    tmp = os.path.realpath(os.environ.get("TMPDIR", "/tmp"))
    found = [name for name, text in texts_of(folder).items() if tmp + "/shpb-" in text]
    return found + [w for w in result.warnings if tmp + "/shpb-" in w]


def test_compare_names_the_scenes_own_file(tmp_path):
    folder = scene_dir(tmp_path, "lanl-cu-ofe-273k")
    scene = shpb.Scene.load(folder / "scene.json")
    unedited = shpb.compare(scene, dispersion=False)
    assert unedited.summary["scene"] == str(folder / "scene.json")
    scene.striker.velocity_m_s = 14.0
    edited = shpb.compare(scene, dispersion=False)
    assert edited.summary["scene"] == f"{folder / 'scene.json'} (edited in Python)"
    edited.save(tmp_path / "out")
    assert temporary_names(edited, tmp_path / "out") == []


def test_an_error_names_the_scenes_own_file():
    # A scene without a measurement, edited: compare's refusal names the file the user loaded.
    scene = shpb.Scene.load(EXPERIMENTS / "striker-on-bar" / "scene.json")
    scene.striker.velocity_m_s = 3.0
    with pytest.raises(shpb.InputError) as e:
        shpb.compare(scene)
    file = EXPERIMENTS / "striker-on-bar" / "scene.json"
    assert str(e.value).startswith(f"{file} (edited in Python): measurement: ")


def test_a_campaign_of_scenes_names_each_test_as_its_file_does(tmp_path):
    # Tests without a "name" are named by their scene's folder, as from their files; campaign.csv,
    # summary.json and each test's summary name the files, the edited one said to be.
    names = ["epoxy-resin-sample01", "lanl-cu-ofe-273k"]
    scenes = [shpb.Scene.load(EXPERIMENTS / n / "scene.json") for n in names]
    scenes[1].bar("specimen").length_m *= 1.01
    result = shpb.process_campaign(scenes, draws=2)
    files = [str(EXPERIMENTS / names[0] / "scene.json"),
             f"{EXPERIMENTS / names[1] / 'scene.json'} (edited in Python)"]
    assert list(result.tests) == names
    assert list(result.tables["campaign"]["test"]) == names
    assert list(result.tables["campaign"]["scene"]) == files
    assert [t["scene"] for t in result.summary["tests"]] == files
    assert [result.tests[n].summary["scene"] for n in names] == files
    result.save(tmp_path / "out")
    assert temporary_names(result, tmp_path / "out") == []
