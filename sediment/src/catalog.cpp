#include "sedwave/sediment/catalog.hpp"

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "sedwave/forward/catalog/models.hpp"
#include "sedwave/sediment/biot_stoll.hpp"
#include "sedwave/sediment/edfm.hpp"
#include "sedwave/sediment/grain_shearing.hpp"
#include "sedwave/sediment/layered_seabed.hpp"
#include "sedwave/sediment/saturated_granular.hpp"

namespace sedwave::sediment {
namespace {

constexpr std::string_view kSaturated = "saturated-";

std::string accepted() {
  std::string list;
  for (const std::string& name : sediment_model_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

/// forward::make_dispersion_model, its error rephrased with every accepted sediment model.
std::shared_ptr<const forward::DispersionModel> frame_model(const std::string& frame, const std::string& spec) {
  try {
    return forward::make_dispersion_model(frame);
  } catch (const std::invalid_argument& e) {
    if (frame.starts_with("table:")) throw;  // a table's own error (missing file, bad format) says more
    throw std::invalid_argument("unknown model '" + spec + "' (accepted: " + accepted() + ")");
  }
}

/// An entry for a model with one name whose class needs no choices.
template <typename Model>
CatalogEntry closed_form(const std::string& name) {
  return {{name}, [](const std::string&, const ModelChoices&) { return std::make_shared<const Model>(); }, {}, {}};
}

/// The dry grain-contact frame: any forward/ model, and anything forward/ may yet accept (its own
/// error then names the accepted ones).
CatalogEntry dry_frames() {
  return {forward::dispersion_model_names(),
          [](const std::string& spec, const ModelChoices& choices) {
            return std::make_shared<const GrainContactModel>(frame_model(spec, spec), choices.damping);
          },
          {},
          [] { return std::vector<std::shared_ptr<const SedimentModel>>{make_sediment_model("lattice")}; }};
}

CatalogEntry saturated_frames() {
  std::vector<std::string> names;
  for (const std::string& frame : forward::dispersion_model_names()) names.push_back(std::string(kSaturated) + frame);
  return {names,
          [](const std::string& spec, const ModelChoices& choices) {
            return std::make_shared<const SaturatedGranularModel>(
                frame_model(spec.substr(kSaturated.size()), spec), choices.damping,
                choices.permeability_given ? PermeabilityFrom::Parameter : PermeabilityFrom::KozenyCarman);
          },
          [](const std::string& spec) { return spec.starts_with(kSaturated); },
          // The saturated frame once, in the form that lists permeability and pore_size (which --set accepts).
          [] {
            return std::vector<std::shared_ptr<const SedimentModel>>{
                make_sediment_model("saturated-lattice", {DampingForm::Gamma, true})};
          }};
}

/// Layers over a half-space, each part any other specification: "layered:L1+...+HALFSPACE" ('+', not
/// ',': a comparison's --models list is comma-separated).
CatalogEntry layered_seabeds() {
  return {{std::string(kLayeredPrefix) + "LAYER+...+HALFSPACE"},
          [](const std::string& spec, const ModelChoices& choices) {
            std::vector<std::shared_ptr<const SedimentModel>> parts;
            const std::string list = spec.substr(kLayeredPrefix.size());
            for (std::size_t start = 0; start <= list.size();) {
              const std::size_t plus = std::min(list.find(kLayerSeparator, start), list.size());
              const std::string part = list.substr(start, plus - start);
              if (part.empty() || part.starts_with(kLayeredPrefix)) {
                throw std::invalid_argument("model '" + spec + "': each part of a layered seabed is one model (" +
                                            (part.empty() ? "an empty part" : "'" + part + "' is layered itself") +
                                            "), top layer first, the half-space last");
              }
              parts.push_back(make_sediment_model(part, choices));
              start = plus + 1;
            }
            if (parts.size() < 2) {
              throw std::invalid_argument("model '" + spec + "': a layered seabed names at least one layer and its "
                                          "half-space (layered:LAYER+...+HALFSPACE)");
            }
            const std::shared_ptr<const SedimentModel> halfspace = parts.back();
            parts.pop_back();
            return std::make_shared<const LayeredSeabed>(std::move(parts), halfspace);
          },
          [](const std::string& spec) { return spec.starts_with(kLayeredPrefix); },
          [] { return std::vector<std::shared_ptr<const SedimentModel>>{make_sediment_model("layered:edfm+biot-stoll")}; }};
}

/// The catalog, one entry per model. The dry frame takes any specification no other entry takes
/// (forward/ then names what it accepts), so it is asked last.
struct Catalog {
  std::mutex mutex;
  std::vector<CatalogEntry> entries{
      saturated_frames(),
      closed_form<BiotStollModel>("biot-stoll"),
      closed_form<EffectiveDensityFluidModel>("edfm"),
      closed_form<GrainShearingModel>("grain-shearing"),
      closed_form<ViscousGrainShearingModel>("vgs-lambda"),
      layered_seabeds(),
  };
  CatalogEntry fallback = dry_frames();

  /// Entries in listing order: the dry frame first, as the command line has always listed it.
  std::vector<CatalogEntry> listing() {
    const std::lock_guard lock(mutex);
    std::vector<CatalogEntry> all{fallback};
    all.insert(all.end(), entries.begin(), entries.end());
    return all;
  }
};

Catalog& catalog() {
  static Catalog instance;
  return instance;
}

bool entry_accepts(const CatalogEntry& e, const std::string& spec) {
  if (e.accepts) return e.accepts(spec);
  return std::find(e.names.begin(), e.names.end(), spec) != e.names.end();
}

}  // namespace

void register_model(CatalogEntry entry) {
  if (entry.names.empty() || !entry.make) throw std::invalid_argument("register_model: an entry needs a name and make");
  // A name is taken when an entry accepts it, or when the new entry accepts a name listed already
  // (a broad `accepts` would otherwise shadow a model of the tree). Registrations take turns; the
  // predicates run on a copy, outside the catalog's own lock, so one that asks the catalog cannot
  // deadlock.
  static std::mutex registration;
  const std::lock_guard turn(registration);
  const std::vector<CatalogEntry> existing = catalog().listing();
  std::vector<std::string> listed;
  for (const CatalogEntry& e : existing) listed.insert(listed.end(), e.names.begin(), e.names.end());
  for (const std::string& name : entry.names) {
    const auto takes = [&](const CatalogEntry& e) { return entry_accepts(e, name); };
    if (std::any_of(existing.begin(), existing.end(), takes)) {
      throw std::invalid_argument("register_model: a model named '" + name + "' exists already");
    }
  }
  for (const std::string& name : listed) {
    if (entry_accepts(entry, name)) {
      throw std::invalid_argument("register_model: the new entry would take the name '" + name +
                                  "' of a model registered already");
    }
  }
  Catalog& c = catalog();
  const std::lock_guard lock(c.mutex);
  c.entries.push_back(std::move(entry));
}

void register_model(const std::string& name, std::function<std::shared_ptr<const SedimentModel>()> make) {
  if (!make) throw std::invalid_argument("register_model: '" + name + "' needs a function that makes it");
  register_model({{name}, [make](const std::string&, const ModelChoices&) { return make(); }, {}, {}});
}

std::shared_ptr<const SedimentModel> make_sediment_model(const std::string& spec, const ModelChoices& choices) {
  const std::vector<CatalogEntry> all = catalog().listing();
  for (std::size_t i = 1; i < all.size(); ++i) {
    if (entry_accepts(all[i], spec)) return all[i].make(spec, choices);
  }
  return all[0].make(spec, choices);
}

std::vector<std::string> sediment_model_names() {
  std::vector<std::string> names;
  for (const CatalogEntry& e : catalog().listing()) names.insert(names.end(), e.names.begin(), e.names.end());
  return names;
}

std::vector<std::shared_ptr<const SedimentModel>> model_examples() {
  std::vector<std::shared_ptr<const SedimentModel>> examples;
  for (const CatalogEntry& e : catalog().listing()) {
    if (e.examples) {
      for (auto& m : e.examples()) examples.push_back(std::move(m));
    } else {
      examples.push_back(e.make(e.names.front(), {}));
    }
  }
  return examples;
}

std::optional<std::string> sediment_model_file(const std::string& spec) {
  return forward::dispersion_model_file(spec.starts_with(kSaturated) ? spec.substr(kSaturated.size()) : spec);
}

}  // namespace sedwave::sediment
