#!/usr/bin/python3
"""Why an OS-CFAR loses the slow target of examples/room_clutter.toml (docs/radar.md §7.1).

Re-applies the OS rule to the chain's own range-Doppler maps in NumPy (interior factors of
docs/radar.md §7 and §7.1: range 27.55 at rank 12 of 16, ring 12.06 at rank 99 of 132; Hann,
P_fa 1e-6; edges left out) and asks, per frame, whether the target's peak cell passes its threshold
and lies in one 8-connected object (Doppler wrapping, as the chain groups cells) with the back
wall's peak cell. Beside it, whether fogradar's own chain (the same shape and kind) kept the target.
Usage: PYTHONPATH=build/release/python scripts/cfar-room-merge.py SHAPE BINS [FRAMES]
"""
import pathlib
import sys

import numpy as np
from scipy import ndimage

import fogradar

shape, bins = sys.argv[1], float(sys.argv[2])
frames = int(sys.argv[3]) if len(sys.argv) > 3 else 20
bin_m_per_s = 299792458 / 77e9 / (2 * 64 * 51.2e-6)
text = (pathlib.Path(__file__).resolve().parent.parent / "examples/room_clutter.toml").read_text()
text += (f'\n[target]\nradial_velocity_m_per_s = {bins * bin_m_per_s}\n'
         f'[radar.processing.cfar]\nshape = "{shape}"\nkind = "os"\n')
sim = fogradar.Simulator(fogradar.Scenario.from_toml(text))
g, n, gd, nd = 2, 8, 1, 2
if shape == "range":
    offsets = [(0, dk) for dk in range(-g - n, g + n + 1) if abs(dk) > g]
    alpha, rank = 27.55, 12
else:
    offsets = [(dd, dk) for dd in range(-gd - nd, gd + nd + 1) for dk in range(-g - n, g + n + 1)
               if abs(dk) > g or abs(dd) > gd]
    alpha, rank = 12.06, 99
passed = merged = kept = 0
for item in range(frames):
    m = sim.measure("radar", step=0, index=item, keep=("range_doppler", "detections"))
    power = np.asarray(m.range_doppler)
    ranges = np.asarray(m.axes["range_m"])
    stack = np.stack([np.roll(power, (-dd, -dk), (0, 1)) for dd, dk in offsets])
    mask = power > alpha * np.partition(stack, rank - 1, axis=0)[rank - 1]
    mask[:, :g + n] = False
    mask[:, -g - n:] = False
    rows = power.shape[0]
    labels, _ = ndimage.label(np.vstack([mask] * 3), structure=np.ones((3, 3)))
    target_cell = int(np.argmin(abs(ranges - 10.04)))
    wall_cell = int(np.argmin(abs(ranges - 11.0)))
    target_row = int(np.argmax(power[:, target_cell]))
    passed += bool(mask[target_row, target_cell])
    merged += bool(mask[target_row, target_cell]
                   and labels[rows + target_row, target_cell] == labels[rows, wall_cell])
    kept += m.target is not None and m.target["origin"] == "target"
print(f"{shape} OS, target at {bins:g} bins, {frames} frames: target cell over its threshold in "
      f"{passed}, in the wall's object in {merged}; the chain kept the target in {kept}")
