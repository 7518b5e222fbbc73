"""Ground truth from the chamber: stability() labels a detection with the origin the sensor's own
attribution gives at its range (the measurement's raw kind ``origins``, written in C++ from the
chamber the sensor measured through), never one rebuilt in Python. A detector that returns the
chain's own detections must get the chain's own origins back, detection for detection, in any
chamber, switching order and sensor."""
import collections

import numpy as np
import pytest

import fogradar

# A fog whose radar clutter the CFAR detects: 3 g/m^3 of 50 um drops (the paper's fog gives no fog
# detection at 77 GHz).
WET = {"experiment.sensors": ["radar"], "radar.measurements_per_step": 10,
       "fog.lwc_g_per_m3": 3.0,
       "fog.droplets": {"distribution": "monodisperse", "diameter_m": 50e-6}}


def chain_versus_truth(scenario, sensor, kind, columns, items, steps=None):
    """Runs stability() with a detector that returns the chain's own detections of `kind`
    (`columns` of them); returns (the chain's origins, stability's origins, the report)."""
    chain = []

    def own(m):
        table = m[kind]
        chain.extend(table["origin"].astype(str))
        return table[columns]

    report = fogradar.stability(scenario, sensor, own, keep=kind, items=items, steps=steps)
    return chain, list(report.detections["origin"].astype(str)), report


def test_target_first_fog_detections_are_fog():
    """Switching order target_first: step 1 switches on the layer at 5-6 m. Python's old rebuild
    (layers from the sensor) called its fog detections at 5.2-5.9 m noise."""
    scenario = fogradar.Scenario.from_dict(dict(WET, **{"experiment.switching_order":
                                                        "target_first"}))
    chain, truth, report = chain_versus_truth(scenario, "radar", "detections",
                                              ["range_m", "velocity_m_per_s"], items=10)
    assert truth == chain
    fog = report.detections[report.detections["origin"] == "fog"]
    assert len(fog) >= 3
    assert fog["range_m"].between(5.0, 6.0).all()
    assert set(fog["active_layers"]) == {1}
    table = report.table.set_index("active_layers")
    assert table.loc[1, "fog_false_alarms_per_item"] == len(fog) / 10


def test_a_listed_order_gives_the_chain_s_origins():
    scenario = fogradar.Scenario.from_dict(dict(WET, **{"experiment.switching_order":
                                                        [2, 0, 3, 1]}))
    chain, truth, report = chain_versus_truth(scenario, "radar", "detections",
                                              ["range_m", "velocity_m_per_s"], items=10)
    assert truth == chain
    assert collections.Counter(chain)["fog"] >= 3


def test_fog_detections_name_their_layer_as_the_chain_does():
    """Order [2, 0, 3, 1]: every fog detection names one of the layers active at its step (the
    chain's own layer, from the raw kind origin_layers), every other detection -1; the map of
    layers is -1 exactly where the map of origins is not fog."""
    order = [2, 0, 3, 1]
    scenario = fogradar.Scenario.from_dict(dict(WET, **{"experiment.switching_order": order}))
    chain = []

    def own(m):
        table = m["detections"]
        chain.extend(table["layer"])
        return table[["range_m", "velocity_m_per_s", "range_cell", "doppler_cell"]]

    report = fogradar.stability(scenario, "radar", own, keep="detections", items=10)
    assert list(report.detections["layer"]) == chain
    fog = report.detections[report.detections["origin"] == "fog"]
    assert len(fog) >= 3
    for step, layer in zip(fog["active_layers"], fog["layer"]):
        assert layer in order[:step], (step, layer)
    assert (report.detections.loc[report.detections["origin"] != "fog", "layer"] == -1).all()
    m = fogradar.Simulator(scenario).measure("radar", 4, 0, keep=("origins", "origin_layers"))
    fog_code = fogradar._core.origin_labels.index("fog")
    assert m.origin_layers.dtype == np.int16
    assert ((m.origin_layers >= 0) == (m.origins == fog_code)).all()
    assert set(np.unique(m.origin_layers[m.origins == fog_code])) <= set(order)


