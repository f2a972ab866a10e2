#pragma once
// The linear-response engine: the steady small-amplitude response of a prepared channel to its
// lower wall oscillating at omega, from one sparse complex solve
//   (K + i omega (gamma C1 + D_sponge) - omega^2 M) U = -(K_wall + i omega gamma C1_wall) A e_axis,
// instead of hundreds of thousands of time steps. A loaded far wall (free along z under its static
// load) borders the system with its height as one more unknown. Same packing, drive settings, layers and
// measurement as the time-domain engine (channel/acoustic.hpp), so the two are directly comparable:
// layer-averaged complex displacements along the drive axis, alpha = -d ln|U| / dz and
// k = -d arg U / dz by least squares over the layers between the near field and the absorbing layer.
//
// Where it is valid: wherever contacts neither open nor slide (and gaps do not close) during the
// cycle. Every result counts, from the solved field, how many contacts would open and gaps close at
// the drive amplitude (the response scales with A), warns, and refuses when too many do; the
// time-domain engine is then the right one.
//
// A pore fluid (DriveSettings::fluid) enters as the time-domain engine applies it: squeeze-film
// dashpots between grains closer than its cut-off and drag on every free grain (dynamic_matrices.hpp),
// both linear in the velocities, so the steady response stays exact for them. A channel is built
// for one fluid (or none), and drives must name the same.
//
// Units: dimensionless results, as channel/acoustic.hpp (d, m, kappa; kappa = kn for Hooke, the mean
// tangent stiffness of the contacts for Hertz).
#include <complex>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/channel/packing_units.hpp"
#include "sedwave/forward/channel/contact_network.hpp"
#include "sedwave/forward/linear/dynamic_matrices.hpp"
#include "sedwave/forward/linear/settings.hpp"
#include "sedwave/forward/linear/slab_solver.hpp"

namespace sedwave::forward::linear {

/// Contacts that open, contacts that slide and gaps that close at some drive amplitude: peak
/// relative normal motion beyond the static overlap or gap; with friction, a tangential force
/// (spring and dashpot) beyond mu times the normal force at some phase of the cycle.
struct StateChanges {
  double amplitude = 0.0;       ///< [mean diameters]
  std::int64_t contacts = 0;
  std::int64_t opening = 0;
  std::int64_t sliding = 0;     ///< contacts that stay closed but reach the Coulomb limit
  std::int64_t gaps = 0;        ///< gaps narrower than LinearSettings::gap_search (or a fluid's cut-off)
  std::int64_t closing = 0;
  [[nodiscard]] double fraction() const {
    return contacts > 0 ? static_cast<double>(opening + sliding + closing) / static_cast<double>(contacts) : 0.0;
  }
};

struct LinearResult {
  double omega_hat = 0.0, gamma_hat = 0.0, amplitude = 0.0;
  std::vector<double> layer_z;                    ///< layer centres from the driven wall [d]
  std::vector<int> layer_grains;
  std::vector<std::complex<double>> layer_field;  ///< mean displacement along the drive axis / A
  channel::PropagationFit fit;                    ///< alpha_hat, k_hat, c_hat over the fitted layers
  channel::TwoWaveFit waves;                      ///< the same layers as forward + reflected wave
  int layers_used = 0;
  StateChanges state_changes;                     ///< at the drive amplitude
  /// The same at A = 1e-7, 1e-6, ..., 1e-2 d (the response scales with A): where the linearisation
  /// starts to fail for this packing and frequency.
  std::vector<StateChanges> amplitude_ladder;
  std::string warning;                            ///< set when the linearisation is doubtful
  double solve_seconds = 0.0;
  int iterations = 0;                             ///< equivalent linearisation: iterations (0: plain)
  std::string problem;                            ///< empty when alpha and c were measured
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

class LinearChannel {
 public:
  /// Finds the contacts of `packing` (its grains must be on this rank), assembles K, C1, C_t and M
  /// once, and cuts them into slabs. `fluid`: the pore fluid in the packing's dimensionless groups,
  /// as DriveSettings::fluid holds it (none: dry); gaps are then searched at least up to its
  /// lubrication cut-off. Throws std::invalid_argument for a packing without walls or grains, or a
  /// fluid that FluidSpec::problem() rejects.
  LinearChannel(const channel::PreparedChannel& packing, const dem::ContactSpec& contact, LinearSettings settings = {},
                std::optional<dem::FluidSpec> fluid = std::nullopt);

  /// The steady response to `drive` (its omega_hat, gamma_hat, amplitude, axis, far end, layers).
  /// The far end must be absorbing: in a steady state a frozen end reflects everything. The drive's
  /// fluid must be the channel's (std::invalid_argument otherwise; the same for every solve below).
  [[nodiscard]] LinearResult respond(const channel::DriveSettings& drive) const;

  /// The same with every contact and gap replaced by its equivalent linearisation at the drive
  /// amplitude (equivalent_linearisation.hpp), iterated (under-relaxed) until the field changes by
  /// less than `tolerance` (relative) between iterations. Closes much of the gap to the time-domain
  /// engine where contacts clap; identical to respond() where none does. A fluid's dashpots stay
  /// those of the static gaps (linear in the velocities; a clapping pair keeps its static film).
  [[nodiscard]] LinearResult respond_equivalent(const channel::DriveSettings& drive, int max_iterations = 40,
                                                double tolerance = 1e-6) const;

