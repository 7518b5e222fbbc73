"""fogradar: automotive radar, lidar and camera in fog, from Python (docs/python.md).

    import fogradar
    sim = fogradar.Simulator(fogradar.Scenario.paper())
    results = sim.run()                      # every sensor, every step, as `fogradar run`
    results.summary()                        # one DataFrame: a row per sensor x step
    m = sim.measure("radar", step=4, index=0, keep=("beat", "range_doppler", "detections"))
    m.range_doppler, m.detections, m.target  # NumPy views, a DataFrame, the gate's detection

Scenarios come from the paper, a file, TOML text or a dict of the same keys; bad input raises
InvalidParameter (a ValueError) with the command line's message. The simulator makes everything
once (chamber, FFT plans, CFAR design, fog optics) and is safe to share between threads; the GIL
is released while it computes. ``stability`` runs a user's own detector over every item of every
step and reports its stability per layer the way fogradar reports its own chain.
"""
import io
import threading
import tomllib

import numpy as np
import pandas as pd

from . import _core
from ._errors import InvalidParameter
from ._toml import dumps as dict_to_toml

__version__ = _core.version
__all__ = ["InvalidParameter", "Scenario", "Simulator", "Results", "Measurement", "stability",
           "dict_to_toml", "optical_model_table", "layer_model_table", "longest_layer_m"]


class Scenario:
    """A scenario: the chamber, its fog, the methodology and every sensor's keys
    (docs/scenario.md). Immutable: with_overrides returns a new one."""

    def __init__(self, core):
        self._core = core

    @classmethod
    def paper(cls):
        """The study's scenario, compiled in (examples/paper.toml)."""
        return cls(_core.Scenario.paper())

    @classmethod
    def from_file(cls, path):
        """A scenario file over the paper scenario, as `fogradar run --scenario PATH`."""
        return cls(_core.Scenario.load(str(path)))

    @classmethod
    def from_toml(cls, text, source="<string>"):
        """TOML text over the paper scenario; messages name `source` and the line."""
        return cls(_core.Scenario.parse(text, source))

    @classmethod
    def from_dict(cls, mapping, source="<dict>"):
        """A dict of the same keys over the paper scenario: nested tables or dotted keys
        ({"fog": {"lwc_g_per_m3": 0.5}} or {"fog.lwc_g_per_m3": 0.5}), lists of dicts for arrays
        of tables. It is read as its TOML text, dict_to_toml(mapping); a message names `source`
        and the dotted key ("<dict>: radar.tx_power_dbm = 99.0: ..."), no line of that text."""
        return cls.paper().with_overrides(mapping, source)

    def with_overrides(self, overrides, source="<overrides>"):
        """A new scenario: this one with the keys of `overrides` (dotted keys or nested dicts)
        replaced; the rest as here. Messages as from_dict's."""
        return Scenario(self._core.over(dict_to_toml(overrides), source, line_numbers=False))

    def to_toml(self):
        """The resolved scenario, every key that takes effect (the run's scenario.toml)."""
        return self._core.to_toml()

    def to_dict(self):
        return tomllib.loads(self.to_toml())

    @property
    def sensors(self):
        """The sensors that run (experiment.sensors), in order."""
        return list(self._core.sensors)

    @property
    def steps(self):
        """Steps k = 0 .. max_active_layers."""
        return self._core.steps

    def __repr__(self):
        return f"<fogradar.Scenario sensors={self.sensors} steps={self.steps}>"


