#pragma once
// Reproducible random draws for the samplers. std::mt19937_64's output sequence is fixed by the C++
// standard, but std::uniform_real_distribution and std::normal_distribution are not (each standard
// library maps the raw bits differently), so the uniforms and normals are made here from the raw
// 64-bit output: the same seed gives the same samples with any standard library (up to the last
// bit of std::log in the normal draws).
#include <cstdint>
#include <random>

namespace sedwave::sampling {

class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed) : engine_(seed) {}

  /// Uniform on [0, 1): the top 53 bits of one output, times 2^-53 (every double of that grid).
  [[nodiscard]] double uniform();
  /// Uniform integer in [0, n), n >= 1 (floor(n u); the bias is below 2^-53 n, far below any use).
  [[nodiscard]] int index(int n);
  /// Standard normal by Marsaglia's polar method (Marsaglia & Bray 1964, SIAM Rev. 6, 260); the
  /// second value of each pair is kept for the next call.
  [[nodiscard]] double normal();

 private:
  std::mt19937_64 engine_;
  double spare_normal_ = 0.0;
  bool has_spare_normal_ = false;
};

}  // namespace sedwave::sampling
