#pragma once
// The plane-wave reflection coefficient R(theta, f) of sea water over a seabed: a fluid or elastic
// half-space, under a stack of fluid or elastic layers (docs/reflection.md).
//
// Conventions:
//   time      e^{-i omega t}; a plane wave e^{i omega (p x + q z) - i omega t}, z down. A lossy
//             medium has the complex slowness s = 1/c + i alpha/omega (c phase speed [m/s], alpha
//             attenuation [Np/m]), so waves decay along their direction of travel.
//   angle     theta is the GRAZING angle, from the horizontal (0: grazing, pi/2: normal
//             incidence); the horizontal slowness is p = cos(theta) / c_w.
//   R         the ratio of reflected to incident pressure at the water-seabed interface.
//             BELLHOP's reflection files carry the complex conjugate (its e^{+i omega t}
//             convention): propagation_files.hpp converts.
//   vertical  q = sqrt(s^2 - p^2) with Im q >= 0 (and q >= 0 when real): downgoing waves decay or
//             propagate downward; evanescent waves decay away from the interface.
//
// Method: Kennett's reflectivity recursion (B. L. N. Kennett, Seismic Wave Propagation in
// Stratified Media, Cambridge 1983, ch. 6; G. Müller, J. Geophys. 58, 153-174 (1985)). The
// reflection matrix of everything below an interface is carried up one layer at a time,
//   R_above = R_D + T_U E R_below E (I - R_U E R_below E)^{-1} T_D,
// with the interface's own reflection and transmission matrices R_D, T_D (wave incident from
// above) and R_U, T_U (from below) and the layer's phase matrix E = diag(e^{i omega q h}). Every
// entry of E has |E| <= 1 (Im q >= 0), so a thick, lossy or evanescent layer only makes numbers
// smaller: nothing grows as Thomson-Haskell propagator products do (e^{+|omega q| h}). In a fluid
// the matrices are 1 x 1 (P); in a solid 2 x 2 (P, SV). Interface matrices solve the boundary
// conditions (continuous normal displacement and normal stress; in addition tangential
// displacement and shear stress between two solids; zero shear stress on a solid facing a fluid)
// with the potentials phi (P) and psi (SV), u = grad phi + curl(psi y).
#include <cmath>
#include <complex>
#include <span>
#include <vector>

namespace sedwave::sediment {

/// One homogeneous medium at one frequency.
struct AcousticMedium {
  double compressional_speed = 0.0;        ///< c_p [m/s], phase speed
  double compressional_attenuation = 0.0;  ///< alpha_p [Np/m]
  double shear_speed = 0.0;                ///< c_s [m/s]; 0: a fluid
  double shear_attenuation = 0.0;          ///< alpha_s [Np/m]
  double density = 0.0;                    ///< [kg/m^3]
  [[nodiscard]] bool is_fluid() const { return shear_speed == 0.0; }
};

/// A layer of the seabed: its medium and thickness [m].
struct MediumLayer {
  AcousticMedium medium;
  double thickness = 0.0;
};

/// Water over layers (top first) over a half-space, all at one frequency.
struct LayeredHalfspace {
  AcousticMedium water;  ///< a lossless fluid: compressional_attenuation and shear_speed must be 0
  std::vector<MediumLayer> layers;
  AcousticMedium halfspace;
};

/// Throws std::invalid_argument naming the medium and value where a speed or density is not
/// finite and positive, an attenuation or thickness is negative, or the water is lossy or solid.
void check_layered_halfspace(const LayeredHalfspace& seabed);

/// R at each grazing angle [rad] in [0, pi/2], at frequency_hz > 0.
[[nodiscard]] std::vector<std::complex<double>> reflection_coefficients(const LayeredHalfspace& seabed,
                                                                        std::span<const double> grazing_angles,
                                                                        double frequency_hz);

/// R at one grazing angle [rad].
[[nodiscard]] std::complex<double> reflection_coefficient(const LayeredHalfspace& seabed, double grazing_angle,
                                                          double frequency_hz);

/// The waves at a water-half-space interface (no layers): R and the potential amplitudes of the
/// transmitted P and S waves per unit incident potential (phi_water = e^{i omega (p x + q z)};
/// transmitted_s is 0 for a fluid). The time-averaged normal energy flux of each wave is
/// proportional to rho Re(q) |amplitude|^2 with one common factor, so
///   |R|^2 + rho_b (Re q_p |T_p|^2 + Re q_s |T_s|^2) / (rho_w q_w) = 1 without loss.
struct InterfaceWaves {
  std::complex<double> reflection;
  std::complex<double> transmitted_p;
  std::complex<double> transmitted_s;
  std::complex<double> water_vertical_slowness;  ///< q_w [s/m]
  std::complex<double> p_vertical_slowness;      ///< q_p of the half-space [s/m]
  std::complex<double> s_vertical_slowness;      ///< q_s of the half-space [s/m] (0 for a fluid)
};
[[nodiscard]] InterfaceWaves interface_waves(const AcousticMedium& water, const AcousticMedium& halfspace,
                                             double grazing_angle, double frequency_hz);

/// Bottom loss -20 log10 |R| [dB].
[[nodiscard]] double bottom_loss_db(std::complex<double> reflection);

/// |R|^2 averaged over frequencies: `samples` equally spaced frequencies across
/// [f_c 2^(-fraction/2), f_c 2^(fraction/2)] (fraction 1/3: a third-octave band), at each angle.
/// `seabed_at` gives the seabed at a frequency (its media are dispersive).
template <typename SeabedAt>
std::vector<double> band_averaged_power(const SeabedAt& seabed_at, std::span<const double> grazing_angles,
                                        double centre_hz, double octave_fraction, int samples);

// ---- implementation of the template --------------------------------------------------------------

template <typename SeabedAt>
std::vector<double> band_averaged_power(const SeabedAt& seabed_at, std::span<const double> grazing_angles,
                                        double centre_hz, double octave_fraction, int samples) {
  std::vector<double> power(grazing_angles.size(), 0.0);
  const double low = centre_hz * std::exp2(-octave_fraction / 2.0);
  const double high = centre_hz * std::exp2(octave_fraction / 2.0);
  const int n = samples < 1 ? 1 : samples;
  for (int i = 0; i < n; ++i) {
    const double f = n == 1 ? centre_hz : low + (high - low) * i / (n - 1);
    const std::vector<std::complex<double>> r = reflection_coefficients(seabed_at(f), grazing_angles, f);
    for (std::size_t j = 0; j < r.size(); ++j) power[j] += std::norm(r[j]) / n;
  }
  return power;
}

}  // namespace sedwave::sediment
