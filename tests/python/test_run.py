"""Simulator.run against `fogradar run`: the same summaries, limits and files, byte for byte; Ctrl-C
stops it; other Python threads run while it computes."""
import filecmp
import os
import signal
import subprocess
import threading
import time

import pandas as pd
import pytest

import fogradar


def test_the_summary_equals_the_command_s_summary_files(paper_sim, paper_cli_run):
    summary = paper_sim.run().summary()
    assert list(summary.columns[:2]) == ["sensor", "active_layers"]
    for sensor in ("radar", "lidar", "camera"):
        expected = pd.read_csv(paper_cli_run / f"{sensor}_summary.csv",
                               float_precision="round_trip")
        mine = summary[summary["sensor"] == sensor][expected.columns].reset_index(drop=True)
        # Lists of numbers: the file joins them with ';' (none: an empty field).
        for column in [c for c in expected.columns if c.endswith("outliers")]:
            expected[column] = [[float(v) for v in text.split(";")] if isinstance(text, str)
                                else [] for text in expected[column]]
            mine[column] = [[float(v) for v in values] for values in mine[column]]
        # The radar's and the lidar's files write every number exactly (round_trip reads it
        # back): the same double. The camera's write 10 significant digits: within 5e-10 of it.
        exact = sensor != "camera"
        pd.testing.assert_frame_equal(mine, expected, check_dtype=False, check_exact=exact,
                                      rtol=0 if exact else 5e-10, atol=0)
    assert len(summary) == 15


@pytest.mark.parametrize("threads", [1, 2])
def test_write_gives_the_command_s_files_byte_for_byte(threads, cli, tmp_path):
    subprocess.run([cli, "run", "--out", str(tmp_path / "cli"), "--threads", str(threads)],
                   check=True, stdout=subprocess.DEVNULL)
    fogradar.Simulator(fogradar.Scenario.paper(), threads=threads).run().write(tmp_path / "python")
    names = sorted(os.listdir(tmp_path / "cli"))
    assert names == sorted(os.listdir(tmp_path / "python"))
    match, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli", tmp_path / "python", names,
                                               shallow=False)
    assert mismatch == [] and errors == [] and len(match) == len(names) >= 15


def test_limits_and_tables_are_the_command_s(paper_sim, paper_cli_run):
    results = paper_sim.run()
    limits = results.limits()
    assert list(limits.index) == ["radar", "lidar", "camera"]
    assert limits.loc["lidar", "layers_to_failure"] == 1
    assert limits.loc["camera", "layers_to_failure"] == 3
    assert pd.isna(limits.loc["radar", "layers_to_failure"])
    assert "layers to failure" in results.tables()
    assert results.files["summary.json"] == (paper_cli_run / "summary.json").read_bytes()
    samples = results.samples("radar")
    assert len(samples) == 1000 and set(samples["origin"].dropna()) == {"target"}
    assert results.detections().equals(results.detections("radar"))  # the one that has them
    assert len(results.detections()) >= 1000
    with pytest.raises(fogradar.InvalidParameter) as raised:
        results.samples("lidar")
    assert raised.value.key == "name"
    with pytest.raises(fogradar.InvalidParameter):
        results.table("no_such.csv")


def test_a_run_twice_gives_the_same_results(paper_sim):
    a, b = paper_sim.run().files, paper_sim.run().files
    assert a == b


def _long_scenario():
    return fogradar.Scenario.from_dict({"radar.measurements_per_step": 20000,
                                        "experiment.sensors": ["radar"]})


def test_ctrl_c_stops_a_run_within_a_second():
    sim = fogradar.Simulator(_long_scenario(), threads=2)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run()
    stopped = time.monotonic() - start
    timer.join()
    assert stopped < 1.3


def test_other_python_threads_run_while_it_computes():
    sim = fogradar.Simulator(fogradar.Scenario.from_dict({"experiment.sensors": ["radar"]}),
                             threads=1)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.monotonic()
    sim.run()
    end = time.monotonic()
    done.set()
    counter.join()
    during = [t for t in ticks if start < t < end]
    # The run takes about 0.1 s; a GIL held throughout would leave no tick inside it.
    assert end - start > 0.02 and len(during) >= 10


def test_bad_simulator_arguments_name_themselves():
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Simulator(fogradar.Scenario.paper(), threads=-1)
    assert raised.value.key == "threads"



def test_a_run_over_the_memory_limit_is_refused_as_the_command_refuses_it(cli, tmp_path):
    with pytest.raises(fogradar.InvalidParameter) as raised:
        fogradar.Simulator(fogradar.Scenario.paper(), memory_limit_mib=1)
    done = subprocess.run([cli, "run", "--memory-limit-mib", "1", "--out", str(tmp_path / "o")],
                          capture_output=True, text=True)
    assert done.returncode == 2
    assert "fogradar: " + str(raised.value) == done.stderr.strip()
    assert raised.value.key == "lidar.scans_per_step"  # the largest part, as the message says
