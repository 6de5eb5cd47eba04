"""Python values a notebook may hand the module (docs/python.md, The API): a scene dict's values,
file names, tolerances and bar keys. Each is taken as documented or refused with a documented
exception whose one line names what is wrong; never a crash of the interpreter."""
import gc
import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import shpb
from conftest import SOURCE, run_command

CLASSIC = SOURCE / "experiments" / "classic-al6061" / "scene.json"


def command_message(path):
    """The command's one error line for a scene file, without main's "error: " prefix."""
    code, _, err = run_command("validate", path)
    assert code == 2
    assert len(err.strip().splitlines()) == 1
    return err.strip()[len("error: "):]


def nested(depth):
    """A dict of `depth` dicts, each the value of the key "self" of the one above."""
    d = {}
    for _ in range(depth - 1):
        d = {"self": d}
    return d


# A dict that holds itself made the module recurse until the stack overflowed (a segmentation
# fault: the kernel dies), so it runs in a Python of its own.
SELF_SCRIPT = textwrap.dedent("""
    import json, sys
    import shpb
    d = json.load(open(sys.argv[1]))
    d["bars"][0]["self"] = d["bars"][0]
    try:
        shpb.Scene.from_dict(d, file=sys.argv[1])
    except shpb.InputError as e:
        print(e)
""")


def test_a_dict_that_holds_itself_is_the_readers_nesting_refusal(tmp_path, classic_json):
    # Nested without end, it is refused as the reader refuses a file nested deeper than it takes
    # (core/json_document.hpp): the same line as the same nesting written in a file.
    p = subprocess.run([sys.executable, "-c", SELF_SCRIPT, str(CLASSIC)], capture_output=True,
                       text=True, env=os.environ, timeout=60)
    assert p.returncode == 0, p.stderr
    file = tmp_path / "scene.json"
    classic_json["bars"][0]["self"] = nested(63)  # the top, bars and bars[0]: 66 levels in all
    file.write_text(json.dumps(classic_json))
    assert p.stdout.strip() == command_message(file).replace(str(file), str(CLASSIC))


def test_nesting_beyond_pythons_recursion_limit_is_an_input_error(classic_json):
    # json.dumps raises RecursionError for it: the reader's refusal of nesting, not that.
    x = 1.0
    for _ in range(5000):
        x = [x]
    classic_json["notes"] = x
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.from_dict(classic_json, file=CLASSIC)
    assert ": notes[0][0]" in str(e.value)
    assert "nesting deeper than" in str(e.value)


@pytest.mark.parametrize("value", [np.longdouble(15), np.float16(15), np.array(15.0),
                                   np.array(15, dtype=np.int8), np.uint64(15)],
                         ids=["longdouble", "float16", "0-d", "0-d-int8", "uint64"])
def test_a_numpy_scalar_is_its_value(value, classic_json):
    # A long double's item() is the long double itself: json.dumps asked for its value for ever
    # (RecursionError). Each numpy scalar is the number it holds.
    classic_json["bars"][0]["velocity"] = value
    scene = shpb.Scene.from_dict(classic_json, file=CLASSIC)
    assert scene.striker.velocity_m_s == 15.0


def not_json_values():
    values = [(np.array([1.0, 2.0]), "array([1., 2.])"), (np.array([15.0]), "array([15.])"),
              (np.ma.masked, "masked"), (np.complex128(1), "(1+0j)"),
              (np.longdouble("1e4000"), "1e+4000"), (np.datetime64("2020-01-01"),
                                                     "numpy.datetime64('2020-01-01')")]
    try:
        import pandas as pd
        values += [(pd.Series([1.0, 2.0]), "a Series"), (pd.DataFrame({"a": [1]}), "a DataFrame")]
    except ImportError:
        pass
    return values


@pytest.mark.parametrize("value, shown", not_json_values(),
                         ids=[shown for _, shown in not_json_values()])
def test_a_value_of_no_json_type_is_named_with_its_path(value, shown, classic_json):
    # An array of several values, a Series or a DataFrame raised numpy's "can only convert an
    # array of size 1" (a ValueError naming nothing), a masked value was taken as 0 m/s and a
    # one-value array as its value: each is refused in one line with its JSON path.
    classic_json["bars"][0]["velocity"] = value
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.from_dict(classic_json, file=CLASSIC)
    message = str(e.value)
    assert "\n" not in message
    assert message.startswith(f"{CLASSIC}: bars[0].velocity: {shown}: expected ")


