#include "sedwave/forward/dem/fluid.hpp"

#include <sstream>
#include <stdexcept>

namespace sedwave::forward::dem {

std::string_view drag_law_name(DragLaw law) {
  for (const auto& [name, l] : kDragLaws)
    if (l == law) return name;
  return "?";
}

DragLaw drag_law_of(std::string_view name) {
  for (const auto& [n, law] : kDragLaws)
    if (n == name) return law;
  throw std::invalid_argument("unknown drag law '" + std::string(name) + "'");
}

std::vector<std::string> drag_law_names() {
  std::vector<std::string> names;
  for (const auto& entry : kDragLaws) names.emplace_back(entry.first);
  return names;
}

std::string describe(const FluidSpec& f) {
  std::ostringstream s;
  s.precision(4);
  s << "viscosity " << f.viscosity << ", roughness " << f.roughness << ", cutoff " << f.cutoff << ", "
    << (f.lubrication ? "lubrication" : "no lubrication") << ", drag " << drag_law_name(f.drag);
  if (f.drag == DragLaw::richardson_zaki) s << " (porosity " << f.porosity << ": " << f.drag_factor() << " x Stokes)";
  s << ", density " << f.density;
  return s.str();
}

std::string FluidSpec::problem() const {
  std::ostringstream why;
  why.precision(6);
  if (!(viscosity > 0.0) || !std::isfinite(viscosity))
    why << "viscosity = " << viscosity << ": accepted range (0, inf) (a dry run has no fluid at all)";
  else if (!(density >= 0.0) || !std::isfinite(density))
    why << "density = " << density << ": accepted range [0, inf)";
  else if (!(roughness > 0.0) || !std::isfinite(roughness))
    why << "roughness = " << roughness << ": accepted range (0, inf) (the squeeze-film force diverges at zero gap)";
  else if (!(cutoff > roughness) || !std::isfinite(cutoff))
    why << "cutoff = " << cutoff << ": accepted range (roughness, inf) = (" << roughness << ", inf)";
  else if (drag == DragLaw::richardson_zaki && !(porosity > 0.0 && porosity < 1.0))
    why << "porosity = " << porosity << ": accepted range (0, 1)";
  return why.str();
}

}  // namespace sedwave::forward::dem
