"""Observations: the command's readers and messages, arrays in and out, SI units."""
import numpy as np
import pytest

import sedwave
from conftest import DIGITIZED, FIELD


def rows_of(path):
    lines = [l for l in path.read_text().splitlines() if l and not l.startswith("#")]
    header = lines[0].split(",")
    return [dict(zip(header, l.split(","))) for l in lines[1:]]


def test_field_file_read_in_si():
    data = sedwave.read_observations(FIELD)
    rows = rows_of(FIELD)
    assert len(data) == len(rows)
    assert data.water_sound_speed == 1500.0
    for k, row in enumerate(rows):
        assert data.frequency_hz[k] == float(row["frequency"])
        if row["quantity"] == "attenuation":
            assert data.quantity[k] == "attenuation"
            # dB/m to Np/m: one neper is 20 log10(e) dB.
            assert data.value[k] == pytest.approx(float(row["value"]) / sedwave.NEPER_TO_DB, rel=1e-15)
        else:
            assert data.quantity[k] == "sound_speed"
            assert data.value[k] == pytest.approx(float(row["value"]) * 1500.0, rel=1e-15)


def test_bad_file_names_file_line_and_field(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("quantity,frequency,frequency_unit,value,value_unit,sigma\n"
                   "attenuation,100,Hz,0.01,dB/m,0.001\n"
                   "attenuation,abc,Hz,0.01,dB/m,0.001\n")
    with pytest.raises(sedwave.InputError) as error:
        sedwave.read_observations(bad)
    assert error.value.file == str(bad) and error.value.line == 3 and error.value.field == "frequency"
    assert f"{bad}:3:" in str(error.value)
    assert isinstance(error.value, ValueError)


def test_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="cannot open"):
        sedwave.read_observations(tmp_path / "absent.csv")


def test_digitized_export_as_the_command_reads_it():
    data = sedwave.read_digitized(DIGITIZED, "attenuation", "kHz", "dB/m", relative_sigma=0.1)
    assert len(data) > 3
    assert np.all(data.frequency_hz >= 1.0) and np.allclose(data.sigma / data.value, 0.1)


def test_arrays_in_units_converted_written_and_read_back(tmp_path):
    f = np.array([100.0, 1000.0, 1000.0])
    data = sedwave.Observations(["attenuation", "attenuation", "sound_speed_ratio"], f,
                                [0.01, 0.5, 1.05], sigma=[0.001, 0.05, 0.01],
                                unit=["dB/m", "dB/m", "ratio"], water_speed=1500.0)
    assert data.value[1] == pytest.approx(0.5 / sedwave.NEPER_TO_DB)
    assert data.value[2] == pytest.approx(1575.0) and data.sigma[2] == pytest.approx(15.0)
    path = tmp_path / "obs.csv"
    data.write(path, header=["made in a test"])
    back = sedwave.read_observations(path)
    np.testing.assert_array_equal(back.frequency_hz, data.frequency_hz)
    np.testing.assert_array_equal(back.value, data.value)
    np.testing.assert_array_equal(back.sigma, data.sigma)


def test_bad_arrays_name_the_argument_and_index():
    with pytest.raises(ValueError, match=r"frequency_hz\[1\]"):
        sedwave.Observations("attenuation", [100.0, 0.0], [1e-3, 1e-3])
    with pytest.raises(ValueError, match=r"unit\[0\]"):
        sedwave.Observations("attenuation", [100.0], [1e-3], unit="furlongs")
    with pytest.raises(ValueError, match="value: 1 entries for 2"):
        sedwave.Observations("attenuation", [100.0, 200.0], [1e-3])


def test_bottom_loss_rows_from_arrays_equal_the_files(tmp_path):
    # The same rows from arrays and from an observation file: one set of values, angles in degrees.
    path = tmp_path / "bl.csv"
    path.write_text("# water_sound_speed_m_per_s: 1500\n"
                    "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n"
                    "bottom_loss,1000,Hz,3.5,dB,0.5,20\n"
                    "bottom_loss,1000,Hz,-0.4,dB,0.5,5\n"
                    "shear_speed,1000,Hz,210,m/s,5,\n")
    from_file = sedwave.read_observations(path)
    arrays = sedwave.Observations(["bottom_loss", "bottom_loss", "shear_speed"], [1000.0] * 3, [3.5, -0.4, 210.0],
                                  sigma=[0.5, 0.5, 5.0], water_speed=1500.0, grazing_angle_deg=[20.0, 5.0, np.nan])
    for name in ("frequency_hz", "value", "sigma"):
        np.testing.assert_array_equal(getattr(arrays, name), getattr(from_file, name))
    np.testing.assert_allclose(arrays.grazing_angle_deg[:2], [20.0, 5.0], rtol=1e-15)
    assert np.isnan(arrays.grazing_angle_deg[2]) and np.isnan(from_file.grazing_angle_deg[2])
    assert list(arrays.quantity) == ["bottom_loss", "bottom_loss", "shear_speed"]
    with pytest.raises(ValueError, match=r"grazing_angle_deg: reflection rows need their grazing angles"):
        sedwave.Observations("bottom_loss", [1000.0], [3.0], sigma=[0.5], water_speed=1500.0)
    with pytest.raises(ValueError, match=r"value\[0\]: a bottom loss below 0 dB by more than three sigmas"):
        sedwave.Observations("bottom_loss", [1000.0], [-2.0], sigma=[0.5], grazing_angle_deg=[10.0])
    with pytest.raises(ValueError, match=r"grazing_angle_deg\[0\]: only a reflection row"):
        sedwave.Observations("attenuation", [1000.0], [0.1], grazing_angle_deg=[10.0])
