// Dispersion tables (HDF5, docs/tables.md) opened read-only as numpy arrays: what `sedwave show`
// prints, on the grid's two axes.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "bindings.hpp"
#include "sedwave/forward/table/table.hpp"
#include "sedwave/forward/table/table_file.hpp"

namespace sedwave::python {

void bind_tables(py::module_& m) {
  m.def("read_table", [](const std::filesystem::path& path) {
    namespace table = forward::table;
    table::DispersionTable t = [&] {
      const py::gil_scoped_release released;
      return table::read_table(path);
    }();
    const auto rows = static_cast<py::ssize_t>(t.n_gamma()), columns = static_cast<py::ssize_t>(t.n_omega());
    py::array_t<double> alpha({rows, columns}), c({rows, columns}), sigma_alpha({rows, columns}),
        sigma_c({rows, columns}), seconds({rows, columns});
    py::array_t<std::int8_t> status({rows, columns});
    py::list reasons;
    for (std::size_t g = 0; g < t.n_gamma(); ++g) {
      py::list row;
      for (std::size_t o = 0; o < t.n_omega(); ++o) {
        const table::PointResult& p = t.at(g, o);
        const auto i = static_cast<py::ssize_t>(g), j = static_cast<py::ssize_t>(o);
        alpha.mutable_at(i, j) = p.alpha_hat;
        c.mutable_at(i, j) = p.c_hat;
        sigma_alpha.mutable_at(i, j) = p.sigma_alpha_hat;
        sigma_c.mutable_at(i, j) = p.sigma_c_hat;
        seconds.mutable_at(i, j) = p.wall_seconds;
        status.mutable_at(i, j) = static_cast<std::int8_t>(p.status);
        row.append(p.reason);
      }
      reasons.append(row);
    }
    const table::TableMetadata& meta = t.metadata();
    py::dict metadata;
    metadata["engine"] = meta.engine;
    metadata["code_version"] = meta.code_version;
    metadata["definitions"] = meta.definitions;
    metadata["scene_toml"] = meta.scene_toml;
    metadata["packing_hash"] = meta.packing_hash;
    metadata["packings"] = meta.packings;
    metadata["sigma_includes"] = table::sigma_meaning(meta);
    metadata["pore_fluid"] = meta.pore_fluid;
    py::dict out;
    out["omega_hat"] = py::array_t<double>(columns, t.grid().omega_hat.data());
    out["gamma_hat"] = py::array_t<double>(rows, t.grid().gamma_hat.data());
    out["alpha_hat"] = alpha;
    out["c_hat"] = c;
    out["sigma_alpha_hat"] = sigma_alpha;
    out["sigma_c_hat"] = sigma_c;
    out["status"] = status;
    out["wall_seconds"] = seconds;
    out["reason"] = reasons;
    out["metadata"] = metadata;
    return out;
  }, py::arg("path"), R"doc(
A dispersion table (HDF5; docs/tables.md), read only, with the points its journal holds, as
`sedwave show TABLE` prints it: omega_hat (columns) and gamma_hat (rows) axes, and arrays of shape
(gamma_hat, omega_hat): alpha_hat, c_hat, sigma_alpha_hat, sigma_c_hat (dimensionless; NaN where a
point is not ok), status (0 missing, 1 ok, 2 unresolved, 3 failed), wall_seconds [s]; reason (lists
of str); metadata (engine, version, definitions, the scene, what sigma includes).)doc");
}

}  // namespace sedwave::python
