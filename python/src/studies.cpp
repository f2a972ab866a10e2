// Studies: fit, posterior, compare, synthesize — each set up by inversion::make_candidate (the
// command line's one conversion of settings), run without the GIL under a StudyGuard, and reported
// by the library's own report functions, so to_json() is the command line's fit.json / compare.json.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "sedwave/forward/dispersion.hpp"
#include "sedwave/inversion/comparison.hpp"
#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/report.hpp"
#include "sedwave/inversion/setup.hpp"
#include "sedwave/inversion/study.hpp"
#include "sedwave/inversion/synthetic.hpp"
#include "sedwave/io/atomic_file.hpp"

namespace sedwave::python {
namespace {

using inversion::ObservationSet;

py::array_t<double> array_of(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::array_t<double> array_of(const Eigen::MatrixXd& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto o = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) o(i, j) = m(i, j);
  }
  return out;
}

std::string comma_list(const py::handle& given, const std::string& argument) {
  if (given.is_none()) return "";
  if (py::isinstance<py::str>(given)) return given.cast<std::string>();
  std::string list;
  try {
    for (const std::string& name : given.cast<std::vector<std::string>>()) list += (list.empty() ? "" : ",") + name;
  } catch (const py::cast_error&) {
    throw py::type_error(argument + ": expected a str 'a,b' or a sequence of parameter names");
  }
  return list;
}

double finite_number(const py::handle& value, const std::string& origin) {
  double x = 0.0;
  try {
    x = value.cast<double>();
  } catch (const py::cast_error&) {
    throw py::value_error(origin + ": not a number");
  }
  if (!std::isfinite(x)) throw py::value_error(origin + ": not a finite number");
  return x;
}

/// The settings of one model as the library's ModelSetup, each value and bound keeping its
/// argument (values['kappa'], bounds['d']) as its origin.
inversion::ModelSetup setup_of(const py::handle& model, const py::handle& free, const py::handle& values,
                               const py::handle& bounds, const py::handle& site, const py::handle& priors,
                               bool shared) {
  inversion::ModelSetup setup;
  if (py::isinstance<py::str>(model)) {
    setup.model = model.cast<std::string>();
  } else {
    setup.instance = model_of(model);
  }
  setup.free = comma_list(free, "free");
  if (!values.is_none()) {
    for (const auto& [key, value] : values.cast<py::dict>()) {
      const std::string name = py::str(key), origin = "values['" + name + "']";
      setup.values.push_back({name, finite_number(value, origin), origin, ""});
    }
  }
  if (!bounds.is_none()) {
    for (const auto& [key, value] : bounds.cast<py::dict>()) {
      const std::string name = py::str(key), origin = "bounds['" + name + "']";
      const auto pair = value.cast<py::sequence>();
      if (pair.size() != 2) throw py::value_error(origin + ": expected (lower, upper) [SI]");
      setup.bounds.push_back({name, finite_number(pair[0], origin), finite_number(pair[1], origin), origin, ""});
    }
  }
  if (!site.is_none()) setup.site_file = site.cast<std::filesystem::path>();
  if (!priors.is_none()) {
    setup.priors_source = "priors argument";
    for (const auto& [key, value] : priors.cast<py::dict>()) {
      setup.priors.push_back(py::str(key).cast<std::string>() + "=" + py::str(value).cast<std::string>());
    }
  }
  setup.shared = shared;
  return setup;
}

/// The library names the free list and the priors by the command's options (--fit, --prior); a
/// Python caller gave them as the arguments free= and priors=.
std::string in_python_words(const std::string& message) {
  for (const auto& [option, argument] : {std::pair{"--fit ", "free="}, std::pair{"--prior ", "priors: "}}) {
    if (message.starts_with(option)) return argument + message.substr(std::string(option).size());
  }
  return message;
}

/// inversion::make_candidate, its messages in the Python arguments' words.
inversion::Candidate candidate_of(const inversion::ModelSetup& setup,
                                  inversion::SetupUse use = inversion::SetupUse::Fit) {
  try {
    return inversion::make_candidate(setup, use);
  } catch (const inversion::SetupError& e) {
    throw inversion::SetupError(in_python_words(e.what()));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(in_python_words(e.what()));
  }
}

inversion::FitOptions fit_options_of(const std::string& method, bool profile, double default_sigma,
                                     const std::string& global_algorithm, int max_evaluations,
                                     double determined_log_sigma) {
  inversion::FitOptions options;
  options.method = inversion::parse_fit_method(method);
  options.profile_likelihood = profile;
  options.default_relative_sigma = default_sigma;
  options.global_algorithm = global_algorithm;
  options.max_global_evaluations = max_evaluations;
  options.determined_log_sigma = determined_log_sigma;
  return options;
}

/// A fit (and its posterior, if sampled) with what it was made from.
struct FitHandle {
  inversion::FitResult result;
  ObservationSet data;
  inversion::Candidate candidate;  ///< its model the catalog's (not the call's guarded one)
  std::optional<inversion::PosteriorStudy> study;

