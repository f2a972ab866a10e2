// `sedwave models`: every sediment model `invert` and `synthesize` accept, with each parameter's
// unit, default and physical range, its derived quantities with their plausible ranges, and whether
// it predicts a shear wave (docs/models/).
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "output_paths.hpp"
#include "sedwave/sediment/catalog.hpp"

namespace sedwave::app {

Command add_models_command(CLI::App& app) {
  auto name = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "models", "List the sediment models (--model of invert and synthesize) with their parameters: SI unit, "
                "default, physical range; derived quantities with their plausible ranges (docs/models/)");
  const CLI::Option* given = cmd->add_option("model", *name, "one model's specification (e.g. biot-stoll); all when omitted");
  return {cmd, [name, given]() {
    // An empty name given is a mistake (an unset shell variable, say), not a request for every model.
    if (given->count() > 0 && name->empty()) {
      throw UsageError("models '': an empty model name (omit it to list every model)");
    }
    std::printf("# models: %s\n", name->empty() ? "all (a table stands for every table; saturated-X for any frame X)"
                                                : name->c_str());
    const auto models = name->empty() ? sediment::model_examples()
                                      : std::vector<std::shared_ptr<const sediment::SedimentModel>>{
                                            sediment::make_sediment_model(*name, {sediment::DampingForm::Gamma, true})};
    for (const auto& m : models) {
      std::printf("\n%s: %s\n", m->name().c_str(), m->summary().c_str());
      std::printf("  fitted unless --fit says otherwise: %s\n", sediment::typical_free_parameters(*m).c_str());
      std::printf("  shear wave: %s\n", m->has_shear() ? m->shear_summary().c_str() : "none");
      std::printf("  bulk density (for reflection): %s\n",
                  m->bulk_density(m->default_values()) ? "yes" : "none (not a seabed on its own)");
      std::printf("  %-16s %-8s %12s  %-25s %s\n", "parameter", "unit", "default", "physical range", "meaning");
      for (const sediment::Parameter& p : m->parameters()) {
        char range[64];
        std::snprintf(range, sizeof range, "[%.3g, %.3g]", p.lower, p.upper);
        std::printf("  %-16s %-8s %12.4g  %-25s %s\n", p.name.c_str(), p.unit.c_str(), p.default_value, range,
                    p.meaning.c_str());
      }
      if (!m->derived_quantities().empty()) {
        std::printf("  %-16s %-8s %12s  %-25s %s\n", "derived", "unit", "", "plausible range", "meaning");
        for (const sediment::DerivedQuantity& q : m->derived_quantities()) {
          char range[64] = "-";
          if (q.plausible_upper > q.plausible_lower) {
            std::snprintf(range, sizeof range, "[%.3g, %.3g]", q.plausible_lower, q.plausible_upper);
          }
          std::printf("  %-16s %-8s %12s  %-25s %s\n", q.name.c_str(), q.unit.c_str(), "", range, q.meaning.c_str());
        }
      }
      if (m->name().starts_with("saturated-")) {
        std::printf("  (permeability and pore_size follow from d and porosity by Kozeny-Carman unless --set, --fit "
                    "or --bounds names either)\n");
      }
    }
    return kExitOk;
  }};
}

}  // namespace sedwave::app
