#!/usr/bin/env python3
"""A straightforward vectorised NumPy/SciPy version of fogradar's radar chain, for comparison.

The bench workload of docs/performance.md (examples/bench.toml): 77 GHz FMCW radar, 1 GHz sweep over 51.2 us,
128 chirps x 1024 complex samples at 20 MS/s, the EVT rear 10 m away (2 m gap, four 1 m fog layers,
4 m gap), 200 measurements for each of 0..4 active layers = 1000 frames, one process, one thread of
Python (NumPy's FFT, pocketfft, is single-threaded).

Per frame, as fogradar does it, but written the way one would in NumPy:
  scene     5 scattering centres x 3 floor-multipath paths (direct, direct-floor twice, floor-floor)
            with the radar equation, Gaussian beam pattern and micro-motion jitter; plus
            clutter_scatterers_per_bin = 4 random fog scatterers in every 15 cm range bin inside the
            active layers (7 bins per 1 m layer, 28 tones per layer), complex Gaussian amplitudes.
            All paths are static: one chirp is synthesised (tones x samples matrix of complex
            exponentials) and broadcast to all 128 chirps, as fogradar synthesises a static scene's
            chirp once per frame.
  noise     complex Gaussian thermal noise k T0 F fs on every sample (NumPy's Generator, PCG64 +
            ziggurat normals), one Generator per measurement seeded (seed, layers, index).
  process   2-D Hann window (periodic), np.fft.fft along range (axis 1) then Doppler (axis 0),
            |Y|^2.
  CFAR      cell-averaging CFAR along range in every Doppler bin by cumulative sums: 2 guard and 8
            training cells per side, Pfa 1e-6 (alpha = N (Pfa^(-1/N) - 1), N = 16); the range axis
            wraps around at its ends (fogradar instead slides the training window inward there).
  estimate  detected cells grouped into 8-connected objects (scipy.ndimage.label, find_objects),
            each object's strongest cell interpolated like fogradar: scipy.optimize.minimize_scalar (bounded, within
            +-0.75 bin) of the DTFT magnitude along range via the Dirichlet kernel, then every chirp's
            row interpolated to that range and the same search across Doppler; received power and RCS
            (paper eq. 7); the target is the strongest object within 0.5 m of 10 m.

Amplitudes follow the same physics as fogradar but are simplified (no Segelstein/Mie computation: the
fog's volume backscatter 3.27e-13 m^2/m^3 and 0.41 dB/km loss are those `fogradar fog
--extinction-per-km 900 --diameter-um 1` prints, Liebe water at 20 C), so the statistics are only
roughly those of fogradar; the work per frame is the point. The sweep is fogradar's default up-chirp
centred on 77 GHz: each path's phase at the first sample is 2 pi f_0 tau - pi S tau^2,
f_0 = f_c - B/2 (docs/radar.md §3.2).

Run (Debian's python3-numpy / python3-scipy are installed for /usr/bin/python3):
  /usr/bin/python3 bench/numpy_chain.py [--measurements 200] [--repeats 1]
Prints the NumPy/SciPy versions, the time (time.perf_counter, the whole loop over all frames,
including the per-step setup) and frames per second.
"""

import argparse
import os
import platform
import sys
import time

import numpy as np
import scipy
from scipy import ndimage, optimize

C = 299_792_458.0
K_BOLTZMANN = 1.380649e-23


def db(x):
    return 10.0 ** (x / 10.0)


# --- Radar and chamber (examples/bench.toml over examples/paper.toml) ---------------------------
FC = 77e9
BANDWIDTH = 1e9
CHIRP_S = 51.2e-6
FS = 20e6
N = 1024  # samples per chirp
NC = 128  # chirps per frame
SLOPE = BANDWIDTH / CHIRP_S
F_START = FC - 0.5 * BANDWIDTH  # up-chirp
LAMBDA = C / FC
PT = db(10.0) * 1e-3
G = db(25.0)
NOISE_W = K_BOLTZMANN * 290.0 * db(12.0) * FS
BEAMWIDTH = np.deg2rad(10.0)
OMEGA = np.pi * BEAMWIDTH * BEAMWIDTH / (8.0 * np.log(2.0))  # two-way beam solid angle
RANGE_BIN_M = C * FS / (2.0 * SLOPE * N)

SENSOR_GAP, LAYERS, LAYER_LEN, TARGET_GAP = 2.0, 4, 1.0, 4.0
TARGET_RANGE = SENSOR_GAP + LAYERS * LAYER_LEN + TARGET_GAP  # 10 m
ETA = 3.2716e-13  # volume backscatter of the fog, m^2/m^3
FOG_DB_PER_M = 0.4112e-3  # specific attenuation, dB/m (one way)
CLUTTER_PER_BIN = 4
SENSOR_HEIGHT = 0.5
GAMMA = -0.7
JITTER_STD = 0.2e-3
# EVT rear: (range offset, lateral, height, RCS share of 10 dBsm)
EVT = np.array([[0.00, 0.0, 0.55, 0.40], [0.05, -0.75, 0.45, 0.15], [0.05, 0.75, 0.45, 0.15],
                [0.30, -0.65, 0.85, 0.15], [0.30, 0.65, 0.85, 0.15]])
