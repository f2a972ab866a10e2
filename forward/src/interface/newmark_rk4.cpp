// The paper's scheme (Wang, Zhang & Vakakis 2021, appendix 1, eqs. 15-18) as GranularPlate's second
// integrator: average-acceleration Newmark for the plate, RK4 for the grains against the plate's
// motion interpolated over the step (eq. 16), the forces on the plate iterated to a fixed point.
//
// Sparse LDL^T (Eigen's SimplicialLDLT) rather than CHOLMOD: M + C dt/2 + K dt^2/4 is symmetric
// positive definite and banded (a structured 2D mesh), Eigen is already a dependency, and the
// factorisation is redone only when the step size changes (the last few are kept).
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <list>
#include <stdexcept>
#include <utility>

#include "sedwave/forward/interface/granular_plate.hpp"

namespace sedwave::forward::interface {

struct GranularPlate::Newmark {
  Eigen::SparseMatrix<double> stiffness;  // K, the held degrees of freedom's rows and columns removed
  struct Factor {
    double dt;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  };
  std::list<Factor> factors;  // most recently used first
};

struct GranularPlate::GrainRates {
  std::vector<double> ax, ay, alpha;  // accelerations
  double friction_power = 0.0, dashpot_power = 0.0, drive_power = 0.0;
};

void GranularPlate::make_newmark() {
  newmark_ = std::make_shared<Newmark>();
  const auto& p = *plate_;
  const auto& fixed = p.fixed();
  std::vector<Eigen::Triplet<double>> entries;
  const auto& ke = p.element_stiffness();
  for (int j = 0; j + 1 < p.nodes_y(); ++j)
    for (int i = 0; i + 1 < p.nodes_x(); ++i) {
      const int nodes[4] = {p.node(i, j), p.node(i + 1, j), p.node(i + 1, j + 1), p.node(i, j + 1)};
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const int da = 2 * nodes[a / 2] + a % 2, db = 2 * nodes[b / 2] + b % 2;
          if (fixed[static_cast<std::size_t>(da)] || fixed[static_cast<std::size_t>(db)]) continue;
          entries.emplace_back(da, db, ke(a, b));
        }
    }
  newmark_->stiffness.resize(p.dof_count(), p.dof_count());
  newmark_->stiffness.setFromTriplets(entries.begin(), entries.end());
}

void GranularPlate::restart_newmark() { newmark_started_ = false; }

// The plate's acceleration from M a = F_contact - K u - C v (lumped M), and the contact forces.
void GranularPlate::start_newmark() {
  compute_forces(0.0, false);
  contact_conservative_ = f_conservative_;
  contact_friction_ = f_friction_;
  std::vector<double> elastic(u_.size(), 0.0);
  plate_->add_elastic_forces(u_, elastic);
  const auto& mass = plate_->mass();
  const auto& damping = plate_->damping();
  newmark_acceleration_.assign(u_.size(), 0.0);
  for (std::size_t d = 0; d < u_.size(); ++d)
    if (!plate_->fixed()[d])
      newmark_acceleration_[d] = (f_conservative_[d] + f_friction_[d] + elastic[d] - damping[d] * v_[d]) / mass[d];
  newmark_started_ = true;
}

// Grain accelerations and the powers of the non-conservative forces at time t, for the grain and
// plate state now in grains_, u_ and v_.
void GranularPlate::evaluate_rates(double t, GrainRates& rates) {
  time_ = t;
  compute_forces(0.0, false);
  const std::size_t n = grains_.size();
  rates.ax.resize(n), rates.ay.resize(n), rates.alpha.resize(n);
  rates.friction_power = rates.dashpot_power = rates.drive_power = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& g = grains_[i];
    const auto &c = conservative_[i], &f = friction_[i], &d = dashpot_[i], &w = drive_[i];
    rates.ax[i] = (c.fx + f.fx + d.fx + w.fx) / g.mass;
    rates.ay[i] = (c.fy + f.fy + d.fy + w.fy) / g.mass;
    rates.alpha[i] = contacts_.rotation ? (c.torque + f.torque) / g.inertia : 0.0;
    rates.friction_power += f.fx * g.vx + f.fy * g.vy + (contacts_.rotation ? f.torque * g.spin : 0.0);
    rates.dashpot_power += d.fx * g.vx + d.fy * g.vy;
    rates.drive_power += w.fx * g.vx + w.fy * g.vy;
  }
  // The friction's reaction on the plate dissipates too; step_newmark_rk4 books it.
}

