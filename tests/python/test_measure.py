"""Simulator.measure: exactly an item of `fogradar run`, its raw data as NumPy views of C++
buffers, checked against NumPy's own FFT, the run's CSV files and beat = signal + noise."""
import threading

import numpy as np
import pandas as pd
import pytest

import fogradar


def hann(n):
    """The periodic Hann window (radar/src/window.cpp's, after Harris 1978)."""
    return 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)


@pytest.mark.parametrize("step,index", [(0, 0), (2, 17), (4, 199)])
def test_the_gate_detection_equals_the_run_s_samples_row(paper_sim, paper_cli_run, step, index):
    samples = pd.read_csv(paper_cli_run / "radar_samples.csv", float_precision="round_trip")
    row = samples[(samples["active_layers"] == step) & (samples["item"] == index)].iloc[0]
    target = paper_sim.measure("radar", step, index, keep="detections").target
    assert target is not None
    # The CSV writes every number exactly (shortest round trip): the same doubles.
    for column in ("range_m", "rcs_dbsm", "snr_db", "velocity_m_per_s"):
        assert target[column] == row[column], column
    assert target["origin"] == row["origin"] == "target"


def test_the_map_is_numpy_s_fft_of_the_windowed_beat(paper_sim):
    m = paper_sim.measure("radar", 1, 5, keep=("beat", "range_doppler"))
    chirps, samples = m.beat.shape
    assert (chirps, samples) == (64, 512) and m.range_doppler.shape == (64, 512)
    again = np.abs(np.fft.fft2(m.beat * hann(chirps)[:, None] * hann(samples)[None, :])) ** 2
    # pocketfft and FFTW both round in double: they agree to about N log2 N eps of the peak.
    assert np.max(np.abs(again - m.range_doppler)) / np.max(m.range_doppler) < 1e-11
    assert m.axes["range_m"].shape == (512,) and m.axes["velocity_m_per_s"].shape == (64,)


def test_the_beat_is_its_signal_plus_its_noise(paper_sim):
    m = paper_sim.measure("radar", 3, 9, keep=("beat", "signal", "noise", "detections"))
    assert np.array_equal(m.signal + m.noise, m.beat)  # static paths: exactly
    plain = paper_sim.measure("radar", 3, 9, keep=("beat", "detections"))
    assert np.array_equal(plain.beat, m.beat)  # keeping the parts changes nothing
    pd.testing.assert_frame_equal(plain.detections, m.detections)
    # The noise's power is the receiver's k T0 F fs (the map's thermal_noise_level over its gain).
    scenario = paper_sim.scenario.to_dict()["radar"]
    k_t0_f_fs = (1.380649e-23 * scenario["reference_temperature_k"]
                 * 10 ** (scenario["noise_figure_db"] / 10) * scenario["sample_rate_hz"])
    measured = np.mean(np.abs(m.noise) ** 2)
    assert abs(measured / k_t0_f_fs - 1) < 4 / np.sqrt(m.noise.size)  # 4 sigma of the mean


def test_with_a_moving_target_the_parts_add_up_to_rounding():
    sim = fogradar.Simulator(fogradar.Scenario.from_dict({"target.radial_velocity_m_per_s": 5.0,
                                                          "experiment.sensors": ["radar"]}))
    m = sim.measure("radar", 0, 0, keep=("beat", "signal", "noise"))
    error = np.abs(m.signal + m.noise - m.beat)
    assert np.max(error) <= 4 * np.finfo(float).eps * np.max(np.abs(m.beat))


