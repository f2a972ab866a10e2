#pragma once
// Turns a model written once, templated on its scalar type, into a SedimentModel with exact
// gradients: the values are seeded as ceres::Jet<double, N> (N = the model's parameter count).
//
// A model class M provides
//   static constexpr int kParameters;
//   template <typename T> WaveOf<T> wave(const T* values, double frequency_hz) const;
// and derives from JetEvaluated<M>. A model with derived quantities also provides
//   template <typename T> std::vector<T> derived(const T* values) const;
// in the order of its derived_quantities(); the same Jets give their exact gradients. A model with a
// shear wave provides
//   template <typename T> WaveOf<T> shear_wave(const T* values, double frequency_hz) const;
// (has_shear() and evaluate_shear() then answer with it), and one that fixes its bulk density
//   template <typename T> T density(const T* values) const;   [kg/m^3]
#include <ceres/jet.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

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

/// Evaluates `wave_of(const T* values)` (a generic callable returning WaveOf<T>) as doubles, or with
/// N Jet-seeded values for the gradient. For models whose parameter count is chosen at construction
/// (and so cannot be one static constant); JetEvaluated<M> is the usual way in.
template <int N, typename WaveFunction>
Wave evaluate_with_jets(const std::string& model_name, std::span<const double> values, double frequency_hz,
                        bool derivatives, const WaveFunction& wave_of) {
  if (values.size() != static_cast<std::size_t>(N)) {
    throw std::invalid_argument(model_name + ": " + std::to_string(N) + " parameter values expected, got " +
                                std::to_string(values.size()));
  }
  Wave w;
  if (!derivatives) {
    const WaveOf<double> v = wave_of(values.data());
    w.attenuation = v.attenuation;
    w.speed = v.speed;
    w.sigma_attenuation = v.sigma_attenuation;
    w.sigma_speed = v.sigma_speed;
  } else {
    using Jet = ceres::Jet<double, N>;
    Jet x[N];
    for (int i = 0; i < N; ++i) x[i] = Jet(values[static_cast<std::size_t>(i)], i);
    const WaveOf<Jet> v = wave_of(static_cast<const Jet*>(x));
    w.attenuation = v.attenuation.a;
    w.speed = v.speed.a;
    w.d_attenuation.assign(v.attenuation.v.data(), v.attenuation.v.data() + N);
    w.d_speed.assign(v.speed.v.data(), v.speed.v.data() + N);
    w.sigma_attenuation = v.sigma_attenuation;
    w.sigma_speed = v.sigma_speed;
  }
  if (!std::isfinite(w.attenuation) || !std::isfinite(w.speed)) {
    throw std::domain_error(model_name + ": no finite wave at " + std::to_string(frequency_hz) + " Hz");
  }
  return w;
}

/// Evaluates `derived_of(const T* values)` (a generic callable returning std::vector<T>, one entry
/// per derived quantity) as doubles, or with N Jet-seeded values for the gradients.
template <int N, typename DerivedFunction>
std::vector<DerivedValue> evaluate_derived_with_jets(const std::string& model_name, std::span<const double> values,
                                                     bool derivatives, const DerivedFunction& derived_of) {
  if (values.size() != static_cast<std::size_t>(N)) {
    throw std::invalid_argument(model_name + ": " + std::to_string(N) + " parameter values expected, got " +
                                std::to_string(values.size()));
  }
  std::vector<DerivedValue> out;
  if (!derivatives) {
    for (const double q : derived_of(values.data())) out.push_back({q, {}});
    return out;
  }
  using Jet = ceres::Jet<double, N>;
  Jet x[N];
  for (int i = 0; i < N; ++i) x[i] = Jet(values[static_cast<std::size_t>(i)], i);
  for (const Jet& q : derived_of(static_cast<const Jet*>(x))) {
    out.push_back({q.a, std::vector<double>(q.v.data(), q.v.data() + N)});
  }
  return out;
}

/// A model class that provides a shear wave (see the top of this file).
template <typename M>
concept HasShearWave = requires(const M& model, const double* v) { model.template shear_wave<double>(v, 1.0); };

template <typename M>
class JetEvaluated : public SedimentModel {
 public:
  [[nodiscard]] std::vector<DerivedValue> derived_values(std::span<const double> values,
                                                         bool derivatives) const override {
    const M& model = static_cast<const M&>(*this);
    if constexpr (requires(const double* v) { model.template derived<double>(v); }) {
      return evaluate_derived_with_jets<M::kParameters>(name(), values, derivatives, [&](const auto* x) {
        using T = std::remove_cvref_t<decltype(*x)>;
        return model.template derived<T>(x);
      });
    } else {
      return SedimentModel::derived_values(values, derivatives);
    }
  }

  [[nodiscard]] bool has_shear() const final { return HasShearWave<M>; }

  [[nodiscard]] Wave evaluate_shear(std::span<const double> values, double frequency_hz,
                                    bool derivatives) const final {
    const M& model = static_cast<const M&>(*this);
    if constexpr (HasShearWave<M>) {
      return evaluate_with_jets<M::kParameters>(name() + " (shear)", values, frequency_hz, derivatives,
                                                [&](const auto* x) {
                                                  using T = std::remove_cvref_t<decltype(*x)>;
                                                  return model.template shear_wave<T>(x, frequency_hz);
                                                });
    } else {
      return SedimentModel::evaluate_shear(values, frequency_hz, derivatives);
    }
  }

  [[nodiscard]] std::optional<double> bulk_density(std::span<const double> values) const final {
    const M& model = static_cast<const M&>(*this);
    if constexpr (requires(const double* v) { model.template density<double>(v); }) {
      if (values.size() != static_cast<std::size_t>(M::kParameters)) {
        throw std::invalid_argument(name() + ": " + std::to_string(M::kParameters) +
                                    " parameter values expected, got " + std::to_string(values.size()));
      }
      return model.template density<double>(values.data());
    } else {
      return std::nullopt;
    }
  }

  [[nodiscard]] Wave evaluate(std::span<const double> values, double frequency_hz,
                              bool derivatives) const final {
    const M& model = static_cast<const M&>(*this);
    return evaluate_with_jets<M::kParameters>(name(), values, frequency_hz, derivatives, [&](const auto* x) {
      using T = std::remove_cvref_t<decltype(*x)>;
      return model.template wave<T>(x, frequency_hz);
    });
  }
};

}  // namespace sedwave::sediment
