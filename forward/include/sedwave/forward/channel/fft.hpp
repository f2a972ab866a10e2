#pragma once
// A compact iterative radix-2 FFT for the channel measurements (no external FFT library is a
// dependency of sedwave). Records are short (1e3-1e6 samples) and transformed a handful of times,
// so clarity wins over speed here.
//
// Units: none (sample index <-> frequency bin).
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

namespace sedwave::forward::channel {

/// Sign of the exponent: X_m = sum_n x_n exp(sign * 2 pi i m n / N), never normalized.
enum class FourierSign { negative, positive };

/// Smallest power of two >= n (1 for n = 0).
[[nodiscard]] std::size_t next_power_of_two(std::size_t n);

/// In-place unnormalized DFT of a power-of-two length; throws std::invalid_argument otherwise.
/// Applying it with both signs multiplies the data by N.
void fft_in_place(std::span<std::complex<double>> data, FourierSign sign);

/// DFT of a real record zero-padded to n_fft (a power of two, >= x.size()).
[[nodiscard]] std::vector<std::complex<double>> real_spectrum(std::span<const double> x, std::size_t n_fft,
                                                              FourierSign sign);

}  // namespace sedwave::forward::channel
