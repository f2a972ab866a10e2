#include "sedwave/forward/dem/contact/contact_model.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace sedwave::forward::dem {
namespace {

/// Calls f(tag) with a null Part* for the part of `List` called `name`; false when none is.
template <class List, class F>
bool with_part(std::string_view name, F&& f) {
  return for_each_part(List{}, [&](auto* tag) {
    using Part = std::remove_pointer_t<decltype(tag)>;
    if (Part::name != name) return false;
    f(tag);
    return true;
  });
}

template <class List>
void require_part(std::string_view name, std::string_view role) {
  if (!with_part<List>(name, [](auto*) {}))
    throw std::invalid_argument("contact model: unknown " + std::string(role) + " law '" + std::string(name) + "'");
}

/// A part's word in describe(): its name unless it states a `label` (checkpoints store these).
template <class Part>
constexpr std::string_view label_of_part() {
  if constexpr (requires { Part::label; }) return Part::label;
  else return Part::name;
}

template <class List>
std::string_view label_of(std::string_view name) {
  std::string_view label = name;
  with_part<List>(name, [&](auto* tag) { label = label_of_part<std::remove_pointer_t<decltype(tag)>>(); });
  return label;
}

/// Whether the part of `List` called `name` reads `key`.
template <class List>
bool reads(std::string_view name, std::string_view key) {
  bool found = false;
  with_part<List>(name, [&](auto* tag) {
    for (const ContactKey* k : std::remove_pointer_t<decltype(tag)>::keys) found = found || k->key == key;
  });
  return found;
}

/// A key no chosen part reads is a mistake (a misspelling, or a law that was not selected).
void require_keys_apply(const ContactSpec& s) {
  for (const auto& [key, value] : s.values) {
    if (!reads<NormalLaws>(s.normal, key) && !reads<TangentialLaws>(s.tangential, key) &&
        !reads<RollingLaws>(s.rolling, key))
      throw std::invalid_argument("contact model: key '" + key + "' does not apply to " + describe(s));
  }
}

}  // namespace

std::optional<double> ContactValues::find(const ContactKey& k) const {
  const std::optional<double> x = spec_.find(k.key);
  if (x && !(std::isfinite(*x) && k.bounds.contains(*x))) {
    std::ostringstream why;
    why << "contact model: " << k.key << " = " << *x << " outside " << k.bounds.describe();
    throw std::invalid_argument(why.str());
  }
  return x;
}

double ContactValues::required(const ContactKey& k, std::string_view law) const {
  const std::optional<double> x = find(k);
  if (!x) throw std::invalid_argument(std::string(law) + " needs '" + std::string(k.key) + "'");
  return *x;
}

AnyContactModel make_contact_model(const ContactSpec& s) {
  require_part<NormalLaws>(s.normal, "normal");
  require_part<TangentialLaws>(s.tangential, "tangential");
  require_part<RollingLaws>(s.rolling, "rolling");
  require_keys_apply(s);
  const ContactValues v(s);
  std::optional<AnyContactModel> model;
  with_part<NormalLaws>(s.normal, [&](auto* normal_tag) {
    using Normal = std::remove_pointer_t<decltype(normal_tag)>;
    const Normal normal = Normal::from(v);
    with_part<TangentialLaws>(s.tangential, [&](auto* tangential_tag) {
      using Tangential = std::remove_pointer_t<decltype(tangential_tag)>;
      const Tangential tangential = Tangential::from(v, normal.stiffness_at_contact());
      with_part<RollingLaws>(s.rolling, [&](auto* rolling_tag) {
        using Rolling = std::remove_pointer_t<decltype(rolling_tag)>;
        model.emplace(ContactModel<Normal, Tangential, Rolling>{normal, tangential, Rolling::from(v)});
      });
    });
  });
  return *model;
}

ContactSpec without_dashpot(ContactSpec spec) {
  require_part<NormalLaws>(spec.normal, "normal");
  with_part<NormalLaws>(spec.normal, [&](auto* tag) {
    for (const ContactKey* k : std::remove_pointer_t<decltype(tag)>::dashpot_keys) spec.erase(std::string(k->key));
  });
  return spec;
}

std::string describe(const ContactSpec& s) {
  std::string out(label_of<NormalLaws>(s.normal));
  for (const std::string_view label : {label_of<TangentialLaws>(s.tangential), label_of<RollingLaws>(s.rolling)}) {
    if (label.empty() || label == "none") continue;
    out.push_back('+');
    out.append(label);
  }
  return out;
}

std::optional<TangentialBlock> tangential_block(const AnyContactModel& m, double overlap, double r_i, double r_j) {
  return std::visit(
      [&](const auto& model) -> std::optional<TangentialBlock> {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (!Model::linearised) {
          throw std::invalid_argument("linear engine: rolling resistance and the Coulomb-tanh law are not "
                                      "linearised; use the time-domain engine");
        } else if constexpr (Model::has_tangential) {
          return model.tangential.linear_block(overlap, r_i, r_j);
        } else {
          return std::nullopt;
        }
      },
      m);
}

}  // namespace sedwave::forward::dem