  /// The linearised equations integrated in time exactly as the time-domain engine integrates the
  /// full ones (velocity Verlet, the wall's sinusoid A sin(omega t), the absorbing layer's drag
  /// applied exactly after each step), recording each layer's mean displacement along the drive axis
  /// [d] every `steps_per_sample` steps from t = 0 (as AcousticResult::displacement). With the DEM
  /// run's time step, the difference between the two records is the nonlinearity alone.
  [[nodiscard]] std::vector<std::vector<double>> integrate(const channel::DriveSettings& drive, double time_step,
                                                           std::int64_t steps, std::int64_t steps_per_sample) const;

  /// Complex displacement amplitudes of the free grains (3 or 6 per node, DynamicMatrices order) per
  /// unit wall amplitude; with a loaded far wall (DriveSettings::far_wall) its z displacement follows
  /// as one more entry.
  [[nodiscard]] Eigen::VectorXcd displacement(const channel::DriveSettings& drive) const;
  /// Which contacts open or slide and gaps close at wall amplitude `amplitude` [d], given the
  /// response `u` per unit wall amplitude.
  [[nodiscard]] StateChanges state_changes(const Eigen::VectorXcd& u, const channel::DriveSettings& drive,
                                           double amplitude) const;
  /// The same at several amplitudes, each pair's motion and sliding onset computed once.
  [[nodiscard]] std::vector<StateChanges> state_changes(const Eigen::VectorXcd& u, const channel::DriveSettings& drive,
                                                        std::span<const double> amplitudes) const;

  /// A grain's (translation, rotation) per unit wall amplitude: its unknowns, or its wall's motion.
  [[nodiscard]] Eigen::Matrix<std::complex<double>, 6, 1> grain_motion(const Eigen::VectorXcd& u,
                                                                      const channel::DriveSettings& drive,
                                                                      std::int32_t grain) const;
  /// The tangential law's sticking spring and dashpot at pair p (none without a tangential law).
  [[nodiscard]] std::optional<dem::TangentialBlock> tangential_block(const StaticPair& p) const;
  /// The linearised force of contact p on its grain i per unit wall amplitude, as assemble()'s K and C
  /// act on the response u: normal spring and dashpot, the pre-stress turning a loaded contact, and
  /// with friction the sticking tangential spring and dashpot.
  [[nodiscard]] Eigen::Vector3cd contact_force(const Eigen::VectorXcd& u, const channel::DriveSettings& drive,
                                               const StaticPair& p) const;

  [[nodiscard]] const channel::PackingUnits& units() const { return units_; }
  [[nodiscard]] const ContactNetwork& network() const { return network_; }
  [[nodiscard]] const DynamicMatrices& matrices() const { return matrices_; }
  [[nodiscard]] const SlabSolver& solver() const { return solver_; }
  [[nodiscard]] const std::vector<dem::Grain>& grains() const { return grains_; }
  [[nodiscard]] const dem::ContactSpec& contact() const { return contact_; }
  /// The pore fluid the channel was built with, in the packing's dimensionless groups (none: dry).
  [[nodiscard]] const std::optional<dem::FluidSpec>& fluid() const { return fluid_; }
  /// The channel's cross-section, the periodic box's x by y extent [length^2].
  [[nodiscard]] double cross_section() const { return cross_section_; }

 private:
  /// Throws std::invalid_argument for a drive the engine cannot solve, or whose fluid is not the channel's.
  void check(const channel::DriveSettings& drive) const;
  /// The fluid in the packing's units for assemble(), or null when dry.
  [[nodiscard]] const dem::FluidSpec* packing_fluid() const { return packing_fluid_ ? &*packing_fluid_ : nullptr; }
  [[nodiscard]] Eigen::VectorXd sponge(const channel::DriveSettings& drive, double omega) const;
  [[nodiscard]] Eigen::VectorXcd solve(const DynamicMatrices& m, const SlabSolver& s, const channel::DriveSettings& d) const;
  /// `refuse`: a result with too many state changes is refused (plain linearisation) or only warned
  /// about (equivalent linearisation, which accounts for them).
  [[nodiscard]] LinearResult measure(const Eigen::VectorXcd& u, const channel::DriveSettings& d, bool refuse) const;
  /// n . (U_i - U_j) of a pair per unit wall amplitude (walls: the driven one moves by e_axis).
  [[nodiscard]] std::complex<double> normal_motion(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                                   const StaticPair& p) const;
  /// The sticking tangential spring and dashpot's force on grain i of contact p per unit wall
  /// amplitude (friction only).
  [[nodiscard]] Eigen::Vector3cd tangential_force(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                                  const StaticPair& p) const;
  /// The wall amplitude [length] at which contact p's tangential force first reaches mu times its
  /// normal force during the cycle (infinity: never, or no friction).
  [[nodiscard]] double sliding_onset(const Eigen::VectorXcd& u, const channel::DriveSettings& d,
                                     const StaticPair& p) const;
  [[nodiscard]] PairLinearisation equivalent_pairs(const Eigen::VectorXcd& u, const channel::DriveSettings& d) const;

  std::vector<dem::Grain> grains_;
  double cross_section_;
  dem::ContactSpec contact_;
  dem::AnyContactModel model_;
  LinearSettings settings_;
  channel::PackingUnits units_;
  std::optional<dem::FluidSpec> fluid_;          ///< dimensionless, as drives name it
  std::optional<dem::FluidSpec> packing_fluid_;  ///< in the packing's units
  ContactNetwork network_;
  DynamicMatrices matrices_;
  SlabSolver solver_;
};

}  // namespace sedwave::forward::linear
