#pragma once
// Likelihood profiles (private to the inversion library). The 68 % profile interval of a quantity q
// (a free parameter, or a derived quantity such as c0 or tau) is the set of values t for which chi^2,
// minimised over everything else with q held at t, lies within 1 of the overall minimum (Wilks:
// Delta chi^2 = 1 covers the truth 68 % of the time for one quantity). Unlike the linearised sigma
// it stays honest when the model is strongly nonlinear in q, or when the data leave a direction of
// parameter space flat up to a bound.
//
// How it stays on the valley floor: the minimisation at each new t starts from two points and keeps
// the better: the last minimum, and that minimum moved along the least-constrained path that changes
// q by the step (delta theta = H^-1 a dt / (a^T H^-1 a), with H = J^T J regularised and a = grad ln q;
// along an unseen direction this is exactly the flat ridge). Steps in ln q grow from the linearised
// sigma to at most 1 (a factor e); a Levenberg-Marquardt fit started a factor e^4 away can fall into
// another valley, which would close the interval where chi^2 is in fact flat.
//
// Which ends are open: where chi^2 stays within 1 up to the quantity's own bound, and also where it
// rises only because the re-fit pushed another parameter onto its search bound. Along a ridge the
// data do not see (kappa d gamma of a grain contact at low frequency) holding kappa drags d with it;
// once d sits on its bound, chi^2 climbs, and the profile would close there, at a place the bound
// chose. So at the end found, the rise is compared with what lifting the bounds would take back
// (fall_if_bounds_released, less what it takes back at the best fit): more than half of it, and
// the side is open.
#include <optional>

#include "fit_problem.hpp"

namespace sedwave::inversion::detail {

/// What is profiled: a free parameter (held exactly) or a derived quantity (held by a constraint).
struct ProfiledQuantity {
  int parameter = -1;                      ///< index into theta, or -1 for a derived quantity
  const DerivedFunction* derived = nullptr;
};

struct Profile {
  std::optional<double> lower;  ///< ln units; missing: open (chi^2 stays within 1 up to the bound, or
                                ///< only other parameters' bounds raise it: see above)
  std::optional<double> upper;
  bool bounded_at_2_sigma = true;  ///< both extremes of q within the bounds lie beyond Delta chi^2 = 4
  std::optional<Theta> better;     ///< a point whose chi^2 is below the minimum the fit reported
  double better_chi2 = 0.0;
};

[[nodiscard]] Profile profile(const Setup& s, const Theta& best, double chi2_min, const ProfiledQuantity& q,
                              double linear_sigma, int max_iterations);

/// How much chi^2 at theta, a minimum within the search bounds (with q held, if `held`), would fall
/// if the bounds that hold free parameters there were lifted: the fall of the Gauss-Newton model of
/// chi^2 about theta when the parameters on a bound, with chi^2 falling outwards, may step beyond it
/// and the others follow (q still held), by at most 1 in ln units along each principal direction.
/// 0 where no bound holds a parameter.
[[nodiscard]] double fall_if_bounds_released(const Setup& s, const Theta& theta, const ProfiledQuantity* held);

/// ln q at theta (a parameter's own value, or the derived quantity's).
[[nodiscard]] Differentiated log_quantity(const Setup& s, const Theta& theta, const ProfiledQuantity& q);

}  // namespace sedwave::inversion::detail
