"""Shared fixtures of the Python module's tests: the repository's data and the `sedwave` command
of the same build (SEDWAVE, set by ctest), whose outputs the module's results must equal."""
import json
import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIELD = ROOT / "data" / "field" / "zhou2009_regression.csv"
SITE = ROOT / "data" / "sites" / "medium_sand.toml"
DIGITIZED = ROOT / "data" / "digitized" / "example_webplotdigitizer.csv"


@pytest.fixture(scope="session")
def sedwave_command():
    command = os.environ.get("SEDWAVE") or shutil.which("sedwave")
    if not command:
        pytest.skip("no sedwave command (set SEDWAVE to the build's bin/sedwave)")
    return command


@pytest.fixture(scope="session")
def field_data():
    import sedwave
    return sedwave.read_observations(FIELD)


def run_sedwave(command, *arguments):
    """Runs the command; exit 0 or 3 (it ran and flagged something) are both a finished run."""
    done = subprocess.run([command, *map(str, arguments)], capture_output=True, text=True)
    assert done.returncode in (0, 3), done.stdout + done.stderr
    return done


def without_timings(report):
    """A report with its wall-clock times removed: the one thing two identical runs do not share."""
    if isinstance(report, dict):
        return {k: without_timings(v) for k, v in report.items() if k != "wall_seconds"}
    if isinstance(report, list):
        return [without_timings(v) for v in report]
    return report


def load(path):
    return json.loads(pathlib.Path(path).read_text())
