"""shpb from Python: the virtual Split-Hopkinson pressure bar lab on the same C++ library as the
`shpb` command (docs/python.md).

    import shpb
    run = shpb.simulate(shpb.Scene.load("experiments/classic-al6061/scene.json"))
    run.gauges["incident"]            # numpy array, the gauges.csv column

Scenes load from a file or a dict (the same checks and messages as the command, raised as
shpb.InputError); results hold numpy arrays (tables as pandas DataFrames when pandas is
installed) named as the command's CSV columns and summary.json, and result.save(dir) writes
exactly the command's output folder. Simulations release the GIL (threads run in parallel);
Ctrl-C stops a run as SIGINT stops the command.
"""
import os as _os
import shutil as _shutil
import tempfile as _tempfile
import warnings as _warnings

from . import _shpb
from ._shpb import (Bar, Bilinear, InputError, JohnsonCook, Material, NumericalError, Scene,
                    Viscoelastic, WriteError)

try:
    from ._command_help import HELP as _HELP
except ImportError:  # a source tree without the build's generated help
    _HELP = {}

try:
    import pandas as _pandas
except ImportError:
    _pandas = None

__version__ = _shpb.__version__
__all__ = ["Scene", "Bar", "Material", "JohnsonCook", "Bilinear", "Viscoelastic", "InputError", "NumericalError",
           "WriteError", "ShpbWarning", "simulate", "process", "compare", "dispersion", "fit",
           "study", "plan", "calibrate", "report", "SimulationResult", "ProcessResult", "BarCheckResult",
           "FolderResult", "PlanResult", "process_campaign", "CampaignResult", "validate"]


class ShpbWarning(UserWarning):
    """A warning of a run: what the command prints as `warning: ...` on stderr (a notebook does
    not show the library's stderr). Each is also in the result's `warnings`."""


def _warned(result, calls=1):
    """Issues each of the result's warnings through Python's warnings module (shown under a
    notebook's cell, on a script's stderr), at the line of the user's code `calls` functions of
    this module up, and returns the result."""
    for text in result.warnings:
        _warnings.warn(text, ShpbWarning, stacklevel=2 + calls)
    return result


def _path(value, name):
    """A path given to the module (a str, bytes or os.PathLike); anything else a one-line TypeError
    naming the argument, the value and what is expected (os.fspath names the type alone)."""
    if not isinstance(value, (str, bytes, _os.PathLike)):
        raise TypeError(f"{name}: {_shpb._shown(value)}: expected a path (a str or "
                        "os.PathLike)")
    return _os.fspath(value)


def _table(columns):
    """A pandas DataFrame of the columns when pandas is installed, else the dict of arrays."""
    if columns is None or _pandas is None:
        return columns
    return _pandas.DataFrame(columns, copy=False)


def _with_help(command, python_part):
    def decorate(function):
        function.__doc__ = python_part
        if command in _HELP:
            function.__doc__ += ("\n\nThe command's options (`shpb " + command + " --help`):\n\n"
                                 + _HELP[command])
        return function
    return decorate


class _Returned:
    """A result of the library's run (`_native`), which only the module's functions make: a
    constructor called from Python would give an object whose every attribute fails."""

    _made_by = None

    def __init__(self, *args, **kwargs):
        raise TypeError(f"shpb.{type(self).__name__} is what shpb.{self._made_by}() returns; it is "
                        "not constructed by hand")

    def _arrays(self, table):
        """arrays(table) of each result: the columns of one of its `_tables`."""
        if table not in self._tables:  # not any attribute of the library's object
            raise KeyError(f"{table!r}: expected one of the tables {', '.join(self._tables)}")
        return getattr(self._native, table)

    @classmethod
    def _of(cls, native):
        result = object.__new__(cls)
        result._native = native
        return result