class Measurement:
    """One item (step, index) of a sensor, exactly as `fogradar run` measures it, with the raw
    data kept (docs/data-out.md): arrays as read-only NumPy views of C++ buffers, tables as
    DataFrames whose columns view them too (enumerations such as ``origin`` as pandas Categoricals).
    Attributes and ``m["name"]`` give the kinds; ``axes`` the axes of the arrays (e.g. range_m,
    velocity_m_per_s); ``target`` the detection table's row marked ``associated`` (the radar's
    gate detection), else None."""

    def __init__(self, sensor, step, index, kinds, data):
        self.sensor = sensor
        self.step = step
        self.index = index
        self._kinds = {k["name"]: k for k in kinds}
        self.axes = {}
        self._raw = data
        self._tables = {}
        for name in data:
            for axis_name, axis in self._kinds[name]["axes"].items():
                self.axes[axis_name] = axis["values"]

    @property
    def data(self):
        """{kind: array or DataFrame} of every kind kept."""
        return {name: self[name] for name in self._raw}

    def __getitem__(self, name):
        if name not in self._raw:
            raise KeyError(f"{name!r}: not kept; kept: {sorted(self._raw)}")
        if self._kinds[name]["element"] != "table":
            return self._raw[name]
        if name not in self._tables:  # made on first use: pandas is slow to build a frame
            self._tables[name] = _table(self._raw[name])
        return self._tables[name]

    def __getattr__(self, name):
        raw = self.__dict__.get("_raw", {})
        if name in raw:
            return self[name]
        raise AttributeError(f"{name!r}: not kept; kept: {sorted(raw)}")

    def arrays(self, name):
        """A table kind's columns as the NumPy arrays its DataFrame views (an enumeration's
        codes, int8)."""
        return {c["name"]: c["values"] for c in self._raw[name]["columns"]}

    def units(self, name):
        return self._kinds[name]["units"]

    def attributes(self, name):
        """Numbers a reader needs beside a kind (e.g. the map's thermal_noise_level)."""
        return dict(self._kinds[name]["attributes"])

    def has_associated(self):
        """Whether a kept table marks its gate detection (a column ``associated``)."""
        return any(self._kinds[n]["element"] == "table" and
                   any(c["name"] == "associated" for c in self._raw[n]["columns"])
                   for n in self._raw)

    @property
    def target(self):
        for name, raw in self._raw.items():
            if self._kinds[name]["element"] != "table":
                continue
            columns = {c["name"]: c["values"] for c in raw["columns"]}
            if "associated" in columns:
                rows = np.nonzero(columns["associated"] == 1)[0]
                return self[name].iloc[rows[0]] if len(rows) else None
        return None

    def __repr__(self):
        return (f"<fogradar.Measurement {self.sensor} step={self.step} index={self.index} "
                f"kept={sorted(self._raw)}>")


def _table(table):
    columns = {}
    for column in table["columns"]:
        values = column["values"]
        if column["labels"]:
            columns[column["name"]] = pd.Categorical.from_codes(values, column["labels"])
        else:
            columns[column["name"]] = values
    if not columns:
        return pd.DataFrame(index=range(table["rows"]))
    return pd.DataFrame(columns, copy=False)


class Results:
    """A run's results: the per-step summaries, the sensors' limits and every result file
    `fogradar run` writes."""

    def __init__(self, core):
        self._core = core
        self._files = None

    @property
    def files(self):
        """{file name: bytes} of the result set (as `fogradar run` writes it)."""
        if self._files is None:
            self._files = dict(self._core.files())
        return self._files

    def table(self, name):
        """A result CSV file as a DataFrame."""
        if name not in self.files:
            csv = sorted(n for n in self.files if n.endswith(".csv"))
            raise InvalidParameter(f"{name!r} is no result file of this run: {', '.join(csv)}",
                                   "name")
        # round_trip: the files write every number exactly, pandas' default parser reads it less so.
        return pd.read_csv(io.BytesIO(self.files[name]), float_precision="round_trip")

    def summary(self):
        """One DataFrame, a row per sensor x step: ``sensor``, ``active_layers`` and each
        sensor's summary columns by their CSV names (<sensor>_summary.csv), made from the
        sensors' typed step tables: integers as int64, numbers as float64 (NaN where none),
        lists of numbers (outliers) as lists."""
        frames = []
        for table in self._core.step_tables():
            frame = pd.DataFrame(table["columns"])
            frame.insert(0, "sensor", table["sensor"])
            frames.append(frame)
        summary = pd.concat(frames, ignore_index=True, sort=False)
        first = ["sensor", "active_layers"]
        return summary[first + [c for c in summary.columns if c not in first]]

    def _sensor_table(self, sensor, suffix):
        if sensor is None:
            owners = [n[:-len(suffix)] for n in self.files if n.endswith(suffix)]
            if len(owners) != 1:
                raise InvalidParameter(f"sensor = None: name one of the sensors with a "
                                       f"*{suffix} file: {', '.join(owners) or 'none ran'}",
                                       "sensor")
            sensor = owners[0]
        return self.table(f"{sensor}{suffix}")

    def samples(self, sensor=None):
        """A sensor's per-item table, <sensor>_samples.csv (the radar's: every measurement's gate
        detection); `sensor` may be left out when one sensor that ran has one."""
        return self._sensor_table(sensor, "_samples.csv")

    def detections(self, sensor=None):
        """Every detection of every item with its origin, <sensor>_detections.csv; `sensor` may
        be left out when one sensor that ran has one."""
        return self._sensor_table(sensor, "_detections.csv")

    def limits(self):
        """Per sensor: layers to failure (None: not reached), its criterion and margin."""
        return pd.DataFrame(self._core.limits()).set_index("sensor")

    def tables(self):
        """The per-step tables and benchmark lines `fogradar run` prints."""
        return self._core.tables()

    def write(self, directory):
        """Writes the result set into `directory`, byte-identical to `fogradar run --out`, and
        replaces it whole as the command does."""
        self._core.write(str(directory))


