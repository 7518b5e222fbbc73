"""A user's own detector checked for stability in fog (docs/python.md, "Your own
algorithm in fog")."""
import numbers

import numpy as np
import pandas as pd

from . import _core
from ._errors import InvalidParameter

ORIGINS = list(_core.origin_labels)  # the sensors' one code table (sensor/origin.hpp)


class StabilityReport:
    """What `stability` found, per step (active layers):

    table       a DataFrame, a row per step: items, detection_rate (items with a target-origin
                detection within the gate of the target's range), false_alarms_per_item (fog,
                noise, sidelobe and clipping detections) with its fog_, noise_ and
                sidelobe_false_alarms_per_item and clipping_detections_per_item parts,
                background_detections_per_item (static surfaces such as the lidar's walls: real
                echoes, not false alarms), multipath_detections_per_item (the radar's ghosts of
                the target via the room) and room_detections_per_item (the radar's walls and
                objects: real echoes, neither false alarms nor the target), the spread of
                the target detections' values (value_n, value_median, value_q1, value_q3,
                value_std, value_min, value_max; fogradar's type-7 box-plot statistics) and, where
                the measurements kept a detection table with an ``associated`` column,
                chain_detection_rate (fogradar's own chain on the same items)
    detections  every detection the algorithm returned: active_layers, item, range_m, value,
                origin (a Categorical over the sensors' one code table: noise, target, fog,
                background, clipping, sidelobe, multipath, room) and layer (for a fog origin the chamber layer,
                the index in chamber.layers, that dominates it; -1 otherwise and where the
                sensor's ground truth has no layers)
    layers_to_failure   the first step whose detection rate is below `criterion_rate`, else None
    criterion   the rule, in words
    """

    def __init__(self, table, detections, layers_to_failure, criterion, value_label):
        self.table = table
        self.detections = detections
        self.layers_to_failure = layers_to_failure
        self.criterion = criterion
        self.value_label = value_label

    def boxplot_svg(self, title="Your algorithm: the target's value per step"):
        """fogradar's box plot (as radar_rcs_boxplot.svg) of the target detections' values per
        step, the detection rate as the strip under the boxes, the limit marked."""
        steps = list(self.table["active_layers"])
        values = [list(self.detections.loc[(self.detections["active_layers"] == k)
                                           & (self.detections["origin"] == "target"), "value"]
                       .dropna()) for k in steps]
        marked = steps.index(self.layers_to_failure) if self.layers_to_failure is not None else None
        return _core.box_plot_svg([str(k) for k in steps], values,
                                  list(self.table["detection_rate"]), title, [self.criterion],
                                  "active fog layers", self.value_label, "target detected",
                                  marked, "limit" if marked is not None else "")

    def benchmark_svg(self, title="Detection rate per step"):
        """The detection rate against active layers (as benchmark.svg), the algorithm's and,
        where the table has it, fogradar's own chain's."""
        steps = [float(k) for k in self.table["active_layers"]]
        labels, ys = ["your algorithm"], [list(self.table["detection_rate"])]
        if "chain_detection_rate" in self.table:
            labels.append("fogradar's chain")
            ys.append(list(self.table["chain_detection_rate"]))
        return _core.line_plot_svg(labels, [steps] * len(labels), ys, title, [self.criterion],
                                   "active fog layers", "detection rate")

    def __repr__(self):
        limit = "not reached" if self.layers_to_failure is None else self.layers_to_failure
        return f"<fogradar.StabilityReport layers to failure: {limit}>\n{self.table}"


def _detections_of(result):
    """The algorithm's answer as a list of detections ({"range_m", "value", and where given
    "velocity_m_per_s" and "beam"}), plus a detected flag for answers without ranges."""
    if isinstance(result, (bool, np.bool_)):
        return [], bool(result)
    if isinstance(result, dict) and "detected" in result:
        return ([{"range_m": None, "value": result.get("value", np.nan)}]
                if result["detected"] else []), None
    if isinstance(result, dict):
        result = pd.DataFrame(result)
    elif isinstance(result, (list, tuple)):
        result = pd.DataFrame(list(result), columns=None if result else ["range_m"])
    if not isinstance(result, pd.DataFrame):
        raise TypeError("the algorithm returns its detections as a DataFrame, a list of dicts or a "
                        "dict of arrays with a column range_m (and optionally value), or a bool / "
                        "{'detected': bool, 'value': float} for a sensor without ranges; got "
                        f"{type(result).__name__}")
    if len(result) and "range_m" not in result.columns:
        raise TypeError("the algorithm's detections need a column range_m")
    n = len(result)
    columns = {"range_m": result["range_m"] if n else [],
               "value": result["value"] if "value" in result.columns else [np.nan] * n}
    for extra in ("velocity_m_per_s", "beam", "attributed_range_m", "range_cell",
                  "doppler_cell"):
        if extra in result.columns:
            columns[extra] = result[extra]
    out = []
    for i in range(n):
        d = {name: values.iloc[i] if hasattr(values, "iloc") else values[i]
             for name, values in columns.items()}
        d["range_m"], d["value"] = float(d["range_m"]), float(d["value"])
        out.append(d)
    return out, None