class SimulationResult(_Returned):
    """A run of `shpb simulate`, in memory. Tables (time_s and one column per CSV column):
    gauges, interfaces, specimen (None without a specimen), energy; field: time_s, x_m and
    stress_Pa[time, x]; summary: summary.json as a dict. save(dir) writes the command's folder."""

    _made_by = "simulate"
    _tables = ("gauges", "interfaces", "specimen", "energy", "field")

    scene = property(lambda self: self._native.scene, doc="the scene as run (overrides applied)")
    gauges = property(lambda self: _table(self._native.gauges), doc="gauges.csv")
    interfaces = property(lambda self: _table(self._native.interfaces), doc="interfaces.csv")
    specimen = property(lambda self: _table(self._native.specimen), doc="specimen.csv")
    energy = property(lambda self: _table(self._native.energy), doc="energy.csv")
    field = property(lambda self: self._native.field, doc="field.csv as a time x position grid")
    summary = property(lambda self: self._native.summary, doc="summary.json")
    stable = property(lambda self: self._native.stable)
    failure = property(lambda self: self._native.failure)
    warnings = property(lambda self: self._native.warnings)
    wall_time_s = property(lambda self: self._native.wall_time_s, doc="the solve alone")

    def arrays(self, table):
        """The columns of `table` ("gauges", "interfaces", "specimen", "energy", "field") as
        read-only numpy arrays that view the library's memory (no copy); another name is a
        KeyError."""
        return self._arrays(table)

    def save(self, dir):
        """Writes gauges.csv, interfaces.csv, specimen.csv, energy.csv, field.csv and
        summary.json into `dir`, as `shpb simulate -o dir` (replaced atomically; a folder shpb
        did not write is refused)."""
        self._native.save(_path(dir, "dir"))

    def __repr__(self):
        s = self.summary
        return (f"<shpb.SimulationResult {s['scene']}: {len(self._native.gauges['time_s'])} "
                f"samples, stable={s['stable']}, {s['wall_time_s']:.3g} s>")


class ProcessResult(_Returned):
    """A run of `shpb process`, in memory: raw_signals, pulses, curve (rows up to the end of
    loading, as curve.csv) and summary (summary.json). save(dir) writes the command's folder."""

    _made_by = "process"
    _tables = ("curve", "pulses", "raw_signals")

    scene = property(lambda self: self._native.scene)
    raw_signals = property(lambda self: _table(self._native.raw_signals), doc="raw_signals.csv")
    pulses = property(lambda self: _table(self._native.pulses), doc="pulses.csv")
    curve = property(lambda self: _table(self._native.curve), doc="curve.csv")
    summary = property(lambda self: self._native.summary, doc="summary.json")
    warnings = property(lambda self: self._native.warnings)

    def arrays(self, table):
        """The columns of `table` ("curve", "pulses", "raw_signals") as read-only numpy arrays
        that view the library's memory (no copy); another name is a KeyError."""
        return self._arrays(table)

    def save(self, dir):
        """Writes raw_signals.csv, pulses.csv, curve.csv and summary.json into `dir`, as
        `shpb process -o dir`."""
        self._native.save(_path(dir, "dir"))

    def __repr__(self):
        return f"<shpb.ProcessResult {self.summary['scene']}: peak {self.summary['peak_stress_Pa'] / 1e6:.4g} MPa>"


class BarCheckResult(_Returned):
    """`shpb process` of a scene without a specimen, in memory: the bars-together check (the
    near gauge's pulse moved to the far gauge with Pochhammer-Chree dispersion and by a plain
    delay, against the far record). pulses: pulses.csv; summary: summary.json (rms_of_peak,
    distance_m, ...). save(dir) writes the command's folder."""

    _made_by = "process"
    _tables = ("pulses",)

    scene = property(lambda self: self._native.scene)
    pulses = property(lambda self: _table(self._native.pulses), doc="pulses.csv")
    summary = property(lambda self: self._native.summary, doc="summary.json")
    warnings = property(lambda self: self._native.warnings)

    def arrays(self, table):
        """The columns of `table` ("pulses") as read-only numpy arrays that view the
        library's memory (no copy); another name is a KeyError."""
        return self._arrays(table)

    def save(self, dir):
        """Writes pulses.csv and summary.json into `dir`, as `shpb process -o dir`."""
        self._native.save(_path(dir, "dir"))

    def __repr__(self):
        s = self.summary
        return (f"<shpb.BarCheckResult {s['scene']}: {s['near_gauge']} -> {s['far_gauge']}, RMS "
                f"{100 * s['rms_of_peak']['pochhammer_chree']:.3g} % of peak>")


