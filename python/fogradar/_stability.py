"""A user's own detector checked for stability in fog (DESIGN §12, docs/python.md, "Your own
algorithm in fog")."""
import numbers

import numpy as np
import pandas as pd

from . import _core
from ._errors import InvalidParameter

ORIGINS = ["noise", "target", "fog"]


class StabilityReport:
    """What `stability` found, per step (active layers):

    table       a DataFrame, a row per step: items, detection_rate (items with a detection of the
                target), false_alarms_per_item, fog_ and noise_false_alarms_per_item, the spread
                of the target detections' values (value_n, value_median, value_q1, value_q3,
                value_std, value_min, value_max; fogradar's type-7 box-plot statistics) and, where
                the measurements kept a detection table with an ``associated`` column,
                chain_detection_rate (fogradar's own chain on the same items)
    detections  every detection the algorithm returned: active_layers, item, range_m, value and
                origin (a Categorical: noise, target, fog)
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
    """The algorithm's answer as (range_m or None, value) pairs, plus a detected flag for
    answers without ranges."""
    if isinstance(result, (bool, np.bool_)):
        return [], bool(result)
    if isinstance(result, dict) and "detected" in result:
        return [(None, result.get("value", np.nan))] if result["detected"] else [], None
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
    values = result["value"] if "value" in result.columns else [np.nan] * len(result)
    return [(float(r), float(v)) for r, v in zip(result.get("range_m", []), values)], None


def stability(scenario, sensor, algorithm, keep=None, gate_m=0.5, criterion_rate=0.5,
              steps=None, items=None, value_label="value", threads=0, simulator=None):
    """Runs ``algorithm(measurement)`` over every item of every step of `sensor` (or the
    ``steps`` and first ``items`` per step given) and reports its detections against the ground
    truth, per step, as fogradar reports its own chain: a StabilityReport.

    The measurement is Simulator.measure's (the raw kinds in `keep`, default all). The algorithm
    returns its detections: a DataFrame, a list of dicts or a dict of arrays with a column
    ``range_m`` and optionally ``value`` (an estimate such as an RCS or a power, whose spread is
    reported); or, for a sensor without ranges (the camera), a bool or
    ``{"detected": bool, "value": float}``, the detection counted as the target's.

    Ground truth, from the chamber (docs/python.md): a detection within `gate_m` of the target's
    range is the target's; one inside a fog layer switched on at that step, the fog's; any other,
    the noise's. An item counts as detected when one of its detections is the target's. The limit
    is the first step whose detection rate is below `criterion_rate`.
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
    chamber = scenario.to_dict()["chamber"]
    start = chamber["sensor_gap_m"]
    length = chamber["layer_length_m"]
    layers = chamber["layer_count"]
    target_m = start + layers * length + chamber["target_gap_m"]
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

    def origin(range_m, k):
        if range_m is None or abs(range_m - target_m) <= gate_m:
            return "target"
        if start <= range_m <= start + k * length:
            return "fog"
        return "noise"

    rows, found = [], []
    for k in chosen_steps:
        detected = chain_detected = 0
        chain_seen = False
        fog = noise = 0
        values = []
        for index, m in zip(range(count), sim.items(sensor, k, keep)):
            answer, flag = _detections_of(algorithm(m))
            hit = bool(flag)
            for range_m, value in answer:
                o = origin(range_m, k)
                found.append({"active_layers": k, "item": index, "range_m": range_m,
                              "value": value, "origin": o})
                hit = hit or o == "target"
                fog += o == "fog"
                noise += o == "noise"
                if o == "target" and not np.isnan(value):
                    values.append(value)
            if flag:
                found.append({"active_layers": k, "item": index, "range_m": None,
                              "value": np.nan, "origin": "target"})
            detected += hit
            if m.has_associated():
                chain_seen = True
                chain_detected += m.target is not None
        box = _core.box_plot(values) if values else {}
        row = {"active_layers": k, "items": count, "detection_rate": detected / count,
               "false_alarms_per_item": (fog + noise) / count,
               "fog_false_alarms_per_item": fog / count,
               "noise_false_alarms_per_item": noise / count,
               "value_n": len(values)}
        for stat in ("median", "q1", "q3", "std", "min", "max"):
            row[f"value_{stat}"] = box.get(stat, np.nan)
        if chain_seen:
            row["chain_detection_rate"] = chain_detected / count
        rows.append(row)
    table = pd.DataFrame(rows)
    detections = pd.DataFrame(found, columns=["active_layers", "item", "range_m", "value",
                                              "origin"])
    detections["origin"] = pd.Categorical(detections["origin"], categories=ORIGINS)
    failing = table.loc[table["detection_rate"] < criterion_rate, "active_layers"]
    limit = int(failing.iloc[0]) if len(failing) else None
    criterion = (f"target detected (a detection within {gate_m:g} m of its range) in < "
                 f"{100 * criterion_rate:g} % of the items")
    return StabilityReport(table, detections, limit, criterion, value_label)
