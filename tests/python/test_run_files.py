"""Run files as arrays: an interface run's HDF5 file read by the module equals the CSV tables the
command writes from the same run, and the file is left as it was."""
import csv
import hashlib

import numpy as np
import pytest

import sedwave
from conftest import run_sedwave

SCENE = """# 6 steel beads (5 mm) on a small aluminium plate; SI units (docs/interface.md).
[plate]
length_x = 0.024
length_y = 0.008
elements_x = 8
elements_y = 4
[packing]
rows = 2
columns = 3
[contact]
friction = 0.3
tanh_velocity_scale = 100
[drive]
speed = 1.0
[run]
duration = 4e-5
"""

COLUMNS = {"grain_translation_J": "grain_translation", "plate_kinetic_J": "plate_kinetic",
           "friction_J": "friction_work", "plate_normal_force_N": "plate_normal_force"}


def test_an_interface_run_reads_as_its_csv_tables(sedwave_command, tmp_path):
    scene = tmp_path / "plate.toml"
    scene.write_text(SCENE)
    run_sedwave(sedwave_command, "interface", scene, "--out", tmp_path / "plate.h5", "--csv", tmp_path / "csv")
    before = hashlib.sha256((tmp_path / "plate.h5").read_bytes()).hexdigest()
    run = sedwave.read_run(tmp_path / "plate.h5")
    assert hashlib.sha256((tmp_path / "plate.h5").read_bytes()).hexdigest() == before
    with open(tmp_path / "csv" / "energies.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("# ") or line.startswith("# time")))
    series = run["datasets"]
    for column, dataset in COLUMNS.items():
        from_csv = np.array([float(r[column]) for r in rows])
        stored = series["/time_series/" + dataset]
        assert stored.shape == from_csv.shape
        np.testing.assert_allclose(stored, from_csv, rtol=1e-8, atol=1e-300)
    assert run["attributes"]["/time_series/plate_normal_force"]["unit"] == "N"
    assert series["/grains/x"].shape == (6,)


def test_a_file_that_is_not_hdf5_is_refused_by_name(tmp_path):
    text = tmp_path / "not_a_run.h5"
    text.write_text("time,energy\n")
    with pytest.raises(Exception, match="not_a_run.h5"):
        sedwave.read_run(text)
