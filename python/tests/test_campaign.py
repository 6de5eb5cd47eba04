"""process of several tests from Python: `shpb process --campaign` (or of several scenes) by the
command's own function (process_campaign), so the command's folder, numbers, warnings and
messages."""
import numpy as np
import pytest

import shpb
from conftest import SOURCE, columns, read_csv, run_command

EXPERIMENTS = SOURCE / "experiments"
CAMPAIGN = EXPERIMENTS / "measured-campaign.json"  # the three measured experiments
# The copper test's measurement.uncertainty drawn 20 times (not 1000): seconds, the same draws
# for the command and the module (one seed).
DRAWS = 20


def printed_warnings(err):
    return [line[len("warning: "):] for line in err.splitlines() if line.startswith("warning: ")]


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """The command's folder and stderr, and the module's result with the warnings it issued."""
    tmp = tmp_path_factory.mktemp("campaign")
    code, _, err = run_command("process", "--campaign", CAMPAIGN, "--flow-stress-at", "0.02,0.05",
                               "--draws", DRAWS, "-q", "-o", tmp / "cmd")
    assert code == 0, err
    with pytest.warns(shpb.ShpbWarning) as caught:
        result = shpb.process_campaign(CAMPAIGN, flow_stress_at=[0.02, 0.05], draws=DRAWS)
    return tmp, err, result, [str(w.message) for w in caught]


def files_of(folder):
    return sorted(p.relative_to(folder) for p in folder.rglob("*") if p.is_file())


def test_a_campaign_saves_the_commands_folder_byte_for_byte(campaign):
    tmp, _, result, _ = campaign
    result.save(tmp / "py")
    names = files_of(tmp / "cmd")
    assert names == files_of(tmp / "py")
    assert len(names) > 3 * 4  # campaign.csv, summary.json, and four files a test
    for name in names:
        assert (tmp / "cmd" / name).read_bytes() == (tmp / "py" / name).read_bytes(), name


def test_a_campaigns_tables_are_the_commands_numbers(campaign):
    tmp, _, result, _ = campaign
    assert list(result.tests) == ["epoxy-resin", "cu-ofe-273k", "pmma-mini-kolsky"]
    tables = [(result.tables["campaign"], tmp / "cmd" / "campaign.csv")]
    for name, test in result.tests.items():
        for table in ("curve", "pulses", "raw_signals"):
            tables.append((test.tables[table], tmp / "cmd" / name / f"{table}.csv"))
    for table, csv in tables:
        expected, got = read_csv(csv), columns(table)
        assert list(got) == list(expected), csv
        for column, values in expected.items():
            if isinstance(values, list):  # text: the test's name, scene and warnings
                assert list(got[column]) == values, f"{csv}: {column}"
            else:
                np.testing.assert_array_equal(got[column], values, err_msg=f"{csv}: {column}")
    # The flow stress of copper at 5 % strain, a number a lab plots against temperature or rate.
    copper = columns(result.tables["campaign"])["flow_stress_Pa_at_0.05"][1]
    assert 50e6 < copper < 500e6


def test_a_campaigns_warnings_are_the_lines_the_command_prints(campaign):
    _, err, result, issued = campaign
    expected = printed_warnings(err)
    assert expected  # the epoxy record's rounded time stamps, at least
    assert result.warnings == expected
    assert issued == expected


def test_a_list_of_scenes_is_the_commands_scenes(tmp_path, capfd):
    scenes = [EXPERIMENTS / "lanl-pmma13-mini-kolsky" / "scene.json",
              EXPERIMENTS / "epoxy-resin-sample01" / "scene.json"]
    assert run_command("process", *scenes, "-q", "-o", tmp_path / "cmd")[0] == 0
    capfd.readouterr()
    with pytest.warns(shpb.ShpbWarning):
        result = shpb.process_campaign(scenes)
    # Said once, as Python warnings: not also on the process's stderr, which a notebook hides.
    assert "warning" not in capfd.readouterr().err
    result.save(tmp_path / "py")
    for name in files_of(tmp_path / "cmd"):
        assert (tmp_path / "cmd" / name).read_bytes() == (tmp_path / "py" / name).read_bytes()