  /// fit.json as `sedwave invert` writes it.
  [[nodiscard]] nlohmann::json report() const {
    nlohmann::json report = inversion::fit_report(result, data);
    if (study) report["posterior"] = inversion::posterior_report(study->posterior);
    if (!candidate.notes.empty()) report["site_inputs"] = candidate.notes;
    if (const forward::DispersionModel* engine = candidate.model->dimensionless_engine()) {
      for (const forward::ModelDiagnostic& d : engine->diagnostics()) report[d.key] = d.count;
    }
    return report;
  }
};

py::dict band_of(const inversion::PredictiveBand& band) {
  py::dict out;
  out["frequency_hz"] = array_of(band.frequency_hz);
  const auto quantiles = [](const std::vector<inversion::BandQuantiles>& q) {
    py::array_t<double> a({static_cast<py::ssize_t>(q.size()), static_cast<py::ssize_t>(5)});
    auto o = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < q.size(); ++i) {
      for (std::size_t j = 0; j < 5; ++j) o(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = q[i][j];
    }
    return a;
  };
  out["quantiles"] = py::make_tuple(0.025, 0.16, 0.5, 0.84, 0.975);
  out["alpha"] = quantiles(band.attenuation);
  out["c"] = quantiles(band.speed);
  out["residual"] = array_of(band.residual);
  out["draws"] = band.draws;
  return out;
}

py::dict residuals_of(const inversion::FitResult& r) {
  std::vector<double> f, observed, sigma, model, normalized;
  std::vector<std::string> quantity;
  for (const inversion::PointResidual& p : r.residuals) {
    f.push_back(p.observation.frequency_hz);
    observed.push_back(p.observation.value);
    sigma.push_back(p.sigma);
    model.push_back(p.model);
    normalized.push_back(p.normalized);
    quantity.emplace_back(inversion::quantity_name(p.observation.quantity));
  }
  py::dict out;
  out["quantity"] = py::array(py::cast(quantity));
  out["frequency_hz"] = array_of(f);
  out["observed"] = array_of(observed);
  out["sigma"] = array_of(sigma);
  out["model"] = array_of(model);
  out["normalized"] = array_of(normalized);
  return out;
}

py::dict curves_of(const FitHandle& h, const py::object& frequency_hz) {
  std::vector<double> f;
  if (frequency_hz.is_none()) {
    f = inversion::curve_frequencies(h.data);
  } else {
    const DoubleArray a = DoubleArray::ensure(frequency_hz);
    if (!a) throw py::value_error("frequency_hz: expected numbers [Hz]");
    f.assign(a.data(), a.data() + a.size());
  }
  std::vector<inversion::CurvePoint> points;
  {
    const py::gil_scoped_release released;
    points = inversion::model_curves(h.result, *h.candidate.model, f);
  }
  std::vector<double> fs, alpha, alpha_sigma, c, c_sigma, alpha_hat, c_hat;
  for (const inversion::CurvePoint& p : points) {
    fs.push_back(p.frequency_hz);
    alpha.push_back(p.alpha);
    alpha_sigma.push_back(p.alpha_sigma);
    c.push_back(p.speed);
    c_sigma.push_back(p.speed_sigma);
    alpha_hat.push_back(p.alpha_hat);
    c_hat.push_back(p.c_hat);
  }
  py::dict out;
  out["frequency_hz"] = array_of(fs);
  out["alpha"] = array_of(alpha);
  out["sigma_alpha"] = array_of(alpha_sigma);
  out["c"] = array_of(c);
  out["sigma_c"] = array_of(c_sigma);
  out["alpha_hat"] = array_of(alpha_hat);
  out["c_hat"] = array_of(c_hat);
  return out;
}

FitHandle run_fit(const ObservationSet& data, const py::handle& model, const py::handle& free, const py::handle& values,
                  const py::handle& bounds, const py::handle& site, const py::handle& priors,
                  inversion::FitOptions options, const py::object& progress,
                  std::optional<inversion::PosteriorOptions> posterior) {
  if (data.observations.empty()) throw py::value_error("data: no observations");
  // Made before the handle: GCC 12 destroys the wrong members when an aggregate's initializer throws.
  inversion::Candidate candidate = candidate_of(setup_of(model, free, values, bounds, site, priors, false));
  FitHandle h{{}, data, std::move(candidate), {}};
  StudyGuard guard;
  options.progress = progress_function(progress, guard);
  if (posterior) posterior->progress = options.progress;
  const auto model_in_call = guarded(h.candidate.model, guard);
  guard.run([&] {
    h.result = inversion::fit(h.data, *model_in_call, h.candidate.parameters, options);
    if (posterior) {
      h.study = inversion::posterior_study(h.data, *model_in_call, h.result, h.candidate.priors, options, *posterior);
    }
  });
  return h;
}

struct RankingHandle {
  inversion::Ranking ranking;
  ObservationSet data;
};

}  // namespace

