// An ordered, pre-compressed 1D Hooke chain driven sinusoidally at one end: the measured wave
// number and attenuation per grain agree with the exact lattice theory (theory/lattice.hpp).
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "dem_test_support.hpp"
#include "sedwave/forward/theory/lattice.hpp"

namespace sedwave::forward::dem {
namespace {

struct Fit {
  double slope;
  double intercept;
};
Fit least_squares(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {slope, (sy - slope * sx) / n};
}

struct MeasuredWave {
  double alpha_hat;  ///< attenuation per grain
  double k_hat;      ///< wave number per grain
};

/// Drives a 200-grain pre-compressed Hooke chain (kappa = 1000, density 1, d = 1) at omega_hat with
/// the dashpot gamma_hat, in `fluid` when given, and locks in on grains 5..40.
MeasuredWave measure_driven_chain(double omega_hat, double gamma_hat, const std::optional<FluidSpec>& fluid = {}) {
  constexpr int n_grains = 200;
  constexpr double precompression = 0.01;  // overlap per contact: contacts never open
  const double m = testing::sphere_mass(1.0, 0.5);
  const double kappa = 1000.0;
  const double time_unit = std::sqrt(m / kappa);
  const double omega = omega_hat / time_unit;
  const double period = 2.0 * std::numbers::pi / omega;

  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact["kn"] = kappa;
  s.contact["gamma"] = gamma_hat * std::sqrt(kappa * m);
  s.skin = 0.05;
  s.fluid = fluid;
  std::vector<Grain> grains;
  for (int n = 0; n < n_grains; ++n) {
    Grain g = testing::make_grain(n, {0, 0, n * (1.0 - precompression)});
    if (n == 0) g.body = 1;             // driver
    if (n == n_grains - 1) g.body = 2;  // fixed far end
    grains.push_back(g);
  }
  std::vector<RigidBody> bodies{RigidBody("driver", Wiggle{2, 1e-4, period}),
                                RigidBody("anchor", Frozen{})};
  Engine engine(MPI_COMM_SELF, s, grains, bodies);

  // Lock-in over whole periods once the start-up transient has passed and before any reflection
  // from the far end could return: U_n = (2/T) sum u_n(t) exp(i omega t) dt.
  constexpr int first = 5, last = 40;
  const double dt = engine.time_step();
  const double t_start = 100.0 * time_unit;
  const double t_stop = t_start + std::floor(200.0 * time_unit / period) * period;
  std::vector<std::complex<double>> amplitude(last - first + 1);
  std::vector<double> rest(n_grains);
  for (int n = 0; n < n_grains; ++n) rest[n] = grains[n].position.z;
  engine.add_step_callback(1, [&](const Engine& e) {
    const double t = e.time();
    if (t < t_start || t >= t_stop) return;
    const GrainArrays& g = e.grains();
    const std::complex<double> phase = std::polar(dt, omega * t);
    for (std::size_t i = 0; i < g.n_local(); ++i) {
      const auto id = static_cast<int>(g.id[i]);
      if (id >= first && id <= last) amplitude[id - first] += (g.position[i].z - rest[id]) * phase;
    }
  });
  engine.run(static_cast<std::int64_t>(std::ceil(t_stop / dt)) + 1);

  std::vector<double> index, log_amplitude, phase;
  for (int n = first; n <= last; ++n) {
    index.push_back(n);
    log_amplitude.push_back(std::log(std::abs(amplitude[n - first])));
    phase.push_back(std::arg(amplitude[n - first]));
  }
  for (std::size_t k = 1; k < phase.size(); ++k)  // unwrap
    while (phase[k] - phase[k - 1] > std::numbers::pi) phase[k] -= 2 * std::numbers::pi;
  for (std::size_t k = 1; k < phase.size(); ++k)
    while (phase[k] - phase[k - 1] < -std::numbers::pi) phase[k] += 2 * std::numbers::pi;
  return {-least_squares(index, log_amplitude).slope, std::abs(least_squares(index, phase).slope)};
}

void expect_matches(const MeasuredWave& w, double omega_hat, std::complex<double> theory) {
  EXPECT_NEAR(w.alpha_hat / theory.imag(), 1.0, 0.01) << "alpha_hat " << w.alpha_hat << " vs " << theory.imag();
  EXPECT_NEAR((omega_hat / w.k_hat) / (omega_hat / theory.real()), 1.0, 0.01)
      << "c_hat " << omega_hat / w.k_hat << " vs " << omega_hat / theory.real();
}

class DrivenChain : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(DrivenChain, WaveSpeedAndAttenuationMatchLatticeTheory) {
  const auto [omega_hat, gamma_hat] = GetParam();
  expect_matches(measure_driven_chain(omega_hat, gamma_hat), omega_hat, lattice_wavenumber(omega_hat, gamma_hat).k);
}

/// The chain's exact dispersion relation with a dashpot gamma_hat across every contact and one of
/// drag_hat from every grain to the ground (all in sqrt(kappa m)): for u_n ~ exp(i(q n - omega t)),
///   -omega^2 = -4 sin^2(q/2) (1 - i omega gamma) + i omega drag,
/// so q = 2 asin(sqrt((omega^2 + i omega drag) / (1 - i omega gamma)) / 2), the root decaying
/// along the chain.
std::complex<double> chain_wavenumber(double omega_hat, double gamma_hat, double drag_hat) {
  using C = std::complex<double>;
  const C z = (omega_hat * omega_hat + C(0.0, omega_hat * drag_hat)) / (1.0 - C(0.0, omega_hat * gamma_hat));
  return 2.0 * std::asin(std::sqrt(z) / 2.0);
}

TEST(DrivenChainInFluid, ClosedFormWithoutFluidIsTheLatticeTheory) {
  for (const auto& [omega_hat, gamma_hat] : {std::pair{0.5, 0.2}, std::pair{1.5, 0.05}}) {
    const std::complex<double> q = chain_wavenumber(omega_hat, gamma_hat, 0.0);
    const std::complex<double> lattice = lattice_wavenumber(omega_hat, gamma_hat).k;
    EXPECT_NEAR(q.real(), lattice.real(), 1e-12 * lattice.real());
    EXPECT_NEAR(q.imag(), lattice.imag(), 1e-12 * lattice.imag());
  }
}

// In the overlapping chain every contact's gap is below the roughness: the squeeze film acts as a
// dashpot 6 pi mu R_eff^2 / h_r beside the contact's, and every grain feels the drag 6 pi mu r f.
TEST(DrivenChainInFluid, LubricationAndDragAreTheLatticeWithTheirDashpots) {
  const double m = testing::sphere_mass(1.0, 0.5), kappa = 1000.0;
  const double unit = std::sqrt(kappa * m);  // of a dashpot
  FluidSpec fluid;
  fluid.viscosity = 0.02;
  fluid.density = 0.0;
  fluid.roughness = 0.01;
  fluid.cutoff = 0.1;  // the second neighbours, 0.98 apart, feel nothing
  fluid.drag = DragLaw::richardson_zaki;
  fluid.porosity = 0.7;
  const double film = 6.0 * std::numbers::pi * fluid.viscosity * 0.25 * 0.25 / fluid.roughness / unit;
  const double drag = 6.0 * std::numbers::pi * fluid.viscosity * 0.5 * std::pow(0.7, 1.0 - 4.65) / unit;
  constexpr double omega_hat = 0.5, gamma_hat = 0.05;
  const MeasuredWave w = measure_driven_chain(omega_hat, gamma_hat, fluid);
  expect_matches(w, omega_hat, chain_wavenumber(omega_hat, gamma_hat + film, drag));
  // And the fluid's share is large enough that a missing term would fail the comparison above.
  EXPECT_GT(chain_wavenumber(omega_hat, gamma_hat + film, drag).imag(),
            1.5 * lattice_wavenumber(omega_hat, gamma_hat).k.imag());
}

INSTANTIATE_TEST_SUITE_P(Lattice, DrivenChain,
                         ::testing::Values(std::pair{0.5, 0.2}, std::pair{1.0, 0.1}, std::pair{1.5, 0.05}));

}  // namespace
}  // namespace sedwave::forward::dem
