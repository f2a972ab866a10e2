// A model defined in Python: its wave (and, if given, its derivatives) are Python functions, called
// under the GIL, one evaluation at a time. Registered with the catalog it is fitted, sampled and
// ranked like a built-in model; without derivatives the fit's Jacobians are central finite
// differences.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include "bindings.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::python {
namespace {

/// Relative step of the central differences: about the cube root of the double's precision, the
/// step that balances truncation (step^2) against rounding (eps / step).
constexpr double kRelativeStep = 6e-6;

/// Python objects kept for as long as the catalog keeps the model (to the process's end): released
/// with the GIL, and not at all once the interpreter is gone.
struct Callbacks {
  py::object wave, derivatives;
  ~Callbacks() {
    if (!Py_IsInitialized()) {
      wave.release();
      derivatives.release();
      return;
    }
    const py::gil_scoped_acquire gil;
    wave = py::object();
    derivatives = py::object();
  }
};

class PythonModel final : public sediment::SedimentModel {
 public:
  PythonModel(std::string name, std::string summary, std::vector<sediment::Parameter> parameters,
              std::string typical_free, std::shared_ptr<Callbacks> callbacks)
      : name_(std::move(name)),
        summary_(std::move(summary)),
        parameters_(std::move(parameters)),
        typical_free_(std::move(typical_free)),
        callbacks_(std::move(callbacks)) {}

  std::string name() const override { return name_; }
  std::string summary() const override { return summary_; }
  const std::vector<sediment::Parameter>& parameters() const override { return parameters_; }
  std::string typical_free_parameters() const override {
    return typical_free_.empty() ? sediment::SedimentModel::typical_free_parameters() : typical_free_;
  }
  [[nodiscard]] bool supplies_derivatives() const { return !callbacks_->derivatives.is_none(); }

  sediment::Wave evaluate(std::span<const double> values, double frequency_hz, bool derivatives) const override {
    const py::gil_scoped_acquire gil;
    try {
      sediment::Wave w;
      std::tie(w.attenuation, w.speed) = call(values, frequency_hz);
      if (derivatives) supply_derivatives(values, frequency_hz, w);
      return w;
    } catch (py::error_already_set& e) {
      // Inside a study the error stops it and is raised in Python; the library must not take it for
      // a model without an answer there.
      if (StudyGuard* guard = StudyGuard::active()) {
        guard->fail(std::move(e));
        throw StopStudy{};
      }
      throw;
    }
  }

 private:
  /// The values as a tuple of floats: a Python function unpacks and computes with those several
  /// times faster than with a numpy array's elements.
  static py::tuple tuple_of(std::span<const double> values) {
    py::tuple t(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) t[i] = py::float_(values[i]);
    return t;
  }

  std::pair<double, double> call(std::span<const double> values, double frequency_hz) const {
    const py::object result = callbacks_->wave(tuple_of(values), frequency_hz);
    const auto pair = result.cast<std::pair<double, double>>();
    if (!std::isfinite(pair.first) || !std::isfinite(pair.second)) {
      throw std::domain_error(name_ + ": no finite wave at " + std::to_string(frequency_hz) + " Hz");
    }
    return pair;
  }

  void supply_derivatives(std::span<const double> values, double frequency_hz, sediment::Wave& w) const {
    const std::size_t n = values.size();
    if (supplies_derivatives()) {
      const auto [da, dc] = callbacks_->derivatives(tuple_of(values), frequency_hz).cast<std::pair<std::vector<double>, std::vector<double>>>();
      if (da.size() != n || dc.size() != n) {
        throw std::invalid_argument(name_ + ": derivatives must return two sequences of " + std::to_string(n) + " numbers");
      }
      w.d_attenuation = da;
      w.d_speed = dc;
      return;
    }
    w.d_attenuation.assign(n, 0.0);
    w.d_speed.assign(n, 0.0);
    std::vector<double> x(values.begin(), values.end());
    for (std::size_t i = 0; i < n; ++i) {
      const double h = kRelativeStep * std::abs(values[i]);
      x[i] = values[i] + h;
      const auto [a_plus, c_plus] = call(x, frequency_hz);
      x[i] = values[i] - h;
      const auto [a_minus, c_minus] = call(x, frequency_hz);
      x[i] = values[i];
      w.d_attenuation[i] = (a_plus - a_minus) / (2.0 * h);
      w.d_speed[i] = (c_plus - c_minus) / (2.0 * h);
    }
  }

  std::string name_, summary_;
  std::vector<sediment::Parameter> parameters_;
  std::string typical_free_;
  std::shared_ptr<Callbacks> callbacks_;
};

sediment::Parameter parameter_of(const py::dict& d) {
  const auto get = [&](const char* key) -> py::object {
    if (!d.contains(key)) throw py::value_error(std::string("parameters: each needs '") + key + "'");
    return d[key];
  };
  sediment::Parameter p;
  p.name = py::str(get("name"));
  p.unit = d.contains("unit") ? py::str(d["unit"]).cast<std::string>() : "1";
  p.default_value = get("default").cast<double>();
  const auto range = get("range").cast<std::pair<double, double>>();
  p.lower = range.first;
  p.upper = range.second;
  p.log_scale = d.contains("log_scale") ? d["log_scale"].cast<bool>() : true;
  p.meaning = d.contains("meaning") ? py::str(d["meaning"]).cast<std::string>() : "";
  p.typical = d.contains("typical") ? d["typical"].cast<bool>() : true;
  if (!(p.lower > 0.0) || !(p.upper > p.lower) || !(p.default_value >= p.lower && p.default_value <= p.upper)) {
    throw py::value_error("parameters['" + p.name + "']: need 0 < lower < upper and the default inside the range");
  }
  return p;
}

}  // namespace

void bind_python_model(py::module_& m) {
  m.def("_register_model",
        [](const std::string& name, const py::list& parameters, const py::function& wave, const py::object& derivatives,
           const std::string& summary, const std::string& typical_free) {
          std::vector<sediment::Parameter> ps;
          for (const py::handle& p : parameters) ps.push_back(parameter_of(p.cast<py::dict>()));
          if (ps.empty()) throw py::value_error("parameters: a model needs at least one");
          auto callbacks = std::make_shared<Callbacks>();
          callbacks->wave = wave;
          callbacks->derivatives = derivatives;
          const auto model = std::make_shared<const PythonModel>(name, summary, ps, typical_free, callbacks);
          sediment::register_model(name, [model] { return model; });
          return holder_of(model);
        },
        py::arg("name"), py::arg("parameters"), py::arg("wave"), py::arg("derivatives"), py::arg("summary"),
        py::arg("typical_free"));
  m.def("_is_python_model", [](const ModelHolder& model) {
    return dynamic_cast<const PythonModel*>(model.get()) != nullptr;
  });
  m.def("derivatives_of", [](const ModelHolder& model) -> std::string {
    if (const auto* own = dynamic_cast<const PythonModel*>(model.get())) {
      return own->supplies_derivatives() ? "supplied by its Python derivatives function"
                                         : "central finite differences (relative step 6e-6)";
    }
    return "exact (automatic differentiation)";
  }, py::arg("model"), "how the model's derivatives (the fit's Jacobians) are computed");
}

}  // namespace sedwave::python