def _process_result(native):
    """A ProcessResult, or a BarCheckResult for a scene without a specimen."""
    return (BarCheckResult if isinstance(native, _shpb._BarCheck) else ProcessResult)._of(native)


def _scene_of(scene):
    """A shpb.Scene, or the scene of the file at path `scene`."""
    if isinstance(scene, Scene):
        return scene
    return Scene.load(_scene_file(scene))


@_with_help("validate", """validate(scene, tolerance=None, threads=0, contact=None, stepping=None,
         courant=None) -> dict

Checks `scene` (a shpb.Scene, or the path of a scene file) as `shpb validate` does and returns
what `shpb validate --json` prints: the resolved set-up (materials, meshes, time steps, Courant
numbers, gauges, interfaces, warnings and, for a scene with a measurement, what process reads),
as a dict. Raises shpb.InputError where the command exits 2.""")
def validate(scene, tolerance=None, threads=0, contact=None, stepping=None, courant=None):
    return _shpb._validate(_scene_of(scene), tolerance, contact, stepping, courant, threads)


@_with_help("simulate", """simulate(scene, tolerance=None, threads=0, contact=None, stepping=None,
         courant=None, full_model=False) -> SimulationResult

Runs `scene` (a shpb.Scene, or a path to a scene file) as `shpb simulate` does; nothing is
written until result.save(dir). tolerance: the gauge error accepted, a fraction (0.01) or
text ("1 %"); contact, stepping, courant, full_model: as --contact, --stepping, --courant,
--full-model. threads: accepted for symmetry with the command (a simulation runs on one
thread; run several from Python threads: the GIL is released). Raises shpb.InputError
(exit 2 of the command), KeyboardInterrupt on Ctrl-C. An unstable run is returned with
result.stable False and result.failure saying where and when (the command's exit 3).""")
def simulate(scene, tolerance=None, threads=0, contact=None, stepping=None, courant=None,
             full_model=False):
    scene = _scene_of(scene)
    return _warned(SimulationResult._of(_shpb._simulate(scene, tolerance, contact, stepping, courant,
                                                    threads, full_model)))


@_with_help("process", """process(scene, signals=None, draws=1000, seed=1, threads=0) -> ProcessResult

Reduces the scene's measured signals (its `measurement`), or `signals` (a gauges.csv written
by `shpb simulate`, or a SimulationResult), to the pulses at the specimen faces and the
1/2/3-wave stress-strain curve, as `shpb process` does (a scene without a specimen: the
bars-together check of its measurement, a BarCheckResult); a `measurement.uncertainty` block is
propagated by `draws` Monte Carlo draws from `seed` on `threads` worker threads (0: all cores;
the command's --draws, --seed, --threads). Nothing is
written until result.save(dir). Raises shpb.InputError for a bad scene or signal file, and
shpb.NumericalError when the reduction fails (the command's exit 3).""")
def process(scene, signals=None, draws=1000, seed=1, threads=0):
    scene = _scene_of(scene)
    if isinstance(signals, SimulationResult):
        # Read as the command reads a gauges.csv, through a temporary one; named as what it is
        # (summary.json's signals.file, warnings, errors), not as the temporary gone on return.
        shown = f"the SimulationResult of {signals.scene.file} (in memory)"
        with _tempfile.TemporaryDirectory(prefix="shpb-") as tmp:
            signals.save(_os.path.join(tmp, "run"))
            return _warned(_process_result(_shpb._process(
                scene, _os.path.join(tmp, "run", "gauges.csv"), draws, seed, threads, shown)))
    return _warned(_process_result(_shpb._process(
        scene, None if signals is None else _path(signals, "signals"), draws, seed, threads)))


