"""Fixtures of the Python module's tests (run by ctest with PYTHONPATH=<build>/python and
FOGRADAR_CLI, FOGRADAR_SOURCE_DIR set; tests/CMakeLists.txt)."""
import os
import pathlib
import subprocess

import pytest

import fogradar


@pytest.fixture(scope="session")
def cli():
    """The `fogradar` command of the same build."""
    return os.environ["FOGRADAR_CLI"]


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(os.environ["FOGRADAR_SOURCE_DIR"])


@pytest.fixture(scope="session")
def paper_sim():
    return fogradar.Simulator(fogradar.Scenario.paper())


@pytest.fixture(scope="session")
def paper_cli_run(cli, tmp_path_factory):
    """`fogradar run` of the paper scenario: its result directory."""
    out = tmp_path_factory.mktemp("cli") / "out"
    subprocess.run([cli, "run", "--out", str(out), "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL)
    return out


@pytest.fixture
def cli_error(cli, tmp_path):
    """error(toml_text, name): the message `fogradar run --scenario <tmp>/name` prints for a bad
    scenario, without its "fogradar: " prefix, the file's path, and the exit status."""
    def error(toml_text, name="bad.toml"):
        path = tmp_path / name
        path.write_text(toml_text)
        done = subprocess.run([cli, "run", "--scenario", str(path), "--out",
                               str(tmp_path / "out")], capture_output=True, text=True)
        message = done.stderr.strip()
        assert message.startswith("fogradar: "), message
        return message[len("fogradar: "):], str(path), done.returncode
    return error