EVT_RCS = db(10.0) * EVT[:, 3]

GUARD, TRAIN, PFA = 2, 8, 1e-6
N_REF = 2 * TRAIN
ALPHA = N_REF * (PFA ** (-1.0 / N_REF) - 1.0)
GATE_M = 0.5

T = np.arange(N) / FS
WINDOW = np.outer(0.5 - 0.5 * np.cos(2 * np.pi * np.arange(NC) / NC),
                  0.5 - 0.5 * np.cos(2 * np.pi * np.arange(N) / N))
GAIN = WINDOW.sum()  # coherent amplitude gain of the 2-D window + FFTs
NOISE_PER_CELL = NOISE_W * (WINDOW ** 2).sum()


def received_power(rcs, r1, r2):
    return PT * G * G * LAMBDA ** 2 * rcs / ((4 * np.pi) ** 3 * r1 ** 2 * r2 ** 2)


def loss_one_way(r, k):
    """Fog transmittance (power, one way) to range r through the first k layers."""
    starts = SENSOR_GAP + LAYER_LEN * np.arange(k)
    inside = np.clip(np.asarray(r)[..., None] - starts, 0.0, LAYER_LEN).sum(axis=-1)
    return 10.0 ** (-FOG_DB_PER_M * inside / 10.0)


def scene_tones(rng, k):
    """Two-way path lengths and complex amplitudes of one measurement's paths."""
    along = TARGET_RANGE + EVT[:, 0] + JITTER_STD * rng.standard_normal(len(EVT))
    horizontal = np.hypot(along, EVT[:, 1])
    az = np.arctan2(EVT[:, 1], along)

    def leg(vertical):
        el = np.arctan2(vertical, horizontal)
        gain = np.exp(-4 * np.log(2) * ((az / BEAMWIDTH) ** 2 + (el / BEAMWIDTH) ** 2))
        return np.hypot(horizontal, vertical), np.sqrt(gain)

    direct, pd = leg(EVT[:, 2] - SENSOR_HEIGHT)
    floor, pf = leg(-(EVT[:, 2] + SENSOR_HEIGHT))
    lengths = np.concatenate([2 * direct, direct + floor, 2 * floor])
    coeff = np.concatenate([np.ones(5), np.full(5, 2 * GAMMA), np.full(5, GAMMA * GAMMA)])
    pattern = np.concatenate([pd * pd, pd * pf, pf * pf])
    power = np.concatenate([received_power(EVT_RCS, direct, direct), received_power(EVT_RCS, direct, floor),
                            received_power(EVT_RCS, floor, floor)])
    power = power * loss_one_way(0.5 * lengths, k) ** 2
    tau = lengths / C
    amplitude = coeff * pattern * np.sqrt(power) * np.exp(1j * (2 * np.pi * F_START * tau - np.pi * SLOPE * tau ** 2))

    if k > 0:  # fog clutter: CLUTTER_PER_BIN scatterers in every range bin inside the active layers
        a = np.concatenate([np.arange(SENSOR_GAP + i, SENSOR_GAP + i + LAYER_LEN - 1e-12, RANGE_BIN_M)
                            for i in range(k)])
        layer_end = SENSOR_GAP + LAYER_LEN * (np.floor((a - SENSOR_GAP) / LAYER_LEN + 1e-9) + 1)
        b = np.minimum(a + RANGE_BIN_M, layer_end)
        sigma = ETA * OMEGA * (b ** 3 - a ** 3) / 3.0
        r = a[:, None] + (b - a)[:, None] * rng.random((len(a), CLUTTER_PER_BIN))
        mean_power = received_power(np.repeat(sigma[:, None], CLUTTER_PER_BIN, axis=1) / CLUTTER_PER_BIN, r, r)
        mean_power = mean_power * loss_one_way(r, k) ** 2
        clutter = np.sqrt(mean_power / 2) * (rng.standard_normal(r.shape) + 1j * rng.standard_normal(r.shape))
        lengths = np.concatenate([lengths, 2 * r.ravel()])
        amplitude = np.concatenate([amplitude, clutter.ravel()])
    return lengths, amplitude


def dirichlet(nu, n):
    """K(nu - m), m = 0..n-1: X(nu) = sum_m X[m] K(nu - m) for FFTW/NumPy's forward sign."""
    u = nu - np.arange(n)
    s = np.sin(np.pi * u / n)
    with np.errstate(divide="ignore", invalid="ignore"):
        mag = np.where(np.abs(s) < 1e-12, 1.0, np.sin(np.pi * u) / (n * s))
    return mag * np.exp(-1j * np.pi * u * (n - 1) / n)


