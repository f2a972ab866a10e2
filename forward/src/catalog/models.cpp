#include "sedwave/forward/catalog/models.hpp"

#include <stdexcept>
#include <string_view>

#include "sedwave/forward/table/table_model.hpp"
#include "sedwave/forward/theory/continuum.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward {

std::unique_ptr<DispersionModel> make_dispersion_model(const std::string& spec) {
  if (spec == "continuum") return std::make_unique<ContinuumModel>();
  if (spec == "lattice") return std::make_unique<LatticeModel>();
  if (spec.starts_with("table:")) return table::TableModel::from_spec(spec);
  std::string accepted;
  for (const std::string& name : dispersion_model_names()) accepted += (accepted.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown forward model '" + spec + "' (accepted: " + accepted + ")");
}

std::optional<std::string> dispersion_model_file(const std::string& spec) {
  if (!spec.starts_with("table:")) return std::nullopt;
  return table::TableModel::file_of(spec);
}

std::vector<std::string> dispersion_model_names() { return {"continuum", "lattice", "table:FILE.h5"}; }

}  // namespace sedwave::forward