@pytest.mark.parametrize("args, kwargs", [
    (("--flow-stress-at", "1.5"), {"flow_stress_at": [1.5]}),
    (("--draws", "1"), {"draws": 1}),
    (("--threads", "-1"), {"threads": -1}),
])
def test_a_bad_campaign_option_is_the_commands_line(args, kwargs, tmp_path):
    code, _, err = run_command("process", "--campaign", CAMPAIGN, *args, "-o", tmp_path / "cmd")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process_campaign(CAMPAIGN, **kwargs)
    assert "error: " + str(e.value) == err.strip()


def test_a_bad_scene_of_a_campaign_is_the_commands_line(tmp_path):
    # A campaign naming a scene that is not there: refused before any test is processed, with
    # the line the command prints (its file, the JSON path, the value).
    bad = tmp_path / "campaign.json"
    bad.write_text('{"tests": [{"scene": "nowhere/scene.json", "name": "lost"}]}')
    code, _, err = run_command("process", "--campaign", bad, "-o", tmp_path / "cmd")
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process_campaign(bad)
    assert "error: " + str(e.value) == err.strip()
    assert not (tmp_path / "cmd").exists()


def test_shards_merged_from_python_are_the_commands_campaign(tmp_path):
    # A campaign split in two shards and merged, from Python (each shard could run on its own
    # machine): DIR/result is byte for byte the command's unsharded folder of the same campaign.
    code, _, err = run_command("process", "--campaign", CAMPAIGN, "--draws", DRAWS, "-q",
                               "-o", tmp_path / "cmd")
    assert code == 0, err
    with pytest.warns(shpb.ShpbWarning):
        parts = [shpb.process_campaign(CAMPAIGN, draws=DRAWS, shard=f"{k}/2",
                                       output=tmp_path / "py") for k in range(2)]
    assert [list(p.tests) for p in parts] == [["epoxy-resin", "pmma-mini-kolsky"],
                                              ["cu-ofe-273k"]]
    assert parts[1].json["part"]["shard"] == "1/2"
    merged = shpb.process_campaign(CAMPAIGN, merge=True, output=tmp_path / "py")
    assert list(merged.tests) == ["epoxy-resin", "cu-ofe-273k", "pmma-mini-kolsky"]
    names = files_of(tmp_path / "cmd")
    assert names == files_of(tmp_path / "py" / "result")
    for name in names:
        assert (tmp_path / "cmd" / name).read_bytes() == \
            (tmp_path / "py" / "result" / name).read_bytes(), name


def test_a_merge_refuses_draws_as_the_command_does(tmp_path):
    # The shards draw; the merge copies their tests: draws or a seed given to it are refused
    # (they changed nothing), with the command's line.
    code, _, err = run_command("process", "--campaign", CAMPAIGN, "--merge", "--seed", "7", "-o",
                               tmp_path)
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process_campaign(CAMPAIGN, seed=7, merge=True, output=tmp_path)
    assert "error: " + str(e.value) == err.strip()
    assert str(e.value).startswith("--seed: not with --merge")


def test_a_merge_with_a_part_missing_is_the_commands_line(tmp_path):
    code, _, err = run_command("process", "--campaign", CAMPAIGN, "--merge", "-o", tmp_path)
    assert code == 2
    with pytest.raises(shpb.InputError) as e:
        shpb.process_campaign(CAMPAIGN, merge=True, output=tmp_path)
    assert "error: " + str(e.value) == err.strip()
    with pytest.raises(TypeError, match="output"):  # a shard without its folder
        shpb.process_campaign(CAMPAIGN, shard="0/2")
