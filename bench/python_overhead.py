#!/usr/bin/env python3
"""What a call from Python costs over the same work in C++ (docs/python.md):

  1. one scalar evaluation, Model.wave(f, values), against the C++ evaluate() it wraps;
  2. Model.evaluate over 10^5 frequencies (numpy in and out) against the C++ loop alone;
  3. a model defined in Python (register_model): its cost per evaluation, without and with
     derivatives (finite differences: 2 x parameters + 1 calls).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--repeats N]

Medians of N runs (default 15), measured side by side in one process; the C++ times come from the
module's own loop (_cpp_loop_seconds) over the same model object."""
import argparse
import math
import statistics
import time

import numpy as np

import sedwave


def median_seconds(run, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=15)
    parser.add_argument("--model", default="biot-stoll")
    args = parser.parse_args()
    model = sedwave.Model(args.model)
    values = np.ascontiguousarray(model.defaults)
    rows = []

    # 1. Scalar: 10^4 calls per run, per call.
    n = 10_000
    f_one = np.full(n, 1000.0)
    wave = model.wave

    def python_scalar():
        for _ in range(n):
            wave(1000.0, values)

    py = median_seconds(python_scalar, args.repeats) / n
    cpp = statistics.median(sedwave._sedwave._cpp_loop_seconds(model, f_one, values) for _ in range(args.repeats)) / n
    rows.append(("scalar Model.wave", f"{cpp * 1e6:.3f} us", f"{py * 1e6:.3f} us", f"+{(py - cpp) * 1e6:.3f} us"))

    # 2. Vectorised over 10^5 frequencies.
    # Alternated run by run, so that a change in the machine's load touches both alike.
    f = np.geomspace(10.0, 1e6, 100_000)
    py_times, cpp_times = [], []
    for _ in range(args.repeats):
        py_times.append(median_seconds(lambda: model.evaluate(f, values), 1))
        cpp_times.append(sedwave._sedwave._cpp_loop_seconds(model, f, values))
    py, cpp = statistics.median(py_times), statistics.median(cpp_times)
    rows.append(("evaluate, 1e5 frequencies", f"{cpp * 1e3:.2f} ms", f"{py * 1e3:.2f} ms", f"x{py / cpp:.3f}"))

    # 3. A Python model (Kjartansson's constant Q), through the library's evaluate().
    def constant_q(v, freq):
        g = math.atan(1.0 / v[1]) / math.pi
        c = v[0] * (freq / 1e4) ** g
        return math.tan(math.pi * g / 2.0) * 2.0 * math.pi * freq / c, c

    own = sedwave.register_model("bench-constant-q", [
        {"name": "c_ref", "unit": "m/s", "default": 1700.0, "range": (1000.0, 3000.0)},
        {"name": "Q", "unit": "1", "default": 30.0, "range": (1.0, 1000.0)}], constant_q)
    f_own = np.geomspace(10.0, 1e5, 2000)
    v_own = np.ascontiguousarray(own.defaults)
    plain = statistics.median(sedwave._sedwave._cpp_loop_seconds(own, f_own, v_own)
                              for _ in range(args.repeats)) / f_own.size
    v_tuple = tuple(float(x) for x in v_own)  # as the library passes them
    bare = median_seconds(lambda: [constant_q(v_tuple, x) for x in f_own], args.repeats) / f_own.size
    with_d = median_seconds(lambda: own.evaluate(f_own, v_own, derivatives=True), args.repeats) / f_own.size
    rows.append(("Python model, per evaluation", f"{bare * 1e6:.2f} us (the function alone)",
                 f"{plain * 1e6:.2f} us", f"+{(plain - bare) * 1e6:.2f} us"))
    rows.append(("  with derivatives (finite differences, 5 calls)", "", f"{with_d * 1e6:.2f} us", ""))

    print(f"model {args.model}, medians of {args.repeats} runs")
    print(f"{'what':48s} {'C++ (Python alone)':>28s} {'via sedwave':>14s} {'overhead':>12s}")
    for r in rows:
        print(f"{r[0]:48s} {r[1]:>28s} {r[2]:>14s} {r[3]:>12s}")


if __name__ == "__main__":
    main()