def peak_offset(values, centre):
    n = len(values)
    res = optimize.minimize_scalar(lambda off: -np.abs(values @ dirichlet(centre + off, n)) ** 2,
                                   bounds=(-0.75, 0.75), method="bounded", options={"xatol": 1e-9})
    return res.x


def measure(rng, k):
    lengths, amplitude = scene_tones(rng, k)
    # Static scene: one chirp, the same on every chirp of the frame.
    chirp = amplitude @ np.exp(2j * np.pi * np.outer(SLOPE * lengths / C, T))
    sigma = np.sqrt(NOISE_W / 2)
    x = chirp[None, :] + sigma * (rng.standard_normal((NC, N)) + 1j * rng.standard_normal((NC, N)))
    y = np.fft.fft(np.fft.fft(x * WINDOW, axis=1), axis=0)
    p = np.abs(y) ** 2

    # CA-CFAR along range by cumulative sums (range axis wrapped at its ends).
    w = GUARD + TRAIN
    padded = np.concatenate([p[:, -w:], p, p[:, :w]], axis=1)
    cs = np.concatenate([np.zeros((NC, 1)), np.cumsum(padded, axis=1)], axis=1)
    i = np.arange(N) + w  # index of cell i in padded
    left = cs[:, i - GUARD] - cs[:, i - w]
    right = cs[:, i + w + 1] - cs[:, i + GUARD + 1]
    detected = p > ALPHA * (left + right) / N_REF

    labels, count = ndimage.label(detected, structure=np.ones((3, 3)))
    best = None
    if count:
        # Strongest cell of each object inside its bounding box (ndimage.maximum_position would
        # argsort the whole map on every call, 14 ms per frame here).
        for label, (rows, cols) in enumerate(ndimage.find_objects(labels), start=1):
            box = np.where(labels[rows, cols] == label, p[rows, cols], -1.0)
            dd, kk = np.unravel_index(np.argmax(box), box.shape)
            d, kbin = rows.start + dd, cols.start + kk
            range_off = peak_offset(y[d], kbin)
            kernel = dirichlet(kbin + range_off, N)
            doppler = y @ kernel
            doppler_off = peak_offset(doppler, d)
            peak_power = np.abs(doppler @ dirichlet(d + doppler_off, NC)) ** 2
            range_m = (kbin + range_off) * RANGE_BIN_M
            received = peak_power / GAIN ** 2
            rcs = received * (4 * np.pi) ** 3 * range_m ** 4 / (PT * G * G * LAMBDA ** 2)
            if abs(range_m - TARGET_RANGE) <= GATE_M and (best is None or received > best[1]):
                best = (range_m, received, 10 * np.log10(rcs), 10 * np.log10(peak_power / NOISE_PER_CELL))
    return best, count


def run(measurements, seed=1):
    detected, objects = 0, 0
    rcs = [[] for _ in range(LAYERS + 1)]
    for k in range(LAYERS + 1):
        for i in range(measurements):
            rng = np.random.default_rng([seed, k, i])
            best, count = measure(rng, k)
            objects += count
            if best is not None:
                detected += 1
                rcs[k].append(best[2])
    return detected, objects, [float(np.median(r)) if r else float("nan") for r in rcs]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--measurements", type=int, default=200, help="per layer step (default 200)")
    parser.add_argument("--repeats", type=int, default=1, help="timed runs; the median is reported")
    args = parser.parse_args()
    frames = (LAYERS + 1) * args.measurements
    print(f"numpy_chain: {NC} chirps x {N} samples, {frames} frames ({LAYERS + 1} steps x {args.measurements})")
    print(f"  Python {platform.python_version()} ({sys.executable}), NumPy {np.__version__}, SciPy {scipy.__version__}")
    print(f"  load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} (at start)")
    times = []
    for r in range(args.repeats):
        start = time.perf_counter()
        detected, objects, medians = run(args.measurements)
        times.append(time.perf_counter() - start)
        print(f"  run {r + 1}: {times[-1]:.3f} s, {frames / times[-1]:.1f} frames/s; target detected in "
              f"{detected} of {frames}, {objects / frames:.2f} objects per frame; median RCS per step (dBsm) "
              + " ".join(f"{m:.2f}" for m in medians))
    t = float(np.median(times))
    print(f"  median {t:.3f} s = {1e3 * t / frames:.2f} ms per frame = {frames / t:.1f} frames/s (1 process, 1 thread)")
    print(f"  load average {' '.join(f'{x:.2f}' for x in os.getloadavg())} (at end)")


if __name__ == "__main__":
    main()
