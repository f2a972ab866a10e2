#pragma once
// Short content hashes that checkpoints and tables store, so that a restart or a resumed table can
// tell whether its inputs (a data file, a packing) are still the ones it started from. FNV-1a,
// 64 bits, as 16 hex digits: a guard against mix-ups, not against deliberate collisions.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sedwave::io {

/// Accumulates bytes into a 64-bit FNV-1a hash.
class Fingerprint {
 public:
  Fingerprint() = default;
  /// Goes on from the state() of another: records spread over processes are hashed in turn.
  explicit Fingerprint(std::uint64_t state) : state_(state) {}
  [[nodiscard]] std::uint64_t state() const { return state_; }
  Fingerprint& add(std::span<const std::byte> bytes);
  Fingerprint& add(std::string_view text) { return add(std::as_bytes(std::span(text.data(), text.size()))); }
  /// A trivially copyable value's bytes (doubles bit for bit).
  template <typename T>
  Fingerprint& add_value(const T& value) {
    return add(std::as_bytes(std::span(&value, 1)));
  }
  [[nodiscard]] std::string hex() const;

 private:
  std::uint64_t state_ = 14695981039346656037ull;  // FNV offset basis
};

/// One hash for several, in order (an ensemble's packings, member 0 first).
[[nodiscard]] std::string combined_fingerprint(std::span<const std::string> hashes);

/// The hash of a file's bytes; throws std::runtime_error naming the file if it cannot be read.
[[nodiscard]] std::string file_fingerprint(const std::filesystem::path& path);

}  // namespace sedwave::io