def test_arrays_and_table_columns_are_read_only_views_without_copies(paper_sim):
    m = paper_sim.measure("radar", 0, 0, keep=("beat", "range_doppler", "detections"))
    for array in (m.beat, m.range_doppler):
        assert array.base is not None and array.flags["C_CONTIGUOUS"]
        assert not array.flags["WRITEABLE"]
        with pytest.raises(ValueError):
            array[0, 0] = 0
    columns = m.arrays("detections")
    assert np.shares_memory(m.detections["range_m"].to_numpy(), columns["range_m"])
    assert np.shares_memory(m.detections["origin"].cat.codes.to_numpy(), columns["origin"])
    assert isinstance(m.detections["origin"].dtype, pd.CategoricalDtype)
    assert list(m.detections["origin"].cat.categories) == ["noise", "target", "fog", "background",
                                                           "clipping", "sidelobe", "multipath",
                                                           "room"]


def test_items_are_the_measurements_of_a_step_in_order(paper_sim):
    items = list(paper_sim.items("camera", 2, keep="images"))
    assert [m.index for m in items] == list(range(paper_sim.items_per_step("camera")))
    single = paper_sim.measure("camera", 2, 7, keep="images")
    assert np.array_equal(items[7].images, single.images)


def test_the_camera_s_images_make_the_run_s_histograms(paper_sim, paper_cli_run):
    histograms = pd.read_csv(paper_cli_run / "camera_histograms.csv")
    for step in (0, 4):
        counts = np.zeros(256, dtype=np.int64)
        for m in paper_sim.items("camera", step, keep="images"):
            assert m.images.dtype == np.uint8 and m.images.shape == (120, 160)
            counts += np.bincount(m.images.ravel(), minlength=256)
        listed = histograms[histograms["active_layers"] == step]
        expected = np.zeros(256, dtype=np.int64)
        expected[listed["grey_level"].to_numpy()] = listed["count"].to_numpy()
        assert np.array_equal(counts, expected)


def test_the_lidar_s_echoes_are_the_run_s(paper_sim, paper_cli_run):
    echoes = pd.read_csv(paper_cli_run / "lidar_echoes.csv", float_precision="round_trip")
    m = paper_sim.measure("lidar", 2, 3)
    listed = echoes[(echoes["active_layers"] == 2) & (echoes["item"] == 3)].reset_index(drop=True)
    assert len(listed) == len(m.echoes) > 0
    assert np.allclose(m.echoes["range_m"], listed["range_m"], atol=5e-5)  # the CSV's 4 decimals
    assert list(m.echoes["origin"].astype(str)) == list(listed["origin"])
    assert list(m.echoes["layer"]) == list(listed["layer"])
    assert m.waveforms.shape == (361, len(m.axes["time_s"]))


def test_bad_measure_arguments_name_themselves(paper_sim):
    cases = [(("radar", 5, 0, None), "step"), (("radar", 0, 200, None), "index"),
             (("sonar", 0, 0, None), "sensor"), (("radar", 0, 0, ("beat", "x")), "keep"),
             (("radar", -1, 0, None), "step")]
    for (sensor, step, index, keep), key in cases:
        with pytest.raises(fogradar.InvalidParameter) as raised:
            paper_sim.measure(sensor, step, index, keep=keep)
        assert raised.value.key == key, (sensor, step, index, keep)
    with pytest.raises(AttributeError):
        paper_sim.measure("radar", 0, 0, keep="beat").range_doppler


def test_a_memory_limit_outside_its_range_is_refused_by_name():
    # NaN would pass a `limit < x` test and become an undefined size_t in the C++ cast.
    scenario = fogradar.Scenario.paper()
    for bad in (float("nan"), float("inf"), 0.5, -1, 2e9, "64"):
        with pytest.raises(fogradar.InvalidParameter) as raised:
            fogradar.Simulator(scenario, memory_limit_mib=bad)
        assert raised.value.key == "memory_limit_mib", bad
        assert "[1, 1e9]" in str(raised.value), bad


def test_threads_share_one_simulator(paper_sim):
    expected = [paper_sim.measure("radar", 1, i, keep="beat").beat.copy() for i in range(4)]
    got = [None] * 4

    def measure(i):
        got[i] = paper_sim.measure("radar", 1, i, keep="beat").beat

    threads = [threading.Thread(target=measure, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(a, b) for a, b in zip(expected, got))
