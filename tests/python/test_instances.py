"""Sensor instances from Python: a second radar and a second lidar beside the kinds' own, each
measured, summarised, limited and judged by its own name, with the numbers the command writes."""
import subprocess

import numpy as np
import pandas as pd

import fogradar

INSTANCES = {
    "experiment": {"sensors": ["radar", "radar_24", "lidar_1550"], "max_active_layers": 1},
    "radar": {"chirps_per_frame": 16, "measurements_per_step": 4},
    "radar_24": {"kind": "radar", "centre_frequency_hz": 24.125e9,
                 "sweep_bandwidth_hz": 250e6, "chirps_per_frame": 16,
                 "measurements_per_step": 4},
    "lidar_1550": {"kind": "lidar", "wavelength_m": 1550e-9, "scans_per_step": 3,
                   "field_of_view_deg": 12.0},
}


def test_each_instance_has_its_rows_limit_and_files_under_its_name(cli, tmp_path):
    scenario = fogradar.Scenario.from_dict(INSTANCES)
    assert scenario.sensors == ["radar", "radar_24", "lidar_1550"]
    results = fogradar.Simulator(scenario, threads=2).run()
    summary = results.summary()
    assert list(summary["sensor"].unique()) == ["radar", "radar_24", "lidar_1550"]
    assert list(results.limits().index) == ["radar", "radar_24", "lidar_1550"]
    # The command writes the instance's summary under its name, with the same numbers.
    path = tmp_path / "s.toml"
    path.write_text(scenario.to_toml())
    subprocess.run([cli, "run", "--scenario", str(path), "--out", str(tmp_path / "out"),
                    "--threads", "1"], check=True, capture_output=True)
    written = pd.read_csv(tmp_path / "out" / "radar_24_summary.csv",
                          float_precision="round_trip")
    mine = summary[summary["sensor"] == "radar_24"].reset_index(drop=True)
    assert np.array_equal(mine["median_dbsm"].to_numpy(), written["median_dbsm"].to_numpy())


def test_an_instance_is_measured_and_judged_by_its_name():
    scenario = fogradar.Scenario.from_dict(INSTANCES)
    sim = fogradar.Simulator(scenario)
    m = sim.measure("radar_24", step=1, index=0, keep=("detections",))
    assert (m.detections["origin"] == "target").any()
    report = fogradar.stability(scenario, "lidar_1550",
                                lambda m: m.echoes[["beam", "range_m", "intensity"]]
                                .rename(columns={"intensity": "value"}),
                                keep="echoes", gate_m=0.5)
    assert list(report.table["active_layers"]) == [0, 1]
