#pragma once
// The evidence Z = integral of L(x) pi(x) dx over a box in few dimensions (up to about 3) by
// deterministic h-adaptive cubature (S. G. Johnson's hcubature: Genz & Malik 1980, J. Comput. Appl.
// Math. 6, 295, degree-7 rule with an embedded degree-5 rule, the region of largest error bisected
// until the error is small enough), for several priors over the same parameters from the same
// likelihood evaluations (a vector-valued integrand, one column per prior).
//
// The box is the union of the priors' supports. Each coordinate is mapped from [0, 1] by an
// AxisMap: the inverse CDF of a continuous, piecewise-linear density g that the caller puts where
// the posterior is expected (around a fit, along a ridge, at a second mode), plus a floor that
// reaches the whole support. The cubature integrates L pi / prod g over the unit cube: a plateau
// or ridge that the prior closes, several modes and a posterior pressed against a bound all lie
// inside one bounded domain, and a prior support narrower than the box starts a sub-box of its
// own (no column is discontinuous inside a sub-box). The error of each column is hcubature's
// embedded-rule estimate (|degree 7 - degree 5| summed over the regions), summed over the
// sub-boxes: an estimate, not a bound (docs/sampling.md measures it against quadrature).
//
// Reproducible for any thread count: hcubature's subdivision is deterministic, and the threads
// only share each batch of points, each point evaluated on its own.
#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "sedwave/sampling/ensemble.hpp"
#include "sedwave/sampling/importance.hpp"
#include "sedwave/sampling/random_stream.hpp"

namespace sedwave::sampling {

/// A monotone map u in [0, 1] -> x in [nodes.front(), nodes.back()] with dx/du = 1/g(x), g the
/// continuous piecewise-linear density through (nodes[i], density[i]) normalised to 1.
class AxisMap {
 public:
  /// `nodes` strictly increasing (at least two), `density` one positive finite value per node.
  /// Throws std::invalid_argument otherwise.
  AxisMap(std::vector<double> nodes, std::vector<double> density);
  [[nodiscard]] double lower() const { return nodes_.front(); }
  [[nodiscard]] double upper() const { return nodes_.back(); }
  /// x at u (clamped to [0, 1]).
  [[nodiscard]] double at(double u) const;
  /// g(x), normalised; 0 outside [lower, upper].
  [[nodiscard]] double density(double x) const;
  /// The CDF of g at x (0 below, 1 above).
  [[nodiscard]] double cdf(double x) const;

 private:
  std::vector<double> nodes_, density_, cdf_;
};

struct CubatureOptions {
  /// The relative error sought on every column's Z (about the standard error of ln Z).
  double relative_error = 0.003;
  /// Every axis's [0, 1] starts cut into this many equal pieces (besides the supports' ends): the
  /// rule then looks at every part of the box before it judges where the mass is.
  int splits = 4;
  /// Likelihood evaluations allowed in all (the sub-boxes share them); reached first: not converged.
  long max_evaluations = 100000;
  int threads = 1;  ///< share each batch of points; the result does not depend on it
};

struct CubatureEstimate {
  double log_evidence = 0.0;
  /// The estimated error of Z over Z: the embedded-rule estimates summed over the sub-boxes.
  double uncertainty = 0.0;
};

struct CubatureRun {
  std::vector<CubatureEstimate> priors;  ///< one per prior, in the order given
  long evaluations = 0;                  ///< likelihood evaluations
  int boxes = 0;                         ///< sub-boxes integrated
  /// Every sub-box reached its error target within max_evaluations.
  bool converged = false;
};

/// Each prior's evidence with `log_likelihood` (-inf where it has no value) over the box that
/// `axes` span (one per coordinate), the integrand scaled by exp(-log_scale) (e.g. the largest ln L,
/// so that it stays near 1). supports[p] is where prior p is non-zero (a box inside the axes'); a
/// missing entry: the whole box. `reference_log_evidence` (per prior; missing or not finite: none)
/// is a rough ln Z known beforehand (e.g. from importance draws): every sub-box is then integrated
/// to an absolute error of relative_error x that Z over the number of sub-boxes, so that a sub-box
/// with little mass is not refined for its own sake, nor one with much left coarse; without it,
/// each sub-box to relative_error of its own integral. Converged: the summed error of every column
/// is at most relative_error of its Z. Throws std::invalid_argument for no priors or a support
/// outside the box.
[[nodiscard]] CubatureRun cubature_evidence(const LogDensity& log_likelihood, const std::vector<LogDensity>& log_priors,
                                            const std::vector<AxisMap>& axes, double log_scale,
                                            const std::vector<Support>& supports, const CubatureOptions& options = {},
                                            const std::vector<double>& reference_log_evidence = {});

/// Importance sampling from the axes' own density prod g (what the cubature integrates is the
/// weight L pi / prod g): `count` independent draws from one seeded stream, their ln L (evaluated
/// in parallel where some prior is not zero; -inf elsewhere) and each prior's estimate
/// (weighted_estimate): equally weighted posterior draws by resampling, and an estimate of every Z
/// independent of the cubature's rule.
struct MappedSample {
  Eigen::MatrixXd draws;
  Eigen::VectorXd log_likelihood;
  std::vector<ImportanceEstimate> priors;
  int evaluations = 0;
};
[[nodiscard]] MappedSample mapped_importance(const LogDensity& log_likelihood, const std::vector<LogDensity>& log_priors,
                                             const std::vector<AxisMap>& axes, int count, std::uint64_t seed,
                                             int threads = 1);

}  // namespace sedwave::sampling
