#pragma once
// Biot's theory of a fluid-saturated porous frame, in the form Stoll uses for marine sediments:
// the fast compressional wave's complex wave number, templated on the scalar type T (double or
// ceres::Jet) so that every model built on it gets exact gradients.
//
// Sources:
//   M. A. Biot, J. Acoust. Soc. Am. 28, 168-178 (1956) (low-frequency range) and 28, 179-191
//     (1956) (higher frequency range: the viscous correction F(kappa)).
//   R. D. Stoll, "Acoustic waves in saturated sediments", in Physics of Sound in Marine Sediments
//     (Plenum, 1974), and Sediment Acoustics (Springer, 1989), ch. 2: H, C, M and the determinant.
//   R. D. Stoll and T. K. Kan, J. Acoust. Soc. Am. 70, 149-156 (1981): the same equations as used
//     for reflection at the sea floor.
//   F. Gassmann, Vierteljahrsschr. Naturforsch. Ges. Zuerich 96, 1-23 (1951); A. B. Wood, A
//     Textbook of Sound (Bell, 1930).
//   M. Abramowitz and I. A. Stegun, Handbook of Mathematical Functions (1964), 9.6.10, 9.7.1,
//     9.9.1: the Kelvin functions.
// Equation numbers are quoted where the source could be checked (Abramowitz & Stegun). The texts
// of Biot, Stoll, Stoll & Kan and Gassmann were not at hand: their formulas are cited by paper and
// chapter and identified by content, and tests/sediment/independent_reference.py solves Stoll's
// equations of motion in Stoll's own convention as an independent check (docs/models/poroelastic.md).
//
// Sign convention: fields vary as exp(i(k x - omega t)); a wave that decays along +x has
// Im k > 0, and attenuation = Im k [Np/m], phase speed = omega / Re k. In this convention a lossy
// modulus has a NEGATIVE imaginary part (Stoll writes exp(+i omega t) and K(1 + i delta/pi); here
// that is K(1 - i delta/pi)), and the viscous drag adds +i eta F* / (k omega) to the fluid's
// effective density.
//
// The equations of motion (Stoll 1989, ch. 2) for the dilatations e (frame) and zeta (relative
// fluid flow), with the frame P-wave modulus inside H:
//   laplacian(H e - C zeta) = d2/dt2 (rho e - rho_f zeta)
//   laplacian(C e - M zeta) = d2/dt2 (rho_f e - m zeta) - (eta F / k) d/dt zeta
// give, with s = (k/omega)^2 (slowness squared),
//   (H M - C^2) s^2 - (H m~ + rho M - 2 C rho_f) s + (rho m~ - rho_f^2) = 0,
//   m~ = alpha_inf rho_f / beta + i eta F*(kappa) / (k omega).
// The two roots are the fast and the slow (Biot type II) compressional waves.
#include <ceres/jet.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sedwave/sediment/complex.hpp"

