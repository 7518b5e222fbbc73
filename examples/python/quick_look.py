#!/usr/bin/python3
"""One frame of the paper scenario at a glance (docs/python.md): the radar's beat signal, its
range-Doppler map with the chain's detections coloured by origin, and a lidar scan's echoes by
origin, drawn with matplotlib into one PNG.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/quick_look.py \\
        [--step K] [--out quick_look.png]
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fogradar  # noqa: E402

COLOURS = {"target": "tab:red", "fog": "tab:blue", "noise": "tab:grey", "background": "tab:green",
           "clipping": "tab:purple", "sidelobe": "tab:olive", "multipath": "tab:orange",
           "room": "tab:brown"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=int, default=2, help="active fog layers (default 2)")
    parser.add_argument("--out", default="quick_look.png")
    args = parser.parse_args()

    sim = fogradar.Simulator(fogradar.Scenario.paper())
    radar = sim.measure("radar", step=args.step, index=0)
    lidar = sim.measure("lidar", step=args.step, index=0)

    fig, (beat_ax, map_ax, scan_ax) = plt.subplots(1, 3, figsize=(16, 4.8))
    t_us = radar.axes["sample_time_s"] * 1e6
    beat_ax.plot(t_us, radar.beat[0].real, lw=0.6, label="I")
    beat_ax.plot(t_us, radar.beat[0].imag, lw=0.6, label="Q")
    beat_ax.set(title="beat signal, chirp 0", xlabel="time (µs)",
                ylabel=f"amplitude ({radar.units('beat')})")
    beat_ax.legend(loc="upper right")

    velocity = np.fft.fftshift(radar.axes["velocity_m_per_s"])
    power_db = 10 * np.log10(np.fft.fftshift(radar.range_doppler, axes=0))
    range_m = radar.axes["range_m"]
    map_ax.imshow(power_db, aspect="auto", origin="lower", cmap="viridis",
                  extent=[range_m[0], range_m[-1], velocity[0], velocity[-1]])
    for origin, rows in radar.detections.groupby("origin", observed=True):
        map_ax.scatter(rows["range_m"], rows["velocity_m_per_s"], s=30, facecolors="none",
                       edgecolors=COLOURS[origin], label=origin)
    map_ax.set(title=f"range-Doppler |X|² (dB), {args.step} layers", xlabel="range (m)",
               ylabel="radial velocity (m/s)", xlim=(0, 20))
    map_ax.legend(loc="upper right")

    echoes = lidar.echoes
    for origin, rows in echoes.groupby("origin", observed=True):
        a = np.radians(rows["angle_deg"])
        scan_ax.scatter(rows["range_m"] * np.sin(a), rows["range_m"] * np.cos(a), s=4,
                        color=COLOURS[origin], label=origin)
    scan_ax.set(title=f"lidar scan 0, {args.step} layers", xlabel="x (m)", ylabel="y (m)",
                aspect="equal")
    scan_ax.legend(loc="upper right", markerscale=3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