class FolderResult:
    """The output of `shpb compare`, `shpb study`, `shpb fit`, `shpb calibrate` or `shpb plan`
    (a PlanResult), read into memory: tables (every
    CSV file, by name without .csv) and json (every JSON file, by name without .json), as the
    command wrote them. exit_code: 0, or 3 when the command wrote its result with a numerical
    failure said in its summary. save(dir) writes the very files into `dir`."""

    def __init__(self, command, folder, exit_code, inputs=()):
        self.command, self.exit_code, self._folder = command, exit_code, folder
        self._inputs = list(inputs)  # the files the run read: save(dir) may hold none of them
        self.tables, self.json = {}, {}
        for name in sorted(_os.listdir(folder)):
            path = _os.path.join(folder, name)
            if name.endswith(".csv"):
                self.tables[name[:-4]] = _table(_read_csv(path))
            elif name.endswith(".json"):
                import json
                with open(path, encoding="utf-8") as f:
                    self.json[name[:-5]] = json.load(f)

    @property
    def summary(self):
        return self.json.get("summary")

    @property
    def warnings(self):
        """The run's warnings, what the command prints on stderr: summary.json's `undetermined`
        (calibrate's directions the shots do not fix) then its `warnings`."""
        lines = []
        for key in ("undetermined", "warnings"):
            found = (self.summary or {}).get(key)
            lines += found if isinstance(found, list) else []
        return lines

    def save(self, dir):
        """Writes the command's folder into `dir` (replaced atomically; a folder shpb did not
        write is refused)."""
        _shpb._save_folder(self._folder, _path(dir, "dir"), self.command, self._inputs)

    def __repr__(self):
        return f"<shpb.FolderResult of {self.command}: {', '.join(self.tables) or 'no tables'}>"


def _read_csv(path):
    """{column: float64 array} of a CSV the library wrote (numbers; text cells kept as text)."""
    import csv
    import numpy as np
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    columns = {}
    for i, name in enumerate(rows[0]):
        cells = [r[i] if i < len(r) else "" for r in rows[1:]]
        try:
            columns[name] = np.array([float(c) if c != "" else np.nan for c in cells])
        except ValueError:
            columns[name] = np.array(cells, dtype=object)
    return columns


def _folder_run(command, run, files, distributions=None, inputs_of=None, kind=None):
    """Runs `command` on its scene or campaign file (calibrate and process_campaign: its scene
    files) `files`, each a path or a shpb.Scene (_SceneFiles), into a temporary folder:
    `run(out, paths)`; `inputs_of(paths)` the files it read, if not the command's `_inputs`;
    `kind` the result's class (a FolderResult)."""
    import weakref
    tmp = _tempfile.mkdtemp(prefix=f"shpb-{command}-")
    folder = _os.path.join(tmp, "out")
    try:
        scenes = _SceneFiles(files, tmp)
        with scenes:
            code = run(folder, scenes.paths)
            inputs = (inputs_of(scenes.paths) if inputs_of
                      else _shpb._inputs(command, scenes.paths, distributions or ""))
        scenes.rename_in(folder)
        result = (kind or FolderResult)(command, folder, code, inputs)
    except BaseException:
        _shutil.rmtree(tmp, True)
        raise
    # The temporary folder is this function's and goes with its result; a FolderResult made of
    # any other folder removes nothing.
    weakref.finalize(result, _shutil.rmtree, tmp, True)
    return _warned(result, calls=2)  # _folder_run, called by compare, study, fit, calibrate or
    # process_campaign


def _scene_file(scene):
    """The path of a scene or campaign file given as one; a shpb.Scene is a TypeError (a command
    that reads a Scene from a file takes it through _SceneFiles)."""
    if isinstance(scene, Scene):
        raise TypeError(f"{_shpb._shown(scene)}: expected the path of a file here (a campaign "
                        "file, or a scene file that a later step reads again: a study plan's, "
                        "the scene files of shard and merge, which part.json names): "
                        "scene.save(path) and pass the path")
    if not isinstance(scene, (str, _os.PathLike)):
        raise TypeError(f"scene: {_shpb._shown(scene)}: expected a shpb.Scene or the path of "
                        "a scene file (a str or os.PathLike)")
    return _os.fspath(scene)


