"""sedwave from Python: sediment models, observations, fits, posteriors and model comparison.

Units are SI everywhere: frequencies in Hz, attenuation alpha in Np/m (8.6859 dB per neper), sound
speed c in m/s, parameters in the unit each model lists (``Model(spec).parameters``).

By task (docs/python.md):

- models: ``model_names()``, ``models()``, ``Model(spec).evaluate(f, values, derivatives=True)``,
  ``register_model(name, parameters, wave, derivatives=None)``
- data: ``read_observations(path)``, ``read_digitized(path, ...)``,
  ``Observations(quantity, frequency_hz, value, sigma)``, ``Observations.write(path)``
- tables: ``read_table(path)`` (a dispersion table's points as arrays, read only)
- run files: ``read_run(path)`` (any HDF5 output of a run -- forward, interface, checkpoints -- as arrays, read only)
- studies: ``fit(data, model=...)``, ``posterior(data, model=...)``, ``compare(data, models=[...])``,
  ``synthesize(model, values, lowest_hz, highest_hz)``

Each study calls the same library functions as the ``sedwave`` command with the same settings, so
its numbers are the command's, and ``to_json()`` is its fit.json or compare.json. Long calls run
without the GIL, report progress to a callback and stop on Ctrl-C (KeyboardInterrupt) without
writing anything. Flags arrive as warnings (``SedwaveWarning`` and its subclasses) and as fields.
"""

import json
import os
import sys
import warnings

from ._sedwave import (
    InputError,
    Model,
    Observations,
    SetupError,
    __version__,
    derivatives_of,
    model_examples,
    model_names,
    read_digitized,
    read_observations,
    read_table,
    read_run,
)
from . import _sedwave

__all__ = [
    "InputError", "Model", "Observations", "SetupError", "model_names", "model_examples", "models",
    "read_observations", "read_digitized", "read_table", "read_run", "register_model", "derivatives_of", "fit", "posterior",
    "compare", "synthesize", "FitResult", "Ranking", "SedwaveWarning", "NotDeterminedWarning",
    "PriorControlledWarning", "FlagWarning", "NotConvergedWarning", "NEPER_TO_DB",
]

NEPER_TO_DB = 8.685889638065035
"""dB per neper: alpha [dB/m] = NEPER_TO_DB * alpha [Np/m]."""


class SedwaveWarning(UserWarning):
    """Something a result's reader must know (the command line prints these in capitals)."""


class NotDeterminedWarning(SedwaveWarning):
    """NOT DETERMINED: the data leave a free parameter (or combination) open."""


class PriorControlledWarning(SedwaveWarning):
    """PRIOR-CONTROLLED: a posterior interval that the prior, not the data, made."""


class FlagWarning(SedwaveWarning):
    """WARNING: a result outside its physical range, or at a search bound, with its likely cause."""


class NotConvergedWarning(SedwaveWarning):
    """A solver or sampler stopped at its cap before converging."""


def models():
    """Every model family as a dict: name, summary, parameters (name, unit, default, range,
    log_scale, meaning, typical), derived quantities, typical free set, derivatives (how computed).
    The list ``sedwave models`` prints."""
    out = []
    for m in model_examples():
        out.append({
            "name": m.name, "summary": m.summary, "parameters": m.parameters,
            "derived": m.derived_quantities, "typical_free": m.typical_free,
            "derivatives": derivatives_of(m),
        })
    return out


def register_model(name, parameters, wave, derivatives=None, summary="", typical_free=""):
    """Registers a model defined in Python under ``name``: fit, posterior, compare and synthesize
    then take it by name like a built-in one (in this process).

    parameters: a list of dicts with name, unit (SI; "1" if dimensionless), default, range
    (lower, upper), and optionally meaning, log_scale, typical. Every value must be positive.
    wave(values, frequency_hz) -> (alpha [Np/m], c [m/s]); values a tuple of floats in parameter
    order [SI], frequency_hz a float [Hz].
    derivatives(values, frequency_hz) -> (d_alpha, d_c), each one number per parameter; without it
    the fit uses central finite differences (``derivatives_of(model)`` says which).
    The functions are called under the GIL, one evaluation at a time, from whichever thread the
    library runs on; an exception they raise stops the study and is raised by it. A comparison
    that includes a Python model runs its jobs one after the other (threads=1): threads taking
    turns at the GIL for every evaluation would be several times slower.
    Returns the Model."""
    return _sedwave._register_model(name, list(parameters), wave, derivatives, summary or
                                    f"{name} (defined in Python)", typical_free or "")