def test_the_layered_example_runs_and_gives_the_chain_s_origins(source_dir):
    """examples/layered_chamber.toml has no layer_length_m: the old rebuild raised KeyError."""
    scenario = fogradar.Scenario.from_file(source_dir / "examples" / "layered_chamber.toml")
    chain, truth, report = chain_versus_truth(scenario, "radar", "detections",
                                              ["range_m", "velocity_m_per_s"], items=5)
    assert truth == chain and "target" in chain
    assert list(report.table["detection_rate"]) == [1.0] * 5
    chain, truth, _ = chain_versus_truth(scenario, "lidar", "echoes",
                                         ["range_m", "beam", "attributed_range_m"], items=1)
    assert truth == chain and {"fog", "background", "target"} <= set(chain)


def test_the_lidar_s_background_is_counted_apart_from_noise():
    """In clear air the lidar sees the chamber's walls and barrels in every scan: background
    echoes, not noise false alarms (the old rebuild counted 124 per scan as noise)."""
    scenario = fogradar.Scenario.from_dict({"experiment.sensors": ["lidar"],
                                            "lidar.scans_per_step": 2})
    chain, truth, report = chain_versus_truth(scenario, "lidar", "echoes",
                                              ["range_m", "beam", "attributed_range_m"], items=2,
                                              steps=[0])
    assert truth == chain
    counts = collections.Counter(chain)
    row = report.table.set_index("active_layers").loc[0]
    assert row["background_detections_per_item"] > 100
    assert row["background_detections_per_item"] == counts["background"] / 2
    assert row["noise_false_alarms_per_item"] == counts["noise"] / 2 < 5
    assert row["detection_rate"] == 1.0


def test_a_lidar_answer_needs_its_beam():
    scenario = fogradar.Scenario.from_dict({"experiment.sensors": ["lidar"],
                                            "lidar.scans_per_step": 1})
    with pytest.raises(TypeError, match="beam"):
        fogradar.stability(scenario, "lidar", lambda m: m.echoes[["range_m"]], items=1,
                           steps=[0])


def test_a_clipping_adc_labels_its_products_clipping_and_claims_no_margin():
    """An ADC clipped on every sample (full scale -80 dBm, far below the target's echo): the
    harmonics and intermodulation products it makes are detections of origin clipping, none is
    counted a noise false alarm, and the benchmark claims no SNR margin above the CFAR threshold
    (the old run claimed 40.8 dB and 3 noise false alarms per frame)."""
    scenario = fogradar.Scenario.from_dict({"experiment.sensors": ["radar"],
                                            "radar.measurements_per_step": 10,
                                            "radar.adc_bits": 12,
                                            "radar.adc_full_scale_dbm": -80.0})
    results = fogradar.Simulator(scenario).run()
    summary = results.summary()
    assert (summary["adc_clipped_fraction"] > 0.99).all()
    assert (summary["false_alarms_per_frame"] == 0).all()
    assert (summary["clipping_detections_per_frame"] >= 1).all()
    detections = results.detections("radar")
    assert set(detections["origin"]) == {"target", "clipping"}
    limits = results.limits()
    assert limits.loc["radar", "margin"].startswith("unknown: the ADC clipped")
    assert "above the CFAR threshold" not in results.tables()
    assert results.files["radar_summary.json"].find(b'"attenuation_margin_db": null') > 0
    # stability() agrees with the chain, clipping included.
    chain, truth, report = chain_versus_truth(scenario, "radar", "detections",
                                              ["range_m", "velocity_m_per_s"], items=5,
                                              steps=[0])
    assert truth == chain and "clipping" in chain
    assert report.table["noise_false_alarms_per_item"].iloc[0] == 0
    assert report.table["clipping_detections_per_item"].iloc[0] > 0


def test_the_radar_map_is_the_chain_s_attribution_at_every_detection(paper_sim):
    """The origins map holds the chain's own origin in the cell each detection peaks in."""
    m = paper_sim.measure("radar", step=4, index=0, keep=("detections", "origins"))
    labels = fogradar._core.origin_labels
    assert m.origins.shape == m.axes["velocity_m_per_s"].shape + m.axes["range_m"].shape
    assert set(np.unique(m.origins)) <= set(range(len(labels)))
    assert m.attributes("origins")["range_bin_m"] == pytest.approx(
        m.axes["range_m"][1] - m.axes["range_m"][0], rel=1e-12)