def _scene_shown(scene):
    """What a shpb.Scene is named by in a run's outputs and messages: its file, as the user knows
    it, said to be edited unless the scene is that file's (read and unchanged)."""
    import json
    file = _os.fspath(scene.file)
    try:
        with open(file, encoding="utf-8") as f:
            unchanged = json.load(f) == scene.to_dict()
    except (OSError, ValueError):  # no such file (Scene.from_dict), or not JSON any more
        unchanged = False
    return file if unchanged else f"{file} (edited in Python)"


class _SceneFiles:
    """The scene files of a run of a command that reads its scenes from files, the one owner of
    the temporary ones: each path given as is; each shpb.Scene written by Scene.save into the
    run's temporary folder `tmp` (scenes/K/FOLDER/NAME, its own file's folder and name: a scene
    or test without a name is named by them, as from its own file), and named as the user knows
    it (_scene_shown) wherever the run names the temporary file, gone on return: an error raised
    in the `with` block, and the files of the output folder (rename_in), which summary.json's
    `scene`, a campaign's campaign.csv and the warnings are read from."""

    def __init__(self, given, tmp):
        self.paths, self._names = [], []
        for k, scene in enumerate(given):
            if not isinstance(scene, Scene):
                self.paths.append(_scene_file(scene))
                continue
            own = _os.path.abspath(scene.file)
            folder = _os.path.join(tmp, "scenes", str(k),
                                   _os.path.basename(_os.path.dirname(own)) or "scene")
            path = _os.path.join(folder, _os.path.basename(own) or "scene.json")
            self._names.append((path, _scene_shown(scene)))
            with self:  # an edit no file can hold is refused naming the scene
                scene.save(path)
            self.paths.append(path)

    def renamed(self, text, quote=lambda name: name):
        for path, name in self._names:
            text = text.replace(quote(path), quote(name))
        return text

    def __enter__(self):
        return self

    def __exit__(self, kind, error, trace):
        if self._names and isinstance(error, (InputError, NumericalError, WriteError)):
            raise type(error)(self.renamed(str(error))) from None
        return False

    def rename_in(self, folder):
        """The temporary files' names in the text files under `folder` replaced: as a JSON
        string's text in .json files, as a cell of the library's CSV files (core/csv_writer.hpp:
        quoted when it holds a comma, a quote or a line break)."""
        import json
        if not self._names:
            return
        for root, _, files in _os.walk(folder):
            for name in files:
                path = _os.path.join(root, name)
                try:
                    with open(path, encoding="utf-8", newline="") as f:
                        text = f.read()
                except (UnicodeDecodeError, OSError):
                    continue  # not text
                if not any(p in text or json.dumps(p)[1:-1] in text for p, _ in self._names):
                    continue
                if name.endswith(".json"):
                    text = self.renamed(text, lambda s: json.dumps(s, ensure_ascii=False)[1:-1])
                elif name.endswith(".csv"):
                    text = _csv_renamed(text, self.renamed)
                else:
                    text = self.renamed(text)
                with open(path, "w", encoding="utf-8", newline="") as f:
                    f.write(text)


def _csv_cell(text):
    """A cell as the library writes it (quote_cell, core/csv_writer.cpp)."""
    if not any(c in text for c in ',"\n\r'):
        return text
    return '"' + text.replace('"', '""') + '"'


def _csv_renamed(text, renamed):
    """A CSV file of the library with `renamed` applied to each cell."""
    import csv
    import io
    rows = list(csv.reader(io.StringIO(text, newline="")))
    if "".join(",".join(map(_csv_cell, row)) + "\n" for row in rows) != text:
        return renamed(text)  # not written cell by cell as the library writes them
    return "".join(",".join(_csv_cell(renamed(c)) for c in row) + "\n" for row in rows)


@_with_help("compare", """compare(scene, tolerance=None, threads=0, contact=None, stepping=None,
        courant=None, dispersion=True, striker_velocity=None) -> FolderResult

Simulates the scene file and lays the simulated gauges over its measured signals, as
`shpb compare` does; the command's files are in result.tables and result.json.""")
def compare(scene, tolerance=None, threads=0, contact=None, stepping=None, courant=None,
            dispersion=True, striker_velocity=None):
    return _folder_run("compare", lambda out, paths: _shpb._compare(
        paths[0], out, tolerance, contact, stepping, courant, threads, dispersion,
        striker_velocity), [scene])