def _progress_function(progress):
    """None: silent; True: lines on stderr (through tqdm.write where tqdm is installed); a callable
    taking one str: called with each line."""
    if progress is None or progress is False:
        return None
    if progress is True:
        try:
            from tqdm import tqdm
            return lambda line: tqdm.write(line, file=sys.stderr)
        except ImportError:
            return lambda line: print(line, file=sys.stderr, flush=True)
    if not callable(progress):
        raise TypeError("progress: expected None, True or a function of one str")
    return progress


def _usable_cores():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def _prior_controlled(posterior):
    return [name for group in ("parameters", "combinations")
            for name, q in posterior.get(group, {}).items() if q.get("prior_dominated")]


class FitResult:
    """A fit (``fit``) or a fit and its posterior (``posterior``).

    Fields from the report (the command line's fit.json, ``report``): model, method, chi2, dof,
    aic, bic, converged, parameters {name: {value, unit, free, sigma, log_sigma, at_bound,
    identifiable, profile_interval_68}}, combinations, flags (list of str), not_determined (names),
    and for a posterior: posterior (its report), prior_controlled (names).
    Arrays: values (every parameter, SI, model order), covariance and correlation (free
    ln-parameters), residuals (dict of arrays), samples (posterior draws x free parameters, SI),
    band (posterior predictive quantiles), curves(frequency_hz) (alpha, c with 1-sigma bands)."""

    def __init__(self, handle):
        self._handle = handle
        self.report = json.loads(handle.report_json())
        r = self.report
        self.model = r["model"]
        self.method = r["method"]
        self.chi2 = r["chi2"]
        self.dof = r["dof"]
        self.aic = r["aic"]
        self.bic = r["bic"]
        self.converged = r["converged"]
        self.parameters = r["parameters"]
        self.combinations = r.get("combinations", {})
        self.flags = [f["message"] if isinstance(f, dict) else str(f) for f in r.get("flags", [])]
        self.not_determined = [n for n, p in self.parameters.items() if p["free"] and not p["identifiable"]]
        self.derivatives = derivatives_of(handle.model)
        self.site_notes = handle.notes
        self.posterior = r.get("posterior")
        self.prior_controlled = _prior_controlled(self.posterior) if self.posterior else []

    def _warn(self):
        for name in self.not_determined:
            warnings.warn(f"{self.model}: {name} NOT DETERMINED by these data (see parameters['{name}']"
                          "['profile_interval_68'])", NotDeterminedWarning, stacklevel=3)
        for message in self.flags:
            warnings.warn(f"{self.model}: {message}", FlagWarning, stacklevel=3)
        for name in self.prior_controlled:
            warnings.warn(f"{self.model}: the posterior interval of {name} is PRIOR-CONTROLLED",
                          PriorControlledWarning, stacklevel=3)
        if not self.converged:
            warnings.warn(f"{self.model}: the fit did NOT converge", NotConvergedWarning, stacklevel=3)
        if self.posterior is not None and not self.posterior.get("converged", True):
            warnings.warn(f"{self.model}: the posterior sampler did NOT converge: "
                          f"{self.posterior.get('advice', '')}", NotConvergedWarning, stacklevel=3)

    @property
    def values(self):
        """Every parameter's value at the fit [SI], in the model's order."""
        return self._handle.values

    @property
    def free(self):
        return list(self._handle.free_names)

    @property
    def covariance(self):
        return self._handle.covariance

    @property
    def correlation(self):
        return self._handle.correlation

    @property
    def residuals(self):
        return self._handle.residuals

    @property
    def samples(self):
        """Posterior draws x free parameters [SI] (columns: sample_names), or None."""
        return self._handle.samples

    @property
    def sample_names(self):
        return list(self._handle.sample_names)

    @property
    def band(self):
        """The posterior's predictive band over the data's frequencies: frequency_hz, alpha and c
        (frequencies x the quantiles 2.5, 16, 50, 84, 97.5 %), residual; None without a posterior."""
        return self._handle.band

    def curves(self, frequency_hz=None):
        """The fitted model at frequency_hz [Hz] (default: the command's 241 log-spaced frequencies
        from a decade below the data to a decade above): alpha [Np/m], c [m/s], their 1-sigma from the
        covariance, and alpha_hat, c_hat (dry grain-contact frames; NaN for other models). A
        frequency where the model has no answer is left out."""
        return self._handle.curves(frequency_hz)

    def to_json(self):
        """The report, byte for byte as `sedwave invert` writes fit.json."""
        return self._handle.report_json()

    def write(self, out):
        """fit.json, curves.csv, observations.csv (and the posterior's files) in folder ``out``, all
        or none (as `sedwave invert --no-plot --out OUT`)."""
        self._handle.write(os.fspath(out))

    def __repr__(self):
        free = ", ".join(f"{n}={self.parameters[n]['value']:.4g}" for n in self.free)
        return f"<sedwave.FitResult {self.model}: {free}; chi2 {self.chi2:.4g} for {self.dof} dof>"