def _cell(truth, attributes, detection):
    """The (row, column) of the radar's map a detection peaks in: its range_cell and doppler_cell
    when it gives them (the chain's own detections do), else its range column with the
    range-Doppler coupling put back and its velocity's Doppler row (0 m/s when not given)."""
    rows, columns = truth.shape
    if "range_cell" in detection and "doppler_cell" in detection:
        return int(detection["doppler_cell"]) % rows, int(detection["range_cell"]) % columns
    velocity = float(detection.get("velocity_m_per_s", 0.0))
    range_bin = (detection["range_m"] + attributes["range_coupling_s"] * velocity) / \
        attributes["range_bin_m"]
    column = int(np.clip(np.floor(range_bin + 0.5), 0, columns - 1))
    row = int(np.floor(velocity / attributes["velocity_bin_m_per_s"] + 0.5)) % rows
    return row, column


def _stretch_origin(truth, labels, detection):
    """The origin and fog layer of the lidar's stretch of the detection's beam that holds its
    attributed_range_m (the peak of the return whose leading edge made the echo, where the lidar
    attributes it), else its range_m; noise outside every stretch. The layer is the table's
    ``layer`` where it has that column, else -1."""
    if "beam" not in detection:
        raise TypeError("the lidar's detections need a column beam (the beam index, as the "
                        "echoes' table has it): its ground truth is per beam")
    beam = int(detection["beam"])
    range_m = float(detection.get("attributed_range_m", detection["range_m"]))
    inside = np.nonzero((truth["beam"] == beam) & (truth["start_m"] <= range_m)
                        & (range_m < truth["end_m"]))[0]
    if not len(inside):
        return "noise", -1
    layer = int(truth["layer"][inside[0]]) if "layer" in truth else -1
    return labels[truth["origin"][inside[0]]], layer


def _origin_of(m, detection):
    """A detection's origin and fog layer (-1 where not fog) from the measurement's own ground
    truth (its kinds ``origins`` and, for the radar, ``origin_layers``, which the sensor's
    attribution wrote from the chamber it measured through)."""
    if detection["range_m"] is None:
        return "target", -1  # an answer without ranges (the camera's) says whether it saw it
    kind = m._kinds.get("origins")
    if kind is None:
        raise TypeError(f"the {m.sensor} has no ground truth per range (no raw kind 'origins'): "
                        "answer with a bool or {'detected': bool, 'value': float}")
    raw = m._raw["origins"]
    if kind["element"] == "table":
        truth = {c["name"]: c["values"] for c in raw["columns"]}
        return _stretch_origin(truth, ORIGINS, detection)
    row, column = _cell(raw, kind["attributes"], detection)
    origin = kind["labels"][raw[row, column]]
    layers = m._raw.get("origin_layers")
    layer = int(layers[row, column]) if layers is not None and origin == "fog" else -1
    return origin, layer