@_with_help("study", """study(scene=None, sweep=None, refine=1, tolerance=None, threads=0,
      contact=None, stepping=None, courant=None, distributions=None, draws=None, seed=None,
      plan=None, run=None, shard=None, merge=None, output=None) -> FolderResult

Runs the sweep of `shpb study` on the scene file (threads: parallel runs, 0 = all cores):
"pareto" (sweep None: the command's default), "stability" (refine: the map's refinement) or
"monte-carlo" (distributions: the file of the scene values to draw, draws and seed as --draws
and --seed); the command's files are in result.tables and result.json. Its steps, as the
command's --plan, --run, --shard, --merge and -o: plan=DIR writes DIR/plan.json (the scene a
path: the runs read it again) and returns DIR read back (json["plan"]); run=DIR with
shard="K/N" runs that shard into DIR/parts/K-of-N.json and returns it as a dict; merge=DIR
writes the whole study into `output` (None: DIR/result) and returns it, as study() in one
call returns its folder.""")
def study(scene=None, sweep=None, refine=1, tolerance=None, threads=0, contact=None,
          stepping=None, courant=None, distributions=None, draws=None, seed=None, plan=None,
          run=None, shard=None, merge=None, output=None):
    distributions = None if distributions is None else _path(distributions, "distributions")
    steps = {"plan": plan, "run": run, "merge": merge}
    steps = {k: None if v is None else _path(v, k) for k, v in steps.items()}

    def command(scene_path, out):
        return _shpb._study(scene_path, out, sweep, refine, tolerance, contact, stepping, courant,
                            threads, distributions, draws, seed, steps["plan"], steps["run"],
                            shard, steps["merge"])

    if output is not None and steps["merge"] is None:
        raise TypeError("output: the folder of merge (its -o), given with it alone: a study's "
                        "result is written by result.save(dir)")
    if not any(steps.values()):
        return _folder_run("study", lambda out, paths: command(paths[0], out)[0], [scene],
                           distributions)
    # The user's folders: nothing removed. A plan names its scene's file, which each run and the
    # merge read again: a path (a Scene is one once saved).
    import json
    code, wrote = command("" if scene is None else _scene_file(scene),
                          "" if output is None else _path(output, "output"))
    wrote = _os.fspath(wrote)
    if steps["run"] is not None:
        with open(wrote, encoding="utf-8") as f:
            return json.load(f)
    # What save(dir) may not replace: the plan's scene and materials, and a merge's plan and parts.
    plan_file = _os.path.join(steps["plan"] or steps["merge"], "plan.json")
    with open(plan_file, encoding="utf-8") as f:
        inputs = _shpb._inputs("study", [json.load(f)["scene"]], distributions or "")
    if steps["merge"] is not None:
        inputs += [plan_file, _os.path.join(steps["merge"], "parts")]
    return _warned(FolderResult("study", wrote, code, inputs))


@_with_help("fit", """fit(campaign, threads=0, max_iterations=40, relative_step=0.05, bootstrap=30,
    seed=1) -> FolderResult

Fits the campaign file's free material parameters to its tests, as `shpb fit` does (bootstrap:
refits checking each parameter's interval, 0 for the linearised ones only);
result.json["fit"] is fit.json (a material file), result.tables the command's CSV files.""")
def fit(campaign, threads=0, max_iterations=40, relative_step=0.05, bootstrap=30, seed=1):
    campaign = _scene_file(campaign)  # a campaign file: a Scene is none
    return _folder_run("fit", lambda out, paths: _shpb._fit(
        paths[0], out, threads, max_iterations, relative_step, bootstrap, seed), [campaign])


@_with_help("calibrate", """calibrate(scenes, threads=0) -> FolderResult

Fits the bars (wave speed, Poisson ratio), gauge positions and channel gains and delays to the
calibration shots of `scenes` (the paths of their scene files: bars apart, bars together; one
path alone is one shot), as `shpb calibrate` does; result.json["calibration"] is
calibration.json (what a scene's "calibration" names), result.tables the shot-K.csv files.""")
def calibrate(scenes, threads=0):
    if isinstance(scenes, (str, bytes, _os.PathLike, Scene)):
        scenes = [scenes]
    return _folder_run("calibrate", lambda out, paths: _shpb._calibrate(paths, out, threads),
                       list(scenes))


