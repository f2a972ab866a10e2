// sedwave.Model: a catalog model evaluated on numpy arrays of frequencies [Hz], with exact
// derivatives, derived quantities and, for the dry grain-contact frames, the dimensionless wave.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>

#include "bindings.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::python {
namespace {

using sediment::SedimentModel;
using ModelPtr = std::shared_ptr<const SedimentModel>;

py::list derived_of(const SedimentModel& model) {
  py::list list;
  for (const sediment::DerivedQuantity& q : model.derived_quantities()) {
    py::dict d;
    d["name"] = q.name;
    d["unit"] = q.unit;
    d["meaning"] = q.meaning;
    if (q.plausible_lower != 0.0 || q.plausible_upper != 0.0) {
      d["plausible"] = py::make_tuple(q.plausible_lower, q.plausible_upper);
    } else {
      d["plausible"] = py::none();
    }
    list.append(d);
  }
  return list;
}

/// Frequencies as a flat array of doubles, with the shape to give the results.
std::pair<DoubleArray, std::vector<py::ssize_t>> frequencies_of(const py::handle& frequency_hz) {
  DoubleArray f = DoubleArray::ensure(frequency_hz);
  if (!f) throw py::value_error("frequency_hz: expected numbers [Hz]");
  std::vector<py::ssize_t> shape(f.shape(), f.shape() + f.ndim());
  return {f, shape};
}

/// The wave over an array of frequencies: alpha [Np/m], c [m/s], the model's own sigmas, and with
/// `derivatives` d alpha / d value_i and d c / d value_i (shape + (parameters,)). The loop runs
/// without the GIL.
py::dict evaluate(const ModelPtr& model, const py::handle& frequency_hz, const py::handle& values, bool derivatives) {
  const std::vector<double> v = values_of(*model, values, "values");
  auto [f, shape] = frequencies_of(frequency_hz);
  const auto n = static_cast<std::size_t>(f.size());
  const auto p = static_cast<py::ssize_t>(v.size());
  py::array_t<double> alpha(shape), speed(shape), sigma_alpha(shape), sigma_speed(shape);
  std::vector<py::ssize_t> jacobian_shape = shape;
  jacobian_shape.push_back(derivatives ? p : 0);
  py::array_t<double> d_alpha(jacobian_shape), d_speed(jacobian_shape);
  const double* fs = f.data();
  double *a = alpha.mutable_data(), *c = speed.mutable_data(), *sa = sigma_alpha.mutable_data(),
         *sc = sigma_speed.mutable_data(), *da = d_alpha.mutable_data(), *dc = d_speed.mutable_data();
  {
    const py::gil_scoped_release released;
    model->check_values(v);
    for (std::size_t k = 0; k < n; ++k) {
      if (!(fs[k] > 0.0) || !std::isfinite(fs[k])) {
        throw py::value_error("frequency_hz[" + std::to_string(k) + "] = " + std::to_string(fs[k]) +
                              ": a frequency must be positive and finite [Hz]");
      }
      const sediment::Wave w = model->evaluate(v, fs[k], derivatives);
      a[k] = w.attenuation;
      c[k] = w.speed;
      sa[k] = w.sigma_attenuation;
      sc[k] = w.sigma_speed;
      if (derivatives) {
        for (std::size_t i = 0; i < v.size(); ++i) {
          da[k * v.size() + i] = w.d_attenuation[i];
          dc[k * v.size() + i] = w.d_speed[i];
        }
      }
    }
  }
  py::dict out;
  out["frequency_hz"] = f;
  out["alpha"] = alpha;
  out["c"] = speed;
  out["sigma_alpha"] = sigma_alpha;
  out["sigma_c"] = sigma_speed;
  if (derivatives) {
    out["d_alpha"] = d_alpha;
    out["d_c"] = d_speed;
  }
  return out;
}

/// alpha [Np/m] and c [m/s] at one frequency [Hz] and parameter values in the model's order: the
/// call with the least in between.
py::tuple wave(const ModelPtr& model, double frequency_hz, const DoubleArray& values) {
  const std::span<const double> v(values.data(), static_cast<std::size_t>(values.size()));
  const sediment::Wave w = model->evaluate(v, frequency_hz, false);
  return py::make_tuple(w.attenuation, w.speed);
}

/// The dimensionless coordinates of a dry grain-contact frame (omega_hat, gamma_hat, alpha_hat,
/// c_hat); NaN for a model that is not one dimensionless engine scaled to SI.
py::dict dimensionless(const ModelPtr& model, const py::handle& frequency_hz, const py::handle& values) {
  const std::vector<double> v = values_of(*model, values, "values");
  auto [f, shape] = frequencies_of(frequency_hz);
  py::array_t<double> omega_hat(shape), gamma_hat(shape), alpha_hat(shape), c_hat(shape);
  const double* fs = f.data();
  double *o = omega_hat.mutable_data(), *g = gamma_hat.mutable_data(), *a = alpha_hat.mutable_data(),
         *c = c_hat.mutable_data();
  {
    const py::gil_scoped_release released;
    model->check_values(v);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (py::ssize_t k = 0; k < f.size(); ++k) {
      const std::optional<sediment::DimensionlessWave> w = model->dimensionless_wave(v, fs[k]);
      o[k] = w ? w->omega_hat : nan;
      g[k] = w ? w->gamma_hat : nan;
      a[k] = w ? w->alpha_hat : nan;
      c[k] = w ? w->c_hat : nan;
    }
  }
  py::dict out;
  out["omega_hat"] = omega_hat;
  out["gamma_hat"] = gamma_hat;
  out["alpha_hat"] = alpha_hat;
  out["c_hat"] = c_hat;
  return out;
}

/// The derived quantities at `values`: {name: value}, and with `derivatives` {name: gradient}.
py::dict derived(const ModelPtr& model, const py::handle& values, bool derivatives) {
  const std::vector<double> v = values_of(*model, values, "values");
  model->check_values(v);
  const std::vector<sediment::DerivedValue> d = model->derived_values(v, derivatives);
  py::dict out;
  const auto& quantities = model->derived_quantities();
  for (std::size_t i = 0; i < d.size() && i < quantities.size(); ++i) {
    if (derivatives) {
      out[py::str(quantities[i].name)] = py::make_tuple(d[i].value, py::array_t<double>(
                                                                       static_cast<py::ssize_t>(d[i].gradient.size()),
                                                                       d[i].gradient.data()));
    } else {
      out[py::str(quantities[i].name)] = d[i].value;
    }
  }
  return out;
}

}  // namespace