def _fit_settings(model, free, values, bounds, site, priors):
    return dict(model=model, free=free, values=values, bounds=bounds,
                site=None if site is None else os.fspath(site), priors=priors)


def fit(data, model="lattice", free=None, values=None, bounds=None, site=None, priors=None,
        method="global", profile=True, default_sigma=0.1, global_algorithm="direct-l",
        max_evaluations=5000, determined_log_sigma=0.5, progress=None):
    """Fits a model's free parameters to observations, as `sedwave invert` does.

    data: Observations (read_observations, read_digitized or from arrays).
    model: a catalog name (model_names(); registered Python models too) or a Model.
    free: the free parameters, "a,b" or a list (default: the model's typical set).
    values: {name: value [SI]}: start values of free parameters, the values of fixed ones
    (the command line's --set / --kappa ...). bounds: {name: (lower, upper) [SI]}: search bounds.
    site: a site file (TOML; docs/inversion.md): measured values and priors. priors: {name:
    "KIND:A,B"}, used by posterior().
    method: "global" (search, then polish), "ceres" (local) or "nlopt" (search). profile: the
    likelihood profiles (most of the time on large data). default_sigma: relative 1-sigma for
    observations without one.
    progress: None, True (stderr) or a function of one str.
    Returns a FitResult; NOT DETERMINED parameters, flags and non-convergence are also warned."""
    handle = _sedwave._fit(data, **_fit_settings(model, free, values, bounds, site, priors),
                           method=method, profile=profile, default_sigma=default_sigma,
                           global_algorithm=global_algorithm, max_evaluations=max_evaluations,
                           determined_log_sigma=determined_log_sigma,
                           progress=_progress_function(progress))
    result = FitResult(handle)
    result._warn()
    return result


def posterior(data, model="lattice", free=None, values=None, bounds=None, site=None, priors=None,
              profile=True, default_sigma=0.1, max_evaluations=5000, walkers=0, steps=100000,
              temperatures=-1, threads=1, seed=20090501, progress=None):
    """The global fit, then the Bayesian posterior of its free parameters and its predictive band,
    as `sedwave invert --method posterior` (same settings, same numbers).

    priors: {name: "KIND:A,B"}, KIND uniform | log-uniform | normal | log-normal (SI; default
    log-uniform over the search bounds, then the site file's). walkers (0: max(4 x free, 16)),
    steps (the cap on ensemble updates; stops once converged), temperatures (-1: a tempering
    ladder where a flat prior's parameter is left open; 0: one ensemble), threads (share each
    half-ensemble's evaluations; the samples do not depend on it).
    Returns a FitResult with posterior, samples, band; PRIOR-CONTROLLED intervals are warned."""
    handle = _sedwave._posterior(data, **_fit_settings(model, free, values, bounds, site, priors),
                                 profile=profile, default_sigma=default_sigma,
                                 max_evaluations=max_evaluations, walkers=walkers, steps=steps,
                                 temperatures=temperatures, threads=threads, seed=seed,
                                 progress=_progress_function(progress))
    result = FitResult(handle)
    result._warn()
    return result