class CampaignResult(FolderResult):
    """What `process_campaign` returns: the folder of `shpb process --campaign` read back,
    campaign.csv as tables["campaign"], summary.json as summary, and each test's folder as
    tests[name] (a FolderResult: its curve, pulses and raw_signals tables, its summary); of a
    shard, its part: json["part"] (part.json) and the tests it processed."""

    def __init__(self, command, folder, exit_code, inputs=()):
        super().__init__(command, folder, exit_code, inputs)
        # summary.json's tests, each in its folder; a shard's part: part.json's, those it holds.
        listed = (self.summary or self.json["part"])["tests"]
        folders = [(t["name"], _os.path.join(folder, t.get("folder", t["name"]))) for t in listed]
        self.tests = {name: FolderResult(command, path, exit_code, inputs)
                      for name, path in folders if _os.path.isdir(path)}

    @property
    def warnings(self):
        """Each test's warnings in the campaign's order: what the command prints on stderr."""
        return [w for test in self.tests.values() for w in test.warnings]

    def __repr__(self):
        return f"<shpb.CampaignResult of {len(self.tests)} tests: {', '.join(self.tests)}>"


@_with_help("process", """process_campaign(campaign, flow_stress_at=(), draws=None, seed=None,
                 threads=0, shard=None, merge=False, output=None) -> CampaignResult

Processes several measured tests as `shpb process --campaign FILE` (campaign: the path of a
campaign file) or `shpb process SCENE...` (campaign: a list of scene files' paths) does, each
test as the one-test command, plus campaign.csv (result.tables["campaign"]); flow_stress_at:
the engineering strains of --flow-stress-at; draws, seed and threads: each test's
measurement.uncertainty as --draws, --seed and --threads (None: not given, the command's
defaults 1000 and 1). shard="K/N" and merge=True are --shard and --merge, writing into `output`
(the command's -o DIR, needed with them alone): shard returns its part DIR/parts/K-of-N as a
FolderResult, merge DIR/result; the shards draw, so a merge refuses draws or a seed, and a shard
flow_stress_at, as the command does.""")
def process_campaign(campaign, flow_stress_at=(), draws=None, seed=None, threads=0, shard=None,
                     merge=False, output=None):
    if isinstance(campaign, (str, bytes, _os.PathLike, Scene)):
        file, scenes = _scene_file(campaign), []  # a campaign file: a Scene is none
    else:
        file, scenes = None, list(campaign)  # paths or Scenes
    if isinstance(flow_stress_at, (str, bytes)):  # not its characters, one by one
        raise TypeError(f"flow_stress_at: {_shpb._shown(flow_stress_at)}: expected a list of "
                        "engineering strains, e.g. [0.02, 0.05]")
    if isinstance(flow_stress_at, (int, float)):
        flow_stress_at = [flow_stress_at]

    def run(out, paths):
        return _shpb._process_campaign(file, paths, out, list(flow_stress_at), draws, seed,
                                       threads, shard, merge)

    def inputs(paths):
        return _shpb._campaign_inputs(file, paths)

    if (shard is None and not merge) != (output is None):
        raise TypeError("output: the folder of shard and merge (their -o DIR), needed with them "
                        "alone: a campaign's result is written by result.save(dir)")
    if output is None:
        return _folder_run("process", lambda out, paths: [run(out, paths), 0][1], scenes,
                           inputs_of=inputs, kind=CampaignResult)
    # The part or DIR/result, the user's: nothing removed; its part.json names the scenes'
    # files, which a merge reads again (a Scene is run from its file here).
    paths = [_scene_file(s) for s in scenes]
    folder = run(_path(output, "output"), paths)
    return _warned(CampaignResult("process", folder, 0, inputs(paths)))