std::shared_ptr<const SedimentModel> model_of(const py::handle& model) {
  if (py::isinstance<py::str>(model)) return sediment::make_sediment_model(model.cast<std::string>());
  try {
    return model.cast<ModelHolder>();
  } catch (const py::cast_error&) {
    throw py::type_error("model: expected a model name (str; sedwave.model_names()) or a sedwave.Model, got " +
                         py::repr(model).cast<std::string>());
  }
}

std::vector<double> values_of(const SedimentModel& model, const py::handle& values, const std::string& argument) {
  std::vector<double> v = model.default_values();
  if (values.is_none()) return v;
  if (py::isinstance<py::dict>(values)) {
    for (const auto& [key, value] : values.cast<py::dict>()) {
      const std::string name = py::str(key);
      int i = 0;
      try {
        i = model.index_of(name);
      } catch (const std::invalid_argument& e) {
        throw py::value_error(argument + "['" + name + "']: " + e.what());
      }
      try {
        v[static_cast<std::size_t>(i)] = value.cast<double>();
      } catch (const py::cast_error&) {
        throw py::value_error(argument + "['" + name + "']: not a number");
      }
    }
    return v;
  }
  const DoubleArray array = DoubleArray::ensure(values);
  if (!array || array.ndim() != 1 || static_cast<std::size_t>(array.size()) != v.size()) {
    throw py::value_error(argument + ": expected a dict {name: value} or " + std::to_string(v.size()) +
                          " values in the order of " + model.name() + "'s parameters");
  }
  return {array.data(), array.data() + array.size()};
}

py::list parameters_of(const SedimentModel& model) {
  py::list list;
  for (const sediment::Parameter& p : model.parameters()) {
    py::dict d;
    d["name"] = p.name;
    d["unit"] = p.unit;
    d["default"] = p.default_value;
    d["range"] = py::make_tuple(p.lower, p.upper);
    d["log_scale"] = p.log_scale;
    d["meaning"] = p.meaning;
    d["typical"] = p.typical;
    list.append(d);
  }
  return list;
}