class Ranking:
    """Models ranked by their evidence (``compare``).

    report: the command line's compare.json (a list, one entry per model in the order given);
    models: the labels in that order; order: indices, largest evidence first; order_widened: the
    same under priors widened tenfold; best: the label ranked first; log_evidence, uncertainty:
    {label: ln Z, its standard error}; converged: every evidence run reached its target.
    fit(i): model i's FitResult-like report (dict); samples(i), sample_names(i): its posterior
    draws [SI]; band(i): its posterior predictive band."""

    def __init__(self, handle, labels):
        self._handle = handle
        self.report = json.loads(handle.report_json())
        self.models = labels
        self.order = list(handle.order)
        self.order_widened = list(handle.order_widened)
        self.converged = handle.converged
        self.best = labels[self.order[0]]
        self.log_evidence = {m: e["evidence"]["log_evidence"] for m, e in zip(labels, self.report)}
        self.uncertainty = {m: e["evidence"]["uncertainty"] for m, e in zip(labels, self.report)}

    def _warn(self):
        for label, entry in zip(self.models, self.report):
            if not entry["evidence"]["converged"]:
                warnings.warn(f"{label}: the evidence did NOT converge: {entry['evidence'].get('advice', '')}",
                              NotConvergedWarning, stacklevel=3)

    def fit(self, i):
        """Model i's fit as fit.json's dict (`sedwave invert` on the same settings)."""
        return json.loads(self._handle.fit_report_json(self._index(i)))

    def samples(self, i):
        return self._handle.samples(self._index(i))

    def sample_names(self, i):
        return list(self._handle.sample_names(self._index(i)))

    def band(self, i):
        return self._handle.band(self._index(i))

    def _index(self, i):
        return self.models.index(i) if isinstance(i, str) else int(i)

    def to_json(self):
        """The ranking, byte for byte as `sedwave compare` writes compare.json."""
        return self._handle.report_json()

    def write(self, out):
        """compare.json, each model's predictive band and samples, predictive_residuals.csv in
        folder ``out``, all or none (as `sedwave compare --no-plot --out OUT`)."""
        self._handle.write(os.fspath(out))

    def __repr__(self):
        rows = ", ".join(f"{self.models[i]} {self.log_evidence[self.models[i]]:.2f}" for i in self.order)
        return f"<sedwave.Ranking by ln Z: {rows}>"


def compare(data, models, free=None, values=None, site=None, priors=None, temperatures=32,
            steps=4000, seed=20090501, target_uncertainty=0.1, threads=0, progress=None, out=None):
    """Fits several models to the same data and ranks them by evidence, as `sedwave compare`.

    models: a list of catalog names or Models. free: {model: "a,b"} (default: each model's typical
    set). values: {name: value [SI]} and priors: {name: "KIND:A,B"}, each for every model that has
    the parameter (the command's --set, --prior); a name none of the models has is refused.
    site: a site file for every model. temperatures, steps, seed, target_uncertainty: the evidence
    runs' ladder, step cap, seed and target standard error of ln Z. threads: jobs side by side
    (0: every usable core; 1 where a model is defined in Python; the ranking is the same for any
    count).
    out: a folder to write compare.json and the bands into once the ranking is done (all or none;
    an interrupted call leaves it as it was).
    Returns a Ranking."""
    models = list(models)
    labels = [m if isinstance(m, str) else m.name for m in models]
    if len(set(labels)) != len(labels):
        raise ValueError(f"models {labels}: a model named twice: its rows would be identical")
    instances = [Model(m) if isinstance(m, str) else m for m in models]
    for argument, given in (("values", values), ("priors", priors)):
        for name in (given or {}):
            if not any(name in m.parameter_names for m in instances):
                raise ValueError(f"{argument}['{name}']: none of the models has a parameter '{name}'")
    free = dict(free or {})
    for label in free:
        if label not in labels:
            raise ValueError(f"free['{label}']: '{label}' is not one of models")
    if any(_sedwave._is_python_model(m) for m in instances):
        threads = 1
    handle = _sedwave._compare(data, models, free, values, None if site is None else os.fspath(site), priors,
                               temperatures=temperatures, steps=steps, seed=seed,
                               target_uncertainty=target_uncertainty,
                               threads=threads if threads > 0 else _usable_cores(),
                               progress=_progress_function(progress))
    ranking = Ranking(handle, labels)
    if out is not None:
        ranking.write(out)
    ranking._warn()
    return ranking


def synthesize(model, values=None, lowest_hz=10.0, highest_hz=1.0e6, points=25, alpha_noise=0.05,
               speed_noise=0.05, seed=1, site=None):
    """Observations a model predicts for known values, with noise, as `sedwave synthesize`:
    ``points`` log-spaced frequencies from lowest_hz to highest_hz [Hz], one attenuation [Np/m] and
    one sound speed [m/s] at each; attenuation x exp(alpha_noise N(0,1)), speed x (1 + speed_noise
    N(0,1)), each with that relative sigma; seed of the noise. values: {name: value [SI]}; a
    parameter without a typical value (a grain contact's kappa) must be given."""
    data, notes = _sedwave._synthesize(model, values, None if site is None else os.fspath(site),
                                       lowest_hz, highest_hz, points, alpha_noise, speed_noise, seed)
    return data