def stability(scenario, sensor, algorithm, keep=None, gate_m=0.5, criterion_rate=0.5,
              steps=None, items=None, value_label="value", threads=0, simulator=None):
    """Runs ``algorithm(measurement)`` over every item of every step of `sensor` (or the
    ``steps`` and first ``items`` per step given) and reports its detections against the ground
    truth, per step, as fogradar reports its own chain: a StabilityReport.

    The measurement is Simulator.measure's (the raw kinds in `keep`, default those `fogradar run
    --raw` keeps, and always the ground truth ``origins`` where the sensor has one). The algorithm
    returns its detections: a DataFrame, a list of dicts or a dict of arrays with a column
    ``range_m`` and optionally ``value`` (an estimate such as an RCS or a power, whose spread is
    reported); or, for a sensor without ranges (the camera), a bool or
    ``{"detected": bool, "value": float}``, the detection counted as the target's.

    Ground truth, from C++ (docs/python.md): each measurement carries the origin the sensor's own
    attribution gives at each range of that item (its raw kind ``origins``: the radar's per cell
    of the range-Doppler map, the lidar's per beam), made from the chamber it measured through.
    A radar detection is looked up at its peak cell ``range_cell`` and ``doppler_cell`` when it
    gives them (the chain's detections table has them), else at its range and
    ``velocity_m_per_s`` (0 when not given); its fog layer in the kind ``origin_layers``. A lidar
    detection at its ``beam`` and ``attributed_range_m`` (the peak of the return whose leading
    edge made the echo, where the lidar attributes it; its ``range_m`` when not given). An item
    counts as detected when one of its detections is the target's and within `gate_m` of the
    target's range. The limit is the first step whose detection rate is below `criterion_rate`.
    """
    from . import Scenario, Simulator  # the package's classes (this module is imported by it)

    if not isinstance(scenario, Scenario):
        raise TypeError("stability needs a fogradar.Scenario")
    if not callable(algorithm):
        raise TypeError("algorithm must be callable with one fogradar.Measurement")
    for name, value, low, high in (("gate_m", gate_m, 0.0, 1e4),
                                   ("criterion_rate", criterion_rate, 0.0, 1.0)):
        if not isinstance(value, numbers.Real) or not (low < value <= high):
            raise InvalidParameter(f"{name} = {value!r}: must be in ({low:g}, {high:g}]", name)
    sim = simulator if simulator is not None else Simulator(scenario, threads=threads)
    target_m = scenario._core.target_range_m
    all_steps = list(range(scenario.steps))
    chosen_steps = all_steps if steps is None else list(steps)
    for k in chosen_steps:
        if k not in all_steps:
            raise InvalidParameter(f"steps: {k!r} is no step of the scenario: [0, "
                                   f"{all_steps[-1]}]", "steps")
    per_step = sim.items_per_step(sensor)
    count = per_step if items is None else min(int(items), per_step)
    if count < 1:
        raise InvalidParameter(f"items = {items!r}: must be at least 1", "items")

    offered = [k["name"] for k in sim.kinds(sensor)]
    if keep is None:
        keep = [k["name"] for k in sim.kinds(sensor) if k["by_default"]]
    else:
        keep = [keep] if isinstance(keep, str) else list(keep)
    for truth in ("origins", "origin_layers"):
        if truth in offered and truth not in keep:
            keep.append(truth)

    rows, found = [], []
    for k in chosen_steps:
        detected = chain_detected = 0
        chain_seen = False
        counts = dict.fromkeys(ORIGINS, 0)
        values = []
        for index, m in zip(range(count), sim.items(sensor, k, keep)):
            answer, flag = _detections_of(algorithm(m))
            hit = bool(flag)
            for d in answer:
                o, layer = _origin_of(m, d)
                found.append({"active_layers": k, "item": index, "range_m": d["range_m"],
                              "value": d["value"], "origin": o, "layer": layer})
                counts[o] += 1
                in_gate = d["range_m"] is None or abs(d["range_m"] - target_m) <= gate_m
                if o == "target" and in_gate:
                    hit = True
                    if not np.isnan(d["value"]):
                        values.append(d["value"])
            if flag:
                found.append({"active_layers": k, "item": index, "range_m": None,
                              "value": np.nan, "origin": "target", "layer": -1})
            detected += hit
            if m.has_associated():
                chain_seen = True
                chain_detected += m.target is not None and m.target["origin"] == "target"
        box = _core.box_plot(values) if values else {}
        row = {"active_layers": k, "items": count, "detection_rate": detected / count,
               "false_alarms_per_item":
                   (counts["fog"] + counts["noise"] + counts["sidelobe"] + counts["clipping"])
                   / count,
               "fog_false_alarms_per_item": counts["fog"] / count,
               "noise_false_alarms_per_item": counts["noise"] / count,
               "sidelobe_false_alarms_per_item": counts["sidelobe"] / count,
               "clipping_detections_per_item": counts["clipping"] / count,
               "background_detections_per_item": counts["background"] / count,
               "multipath_detections_per_item": counts["multipath"] / count,
               "room_detections_per_item": counts["room"] / count,
               "value_n": len(values)}
        for stat in ("median", "q1", "q3", "std", "min", "max"):
            row[f"value_{stat}"] = box.get(stat, np.nan)
        if chain_seen:
            row["chain_detection_rate"] = chain_detected / count
        rows.append(row)
    table = pd.DataFrame(rows)
    detections = pd.DataFrame(found, columns=["active_layers", "item", "range_m", "value",
                                              "origin", "layer"])
    detections["origin"] = pd.Categorical(detections["origin"], categories=ORIGINS)
    failing = table.loc[table["detection_rate"] < criterion_rate, "active_layers"]
    limit = int(failing.iloc[0]) if len(failing) else None
    criterion = (f"target detected (a target-origin detection within {gate_m:g} m of its range) in < "
                 f"{100 * criterion_rate:g} % of the items")
    return StabilityReport(table, detections, limit, criterion, value_label)