def test_a_key_of_no_json_type_is_named_with_its_path(classic_json):
    classic_json["bars"][0][(1, 2)] = 3
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.from_dict(classic_json, file=CLASSIC)
    assert str(e.value).startswith(f'{CLASSIC}: bars[0]["(1, 2)"]: key (1, 2): expected ')


@pytest.mark.parametrize("path", [b"/nonexistent/\xff\xfe/scene.json",
                                  "/nonexistent/\udcff/scene.json"], ids=["bytes", "surrogate"])
def test_a_file_name_that_is_not_utf8_is_named_in_the_message(path):
    # The message was empty: the library's bytes could not be decoded as UTF-8. It is the path as
    # Python names it (os.fsdecode), in the command's line.
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.load(path)
    assert str(e.value) == os.fsdecode(path) + ": no such file: expected an existing JSON file"


def test_an_empty_path_is_the_commands_message():
    # std::filesystem::absolute("") threw: a RuntimeError "cannot make absolute path".
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.load("")
    assert str(e.value) == command_message("")
    with pytest.raises(shpb.InputError) as e:
        shpb.Scene.from_dict({}, file="")
    assert str(e.value).startswith("file: ")


@pytest.mark.parametrize("value", [b"1 %", [0.01], 1j, object()], ids=str)
def test_a_tolerance_of_no_number_type_is_a_type_error_naming_it(value):
    # pybind11's cast raised RuntimeError("Unable to cast Python instance to C++ type").
    scene = shpb.Scene.load(CLASSIC)
    with pytest.raises(TypeError) as e:
        scene.tolerance = value
    assert str(e.value).startswith("tolerance: ")
    with pytest.raises(TypeError) as e:
        shpb.simulate(scene, tolerance=value)
    assert str(e.value).startswith("tolerance: ")


def number_arguments():
    """Each numeric keyword argument of the module and each numeric edit, as a call of a value."""
    striker = SOURCE / "experiments" / "striker-on-bar" / "scene.json"
    scene = shpb.Scene.load(striker)
    return [
        ("validate-tolerance", "tolerance", lambda v: scene.validate(tolerance=v)),
        ("simulate-tolerance", "tolerance", lambda v: shpb.simulate(scene, tolerance=v)),
        ("simulate-courant", "courant", lambda v: shpb.simulate(scene, courant=v)),
        ("simulate-threads", "threads", lambda v: shpb.simulate(scene, threads=v)),
        ("process-draws", "draws", lambda v: shpb.process(CLASSIC, draws=v)),
        ("process-seed", "seed", lambda v: shpb.process(CLASSIC, seed=v)),
        ("compare-striker", "striker_velocity",
         lambda v: shpb.compare(CLASSIC, striker_velocity=v)),
        ("study-refine", "refine", lambda v: shpb.study(striker, sweep="stability", refine=v)),
        ("fit-relative-step", "relative_step", lambda v: shpb.fit(CLASSIC, relative_step=v)),
        ("dispersion-poisson", "poisson", lambda v: shpb.dispersion(poisson=v)),
        ("dispersion-points", "points", lambda v: shpb.dispersion(points=v)),
        ("dispersion-a-over-lambda", "a_over_lambda[0]",
         lambda v: shpb.dispersion(a_over_lambda=[v])),
        ("edit-velocity", "bar.velocity_m_s", lambda v: setattr(scene.striker, "velocity_m_s", v)),
        ("edit-elements", "bar.elements", lambda v: setattr(scene.bars[0], "elements", v)),
        ("edit-tolerance", "tolerance", lambda v: setattr(scene, "tolerance", v)),
        ("edit-duration", "duration_s", lambda v: setattr(scene, "duration_s", v)),
    ]


@pytest.mark.parametrize("name, call", [(n, c) for _, n, c in number_arguments()],
                         ids=[i for i, _, _ in number_arguments()])
def test_a_one_value_array_is_no_number_argument(name, call):
    # A scene dict refuses a numpy array of one value (test_a_value_of_no_json_type_is_named_with
    # _its_path); a keyword argument or an edit took it as its value (float() of the array). Each
    # follows the scene values' rule (json_value_of): a TypeError naming the argument, before any
    # work.
    with pytest.raises(TypeError) as e:
        call(np.array([1]))
    message = str(e.value)
    assert "\n" not in message
    assert message.startswith(f"{name}: array([1]): expected ")


