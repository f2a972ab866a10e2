#pragma once
// Turns a model written once, templated on its scalar type, into a SedimentModel with exact
// gradients: the values are seeded as ceres::Jet<double, N> (N = the model's parameter count).
//
// A model class M provides
//   static constexpr int kParameters;
//   template <typename T> WaveOf<T> wave(const T* values, double frequency_hz) const;
// and derives from JetEvaluated<M>.
#include <ceres/jet.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sedwave/sediment/sediment_model.hpp"

namespace sedwave::sediment {

/// Attenuation [Np/m] and phase speed [m/s] in the scalar type of the evaluation.
template <typename T>
struct WaveOf {
  T attenuation;
  T speed;
  double sigma_attenuation = 0.0;  ///< the model's own 1-sigma [Np/m] (not differentiated)
  double sigma_speed = 0.0;        ///< [m/s]
};

template <typename M>
class JetEvaluated : public SedimentModel {
 public:
  [[nodiscard]] Wave evaluate(std::span<const double> values, double frequency_hz,
                              bool derivatives) const final {
    constexpr int n = M::kParameters;
    if (values.size() != static_cast<std::size_t>(n)) {
      throw std::invalid_argument(name() + ": " + std::to_string(n) + " parameter values expected, got " +
                                  std::to_string(values.size()));
    }
    const M& model = static_cast<const M&>(*this);
    Wave w;
    if (!derivatives) {
      const WaveOf<double> v = model.template wave<double>(values.data(), frequency_hz);
      w.attenuation = v.attenuation;
      w.speed = v.speed;
      w.sigma_attenuation = v.sigma_attenuation;
      w.sigma_speed = v.sigma_speed;
    } else {
      using Jet = ceres::Jet<double, n>;
      Jet x[n];
      for (int i = 0; i < n; ++i) x[i] = Jet(values[i], i);
      const WaveOf<Jet> v = model.template wave<Jet>(x, frequency_hz);
      w.attenuation = v.attenuation.a;
      w.speed = v.speed.a;
      w.d_attenuation.assign(v.attenuation.v.data(), v.attenuation.v.data() + n);
      w.d_speed.assign(v.speed.v.data(), v.speed.v.data() + n);
      w.sigma_attenuation = v.sigma_attenuation;
      w.sigma_speed = v.sigma_speed;
    }
    if (!std::isfinite(w.attenuation) || !std::isfinite(w.speed)) {
      throw std::domain_error(name() + ": no finite wave at " + std::to_string(frequency_hz) + " Hz");
    }
    return w;
  }
};

}  // namespace sedwave::sediment