namespace sedwave::sediment {

namespace biot_detail {
inline double value_of(double x) { return x; }
template <typename J>
double value_of(const J& x) {
  return x.a;
}
/// |term| < 1e-17 |re + i im| for a series' real term and its sum {re, im}, value parts only.
template <typename T>
bool below_relative(const T& term, const T (&sum)[2]) {
  const double size = value_of(term), re = value_of(sum[0]), im = value_of(sum[1]);
  return size * size < 1e-34 * (re * re + im * im);
}
}  // namespace biot_detail

// ---- Mixtures: Wood and Gassmann ------------------------------------------------------------------

/// Density [kg/m^3] of the saturated sediment, the mass balance of grains and pore fluid
/// (Stoll 1989, ch. 2): rho = beta rho_f + (1 - beta) rho_s.
template <typename T>
T mixture_density(const T& porosity, const T& grain_density, const T& fluid_density) {
  return porosity * fluid_density + (1.0 - porosity) * grain_density;
}

/// Wood's (1930) bulk modulus [Pa] of a suspension: 1/K = beta/K_f + (1 - beta)/K_s (Reuss average).
template <typename T>
T wood_bulk_modulus(const T& porosity, const T& grain_bulk, const T& fluid_bulk) {
  return 1.0 / (porosity / fluid_bulk + (1.0 - porosity) / grain_bulk);
}

/// Wood's sound speed [m/s]: sqrt(K_Wood / rho).
template <typename T>
T wood_speed(const T& porosity, const T& grain_density, const T& grain_bulk, const T& fluid_density,
             const T& fluid_bulk) {
  using std::sqrt;
  return sqrt(wood_bulk_modulus(porosity, grain_bulk, fluid_bulk) /
              mixture_density(porosity, grain_density, fluid_density));
}

/// Biot's characteristic frequency [Hz], f_c = eta beta / (2 pi rho_f k): where the viscous and the
/// inertial coupling of pore fluid and frame are equal (M. A. Biot, J. Acoust. Soc. Am. 28, 168-178
/// (1956), "low-frequency range", his f_t = b / (2 pi rho_2) with b = eta beta^2 / k and
/// rho_2 = beta rho_f; Stoll 1989, ch. 2). Below it the pore fluid moves with the frame (loss ~ f^2),
/// above it the fluid lags (loss ~ f^(1/2)).
template <typename T>
T biot_characteristic_frequency(const T& viscosity, const T& porosity, const T& fluid_density,
                                const T& permeability) {
  return viscosity * porosity / (2.0 * std::numbers::pi * fluid_density * permeability);
}

/// Biot's elastic coefficients [Pa] in Stoll's notation (Stoll 1989, ch. 2; Stoll & Kan 1981):
///   D = K_s (1 + beta (K_s/K_f - 1)),
///   H = (K_s - K_b)^2 / (D - K_b) + K_b + 4/3 mu,  C = K_s (K_s - K_b) / (D - K_b),
///   M = K_s^2 / (D - K_b).
/// H is Gassmann's saturated P-wave modulus (K_Gassmann + 4/3 mu).
template <typename T>
struct BiotModuli {
  Complex<T> H;
  Complex<T> C;
  Complex<T> M;
};

template <typename T>
BiotModuli<T> biot_moduli(const Complex<T>& frame_bulk, const Complex<T>& frame_shear, const T& porosity,
                          const T& grain_bulk, const T& fluid_bulk) {
  const T d = grain_bulk * (1.0 + porosity * (grain_bulk / fluid_bulk - 1.0));
  const Complex<T> denominator = Complex<T>(d) - frame_bulk;
  const Complex<T> ks_minus_kb = Complex<T>(grain_bulk) - frame_bulk;
  const Complex<T> H = ks_minus_kb * ks_minus_kb / denominator + frame_bulk + frame_shear * T(4.0 / 3.0);
  const Complex<T> C = grain_bulk * ks_minus_kb / denominator;
  const Complex<T> M = Complex<T>(grain_bulk * grain_bulk) / denominator;
  return {H, C, M};
}

/// Gassmann's (1951) saturated bulk modulus [Pa] in its textbook form
///   K = K_b + (1 - K_b/K_s)^2 / (beta/K_f + (1 - beta)/K_s - K_b/K_s^2),
/// written independently of biot_moduli (whose H - 4/3 mu is the same quantity).
template <typename T>
Complex<T> gassmann_bulk_modulus(const Complex<T>& frame_bulk, const T& porosity, const T& grain_bulk,
                                 const T& fluid_bulk) {
  const Complex<T> one_minus = Complex<T>(T(1.0)) - frame_bulk / grain_bulk;
  const Complex<T> denominator =
      Complex<T>(porosity / fluid_bulk + (1.0 - porosity) / grain_bulk) - frame_bulk / (grain_bulk * grain_bulk);
  return frame_bulk + one_minus * one_minus / denominator;
}

// ---- Kelvin functions and Biot's viscous correction F(kappa) --------------------------------------
// ber x + i bei x = I_0(z) and ber' x + i bei' x = e^{i pi/4} I_1(z) at z = x e^{i pi/4}
// (Abramowitz & Stegun 9.9.1, 9.6.3). Below kKelvinSeriesLimit the ascending series
//   I_n(z) = (z/2)^n sum_j (z^2/4)^j / (j! (j+n)!)          (A&S 9.6.10)
// converges without harmful cancellation; above it the asymptotic expansion
//   I_n(z) ~ e^z / sqrt(2 pi z) sum_k (-1)^k a_k(n) / z^k,  a_k = prod_{j<=k} (4n^2 - (2j-1)^2) / (k! 8^k)
// (A&S 9.7.1) is accurate to the neglected e^{-z} branch, relatively e^{-sqrt(2) x} < 1e-11 there.

inline constexpr double kKelvinSeriesLimit = 18.0;

/// 1 / (j (j + n)) and 1 / (j + n + 1) for the series below, n < kKelvinSeriesOrders,
/// j < kKelvinSeriesTerms: multiplications by these keep divisions off the loop's chain of
/// dependent operations.
inline constexpr int kKelvinSeriesOrders = 3;
inline constexpr int kKelvinSeriesTerms = 81;
struct KelvinSeriesFactors {
  double step[kKelvinSeriesOrders][kKelvinSeriesTerms];  ///< 1 / (j (j + n))
  double next[kKelvinSeriesOrders][kKelvinSeriesTerms];  ///< 1 / (j + n + 1)
  double first[kKelvinSeriesOrders];                     ///< 1 / n!, the term j = 0
};
inline constexpr KelvinSeriesFactors kKelvinSeriesFactors = [] {
  KelvinSeriesFactors f{};
  for (int n = 0; n < kKelvinSeriesOrders; ++n) {
    f.first[n] = n == 0 ? 1.0 : f.first[n - 1] / n;
    for (int j = 0; j < kKelvinSeriesTerms; ++j) {
      f.step[n][j] = j == 0 ? 0.0 : 1.0 / (static_cast<double>(j) * (j + n));
      f.next[n][j] = 1.0 / (j + n + 1.0);
    }
  }
  return f;
}();

/// The reduced series of I_n and I_{n+1} on the Kelvin ray, sum_j w^j / (j! (j+m)!) for m = n and
/// m = n + 1 (I_m(z) / (z/2)^m), at w = z^2/4 = i t, t = x^2/4 >= 0. The j-th term is i^j times a
/// real number, so each sum is two real series, accumulated in real arithmetic (a quarter of the
/// multiplications of complex terms), and both orders share one loop: term j of order n + 1 is
/// term j of order n over (j + n + 1). Orders 0 <= n < kKelvinSeriesOrders.
template <typename T>
struct ReducedSeriesPair {
  Complex<T> order_n;
  Complex<T> order_n_plus_1;
};

template <typename T>
ReducedSeriesPair<T> reduced_bessel_i_series_on_kelvin_ray(int n, const T& t) {
  if (n < 0 || n >= kKelvinSeriesOrders) {
    throw std::invalid_argument("Kelvin-ray series: order " + std::to_string(n) + " outside [0, " +
                                std::to_string(kKelvinSeriesOrders - 1) + "]");
  }
  const double* step = kKelvinSeriesFactors.step[n];
  const double* to_next = kKelvinSeriesFactors.next[n];
  T term(kKelvinSeriesFactors.first[n]);  // t^j / (j! (j+n)!)
  // [0]: real parts (even j), [1]: imaginary parts (odd j).
  T sum_n[2] = {term, T(0.0)};
  T sum_next[2] = {term * to_next[0], T(0.0)};
  for (int j = 1; j + 3 < kKelvinSeriesTerms; j += 4) {
    T next;
    for (int k = 0; k < 4; ++k) {  // terms j .. j+3, j = 1 mod 4: i^j = i, -1, -i, 1
      term = term * (t * step[j + k]);
      next = term * to_next[j + k];
      const int part = (k + 1) % 2;
      if (k == 0 || k == 3) {
        sum_n[part] = sum_n[part] + term;
        sum_next[part] = sum_next[part] + next;
      } else {
        sum_n[part] = sum_n[part] - term;
        sum_next[part] = sum_next[part] - next;
      }
    }
    // Converged once each order's term is below 1e-17 of its own sum (compared squared).
    if (biot_detail::below_relative(term, sum_n) && biot_detail::below_relative(next, sum_next)) break;
  }
  return {{sum_n[0], sum_n[1]}, {sum_next[0], sum_next[1]}};
}

/// sum_k (-1)^k a_k(n) / z^k: I_n(z) sqrt(2 pi z) e^{-z} for large |z|, on the Kelvin ray
/// z = x e^{i pi/4}, x > 0. Term k is e^{-i k pi/4} times the real (-1)^k a_k(n) / x^k, so the sum
/// is accumulated in real arithmetic with the eight phases of e^{-i k pi/4}.
template <typename T>
Complex<T> bessel_i_asymptotic_factor_on_kelvin_ray(int n, const T& x) {
  constexpr double h = std::numbers::sqrt2 / 2.0;
  constexpr double kPhaseRe[8] = {1.0, h, 0.0, -h, -1.0, -h, 0.0, h};
  constexpr double kPhaseIm[8] = {0.0, -h, -1.0, -h, 0.0, h, 1.0, h};
  const double mu = 4.0 * n * n;
  const T inverse = T(1.0) / x;
  T term(1.0);
  T re(1.0), im(0.0);
  double previous = 1.0;
  for (int k = 1; k < 40; ++k) {
    const double odd = 2.0 * k - 1.0;
    term = term * inverse * (-(mu - odd * odd) / (8.0 * k));
    const double size = std::abs(biot_detail::value_of(term));
    if (size > previous) break;  // the asymptotic series starts to diverge: stop at its smallest term
    re = re + term * kPhaseRe[k % 8];
    im = im + term * kPhaseIm[k % 8];
    if (size < 1e-17) break;
    previous = size;
  }
  return {re, im};
}

/// z = x e^{i pi/4}.
template <typename T>
Complex<T> kelvin_argument(const T& x) {
  return Complex<T>(x * std::numbers::sqrt2 / 2.0, x * std::numbers::sqrt2 / 2.0);
}

/// I_n(z) at z = x e^{i pi/4}, x >= 0, by the series or the asymptotic form.
template <typename T>
Complex<T> bessel_i_on_kelvin_ray(int n, const T& x) {
  const Complex<T> z = kelvin_argument(x);
  if (biot_detail::value_of(x) < kKelvinSeriesLimit) {
    Complex<T> half_power(T(1.0));
    for (int i = 0; i < n; ++i) half_power = half_power * z / T(2.0);
    return half_power * reduced_bessel_i_series_on_kelvin_ray(n, x * x / T(4.0)).order_n;
  }
  return exp(z) / sqrt(z * T(2.0 * std::numbers::pi)) * bessel_i_asymptotic_factor_on_kelvin_ray(n, x);
}

/// ber x + i bei x (Kelvin functions of order 0), x >= 0.
template <typename T>
Complex<T> kelvin_ber_bei(const T& x) {
  return bessel_i_on_kelvin_ray(0, x);
}

/// ber' x + i bei' x, x >= 0.
template <typename T>
Complex<T> kelvin_ber_bei_derivative(const T& x) {
  const T h = T(std::numbers::sqrt2 / 2.0);
  return Complex<T>(h, h) * bessel_i_on_kelvin_ray(1, x);
}

/// Biot's (1956b) viscous correction F(kappa) for oscillatory flow in a pore of size a,
/// kappa = a sqrt(omega rho_f / eta), as Biot defines it (his exp(+i omega t) convention):
///   F = (kappa/4) T / (1 - 2 T / (i kappa)),  T = (ber' + i bei') / (ber + i bei).
/// F -> 1 for kappa -> 0 (Poiseuille flow) and F -> kappa (1 + i) / (4 sqrt 2) for kappa -> inf.
/// With the Bessel forms above F = (z/4) I_1(z) / I_2(z); the series form R_1/(2 R_2) of the
/// reduced sums avoids the 0/0 of Biot's expression at small kappa.
template <typename T>
Complex<T> biot_viscous_correction_direct(const T& kappa) {
  const Complex<T> z = kelvin_argument(kappa);
  if (biot_detail::value_of(kappa) < kKelvinSeriesLimit) {
    const ReducedSeriesPair<T> r = reduced_bessel_i_series_on_kelvin_ray(1, kappa * kappa / T(4.0));
    return r.order_n / (r.order_n_plus_1 * T(2.0));
  }
  return z / T(4.0) * bessel_i_asymptotic_factor_on_kelvin_ray(1, kappa) /
         bessel_i_asymptotic_factor_on_kelvin_ray(2, kappa);
}

inline Complex<double> biot_viscous_correction(double kappa) { return biot_viscous_correction_direct(kappa); }

/// F(kappa) for a Jet with many derivatives: F depends on the one scalar kappa, so it is evaluated
/// once with a single-derivative Jet and carried onto the N derivatives by the chain rule (the
/// series in N-derivative Jets would cost N times as much).
template <int N>
Complex<ceres::Jet<double, N>> biot_viscous_correction(const ceres::Jet<double, N>& kappa) {
  using Scalar = ceres::Jet<double, 1>;
  const Complex<Scalar> f = biot_viscous_correction_direct(Scalar(kappa.a, 0));
  using J = ceres::Jet<double, N>;
  return {J(f.re.a, f.re.v[0] * kappa.v), J(f.im.a, f.im.v[0] * kappa.v)};
}

// ---- The medium and its compressional waves -------------------------------------------------------

/// A saturated porous medium in SI units. Frame moduli are complex (loss: Im < 0, see the top).
template <typename T>
struct BiotMedium {
  Complex<T> frame_bulk;   ///< K_b [Pa], drained frame bulk modulus
  Complex<T> frame_shear;  ///< mu [Pa], frame shear modulus
  T porosity;              ///< beta [1]
  T grain_density;         ///< rho_s [kg/m^3]
  T grain_bulk;            ///< K_s [Pa]
  T fluid_density;         ///< rho_f [kg/m^3]
  T fluid_bulk;            ///< K_f [Pa]
  T viscosity;             ///< eta [Pa s]
  T permeability;          ///< k [m^2]
  T tortuosity;            ///< alpha_inf [1] (Stoll's structure factor), >= 1
  T pore_size;             ///< a [m], the pore-size parameter of F(kappa)
};

/// The fluid's effective density [kg/m^3] in relative motion (Stoll 1989, ch. 2: Stoll's mass
/// coefficient m = alpha_inf rho_f / beta and viscous term eta F / k; Biot 1956b: F and kappa):
///   m~ = alpha_inf rho_f / beta + i eta F*(kappa) / (k omega),  kappa = a sqrt(omega rho_f / eta).
/// F* because F is published for exp(+i omega t) (Biot 1956b).
template <typename T>
Complex<T> biot_effective_fluid_density(const BiotMedium<T>& m, double omega) {
  using std::sqrt;
  const T kappa = m.pore_size * sqrt(omega * m.fluid_density / m.viscosity);
  const Complex<T> f = biot_viscous_correction(kappa);
  const T drag = m.viscosity / (m.permeability * omega);
  return {m.tortuosity * m.fluid_density / m.porosity + drag * f.im, drag * f.re};
}

/// The slowness-squared quadratic a s^2 - b s + c = 0 (see the top of this file).
template <typename T>
struct BiotQuadratic {
  Complex<T> a;
  Complex<T> b;
  Complex<T> c;
  /// sqrt(b^2 - 4 a c) with the sign that makes |b + root| the larger (no cancellation).
  Complex<T> root;
};

template <typename T>
BiotQuadratic<T> biot_quadratic(const BiotMedium<T>& m, double omega) {
  const BiotModuli<T> bm = biot_moduli(m.frame_bulk, m.frame_shear, m.porosity, m.grain_bulk, m.fluid_bulk);
  const Complex<T> m_eff = biot_effective_fluid_density(m, omega);
  const T rho = mixture_density(m.porosity, m.grain_density, m.fluid_density);
  const T& rho_f = m.fluid_density;
  BiotQuadratic<T> q;
  q.a = bm.H * bm.M - bm.C * bm.C;
  q.b = bm.H * m_eff + bm.M * rho - bm.C * (T(2.0) * rho_f);
  q.c = m_eff * rho - Complex<T>(rho_f * rho_f);
  q.root = sqrt(q.b * q.b - q.a * q.c * T(4.0));
  // Re(conj(b) root) >= 0 puts root along b: |b + root| >= |b - root|.
  if (biot_detail::value_of(q.b.re * q.root.re + q.b.im * q.root.im) < 0.0) q.root = -q.root;
  return q;
}

/// Wave number k [1/m] from slowness squared s at omega: k = omega sqrt(s), Re k > 0.
template <typename T>
Complex<T> wavenumber_from_slowness_squared(const Complex<T>& s, double omega) {
  return sqrt(s) * T(omega);
}

/// The fast compressional wave's wave number [1/m]. The fast wave is the root of smaller |s|:
/// s_fast = 2c / (b + root) (no cancellation; finite also where a = 0, a frame without rigidity).
/// By the choice of root, |s_fast| <= |s_slow| always, so the slow wave is never returned.
template <typename T>
Complex<T> biot_fast_wavenumber(const BiotMedium<T>& m, double omega) {
  const BiotQuadratic<T> q = biot_quadratic(m, omega);
  return wavenumber_from_slowness_squared(q.c * T(2.0) / (q.b + q.root), omega);
}

/// The slow (Biot type II) wave's wave number [1/m]: s_slow = (b + root) / (2a). Infinite when the
/// frame has no rigidity (a = 0); for checks and completeness.
template <typename T>
Complex<T> biot_slow_wavenumber(const BiotMedium<T>& m, double omega) {
  const BiotQuadratic<T> q = biot_quadratic(m, omega);
  return wavenumber_from_slowness_squared((q.b + q.root) / (q.a * T(2.0)), omega);
}

/// The shear wave's wave number [1/m] (Stoll 1989, ch. 2; Biot 1956): the frame's shear modulus mu
/// against the inertia of the frame with the pore fluid it drags,
///   k_s^2 = omega^2 (rho m~ - rho_f^2) / (mu m~),
/// which is omega^2 rho / mu when the fluid moves with the frame (m~ -> infinity, low frequency) and
/// omega^2 (rho - beta rho_f / alpha_inf) / mu without viscous drag (high frequency).
template <typename T>
Complex<T> biot_shear_wavenumber(const BiotMedium<T>& m, double omega) {
  const Complex<T> m_eff = biot_effective_fluid_density(m, omega);
  const T rho = mixture_density(m.porosity, m.grain_density, m.fluid_density);
  const Complex<T> inertia = rho - Complex<T>(m.fluid_density * m.fluid_density) / m_eff;
  return wavenumber_from_slowness_squared(inertia / m.frame_shear, omega);
}

/// Attenuation [Np/m] and phase speed [m/s] of a wave number.
template <typename T>
struct AttenuationSpeed {
  T attenuation;
  T speed;
};

template <typename T>
AttenuationSpeed<T> attenuation_and_speed(const Complex<T>& k, double omega) {
  return {k.im, T(omega) / k.re};
}

/// Frame moduli from a P-wave modulus M_b = K_b + 4/3 mu and the frame's Poisson ratio nu, the
/// relations among the isotropic elastic constants (e.g. Mavko, Mukerji & Dvorkin, The Rock Physics
/// Handbook, its table of isotropic elastic constants):
///   K_b = M_b (1 + nu) / (3 (1 - nu)),  mu = M_b (1 - 2 nu) / (2 (1 - nu)).
template <typename T>
struct FrameModuli {
  Complex<T> bulk;
  Complex<T> shear;
};

template <typename T>
FrameModuli<T> split_p_wave_modulus(const Complex<T>& p_wave_modulus, const T& poisson_ratio) {
  const T one_minus = 1.0 - poisson_ratio;
  return {p_wave_modulus * ((1.0 + poisson_ratio) / (3.0 * one_minus)),
          p_wave_modulus * ((1.0 - 2.0 * poisson_ratio) / (2.0 * one_minus))};
}

}  // namespace sedwave::sediment
