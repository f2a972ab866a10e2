// The Python module's entry point: `import sedwave` loads sedwave._sedwave (this), which the
// package's pure-Python part (python/sedwave/__init__.py) wraps.
#include "bindings.hpp"
#include "sedwave/version.hpp"

PYBIND11_MODULE(_sedwave, m) {
  m.doc() = "sedwave's C++ library: sediment models, observations, fits, posteriors and model comparison";
  sedwave::python::bind_models(m);
  sedwave::python::bind_data(m);
  sedwave::python::bind_studies(m);
  sedwave::python::bind_python_model(m);
  sedwave::python::bind_tables(m);
  sedwave::python::bind_run_files(m);
  m.attr("__version__") = sedwave::kVersion;
}
