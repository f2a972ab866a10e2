"""Studies from Python equal the command's for the same inputs: fit, posterior, compare and
synthesize run the same library calls, so their reports are identical but for wall-clock times."""
import warnings

import numpy as np
import pytest

import sedwave
from conftest import FIELD, SITE, load, run_sedwave, without_timings


def test_fit_equals_invert(sedwave_command, field_data, tmp_path):
    run_sedwave(sedwave_command, "invert", FIELD, "--model", "biot-stoll", "--no-plot", "--out", tmp_path)
    with pytest.warns(sedwave.NotDeterminedWarning):
        result = sedwave.fit(field_data, model="biot-stoll")
    cli = load(tmp_path / "fit.json")
    assert without_timings(load_text(result.to_json())) == without_timings(cli)
    assert result.chi2 == cli["chi2"]
    assert "delta_b" in result.not_determined
    # Its files are the command's: the curves and the observations beside the fit, byte for byte.
    result.write(tmp_path / "py")
    for name in ("curves.csv", "observations.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / name).read_bytes(), name
    curves = result.curves()
    shown = np.genfromtxt(tmp_path / "curves.csv", delimiter=",", names=True, skip_header=1)
    np.testing.assert_array_equal(curves["frequency_hz"], shown["frequency_hz"])
    np.testing.assert_array_equal(curves["alpha"], shown["alpha_np_per_m"])
    np.testing.assert_array_equal(curves["c"], shown["sound_speed_m_per_s"])


def test_fit_with_settings_equals_invert_with_options(sedwave_command, field_data, tmp_path):
    run_sedwave(sedwave_command, "invert", FIELD, "--model", "edfm", "--fit", "porosity,permeability", "--set",
                "rho_s=2600", "--bounds", "permeability=1e-12,1e-9", "--method", "ceres", "--no-profile", "--no-plot",
                "--out", tmp_path)
    result = sedwave.fit(field_data, model="edfm", free=["porosity", "permeability"], values={"rho_s": 2600.0},
                         bounds={"permeability": (1e-12, 1e-9)}, method="ceres", profile=False)
    assert without_timings(load_text(result.to_json())) == without_timings(load(tmp_path / "fit.json"))
    i = sedwave.Model("edfm").parameter_names.index("rho_s")
    assert result.values[i] == 2600.0


def test_posterior_equals_invert_posterior(sedwave_command, field_data, tmp_path):
    run_sedwave(sedwave_command, "invert", FIELD, "--model", "biot-stoll", "--method", "posterior", "--site", SITE,
                "--steps", "300", "--temperatures", "0", "--no-plot", "--out", tmp_path)
    with pytest.warns(sedwave.SedwaveWarning):
        result = sedwave.posterior(field_data, model="biot-stoll", site=SITE, steps=300, temperatures=0)
    assert without_timings(load_text(result.to_json())) == without_timings(load(tmp_path / "fit.json"))
    # The CSV holds 9 significant digits.
    cli_samples = np.loadtxt(tmp_path / "posterior_samples.csv", delimiter=",", skiprows=2)
    assert result.sample_names == result.free and result.samples.shape == cli_samples.shape
    np.testing.assert_allclose(result.samples, cli_samples, rtol=1e-8)
    band = result.band
    assert band["alpha"].shape == (len(band["frequency_hz"]), 5)
    assert np.all(np.diff(band["alpha"], axis=1) >= 0)  # quantiles in order


def test_compare_equals_compare(sedwave_command, field_data, tmp_path):
    settings = ["--temperatures", "4", "--steps", "300", "--threads", "1"]
    run_sedwave(sedwave_command, "compare", FIELD, "--models", "biot-stoll,edfm", *settings, "--no-plot",
                "--out", tmp_path / "cli")
    # Both evidences come from fast paths (Biot-Stoll's from adaptive cubature), so the short
    # tempering settings are never used and nothing is left unconverged.
    with warnings.catch_warnings():
        warnings.simplefilter("error", sedwave.NotConvergedWarning)
        ranking = sedwave.compare(field_data, ["biot-stoll", "edfm"], temperatures=4, steps=300, threads=2,
                                  out=tmp_path / "py")
    assert ranking.converged
    assert without_timings(load_text(ranking.to_json())) == without_timings(load(tmp_path / "cli" / "compare.json"))
    assert (tmp_path / "py" / "compare.json").read_text() == ranking.to_json()
    assert ranking.best == "biot-stoll"
    assert ranking.samples("edfm").shape[1] == len(ranking.sample_names("edfm"))


def test_synthesize_equals_synthesize(sedwave_command, tmp_path):
    path = tmp_path / "syn.csv"
    run_sedwave(sedwave_command, "synthesize", "--model", "lattice", "--kappa", "2e7", "--d", "3e-4", "--gamma",
                "0.02", "--from", "100", "--to", "1e5", "--points", "7", "--seed", "5", "--out", path)
    data = sedwave.synthesize("lattice", {"kappa": 2e7, "d": 3e-4, "gamma": 0.02}, 100.0, 1e5, points=7, seed=5)
    cli = sedwave.read_observations(path)
    np.testing.assert_array_equal(data.frequency_hz, cli.frequency_hz)
    np.testing.assert_array_equal(data.value, cli.value)
    np.testing.assert_array_equal(data.sigma, cli.sigma)


def test_setup_errors_name_the_argument(field_data):
    with pytest.raises(sedwave.SetupError, match="nonsense"):
        sedwave.fit(field_data, model="biot-stoll", values={"nonsense": 1.0})
    with pytest.raises(ValueError, match=r"porosity \(value 7"):
        sedwave.fit(field_data, model="biot-stoll", values={"porosity": 7.0})
    with pytest.raises(ValueError, match=r"^free='porosity,porosity' names 'porosity' twice"):
        sedwave.fit(field_data, model="biot-stoll", free="porosity,porosity")
    with pytest.raises(ValueError, match=r"^priors: porosity=weird:1,2: unknown kind 'weird'"):
        sedwave.posterior(field_data, model="biot-stoll", priors={"porosity": "weird:1,2"})
    with pytest.raises(ValueError, match=r"values\['nonsense'\]: none of the models"):
        sedwave.compare(field_data, ["biot-stoll"], values={"nonsense": 1.0})
    with pytest.raises(ValueError, match="kappa"):
        sedwave.synthesize("lattice", {"d": 3e-4, "gamma": 0.02}, 100.0, 1e4)


def load_text(text):
    import json
    return json.loads(text)


def test_flags_arrive_as_warnings_and_fields(field_data, recwarn):
    result = sedwave.fit(field_data, model="lattice", profile=False)
    messages = [f["message"] for f in result.report["flags"]]
    assert messages and result.flags == messages
    warned = [str(w.message) for w in recwarn if w.category is sedwave.FlagWarning]
    assert warned == [f"lattice: {m}" for m in messages]
    determined = {n: p["identifiable"] for n, p in result.parameters.items() if p["free"]}
    warned = [str(w.message).split()[1] for w in recwarn if w.category is sedwave.NotDeterminedWarning]
    assert warned == [n for n, ok in determined.items() if not ok] == result.not_determined


def test_prior_controlled_intervals_are_warned(field_data, recwarn):
    result = sedwave.posterior(field_data, model="biot-stoll", site=SITE, steps=300, temperatures=0)
    flagged = [n for n, q in result.posterior["parameters"].items() if q["prior_dominated"]]
    assert flagged and result.prior_controlled == flagged
    warned = [w for w in recwarn if w.category is sedwave.PriorControlledWarning]
    assert len(warned) == len(flagged) and all("PRIOR-CONTROLLED" in str(w.message) for w in warned)
    # As errors where the caller wants them so.
    with warnings.catch_warnings():
        warnings.simplefilter("error", sedwave.SedwaveWarning)
        with pytest.raises(sedwave.SedwaveWarning):
            sedwave.posterior(field_data, model="biot-stoll", site=SITE, steps=300, temperatures=0)
