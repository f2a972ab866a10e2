#include "sedwave/forward/channel/fft.hpp"

#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace sedwave::forward::channel {
namespace {

bool is_power_of_two(std::size_t n) { return n > 0 && (n & (n - 1)) == 0; }

void bit_reverse_permute(std::span<std::complex<double>> data) {
  const std::size_t n = data.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(data[i], data[j]);
  }
}

}  // namespace

std::size_t next_power_of_two(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

void fft_in_place(std::span<std::complex<double>> data, FourierSign sign) {
  const std::size_t n = data.size();
  if (!is_power_of_two(n)) throw std::invalid_argument("fft: length " + std::to_string(n) + " is not a power of two");
  bit_reverse_permute(data);
  // Twiddles from one table of exp(s 2 pi i j / n), each evaluated directly: a recurrence
  // w_{j+1} = w_j w_1 would accumulate rounding error ~ n eps across a stage.
  const double s = sign == FourierSign::positive ? 1.0 : -1.0;
  std::vector<std::complex<double>> twiddle(n / 2);
  for (std::size_t j = 0; j < n / 2; ++j) {
    twiddle[j] = std::polar(1.0, s * 2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(n));
  }
  for (std::size_t length = 2; length <= n; length <<= 1) {
    const std::size_t half = length / 2;
    const std::size_t stride = n / length;
    for (std::size_t start = 0; start < n; start += length) {
      for (std::size_t j = 0; j < half; ++j) {
        const std::complex<double> odd = twiddle[j * stride] * data[start + j + half];
        data[start + j + half] = data[start + j] - odd;
        data[start + j] += odd;
      }
    }
  }
}

std::vector<std::complex<double>> real_spectrum(std::span<const double> x, std::size_t n_fft, FourierSign sign) {
  if (n_fft < x.size()) throw std::invalid_argument("real_spectrum: n_fft shorter than the record");
  std::vector<std::complex<double>> data(n_fft);
  for (std::size_t i = 0; i < x.size(); ++i) data[i] = x[i];
  fft_in_place(data, sign);
  return data;
}

}  // namespace sedwave::forward::channel