void GranularPlate::rk4_grains(const std::vector<Grain>& start, double t0, double dt, const std::vector<double>& x0,
                               const std::vector<double>& v0, const std::vector<double>& x1, double works[3]) {
  // Eq. 16: x(t0 + s) = x0 + s v0 + (s/dt)^2 (x1 - x0 - dt v0), and its derivative. The grains meet
  // the top edge's nodes alone (the last row), and the caller sets the whole plate to x1 afterwards:
  // only that row is placed, its curvatures divided out once for the four stages.
  const std::size_t edge = 2 * static_cast<std::size_t>(plate_->node(0, plate_->mesh().elements_y));
  std::vector<double> curvature(u_.size() - edge);
  for (std::size_t d = edge; d < u_.size(); ++d) curvature[d - edge] = (x1[d] - x0[d] - dt * v0[d]) / (dt * dt);
  const auto place_plate = [&](double s) {
    for (std::size_t d = edge; d < u_.size(); ++d) {
      u_[d] = x0[d] + s * v0[d] + s * s * curvature[d - edge];
      v_[d] = v0[d] + 2.0 * s * curvature[d - edge];
    }
  };
  const std::size_t n = start.size();
  GrainRates k[4];
  const double offsets[4] = {0.0, 0.5 * dt, 0.5 * dt, dt};
  for (int stage = 0; stage < 4; ++stage) {
    grains_ = start;
    if (stage > 0) {
      const GrainRates& r = k[stage - 1];
      const double h = offsets[stage];
      // Stage state = start + h (the previous stage's rates): its velocities for the positions,
      // its accelerations for the velocities.
      for (std::size_t i = 0; i < n; ++i) {
        auto& g = grains_[i];
        const auto& prev = stage_velocity_[stage - 1][i];
        g.x += h * prev.vx;
        g.y += h * prev.vy;
        g.vx += h * r.ax[i];
        g.vy += h * r.ay[i];
        g.spin += h * r.alpha[i];
      }
    }
    place_plate(offsets[stage]);
    evaluate_rates(t0 + offsets[stage], k[stage]);
    stage_velocity_[stage].resize(n);
    for (std::size_t i = 0; i < n; ++i) stage_velocity_[stage][i] = {grains_[i].vx, grains_[i].vy, grains_[i].spin};
  }
  grains_ = start;
  for (std::size_t i = 0; i < n; ++i) {
    auto& g = grains_[i];
    const auto sum = [&](auto member) {
      return (stage_velocity_[0][i].*member + 2.0 * stage_velocity_[1][i].*member + 2.0 * stage_velocity_[2][i].*member +
              stage_velocity_[3][i].*member) / 6.0;
    };
    g.x += dt * sum(&Motion::vx);
    g.y += dt * sum(&Motion::vy);
    g.vx += dt * (k[0].ax[i] + 2.0 * k[1].ax[i] + 2.0 * k[2].ax[i] + k[3].ax[i]) / 6.0;
    g.vy += dt * (k[0].ay[i] + 2.0 * k[1].ay[i] + 2.0 * k[2].ay[i] + k[3].ay[i]) / 6.0;
    g.spin += dt * (k[0].alpha[i] + 2.0 * k[1].alpha[i] + 2.0 * k[2].alpha[i] + k[3].alpha[i]) / 6.0;
  }
  const auto weighted = [&](double GrainRates::*power) {
    return dt * (k[0].*power + 2.0 * k[1].*power + 2.0 * k[2].*power + k[3].*power) / 6.0;
  };
  works[0] = -weighted(&GrainRates::friction_power);
  works[1] = -weighted(&GrainRates::dashpot_power);
  works[2] = weighted(&GrainRates::drive_power);
}