void bind_models(py::module_& m) {
  py::class_<SedimentModel, ModelHolder>(m, "Model", R"doc(
A sediment model: named parameters in SI and the compressional wave it predicts, attenuation
alpha [Np/m] and phase speed c [m/s], with exact derivatives.

Model(spec, damping="gamma", permeability_given=False): spec is a catalog name
(sedwave.model_names(): "biot-stoll", "edfm", "lattice", "table:FILE.h5", a model registered
with sedwave.register_model ...).)doc")
      .def(py::init([](const std::string& spec, const std::string& damping, bool permeability_given) {
             sediment::ModelChoices choices;
             if (damping == "en" || damping == "e_n") {
               choices.damping = sediment::DampingForm::Restitution;
             } else if (damping != "gamma") {
               throw py::value_error("damping '" + damping + "': expected 'gamma' or 'en'");
             }
             choices.permeability_given = permeability_given;
             return holder_of(sediment::make_sediment_model(spec, choices));
           }),
           py::arg("spec"), py::arg("damping") = "gamma", py::arg("permeability_given") = false)
      .def_property_readonly("name", &SedimentModel::name)
      .def_property_readonly("summary", &SedimentModel::summary)
      .def_property_readonly("parameters", &parameters_of,
                             "list of dicts: name, unit (SI), default, range (lower, upper), log_scale, meaning, typical")
      .def_property_readonly("parameter_names",
                             [](const SedimentModel& s) {
                               std::vector<std::string> names;
                               for (const auto& p : s.parameters()) names.push_back(p.name);
                               return names;
                             })
      .def_property_readonly("defaults",
                             [](const SedimentModel& s) {
                               const std::vector<double> v = s.default_values();
                               return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
                             }, "the documented defaults [SI], in parameter order")
      .def_property_readonly("derived_quantities", &derived_of,
                             "list of dicts: name, unit, meaning, plausible (lower, upper) or None")
      .def_property_readonly("typical_free", &SedimentModel::typical_free_parameters,
                             "the parameters a fit frees when not told, comma-separated")
      .def_property_readonly("uncertainty_caveat", &SedimentModel::uncertainty_caveat)
      .def("values", [](const ModelHolder& s, const py::object& values) {
             const std::vector<double> v = values_of(*s, values, "values");
             return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
           }, py::arg("values") = py::none(),
           "parameter values [SI] in parameter order: the defaults, with those a dict names replaced")
      .def("evaluate", [](const ModelHolder& s, const py::handle& f, const py::handle& v, bool d) { return evaluate(s, f, v, d); }, py::arg("frequency_hz"), py::arg("values") = py::none(),
           py::arg("derivatives") = false, R"doc(
The wave at each frequency [Hz] (any array shape) for parameter values [SI] (None: the defaults; a
dict {name: value}; or a sequence in parameter order). Returns a dict of numpy arrays:
alpha [Np/m], c [m/s], sigma_alpha, sigma_c (the model's own 1-sigma; 0 for closed forms) and,
with derivatives=True, the exact Jacobians d_alpha, d_c of shape frequency_hz.shape + (parameters,)
[SI per SI]. Raises ValueError for values outside a parameter's range or a frequency where the
model has no answer (a table's range).)doc")
      .def("wave", [](const ModelHolder& s, double f, const DoubleArray& v) { return wave(s, f, v); }, py::arg("frequency_hz"), py::arg("values"),
           "(alpha [Np/m], c [m/s]) at one frequency [Hz]; values: a float64 array in parameter order")
      .def("dimensionless", [](const ModelHolder& s, const py::handle& f, const py::handle& v) { return dimensionless(s, f, v); }, py::arg("frequency_hz"), py::arg("values") = py::none(),
           "the dry grain-contact frame's omega_hat, gamma_hat, alpha_hat, c_hat (NaN for other models)")
      .def("derived", [](const ModelHolder& s, const py::handle& v, bool d) { return derived(s, v, d); }, py::arg("values") = py::none(), py::arg("derivatives") = false,
           "the derived quantities {name: value [unit]}; with derivatives, {name: (value, gradient)}")
      .def("__repr__", [](const SedimentModel& s) { return "sedwave.Model('" + s.name() + "')"; });

  // The C++ loop the module's evaluate() wraps, timed in C++ (bench/python_overhead.py compares).
  m.def("_cpp_loop_seconds", [](const ModelHolder& model, const DoubleArray& frequency_hz, const DoubleArray& values) {
    const std::span<const double> v(values.data(), static_cast<std::size_t>(values.size()));
    std::vector<double> alpha(static_cast<std::size_t>(frequency_hz.size())), speed(alpha.size());
    const py::gil_scoped_release released;
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < alpha.size(); ++k) {
      const sediment::Wave w = model->evaluate(v, frequency_hz.data()[k], false);
      alpha[k] = w.attenuation;
      speed[k] = w.speed;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    volatile double sink = alpha.empty() ? 0.0 : alpha.back() + speed.back();
    (void)sink;
    return seconds;
  });
  m.def("model_names", &sediment::sediment_model_names, "one line per accepted model specification");
  m.def("model_examples", [] {
          std::vector<ModelHolder> out;
          for (const ModelPtr& model : sediment::model_examples()) out.push_back(holder_of(model));
          return out;
        },
        "a representative Model of every family (a table stands for all tables), as `sedwave models` lists");
}

}  // namespace sedwave::python
