#pragma once
// The standard normal quantile function, for rank normalisation.

namespace sedwave::sampling::detail {

/// Phi^-1(p) for p in (0, 1): Acklam's rational approximation (relative error < 1.2e-9; P. J. Acklam
/// 2003, "An algorithm for computing the inverse normal cumulative distribution function") refined
/// by one Halley step on std::erfc, to about 1e-15.
[[nodiscard]] double normal_quantile(double p);

}  // namespace sedwave::sampling::detail
