#pragma once
// One reader of contact descriptions for scene files ([contact]) and `sedwave dem`'s options. It
// asks its source for the three selector keys, then for the keys of the chosen parts only, so a
// source can reject every key nobody asked for; defaults live in the parts (one place each).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sedwave/forward/dem/contact/contact_spec.hpp"

namespace sedwave::forward::dem {

/// Where contact keys come from. Selector keys name a part: "law" (normal), "tangential", "rolling".
class ContactKeySource {
 public:
  virtual ~ContactKeySource() = default;
  /// The part named by a selector key, which must be one of `names`; nullopt when absent.
  virtual std::optional<std::string> choice(std::string_view selector, const std::vector<std::string>& names) = 0;
  /// A part's number, which must lie within the key's bounds; nullopt when absent.
  virtual std::optional<double> number(const ContactKey& key) = 0;
  /// Reports a mistake involving several keys (e.g. both kn and youngs_modulus).
  [[noreturn]] virtual void fail(const std::string& why) = 0;
};

/// Reads a contact: the normal law (selector "law", default hooke), the tangential law (default
/// spring_history when friction > 0, else none), the rolling law (default none) and the keys of
/// those three parts; then checks that the model can be built (source.fail otherwise).
[[nodiscard]] ContactSpec read_contact(ContactKeySource& source);

/// The part names of each role, in list order (contact/laws.hpp).
[[nodiscard]] std::vector<std::string> normal_law_names();
[[nodiscard]] std::vector<std::string> tangential_law_names();
[[nodiscard]] std::vector<std::string> rolling_law_names();
/// Every key of every part, each once, in list order.
[[nodiscard]] std::vector<const ContactKey*> all_contact_keys();

}  // namespace sedwave::forward::dem
