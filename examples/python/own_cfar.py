#!/usr/bin/python3
"""A user's own detector checked for stability in fog (docs/python.md): a NumPy OS-CFAR on each
frame's range-Doppler map, run over the paper fog and over examples/lost_target.toml, its
detection rate and false alarms per layer printed as tables.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/own_cfar.py [--items N]
"""
import argparse
import os

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

import fogradar


def os_cfar(m, guard=2, train=12, rank=0.75, scale_db=16.0):
    """OS-CFAR along range on every Doppler row: a cell is detected when its power exceeds
    scale x the rank-quantile of its 2 x train training cells; each row's local maxima only."""
    power = np.asarray(m.range_doppler)
    half = guard + train
    padded = np.pad(power, ((0, 0), (half, half)), mode="wrap")
    windows = sliding_window_view(padded, 2 * half + 1, axis=1)
    training = np.concatenate([windows[..., :train], windows[..., -train:]], axis=-1)
    k = int(rank * (2 * train)) - 1
    level = np.partition(training, k, axis=-1)[..., k]
    hits = power > level * 10 ** (scale_db / 10)
    peaks = hits & (power >= np.roll(power, 1, axis=1)) & (power >= np.roll(power, -1, axis=1))
    rows, cols = np.nonzero(peaks)
    return {"range_m": m.axes["range_m"][cols], "value": 10 * np.log10(power[rows, cols])}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--items", type=int, default=25, help="frames per step (default 25)")
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    cases = [("paper fog", fogradar.Scenario.paper()),
             ("lost target", fogradar.Scenario.from_file(os.path.join(root, "examples",
                                                                       "lost_target.toml")))]
    for title, scenario in cases:
        report = fogradar.stability(scenario, "radar", os_cfar, keep=("range_doppler",
                                                                      "detections"),
                                    items=args.items, value_label="peak power (dB)")
        print(f"{title}: {report.criterion}")
        columns = ["active_layers", "detection_rate", "chain_detection_rate",
                   "fog_false_alarms_per_item", "noise_false_alarms_per_item", "value_median"]
        print(report.table[columns].to_string(index=False, float_format=lambda v: f"{v:.3f}"))
        limit = report.layers_to_failure
        print(f"layers to failure: {'not reached' if limit is None else limit}\n")


if __name__ == "__main__":
    main()