double GranularPlate::step_newmark_rk4(double dt) {
  auto& nm = *newmark_;
  if (pairs_stale()) build_pairs();
  if (!newmark_started_) start_newmark();
  const auto& mass = plate_->mass();
  const auto& damping = plate_->damping();
  const auto& fixed = plate_->fixed();
  const std::size_t n = u_.size();

  // M + C dt/2 + K dt^2/4, factorised once per step size (the last four kept).
  auto found = std::find_if(nm.factors.begin(), nm.factors.end(), [&](const Newmark::Factor& f) { return f.dt == dt; });
  if (found == nm.factors.end()) {
    Eigen::SparseMatrix<double> a = (0.25 * dt * dt) * nm.stiffness;
    for (std::size_t d = 0; d < n; ++d) {
      const auto i = static_cast<Eigen::Index>(d);
      a.coeffRef(i, i) += fixed[d] ? 1.0 : mass[d] + 0.5 * dt * damping[d];
    }
    nm.factors.emplace_front();
    nm.factors.front().dt = dt;
    nm.factors.front().solver.compute(a);
    if (nm.factors.front().solver.info() != Eigen::Success)
      throw std::runtime_error("interface: the Newmark matrix M + C dt/2 + K dt^2/4 could not be factorised");
    ++factorisations_;
    if (nm.factors.size() > 4) nm.factors.pop_back();
  } else if (found != nm.factors.begin()) {
    nm.factors.splice(nm.factors.begin(), nm.factors, found);
  }
  const auto& solver = nm.factors.front().solver;

  // Eqs. 21: x1 = x0 + dt v0 + dt^2/4 (a0 + a1), v1 = v0 + dt/2 (a0 + a1), (M + C dt/2 + K dt^2/4) a1
  // = F1 - K (x0 + dt v0 + dt^2/4 a0) - C (v0 + dt/2 a0).
  const std::vector<double> x0 = u_, v0 = v_, a0 = newmark_acceleration_;
  std::vector<double> predicted(n), predicted_v(n), elastic(n, 0.0);
  for (std::size_t d = 0; d < n; ++d) {
    predicted[d] = x0[d] + dt * v0[d] + 0.25 * dt * dt * a0[d];
    predicted_v[d] = v0[d] + 0.5 * dt * a0[d];
  }
  plate_->add_elastic_forces(predicted, elastic);  // -K x_predicted
  const std::vector<Grain> start = grains_;
  const double t0 = time_;
  std::vector<double> force_c = contact_conservative_, force_f = contact_friction_;  // F^(1) = F_s
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n));
  std::vector<double> x1(n), v1(n), a1(n);
  double works[3] = {0.0, 0.0, 0.0};
  int iteration = 0;
  for (bool converged = false; !converged;) {
    if (++iteration > control_.max_iterations) {
      char text[600];
      std::snprintf(text, sizeof text,
                    "interface: the newmark_rk4 iteration of the forces on the plate did not converge in %d iterations "
                    "at t = %.6g s (step %.3g s): the step is beyond the paper's criteria (eqs. 29a,b) or their "
                    "assumptions fail here (lower the step's tolerance), or the iteration's tolerances (%.3g N, "
                    "%.3g relative) lie below what round-off lets the forces settle to (raise them)",
                    control_.max_iterations, t0, dt, control_.abstol, control_.reltol);
      time_ = t0;
      throw std::runtime_error(text);
    }
    for (std::size_t d = 0; d < n; ++d)
      rhs(static_cast<Eigen::Index>(d)) =
          fixed[d] ? 0.0 : force_c[d] + force_f[d] + elastic[d] - damping[d] * predicted_v[d];
    const Eigen::VectorXd a = solver.solve(rhs);
    for (std::size_t d = 0; d < n; ++d) {
      a1[d] = fixed[d] ? 0.0 : a(static_cast<Eigen::Index>(d));
      x1[d] = predicted[d] + 0.25 * dt * dt * a1[d];
      v1[d] = predicted_v[d] + 0.5 * dt * a1[d];
    }
    rk4_grains(start, t0, dt, x0, v0, x1, works);
    // The next iterate of the forces on the plate, from the grains and the plate at t0 + dt.
    u_ = x1;
    v_ = v1;
    time_ = t0 + dt;
    compute_forces(0.0, false);
    converged = true;
    for (std::size_t d = 0; d < n && converged; ++d) {
      const double before = force_c[d] + force_f[d], after = f_conservative_[d] + f_friction_[d];
      const double change = std::abs(after - before);
      converged = change <= control_.abstol || change <= control_.reltol * std::abs(before);
    }
    force_c = f_conservative_;
    force_f = f_friction_;
  }
  iterations_ += iteration;
  most_iterations_ = std::max(most_iterations_, iteration);

  // The energy books. Average-acceleration Newmark changes the plate's energy by exactly
  // (F0 + F1)/2 . (x1 - x0) - dt vbar^T C vbar (vbar = (v0 + v1)/2): the friction's share of the
  // first is its work, the second the absorbing edges'.
  for (std::size_t d = 0; d < n; ++d) {
    const double mean_v = 0.5 * (v0[d] + v1[d]);
    boundary_work_ += dt * damping[d] * mean_v * mean_v;
    friction_work_ -= 0.5 * (contact_friction_[d] + force_f[d]) * (x1[d] - x0[d]);
  }
  friction_work_ += works[0];
  dashpot_work_ += works[1];
  drive_work_ += works[2];
  newmark_acceleration_ = a1;
  contact_conservative_ = force_c;
  contact_friction_ = force_f;
  ++steps_;
  return dt;
}

}  // namespace sedwave::forward::interface