class Simulator:
    """Everything a scenario's run needs, made once (chamber, FFT plans, CFAR design, fog optics);
    immutable and safe to share between threads. `threads` = 0: all cores.
    `memory_limit_mib`: refuse a scenario estimated over it (default as `fogradar run`)."""

    def __init__(self, scenario, threads=0, memory_limit_mib=None):
        if not isinstance(scenario, Scenario):
            raise TypeError("Simulator needs a fogradar.Scenario")
        if not isinstance(threads, int) or threads < 0 or threads > 4096:
            raise InvalidParameter(f"threads = {threads!r}: must be an integer in [0, 4096]",
                                   "threads")
        if memory_limit_mib is not None and not (
                isinstance(memory_limit_mib, (int, float)) and 1 <= memory_limit_mib <= 1e9):
            raise InvalidParameter(
                f"memory_limit_mib = {memory_limit_mib!r}: must be a number in [1, 1e9] (MiB), "
                "as fogradar run's --memory-limit-mib", "memory_limit_mib")
        self.scenario = scenario
        self.threads = threads
        self._core = _core.Simulation(scenario._core, threads, memory_limit_mib)
        self._local = threading.local()  # each thread's item runs, one per sensor

    def _item_run(self, sensor):
        runs = self._local.__dict__.setdefault("runs", {})
        if sensor not in runs:
            runs[sensor] = _core.ItemRun(self._core, sensor)
        return runs[sensor]

    def run(self):
        """Every item of every sensor and step, as `fogradar run`; Ctrl-C stops it."""
        return Results(self._core.run(self.threads))

    def kinds(self, sensor):
        """The raw data kinds the sensor offers: name, description, units, element, dimensions,
        shape, axes."""
        return self._item_run(sensor).kinds

    def measure(self, sensor, step, index, keep=None):
        """Item `index` of step `step` (active layers) of `sensor`, exactly as in `run()`, with the
        raw data kinds in `keep` (default: the kinds `fogradar run --raw` keeps by default; the
        radar's ``signal`` and ``noise``, the beat's two parts, only when named)."""
        return self._measure(self._item_run(sensor), sensor, step, index, keep)

    def items(self, sensor, step, keep=None):
        """Every item of a step, in index order (one sensor run, its step prepared once)."""
        run = _core.ItemRun(self._core, sensor)
        for index in range(run.items_per_step):
            yield self._measure(run, sensor, step, index, keep)

    def items_per_step(self, sensor):
        return self._item_run(sensor).items_per_step

    @staticmethod
    def _measure(run, sensor, step, index, keep):
        kinds = run.kinds
        if keep is None:
            names = [k["name"] for k in kinds if k["by_default"]]
        else:
            names = [keep] if isinstance(keep, str) else list(keep)
        for label, value in (("step", step), ("index", index)):
            if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value < 0:
                raise InvalidParameter(f"{label} = {value!r}: must be a non-negative integer",
                                       label)
        return Measurement(sensor, int(step), int(index), kinds,
                           run.measure(int(step), int(index), names))


def optical_model_table(mie_extinction_per_km, visibility_m, wavelength_nm,
                        models=("kruse", "kim")):
    """The study's optical attenuation models at one wavelength, as `fogradar fog` prints them: Mie
    as given (the fog's own extinction there, 1/km), then eq. 1 with Kruse's q (eq. 2) and Kim's
    from the eq. 6 visibility (m; inf without water). A DataFrame indexed by model:
    extinction_per_km, q (None for Mie and without water)."""
    rows = _core.optical_model_table([models] if isinstance(models, str) else list(models),
                                     mie_extinction_per_km, visibility_m, wavelength_nm)
    return pd.DataFrame(rows).set_index("model")


def layer_model_table(transmittance, reflectance, max_layers, object_reflectivity=1.0):
    """The study's virtual layer model (eq. 3, 4) for a stack of identical layers of transmittance
    tau and reflectance rho, as `fogradar fog --layer-model` prints it: a row per object behind
    0 .. max_layers layers with kappa = 2 layers + 1, the fog's echo (eq. 3) and the object's
    (eq. 4), both per I_0."""
    rows = _core.layer_model_table(transmittance, reflectance, max_layers, object_reflectivity)
    return pd.DataFrame(rows).set_index("layers")


def longest_layer_m(extinction_per_m, eta_m2_per_m3):
    """The longest layer d whose virtual layer keeps exp(-alpha d) + eta d <= 1 (eta < alpha)."""
    return _core.longest_layer_m(extinction_per_m, eta_m2_per_m3)


from ._stability import stability  # noqa: E402  (uses the classes above)
