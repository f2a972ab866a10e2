#include "sedwave/io/fingerprint.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace sedwave::io {

Fingerprint& Fingerprint::add(std::span<const std::byte> bytes) {
  constexpr std::uint64_t kPrime = 1099511628211ull;  // FNV prime
  for (const std::byte b : bytes) state_ = (state_ ^ static_cast<std::uint64_t>(b)) * kPrime;
  return *this;
}

std::string Fingerprint::hex() const {
  std::array<char, 17> text{};
  std::snprintf(text.data(), text.size(), "%016llx", static_cast<unsigned long long>(state_));
  return text.data();
}

std::string combined_fingerprint(std::span<const std::string> hashes) {
  Fingerprint f;
  for (const std::string& hash : hashes) f.add(hash);
  return f.hex();
}

std::string file_fingerprint(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open to fingerprint it");
  Fingerprint f;
  std::array<char, 1 << 16> buffer{};
  while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0) {
    f.add(std::as_bytes(std::span(buffer.data(), static_cast<std::size_t>(in.gcount()))));
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": read error while fingerprinting it");
  return f.hex();
}

}  // namespace sedwave::io
