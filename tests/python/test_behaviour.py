"""How the module behaves around a long call: the GIL released, progress reported, Ctrl-C stops a
comparison without touching its output folder, a Python model registered and fitted."""
import math
import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import sedwave
from conftest import FIELD


def test_fit_releases_the_gil(field_data):
    # With a switch interval far longer than the test, this thread gives the GIL away only where
    # it blocks or a C++ call releases it: the waiting thread can set `during` before the fit
    # returns only if the fit released the GIL.
    go, during = threading.Event(), threading.Event()

    def waiter():
        go.wait()
        during.set()

    thread = threading.Thread(target=waiter)
    thread.start()
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        go.set()
        sedwave.fit(field_data, model="biot-stoll", profile=False)
        set_before_return = during.is_set()
    finally:
        sys.setswitchinterval(interval)
        thread.join()
    assert set_before_return


def test_progress_reaches_the_callback_and_its_error_stops_the_fit(field_data):
    lines = []
    sedwave.fit(field_data, model="biot-stoll", progress=lines.append)
    assert any("global search" in line for line in lines)

    def refuse(line):
        raise RuntimeError("stop here: " + line)

    with pytest.raises(RuntimeError, match="stop here: global search"):
        sedwave.fit(field_data, model="biot-stoll", progress=refuse)


def test_sigint_stops_a_comparison_and_leaves_out_as_it_was(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "compare.json").write_text("the previous run's report\n")
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    child = textwrap.dedent(f"""
        import sys, sedwave
        data = sedwave.read_observations({str(FIELD)!r})
        started = []
        def progress(line):
            if not started:
                started.append(line)
                print("started", flush=True)
        sedwave.compare(data, ["biot-stoll", "edfm"], threads=1, out={str(out)!r}, progress=progress)
        print("finished", flush=True)
    """)
    process = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, env=dict(os.environ))
    assert process.stdout.readline().strip() == "started"
    process.send_signal(signal.SIGINT)
    stdout, stderr = process.communicate(timeout=120)
    assert "KeyboardInterrupt" in stderr and "finished" not in stdout
    assert process.returncode != 0
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


# Kjartansson's constant-Q medium (J. Geophys. Res. 84, 4737 (1979)), as examples/12-own-model
# writes it in C++: c = c_ref (f/f_ref)^g, alpha = tan(pi g/2) omega/c, g = arctan(1/Q)/pi.
F_REF = 1e4


def constant_q(values, f):
    c_ref, q = values
    g = math.atan(1.0 / q) / math.pi
    c = c_ref * (f / F_REF) ** g
    return math.tan(math.pi * g / 2.0) * 2.0 * math.pi * f / c, c


def constant_q_derivatives(values, f):
    c_ref, q = values
    g = math.atan(1.0 / q) / math.pi
    dg_dq = -1.0 / (math.pi * (1.0 + q * q))
    c = c_ref * (f / F_REF) ** g
    dc = (c / c_ref, c * math.log(f / F_REF) * dg_dq)
    t = math.tan(math.pi * g / 2.0)
    alpha = t * 2.0 * math.pi * f / c
    dalpha_dg = 2.0 * math.pi * f / c * (math.pi / 2.0) / math.cos(math.pi * g / 2.0) ** 2
    da = (-alpha / c * dc[0], dalpha_dg * dg_dq - alpha / c * dc[1])
    return da, dc


PARAMETERS = [
    {"name": "c_ref", "unit": "m/s", "default": 1700.0, "range": (1000.0, 3000.0), "log_scale": False,
     "meaning": "phase speed at 10 kHz"},
    {"name": "Q", "unit": "1", "default": 30.0, "range": (1.0, 1000.0), "meaning": "quality factor"},
]


@pytest.mark.parametrize("derivatives", [None, constant_q_derivatives], ids=["finite-differences", "supplied"])
def test_python_model_fitted_as_the_cpp_one(field_data, derivatives):
    name = "py-constant-q-" + ("fd" if derivatives is None else "exact")
    model = sedwave.register_model(name, PARAMETERS, constant_q, derivatives)
    assert name in " ".join(sedwave.model_names())
    said = sedwave.derivatives_of(model)
    assert ("finite differences" in said) == (derivatives is None)
    result = sedwave.fit(field_data, model=name, profile=False)
    assert result.derivatives == said
    # examples/12-own-model's C++ model on the same data (its expected.txt): c_ref 1611.4 +- 0.5,
    # Q 102.35 +- 0.1, chi2 4121 +- 2.
    assert result.parameters["c_ref"]["value"] == pytest.approx(1611.4, abs=0.5)
    assert result.parameters["Q"]["value"] == pytest.approx(102.35, abs=0.1)
    assert result.chi2 == pytest.approx(4121.0, abs=2.0)


def test_python_model_errors_stop_the_fit_and_are_raised(field_data):
    def broken(values, f):
        raise ZeroDivisionError("the model's own error")

    sedwave.register_model("py-broken", PARAMETERS, broken)
    with pytest.raises(ZeroDivisionError, match="the model's own error"):
        sedwave.fit(field_data, model="py-broken", profile=False)
    with pytest.raises(ValueError, match="already|taken"):
        sedwave.register_model("py-broken", PARAMETERS, broken)


def test_python_model_supplied_derivatives_agree_with_differences():
    model = sedwave.register_model("py-constant-q-check", PARAMETERS, constant_q, constant_q_derivatives)
    f = np.array([50.0, 1e3, 1e5])
    out = model.evaluate(f, [1600.0, 80.0], derivatives=True)
    for i, v in enumerate([1600.0, 80.0]):
        h = 1e-6 * v
        up = np.array([1600.0, 80.0])
        down = up.copy()
        up[i] += h
        down[i] -= h
        fd = (model.evaluate(f, up)["alpha"] - model.evaluate(f, down)["alpha"]) / (2 * h)
        np.testing.assert_allclose(out["d_alpha"][:, i], fd, rtol=1e-5)
