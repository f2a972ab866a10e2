// The guard of a long call: the GIL released while the library works, Ctrl-C and Python callbacks'
// errors turned into a clean stop (nothing written, the exception raised in Python).
#include <csignal>
#include <optional>
#include <utility>

#include "bindings.hpp"

namespace sedwave::python {
namespace {

/// Set by the SIGINT handler of a guarded call; read by every evaluation.
std::atomic<bool> interrupted{false};
/// The guard of the innermost call in progress (changed with the GIL held).
StudyGuard* active_guard = nullptr;
struct sigaction python_sigint {};

extern "C" void on_sigint(int /*signal*/) { interrupted.store(true); }

bool in_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

/// A model whose evaluations first check the guard: every other answer is the wrapped model's.
class GuardedModel final : public sediment::SedimentModel {
 public:
  GuardedModel(std::shared_ptr<const sediment::SedimentModel> model, const StudyGuard& guard)
      : model_(std::move(model)), guard_(&guard) {}
  std::string name() const override { return model_->name(); }
  std::string summary() const override { return model_->summary(); }
  const std::vector<sediment::Parameter>& parameters() const override { return model_->parameters(); }
  sediment::Wave evaluate(std::span<const double> values, double frequency_hz, bool derivatives) const override {
    if (guard_->stopping()) throw StopStudy{};
    return model_->evaluate(values, frequency_hz, derivatives);
  }
  std::string uncertainty_caveat() const override { return model_->uncertainty_caveat(); }
  const std::vector<sediment::DerivedQuantity>& derived_quantities() const override {
    return model_->derived_quantities();
  }
  std::vector<sediment::DerivedValue> derived_values(std::span<const double> values, bool derivatives) const override {
    if (guard_->stopping()) throw StopStudy{};
    return model_->derived_values(values, derivatives);
  }
  std::string typical_free_parameters() const override { return model_->typical_free_parameters(); }
  const forward::DispersionModel* dimensionless_engine() const override { return model_->dimensionless_engine(); }
  std::optional<sediment::DimensionlessWave> dimensionless_wave(std::span<const double> values,
                                                                double frequency_hz) const override {
    return model_->dimensionless_wave(values, frequency_hz);
  }

 private:
  std::shared_ptr<const sediment::SedimentModel> model_;
  const StudyGuard* guard_;
};

}  // namespace

StudyGuard::StudyGuard() : previous_(active_guard) {
  active_guard = this;
  // Python's own handler only sets a flag that the interpreter reads between bytecodes, which it
  // does not run while the library works: during the call a handler of ours stops the work.
  if (in_main_thread() && (previous_ == nullptr || !previous_->handles_sigint_)) {
    struct sigaction ours {};
    ours.sa_handler = on_sigint;
    sigemptyset(&ours.sa_mask);
    interrupted.store(false);
    handles_sigint_ = sigaction(SIGINT, &ours, &python_sigint) == 0;
  }
}

StudyGuard::~StudyGuard() {
  if (handles_sigint_) sigaction(SIGINT, &python_sigint, nullptr);
  active_guard = previous_;
}

StudyGuard* StudyGuard::active() { return active_guard; }

bool StudyGuard::stopping() const { return failed_.load() || interrupted.load(); }

void StudyGuard::fail(py::error_already_set error) {
  const std::lock_guard lock(error_mutex_);
  if (!error_) error_ = std::make_unique<py::error_already_set>(std::move(error));
  failed_.store(true);
}

void StudyGuard::run(const std::function<void()>& work) {
  std::exception_ptr failure;
  {
    const py::gil_scoped_release released;
    try {
      work();
    } catch (const StopStudy&) {
    } catch (...) {
      failure = std::current_exception();
    }
  }
  if (error_) {
    error_->restore();
    error_.reset();
    throw py::error_already_set();
  }
  if (handles_sigint_ && interrupted.exchange(false)) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
  if (stopping()) throw std::runtime_error("sedwave: the call was stopped");
}

std::shared_ptr<const sediment::SedimentModel> guarded(std::shared_ptr<const sediment::SedimentModel> model,
                                                       StudyGuard& guard) {
  return std::make_shared<const GuardedModel>(std::move(model), guard);
}

std::function<void(const std::string&)> progress_function(const py::object& progress, StudyGuard& guard) {
  if (progress.is_none()) return nullptr;
  // Held by a shared pointer whose last owner releases it with the GIL: the library copies the
  // callback between threads that do not hold the GIL.
  const std::shared_ptr<py::object> function(new py::object(progress), [](py::object* f) {
    const py::gil_scoped_acquire gil;
    delete f;
  });
  return [function, &guard](const std::string& line) {
    const py::gil_scoped_acquire gil;
    if (guard.stopping()) return;
    try {
      (*function)(line);
    } catch (py::error_already_set& e) {
      guard.fail(std::move(e));
    }
  };
}

}  // namespace sedwave::python
