#include "sedwave/forward/dem/contact/read_contact.hpp"

#include <algorithm>
#include <stdexcept>

#include "sedwave/forward/dem/contact/contact_model.hpp"

namespace sedwave::forward::dem {
namespace {

template <class... Parts>
std::vector<std::string> names(TypeList<Parts...>) {
  return {std::string(Parts::name)...};
}

/// The keys of the part of `List` called `name`.
template <class List>
std::vector<const ContactKey*> keys_of(std::string_view name) {
  std::vector<const ContactKey*> out;
  for_each_part(List{}, [&](auto* tag) {
    using Part = std::remove_pointer_t<decltype(tag)>;
    if (Part::name != name) return false;
    out.assign(Part::keys.begin(), Part::keys.end());
    return true;
  });
  return out;
}

template <class... Parts>
void append_keys(TypeList<Parts...>, std::vector<const ContactKey*>& out) {
  const auto add = [&](const ContactKey* k) {
    const bool known = std::any_of(out.begin(), out.end(), [&](const ContactKey* o) { return o->key == k->key; });
    if (!known) out.push_back(k);
  };
  (std::for_each(Parts::keys.begin(), Parts::keys.end(), add), ...);
}

}  // namespace

std::vector<std::string> normal_law_names() { return names(NormalLaws{}); }
std::vector<std::string> tangential_law_names() { return names(TangentialLaws{}); }
std::vector<std::string> rolling_law_names() { return names(RollingLaws{}); }

std::vector<const ContactKey*> all_contact_keys() {
  std::vector<const ContactKey*> out;
  append_keys(NormalLaws{}, out);
  append_keys(TangentialLaws{}, out);
  append_keys(RollingLaws{}, out);
  return out;
}

ContactSpec read_contact(ContactKeySource& source) {
  ContactSpec s;
  s.normal = source.choice("law", normal_law_names()).value_or(s.normal);
  // Friction alone selects the history spring (the thesis's and LAMMPS's frictional contact).
  const std::optional<double> friction = source.number(keys::friction);
  const std::optional<std::string> tangential = source.choice("tangential", tangential_law_names());
  s.tangential = tangential ? *tangential : friction.value_or(0.0) > 0.0 ? "spring_history" : "none";
  s.rolling = source.choice("rolling", rolling_law_names()).value_or(s.rolling);

  std::vector<const ContactKey*> wanted = keys_of<NormalLaws>(s.normal);
  for (const ContactKey* k : keys_of<TangentialLaws>(s.tangential)) wanted.push_back(k);
  for (const ContactKey* k : keys_of<RollingLaws>(s.rolling)) wanted.push_back(k);
  bool friction_read = false;
  for (const ContactKey* k : wanted) {
    if (k->key == keys::friction.key) {
      friction_read = true;
      if (friction) s.values[std::string(k->key)] = *friction;
    } else if (!s.has(k->key)) {
      if (const std::optional<double> x = source.number(*k)) s.values[std::string(k->key)] = *x;
    }
  }
  if (friction && *friction > 0.0 && !friction_read)
    source.fail("friction needs a tangential law with friction (tangential = \"" + s.tangential + "\")");
  try {
    (void)make_contact_model(s);
  } catch (const std::invalid_argument& e) {
    source.fail(e.what());
  }
  return s;
}

}  // namespace sedwave::forward::dem
