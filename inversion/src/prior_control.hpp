#pragma once
// Whether the prior, not the data, made a credible interval. A quantity's marginal alone cannot
// tell: along a ridge (a derived quantity such as kappa d gamma that the data do not see) each
// parameter's marginal is narrower than its prior and off its centre, because the ridge runs
// diagonally through the prior's box, yet where the interval lies is decided by the prior alone.
//
// So the posterior is compared with what the data alone allow, direction by direction, in the free
// ln-parameters theta. For a Gaussian likelihood with information matrix F (J^T J of the whitened
// residuals, taken at the posterior's central draw) and prior information P, the posterior precision along a direction is the
// sum of the two, so along a direction u of unit posterior variance the data supply the share
// g(u) = u^T F u of it and the prior the rest, 1 - g(u). The posterior's principal directions in
// these units (the eigenvectors of Sigma^(1/2) F Sigma^(1/2), Sigma the posterior covariance of
// the draws) are uncorrelated, so a quantity's posterior variance splits among them, and its
// "prior share" is the variance-weighted mean of 1 - g over them (clamped to [0, 1]; g > 1 where
// the posterior is wider than the curvature at one point says, as on a bent ridge). A
// quantity is prior-controlled when its prior share exceeds one half: along a ridge it is ~1 (the
// data add nothing there, F ~ 0), for a well-determined quantity under a broad prior ~0, and for a
// Gaussian prior as informative as the data exactly one half.
#include <Eigen/Dense>
#include <optional>

namespace sedwave::inversion::detail {

/// The draw nearest the draws' mean in the posterior's own metric (Mahalanobis distance): where
/// the data's information is taken. At the best fit it can mislead: on a ridge that the data close
/// at one end and the prior's bound at the other, the best fit may sit at the closed end, where the
/// data see the ridge's direction, while most of the posterior lies where they do not.
[[nodiscard]] Eigen::Index central_draw(const Eigen::MatrixXd& ln_samples);

/// The prior's share judged globally, by width: (w_posterior / w_prior)^2 of the central 95 %
/// intervals of a quantity's posterior draws and of its draws under the prior alone, both in the
/// prior's own coordinate (ln for a log-uniform or log-normal prior, the value for a uniform or
/// normal one, ln for a derived quantity), clamped to [0, 1]. For a Gaussian prior and likelihood it is
/// exactly the share above (the posterior variance over the prior's). It sees what the data's
/// information at one draw cannot: on a curved ridge the principal directions of the draws mix the
/// ridge's bends, each looks narrowed by the data, and yet the marginal spans most of its prior.
/// 0 where the prior's draws do not vary.
[[nodiscard]] double prior_width_share(const Eigen::VectorXd& posterior, const Eigen::VectorXd& prior);

/// The prior's share judged against what the data alone allow: 1 - (w_credible / w_profile)^2 of
/// the 68 % credible interval [credible_lower, credible_upper] and the 68 % profile-likelihood
/// interval (profile.hpp; a missing end: open, chi^2 within 1 of its minimum up to the bound), both
/// in ln of the positive quantity, clamped to [0, 1]. For a Gaussian prior and likelihood it is
/// exactly P / (F + P), the share above; where the profile is open on a side the data do not bound
/// the quantity there and the credible interval's end is the prior's: 1. 0 for a quantity the fit
/// knows exactly (a profile of zero width).
[[nodiscard]] double prior_share_against_profile(double credible_lower, double credible_upper,
                                                 std::optional<double> profile_lower,
                                                 std::optional<double> profile_upper);

/// A quantity whose prior share exceeds this is prior-controlled.
inline constexpr double kPriorControlledShare = 0.5;

class PriorControl {
 public:
  /// `ln_samples`: posterior draws x free ln-parameters; `data_information`: the likelihood's
  /// information matrix in the same parameters (J^T J of the whitened residuals at central_draw).
  PriorControl(const Eigen::MatrixXd& ln_samples, const Eigen::MatrixXd& data_information);

  /// The prior's share (0..1) of the posterior variance of `ln_values` (ln of a quantity at each
  /// draw, in the order of the samples).
  [[nodiscard]] double prior_share(const Eigen::VectorXd& ln_values) const;

  /// The data's share g of the posterior precision along each principal direction, ascending.
  [[nodiscard]] const Eigen::VectorXd& data_shares() const { return data_shares_; }

 private:
  Eigen::MatrixXd coordinates_;  ///< draws x directions: each of unit posterior variance, uncorrelated
  Eigen::VectorXd data_shares_;
};

}  // namespace sedwave::inversion::detail
