#pragma once
// Run-time description of a contact model: which part of each list (contact/laws.hpp) and the
// values of their keys. Parts name their keys themselves (Part::keys), so a law with new constants
// needs no new field here; scene files and `sedwave dem` fill a spec through read_contact()
// (contact/read_contact.hpp), code that builds an engine may fill one directly.
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "sedwave/io/range.hpp"

namespace sedwave::forward::dem {


/// One number a part reads: its scene key (`key`, in [contact]) and `sedwave dem` option
/// (--option), what it means, the values it accepts and what a range message adds to them.
struct ContactKey {
  std::string_view key;
  std::string_view option;
  std::string_view help;
  io::Range bounds;
  std::string_view unit = "";
};

struct ContactSpec {
  std::string normal = "hooke";     ///< a NormalLaws part's name
  std::string tangential = "none";  ///< a TangentialLaws part's name
  std::string rolling = "none";     ///< a RollingLaws part's name
  /// Key values by ContactKey::key, e.g. "kn", "restitution", "friction".
  std::map<std::string, double, std::less<>> values;

  [[nodiscard]] bool has(std::string_view key) const { return values.find(key) != values.end(); }
  [[nodiscard]] std::optional<double> find(std::string_view key) const {
    const auto it = values.find(key);
    return it == values.end() ? std::nullopt : std::optional(it->second);
  }
  double& operator[](const std::string& key) { return values[key]; }
  void erase(const std::string& key) { values.erase(key); }
};

/// Reads a part's keys out of a spec, checking each against its bounds: std::invalid_argument names
/// the key otherwise.
class ContactValues {
 public:
  explicit ContactValues(const ContactSpec& spec) : spec_(spec) {}
  [[nodiscard]] std::optional<double> find(const ContactKey& k) const;
  [[nodiscard]] double get(const ContactKey& k, double fallback) const { return find(k).value_or(fallback); }
  /// A key without a fallback: std::invalid_argument "<law> needs <key>" when absent.
  [[nodiscard]] double required(const ContactKey& k, std::string_view law) const;
  [[nodiscard]] bool has(const ContactKey& k) const { return spec_.has(k.key); }

 private:
  const ContactSpec& spec_;
};

}  // namespace sedwave::forward::dem
