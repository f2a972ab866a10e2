"""Models from Python: listed with their parameters, evaluated on arrays equal to one-at-a-time
calls, exact derivatives against finite differences, closed forms and limits."""
import math

import numpy as np
import pytest

import sedwave


def test_every_model_family_is_listed_with_units_and_ranges():
    models = {m["name"]: m for m in sedwave.models()}
    assert {"biot-stoll", "edfm", "lattice"} <= set(models)
    for m in models.values():
        for p in m["parameters"]:
            lower, upper = p["range"]
            assert p["unit"] and 0 < lower <= p["default"] <= upper, (m["name"], p)
    for name in ("biot-stoll", "edfm", "lattice"):
        assert models[name]["derivatives"].startswith("exact")


def test_arrays_equal_single_calls_and_keep_their_shape():
    model = sedwave.Model("biot-stoll")
    f = np.geomspace(10.0, 1e5, 12).reshape(3, 4)
    out = model.evaluate(f)
    assert out["alpha"].shape == (3, 4) and out["c"].shape == (3, 4)
    v = model.defaults
    for k, fk in enumerate(f.ravel()):
        alpha, c = model.wave(fk, v)
        assert out["alpha"].ravel()[k] == alpha and out["c"].ravel()[k] == c


def test_exact_derivatives_match_central_differences():
    model = sedwave.Model("edfm")
    f = np.array([100.0, 3e3, 1e5])
    v = model.values()
    out = model.evaluate(f, v, derivatives=True)
    assert out["d_alpha"].shape == (3, len(v))
    for i in range(len(v)):
        h = 1e-6 * v[i]
        up, down = v.copy(), v.copy()
        up[i] += h
        down[i] -= h
        a_up, a_down = model.evaluate(f, up)["alpha"], model.evaluate(f, down)["alpha"]
        c_up, c_down = model.evaluate(f, up)["c"], model.evaluate(f, down)["c"]
        fd_alpha, fd_c = (a_up - a_down) / (2 * h), (c_up - c_down) / (2 * h)
        scale_a = np.abs(out["alpha"]) / v[i]
        scale_c = np.abs(out["c"]) / v[i]
        np.testing.assert_allclose(out["d_alpha"][:, i], fd_alpha, rtol=1e-4, atol=1e-7 * scale_a.max())
        np.testing.assert_allclose(out["d_c"][:, i], fd_c, rtol=1e-4, atol=1e-7 * scale_c.max())


def test_low_frequency_speed_is_woods_for_biot_stoll():
    # Gassmann/Biot at low frequency with a frame much softer than water is close to Wood's mixture
    # speed, the model's derived wood_speed: sqrt(K_wood / rho), 1/K_wood = phi/K_w + (1-phi)/K_s.
    model = sedwave.Model("biot-stoll")
    derived = model.derived()
    p = dict(zip(model.parameter_names, model.defaults))
    phi = p["porosity"]
    k_wood = 1.0 / (phi / p["K_w"] + (1 - phi) / p["K_s"])
    rho = phi * p["rho_w"] + (1 - phi) * p["rho_s"]
    assert derived["wood_speed"] == pytest.approx(math.sqrt(k_wood / rho), rel=1e-12)
    c_low = model.evaluate(np.array([1.0]))["c"][0]
    assert c_low >= derived["wood_speed"] * 0.999 and c_low < derived["wood_speed"] * 1.2


def test_dimensionless_wave_of_a_chain_and_nan_elsewhere():
    lattice = sedwave.Model("lattice")
    values = {"kappa": 1e7, "d": 3e-4}
    hat = lattice.dimensionless(np.array([1e3, 1e4]), values)
    assert np.all(np.isfinite(hat["alpha_hat"])) and np.all(hat["c_hat"] > 0)
    # omega_hat is proportional to the frequency.
    assert hat["omega_hat"][1] / hat["omega_hat"][0] == pytest.approx(10.0, rel=1e-12)
    other = sedwave.Model("biot-stoll").dimensionless(np.array([1e3]))
    assert np.isnan(other["alpha_hat"][0])


def test_bad_values_and_frequencies_raise_value_errors_naming_them():
    model = sedwave.Model("biot-stoll")
    with pytest.raises(ValueError, match="porosity"):
        model.evaluate(np.array([1e3]), {"porosity": 1.5})
    with pytest.raises(ValueError, match=r"values\['nonsense'\]"):
        model.evaluate(np.array([1e3]), {"nonsense": 1.0})
    with pytest.raises(ValueError, match=r"frequency_hz\[1\]"):
        model.evaluate(np.array([1e3, -1.0]))
    with pytest.raises(ValueError, match="accepted|expected|unknown"):
        sedwave.Model("no-such-model")