class PlanResult(FolderResult):
    """The output of `shpb plan`, read into memory: tables["plan_path"] and the other CSV files,
    json["summary"] and json["scene"] (the planned scene, its material files named from the
    result's temporary folder). save(dir) writes the command's folder, its scene.json naming them
    from `dir` as the command's does from its -o."""

    def __init__(self, *args, **kwargs):
        raise TypeError("shpb.PlanResult is what shpb.plan() returns; it is not constructed by "
                        "hand")

    @classmethod
    def _of(cls, native, folder, inputs):
        result = object.__new__(cls)
        FolderResult.__init__(result, "plan", folder, 0, inputs)
        result._native = native
        return result

    def save(self, dir):
        self._native.save(_path(dir, "dir"))


@_with_help("plan", """plan(scene, rate, strain=0.15, search_tolerance="3 %", tolerance="0.5 %",
     threads=0) -> PlanResult

Finds the striker, shaper and specimen within the scene file's `plan` bounds that meet the
target strain `rate` (a number in 1/s or the option's text, "2500 1/s") to the engineering
`strain`, as `shpb plan` does; the tolerances are the gauge errors of the search's runs and of
the verification run (a fraction or text, "3 %"). Raises shpb.NumericalError naming the
criterion missed most when no set-up within the bounds meets the targets (the command's exit 3,
nothing written).""")
def plan(scene, rate, strain=0.15, search_tolerance="3 %", tolerance="0.5 %", threads=0):
    import weakref
    tmp = _tempfile.mkdtemp(prefix="shpb-plan-")
    try:
        scenes = _SceneFiles([scene], tmp)
        with scenes:  # named in summary.json as the user knows it
            native = _shpb._plan(scenes.paths[0], scenes.renamed(scenes.paths[0]), rate, strain,
                                 search_tolerance, tolerance, threads)
        folder = _os.path.join(tmp, "out")
        native.save(folder)
        result = PlanResult._of(native, folder, native.inputs)
    except BaseException:
        _shutil.rmtree(tmp, True)
        raise
    weakref.finalize(result, _shutil.rmtree, tmp, True)
    return _warned(result)


@_with_help("report", """report(folder) -> str

Draws the figures of an output folder (`folder`: a path; a result saved first by
result.save(dir)) into folder/figures and writes folder/report.html, as `shpb report` does
(python3 with matplotlib and numpy), and returns the path of report.html. The script's
warnings are ShpbWarnings; its error is shpb.InputError (exit 2: not an output folder, a
figures/ or report.html shpb did not write) or shpb.WriteError (exit 3).""")
def report(folder):
    folder = _path(folder, "folder")
    for text in _shpb._report(folder):
        _warnings.warn(text, ShpbWarning, stacklevel=2)
    return _os.path.join(_os.path.abspath(folder), "report.html")


@_with_help("dispersion", """dispersion(poisson=0.29, a_over_lambda=None, max_a_over_lambda=None,
           points=None, radius_m=None, c0_m_s=None)

The Pochhammer-Chree table of `shpb dispersion` (columns a_over_lambda, c_over_c0, cg_over_c0,
f_a_over_c0 and, with radius_m and c0_m_s, frequency_Hz): a DataFrame with pandas, else a
dict of numpy arrays. The rows are the list a_over_lambda, or points (default 321) evenly
spaced values up to max_a_over_lambda (default 1.6): not both.""")
def dispersion(poisson=0.29, a_over_lambda=None, max_a_over_lambda=None, points=None,
               radius_m=None, c0_m_s=None):
    # A text is iterable too: "12" was read as the two values 1 and 2.
    if isinstance(a_over_lambda, (str, bytes)) or not (a_over_lambda is None
                                                       or hasattr(a_over_lambda, "__iter__")):
        raise TypeError(f"a_over_lambda: {_shpb._shown(a_over_lambda)}: expected a list of "
                        "numbers such as [0.1, 0.5]")
    with _tempfile.TemporaryDirectory(prefix="shpb-dispersion-") as tmp:
        path = _os.path.join(tmp, "dispersion.csv")
        _shpb._dispersion(poisson, [] if a_over_lambda is None else list(a_over_lambda), max_a_over_lambda, points,
                          radius_m, c0_m_s, path)
        return _table(_read_csv(path))
