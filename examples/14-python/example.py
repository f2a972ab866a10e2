"""sedwave from Python, as a notebook would use it: the shipped field data (points sampled from
Zhou, Zhang & Knobles's 2009 regressions) fitted with Biot-Stoll, a constant-Q model written in
Python registered beside the built-in models, the three ranked by their evidence under a
medium-sand site's priors, and the curves and posterior bands plotted with matplotlib.

    python3 example.py [OUT]     (from anywhere, once `import sedwave` works: docs/python.md)

Copy it into a notebook cell by cell; every number is in SI (Hz, Np/m, m/s) unless said.
"""
import math
import pathlib
import sys

import numpy as np

import sedwave

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE.parent.parent / "data"
OUT = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path("sedwave-example-14")
OUT.mkdir(parents=True, exist_ok=True)

# 1. The data: attenuation in dB/m and sound-speed ratios in the file, SI once read.
data = sedwave.read_observations(DATA / "field" / "zhou2009_regression.csv")
print(f"{len(data)} observations, {data.frequency_hz.min():g}-{data.frequency_hz.max():g} Hz, "
      f"water {data.water_sound_speed:g} m/s")

# 2. One model fitted: what `sedwave invert --model biot-stoll` reports. Parameters the data leave
#    open come as sedwave.NotDeterminedWarning (and in fit.not_determined).
fit = sedwave.fit(data, model="biot-stoll")
print(fit)
for name in fit.free:
    p = fit.parameters[name]
    print(f"  {name:12s} {p['value']:.4g} {p['unit']}  determined: {p['identifiable']}")
print(f"  not determined: {', '.join(fit.not_determined) or 'none'}; derivatives {fit.derivatives}")

# 3. A model of one's own, in Python: Kjartansson's constant-Q medium (J. Geophys. Res. 84, 4737
#    (1979)), the same physics as examples/12-own-model's C++ class. c = c_ref (f / 10 kHz)^g,
#    alpha = tan(pi g / 2) omega / c, g = arctan(1/Q) / pi. No derivatives given: the fit uses
#    central finite differences, and says so.
def constant_q(values, f):
    c_ref, q = values
    g = math.atan(1.0 / q) / math.pi
    c = c_ref * (f / 1e4) ** g
    return math.tan(math.pi * g / 2.0) * 2.0 * math.pi * f / c, c


sedwave.register_model("constant-q-py", [
    {"name": "c_ref", "unit": "m/s", "default": 1700.0, "range": (1000.0, 3000.0), "log_scale": False,
     "meaning": "phase speed at 10 kHz"},
    {"name": "Q", "unit": "1", "default": 30.0, "range": (1.0, 1000.0), "meaning": "quality factor"},
], constant_q, summary="Kjartansson's constant-Q medium, in Python")
own = sedwave.fit(data, model="constant-q-py", profile=False)
print(own, "-", own.derivatives)

# 4. The three ranked by evidence under the site's priors (`sedwave compare --site`). A shorter
#    ladder and a looser target than the command's defaults: enough for Bayes factors of hundreds.
ranking = sedwave.compare(data, ["biot-stoll", "edfm", "constant-q-py"],
                          site=DATA / "sites" / "medium_sand.toml", temperatures=8, steps=2000,
                          target_uncertainty=0.3, out=OUT / "compare")
print(ranking)
for label in ranking.models:
    print(f"  ln Z {label:14s} {ranking.log_evidence[label]:9.2f} +- {ranking.uncertainty[label]:.2f}")

# 5. The figure: data, each model's posterior band (16-84 %) and median, attenuation in dB/m.
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed (Debian: apt-get install python3-matplotlib): no figure")
else:
    fig, (ax_a, ax_c) = plt.subplots(1, 2, figsize=(11, 4.2))
    att = data.quantity == "attenuation"
    ax_a.errorbar(data.frequency_hz[att], sedwave.NEPER_TO_DB * data.value[att],
                  sedwave.NEPER_TO_DB * data.sigma[att], fmt="ko", ms=3, label="data")
    ax_c.errorbar(data.frequency_hz[~att], data.value[~att], data.sigma[~att], fmt="ko", ms=3, label="data")
    for label in ranking.models:
        band = ranking.band(label)
        f = band["frequency_hz"]
        ax_a.fill_between(f, sedwave.NEPER_TO_DB * band["alpha"][:, 1], sedwave.NEPER_TO_DB * band["alpha"][:, 3],
                          alpha=0.3)
        ax_a.plot(f, sedwave.NEPER_TO_DB * band["alpha"][:, 2], label=label)
        ax_c.fill_between(f, band["c"][:, 1], band["c"][:, 3], alpha=0.3)
        ax_c.plot(f, band["c"][:, 2], label=label)
    curves = fit.curves()
    ax_a.plot(curves["frequency_hz"], sedwave.NEPER_TO_DB * curves["alpha"], "k:", label="biot-stoll best fit")
    ax_a.set(xscale="log", yscale="log", xlabel="frequency [Hz]", ylabel="attenuation [dB/m]")
    ax_c.set(xscale="log", xlabel="frequency [Hz]", ylabel="sound speed [m/s]")
    ax_a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(OUT / "bands.png", dpi=120)
    print(f"figure: {OUT / 'bands.png'}")

# 6. Key numbers, for run.sh to compare with expected.txt.
with open(OUT / "results.txt", "w") as results:
    print(f"biot_stoll_chi2 {fit.chi2:.6g}", file=results)
    print(f"constant_q_c_ref {own.parameters['c_ref']['value']:.6g}", file=results)
    print(f"constant_q_Q {own.parameters['Q']['value']:.6g}", file=results)
    print(f"constant_q_chi2 {own.chi2:.6g}", file=results)
    print(f"best_model {ranking.best}", file=results)
    for label in ranking.models:
        print(f"ln_Z_{label} {ranking.log_evidence[label]:.4f}", file=results)
