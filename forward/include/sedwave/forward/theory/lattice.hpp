#pragma once
// The exact discrete spring-dashpot chain (thesis eq. 2.7) with lattice spacing d:
//   sin(k~ / 2) = omega_hat / (2 sqrt(1 - i omega_hat gamma_hat)).
// The branch is the decaying one (alpha_hat >= 0) and is continuous in omega_hat, also through the
// undamped cutoff omega_hat = 2, above which the wave is evanescent (k_hat = pi, alpha_hat > 0).
// For omega_hat -> 0 it reduces to the continuum model.
#include "sedwave/forward/theory/continuum.hpp"

namespace sedwave::forward {

/// k~ of the discrete chain with exact derivatives. Requires omega_hat > 0, gamma_hat >= 0.
[[nodiscard]] ComplexWavenumber lattice_wavenumber(double omega_hat, double gamma_hat);

class LatticeModel final : public DispersionModel {
 public:
  [[nodiscard]] std::string name() const override { return "lattice"; }
  [[nodiscard]] DispersionPoint evaluate(double omega_hat, double gamma_hat) const override;
};

}  // namespace sedwave::forward