@pytest.mark.parametrize("value", [np.float64(0.02), np.array(0.02), np.float16(0.02),
                                   np.longdouble(0.02)],
                         ids=["float64", "0-d", "float16", "longdouble"])
def test_a_numpy_scalar_is_its_value_as_an_argument(value):
    # As in a scene dict: a numpy scalar or a 0-d array is the number it holds.
    scene = shpb.Scene.load(CLASSIC)
    scene.tolerance = value
    assert scene.tolerance == float(value)
    scene.validate(tolerance=value)
    scene.striker.velocity_m_s = value
    assert scene.striker.velocity_m_s == float(value)
    scene.bars[1].elements = np.array(400, dtype=np.int16)
    assert scene.bars[1].elements == 400


@pytest.mark.parametrize("key", [1.5, None, b"striker", [0]], ids=str)
def test_a_bar_key_of_no_index_type_is_a_type_error(key):
    # As a list's index: a RuntimeError of pybind11's cast before.
    with pytest.raises(TypeError) as e:
        shpb.Scene.load(CLASSIC).bar(key)
    assert str(e.value).startswith("bar: ")


def test_a_numpy_integer_is_a_bar_index():
    scene = shpb.Scene.load(CLASSIC)
    assert scene.bar(np.int64(-1)).name == "transmitter"
    with pytest.raises(IndexError):
        scene.bar(2**70)


@pytest.mark.parametrize("value", ["12", "0.5", 0.5], ids=str)
def test_a_list_of_a_over_lambda_is_a_list(value):
    # The text "12" was read, character by character, as the table of a/Λ = 1 and 2.
    with pytest.raises(TypeError) as e:
        shpb.dispersion(a_over_lambda=value)
    assert str(e.value).startswith("a_over_lambda: ")


def test_a_tolerance_text_that_is_not_utf8_is_the_tolerance_message():
    # A lone surrogate failed pybind11's conversion to UTF-8 (RuntimeError) before the tolerance
    # was read.
    with pytest.raises(shpb.InputError) as e:
        shpb.simulate(CLASSIC, tolerance="1 \udcff")
    assert str(e.value).startswith("--tolerance: ")  # the command's message (commands.md)


@pytest.mark.parametrize("kwargs, option", [
    (dict(max_a_over_lambda=float("inf")), "--max-a-over-lambda: inf: "),
    (dict(max_a_over_lambda=1e300), "--max-a-over-lambda: 1e+300: "),
    (dict(radius_m=float("inf"), c0_m_s=4975.0), "--radius/--c0: inf m, 4975 m/s: "),
    (dict(radius_m=0.0095, c0_m_s=float("nan")), "--radius/--c0: 0.0095 m, nan m/s: "),
], ids=["max-inf", "max-1e300", "radius-inf", "c0-nan"])
def test_a_dispersion_option_out_of_range_names_itself(kwargs, option):
    # An infinite largest a/Λ made the table's points NaN, refused as "--a-over-lambda: -nan"
    # (an option not given); an infinite radius or a NaN c0 gave a NaN frequency_Hz column.
    with pytest.raises(shpb.InputError) as e:
        shpb.dispersion(**kwargs)
    assert str(e.value).startswith(option)


@pytest.mark.parametrize("group", ["johnson_cook", "bilinear"])
def test_a_law_group_keeps_its_material_alive(group):
    # The group of parameters refers to its material in the scene: taken from a scene no one
    # holds any more, it must keep that scene alive (it read and wrote freed memory: a message
    # naming the material with garbage).
    scene_file = SOURCE / "experiments" / "classic-al6061" / "scene.json"
    params = getattr(shpb.Scene.load(scene_file).specimen.material, group)
    gc.collect()
    filler = [bytearray(64) for _ in range(20000)]  # reuses freed memory, if any was freed
    expected = shpb.Scene.load(scene_file).specimen.material
    if group == "johnson_cook":
        assert params.A_Pa == expected.johnson_cook.A_Pa
        params.A_Pa = 2 * expected.johnson_cook.A_Pa
        assert params.A_Pa == 2 * expected.johnson_cook.A_Pa
    else:  # the classic specimen is Johnson-Cook: the edit is refused, naming its material
        with pytest.raises(shpb.InputError) as e:
            params.yield_stress_Pa = 3e8
        assert f'material "{expected.name}" is johnson-cook' in str(e.value)
    del filler
