#pragma once
// Shared pieces of the Python module's bindings (one file per part of the API: models, data,
// studies, models defined in Python), and the guard that lets a long call run without the GIL and
// stop on Ctrl-C or on a Python callback's error.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::python {

namespace py = pybind11;

void bind_models(py::module_& m);
void bind_data(py::module_& m);
void bind_studies(py::module_& m);
void bind_python_model(py::module_& m);
void bind_tables(py::module_& m);
void bind_run_files(py::module_& m);

/// A numpy array of doubles, converted (and copied) only where it is not one already.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Thrown through the library to stop a long call: not a std::exception, so that no handler meant
/// for a model's or a solver's failure (NLopt's forced stop, a profile's give-up) swallows it.
struct StopStudy {};

/// One long call (a fit, a posterior, a comparison) in progress without the GIL. Ctrl-C (SIGINT,
/// while the call runs in the main thread) or an error raised by a Python callback (a model, the
/// progress function) stops it: every model evaluation checks `stopping()` and throws StopStudy.
class StudyGuard {
 public:
  StudyGuard();
  ~StudyGuard();
  StudyGuard(const StudyGuard&) = delete;
  StudyGuard& operator=(const StudyGuard&) = delete;

  /// Runs `work` without the GIL; afterwards re-raises what stopped it (KeyboardInterrupt, or the
  /// callback's error), else passes on its C++ exception.
  void run(const std::function<void()>& work);
  [[nodiscard]] bool stopping() const;
  /// Records a Python callback's error (the first one; called with the GIL held) and stops the call.
  void fail(py::error_already_set error);
  /// The guard of the call in progress, or null (evaluations outside a study raise at once).
  static StudyGuard* active();

 private:
  std::atomic<bool> failed_{false};
  std::mutex error_mutex_;
  std::unique_ptr<py::error_already_set> error_;
  bool handles_sigint_ = false;
  StudyGuard* previous_ = nullptr;
};

/// `model` with every evaluation checking `guard` first: the same numbers, and a way out.
std::shared_ptr<const sediment::SedimentModel> guarded(std::shared_ptr<const sediment::SedimentModel> model,
                                                       StudyGuard& guard);

/// A Python progress function as the library's progress callback (called from any thread; the GIL
/// is taken for the call). Null for None.
std::function<void(const std::string&)> progress_function(const py::object& progress, StudyGuard& guard);

/// The model a Python argument names: a catalog specification (str) or a sedwave.Model.
std::shared_ptr<const sediment::SedimentModel> model_of(const py::handle& model);

/// A model's parameter values from None (its defaults), a dict {name: value} (the rest at their
/// defaults) or a sequence in parameter order [SI]. Throws ValueError naming the argument.
std::vector<double> values_of(const sediment::SedimentModel& model, const py::handle& values,
                              const std::string& argument);

/// The Python object of a model (pybind11 holds models as shared pointers to non-const; the
/// library never changes a model after construction).
using ModelHolder = std::shared_ptr<sediment::SedimentModel>;
inline ModelHolder holder_of(const std::shared_ptr<const sediment::SedimentModel>& model) {
  return std::const_pointer_cast<sediment::SedimentModel>(model);
}

/// A model's parameters as a list of dicts (name, unit, default, lower, upper, log_scale, meaning, typical).
py::list parameters_of(const sediment::SedimentModel& model);

}  // namespace sedwave::python