void bind_studies(py::module_& m) {
  py::class_<FitHandle>(m, "_Fit")
      .def("report_json", [](const FitHandle& h) { return h.report().dump(2) + "\n"; })
      .def_property_readonly("model", [](const FitHandle& h) { return holder_of(h.candidate.model); })
      .def_property_readonly("label", [](const FitHandle& h) { return h.candidate.label; })
      .def_property_readonly("notes", [](const FitHandle& h) { return h.candidate.notes; })
      .def_property_readonly("free_names", [](const FitHandle& h) { return h.result.free_names; })
      .def_property_readonly("values", [](const FitHandle& h) { return array_of(h.result.fitted.values()); })
      .def_property_readonly("covariance", [](const FitHandle& h) { return array_of(h.result.covariance); })
      .def_property_readonly("correlation", [](const FitHandle& h) { return array_of(h.result.correlation); })
      .def_property_readonly("singular_values", [](const FitHandle& h) {
        return array_of(std::vector<double>(h.result.singular_values.data(),
                                            h.result.singular_values.data() + h.result.singular_values.size()));
      })
      .def_property_readonly("residuals", [](const FitHandle& h) { return residuals_of(h.result); })
      .def("curves", &curves_of, py::arg("frequency_hz") = py::none())
      .def_property_readonly("samples", [](const FitHandle& h) -> py::object {
        if (!h.study) return py::none();
        return array_of(h.study->posterior.samples);
      })
      .def_property_readonly("sample_names", [](const FitHandle& h) {
        return h.study ? h.study->posterior.sample_names : std::vector<std::string>{};
      })
      .def_property_readonly("band", [](const FitHandle& h) -> py::object {
        if (!h.study) return py::none();
        return band_of(h.study->band);
      })
      .def("write", [](const FitHandle& h, const std::filesystem::path& out) {
        std::filesystem::create_directories(out);
        const io::OutputLock lock(out, "out");
        io::DeferredCommits outputs;
        io::write_text_atomically(out / "fit.json", [&](std::ostream& s) { s << h.report().dump(2) << "\n"; });
        inversion::write_fit_files(out, h.result, *h.candidate.model, h.data);
        if (h.study) inversion::write_posterior_study(out, *h.study, h.result, h.data);
        outputs.commit_all();
      }, py::arg("out"));

  m.def("_fit",
        [](const ObservationSet& data, const py::object& model, const py::object& free, const py::object& values,
           const py::object& bounds, const py::object& site, const py::object& priors, const std::string& method,
           bool profile, double default_sigma, const std::string& global_algorithm, int max_evaluations,
           double determined_log_sigma, const py::object& progress) {
          return run_fit(data, model, free, values, bounds, site, priors,
                         fit_options_of(method, profile, default_sigma, global_algorithm, max_evaluations,
                                        determined_log_sigma),
                         progress, std::nullopt);
        },
        py::arg("data"), py::arg("model"), py::arg("free"), py::arg("values"), py::arg("bounds"), py::arg("site"),
        py::arg("priors"), py::arg("method"), py::arg("profile"), py::arg("default_sigma"),
        py::arg("global_algorithm"), py::arg("max_evaluations"), py::arg("determined_log_sigma"),
        py::arg("progress"));

  m.def("_posterior",
        [](const ObservationSet& data, const py::object& model, const py::object& free, const py::object& values,
           const py::object& bounds, const py::object& site, const py::object& priors, bool profile,
           double default_sigma, int max_evaluations, int walkers, int steps, int temperatures, int threads,
           unsigned seed, const py::object& progress) {
          inversion::PosteriorOptions posterior;
          posterior.walkers = walkers;
          posterior.steps = steps;
          posterior.temperatures = temperatures;
          posterior.threads = threads;
          posterior.seed = seed;
          return run_fit(data, model, free, values, bounds, site, priors,
                         fit_options_of("global", profile, default_sigma, "direct-l", max_evaluations, 0.5), progress,
                         posterior);
        },
        py::arg("data"), py::arg("model"), py::arg("free"), py::arg("values"), py::arg("bounds"), py::arg("site"),
        py::arg("priors"), py::arg("profile"), py::arg("default_sigma"), py::arg("max_evaluations"),
        py::arg("walkers"), py::arg("steps"), py::arg("temperatures"), py::arg("threads"), py::arg("seed"),
        py::arg("progress"));

  py::class_<RankingHandle>(m, "_Ranking")
      .def("report_json", [](const RankingHandle& h) { return inversion::ranking_report(h.ranking).dump(2) + "\n"; })
      .def_property_readonly("order", [](const RankingHandle& h) { return h.ranking.order; })
      .def_property_readonly("order_widened", [](const RankingHandle& h) { return h.ranking.order_widened; })
      .def_property_readonly("converged", [](const RankingHandle& h) { return h.ranking.converged(); })
      .def("fit_report_json", [](const RankingHandle& h, std::size_t i) {
        return inversion::fit_report(h.ranking.models.at(i).fit, h.data).dump(2) + "\n";
      })
      .def("samples", [](const RankingHandle& h, std::size_t i) {
        return array_of(h.ranking.models.at(i).evidence.samples);
      })
      .def("sample_names", [](const RankingHandle& h, std::size_t i) {
        return inversion::sample_columns(h.ranking.models.at(i)).first;
      })
      .def("band", [](const RankingHandle& h, std::size_t i) { return band_of(h.ranking.models.at(i).band); })
      .def("write", [](const RankingHandle& h, const std::filesystem::path& out) {
        std::filesystem::create_directories(out);
        const io::OutputLock lock(out, "out");
        io::DeferredCommits outputs;  // all of them or none
        io::write_text_atomically(out / "compare.json",
                                  [&](std::ostream& s) { s << inversion::ranking_report(h.ranking).dump(2) << "\n"; });
        inversion::write_ranking_files(out, h.ranking, h.data);
        outputs.commit_all();
      }, py::arg("out"));

  m.def("_compare",
        [](const ObservationSet& data, const std::vector<py::object>& models, const py::dict& free,
           const py::object& values, const py::object& site, const py::object& priors, int temperatures, int steps,
           unsigned seed, double target_uncertainty, int threads, const py::object& progress) {
          if (data.observations.empty()) throw py::value_error("data: no observations");
          if (models.empty()) throw py::value_error("models: name at least one model (sedwave.model_names())");
          std::vector<inversion::Candidate> candidates;
          for (const py::object& model : models) {
            const std::string label = py::isinstance<py::str>(model) ? model.cast<std::string>()
                                                                      : model_of(model)->name();
            const py::object own_free = free.contains(label) ? py::object(free[py::str(label)]) : py::none();
            candidates.push_back(
                candidate_of(setup_of(model, own_free, values, py::none(), site, priors, true)));
          }
          StudyGuard guard;
          for (inversion::Candidate& c : candidates) c.model = guarded(c.model, guard);
          inversion::ComparisonOptions options;
          options.evidence.temperatures = temperatures;
          options.evidence.steps = steps;
          options.evidence.seed = seed;
          options.evidence.target_uncertainty = target_uncertainty;
          options.threads = threads;
          options.progress = progress_function(progress, guard);
          RankingHandle h{{}, data};
          guard.run([&] { h.ranking = inversion::compare_models(h.data, candidates, options); });
          return h;
        },
        py::arg("data"), py::arg("models"), py::arg("free"), py::arg("values"), py::arg("site"), py::arg("priors"),
        py::arg("temperatures"), py::arg("steps"), py::arg("seed"), py::arg("target_uncertainty"),
        py::arg("threads"), py::arg("progress"));

  m.def("_synthesize",
        [](const py::object& model, const py::object& values, const py::object& site, double lowest_hz,
           double highest_hz, int points, double alpha_noise, double speed_noise, unsigned seed) {
          const inversion::Candidate candidate = candidate_of(
              setup_of(model, py::none(), values, py::none(), site, py::none(), false), inversion::SetupUse::Truth);
          const std::vector<std::string> missing = inversion::values_not_given(candidate);
          if (!missing.empty()) {
            std::string names;
            for (const std::string& n : missing) names += (names.empty() ? "" : ", ") + n;
            throw py::value_error("values: give " + names + " (no typical value; sedwave.Model('" +
                                  candidate.model->name() + "').parameters)");
          }
          if (!(highest_hz > lowest_hz)) throw py::value_error("lowest_hz must be below highest_hz");
          const inversion::SyntheticDesign design{lowest_hz, highest_hz, points, alpha_noise, speed_noise, seed};
          ObservationSet set;
          {
            const py::gil_scoped_release released;
            set = inversion::synthetic_observations(*candidate.model, candidate.parameters, design);
          }
          return py::make_tuple(set, candidate.notes);
        },
        py::arg("model"), py::arg("values"), py::arg("site"), py::arg("lowest_hz"), py::arg("highest_hz"),
        py::arg("points"), py::arg("alpha_noise"), py::arg("speed_noise"), py::arg("seed"));
}

}  // namespace sedwave::python
