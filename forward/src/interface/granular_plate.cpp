#include "sedwave/forward/interface/granular_plate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/dem/critical_step.hpp"
#include "sedwave/forward/units.hpp"

namespace sedwave::forward::interface {
namespace {

using dem::Vec3;
constexpr double inf = std::numeric_limits<double>::infinity();

/// Whether a contact model's normal law is Hertz's (its step limit ranks pairs by reach_energy).
template <class Model>
constexpr bool hertz_law = std::is_same_v<typename Model::NormalLaw, dem::HertzNormal>;

/// The model's normal law (and its dashpot) alone: no tangential or rolling law.
dem::AnyContactModel normal_law_only(const dem::AnyContactModel& model) {
  return std::visit(
      [](const auto& m) -> dem::AnyContactModel {
        return dem::ContactModel<typename std::decay_t<decltype(m)>::NormalLaw>{m.normal};
      },
      model);
}

}  // namespace

double grain_plate_modulus(const GrainMaterial& grain, const plate::PlateMaterial& plate, PlateContactModel model) {
  if (model == PlateContactModel::rigid_layers)
    return grain.youngs_modulus / (1.0 - grain.poisson_ratio * grain.poisson_ratio);
  return hertz_effective_modulus(grain.youngs_modulus, grain.poisson_ratio, plate.youngs_modulus, plate.poisson_ratio);
}

dem::ContactSpec grain_contact_spec(const InterfaceContacts& contacts, const GrainMaterial& grain) {
  if (contacts.grain_contact) return *contacts.grain_contact;
  dem::ContactSpec spec;
  spec.normal = std::string(dem::HertzNormal::name);
  spec[std::string(dem::keys::youngs_modulus.key)] = grain.youngs_modulus;
  spec[std::string(dem::keys::poisson_ratio.key)] = grain.poisson_ratio;
  if (contacts.restitution < 1.0) spec[std::string(dem::keys::restitution.key)] = contacts.restitution;
  if (contacts.friction > 0.0) {
    spec.tangential = std::string(dem::CoulombTanhFriction::name);
    spec[std::string(dem::keys::friction.key)] = contacts.friction;
    spec[std::string(dem::CoulombTanhFriction::velocity_scale_key.key)] = contacts.tanh_velocity_scale;
  }
  return spec;
}

void check_grains_over_nodes(const std::vector<Grain>& grains, double element_width, double length_x, double reach) {
  const double a = element_width;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const auto& g = grains[i];
    if (!(g.y - g.radius < reach) || g.x < 0.0 || g.x > length_x) continue;
    const double offset = g.x / a - std::round(g.x / a);
    if (std::abs(offset) <= 1e-6) continue;
    const double left = a * std::floor(g.x / a);
    char text[400];
    std::snprintf(text, sizeof text,
                  "interface: the rigid-layer contact acts at the plate's nodes, and grain %zu at x = %.6g m lies "
                  "between the nodes at %.6g and %.6g m: place every grain that can touch the plate over a node",
                  i, g.x, left, left + a);
    throw std::invalid_argument(text);
  }
}

double StepLimits::tightest() const { return std::min({plate, hertz, friction}); }

GranularPlate::GranularPlate(std::vector<Grain> grains, const GrainMaterial& grain_material,
                             std::optional<plate::ElasticPlate> plate, const InterfaceContacts& contacts,
                             const StepControl& control)
    : grains_(std::move(grains)),
      plate_(std::move(plate)),
      contacts_(contacts),
      control_(control),
      grain_model_(dem::make_contact_model(grain_contact_spec(contacts, grain_material))) {
  if (!(control.tolerance > 0.0 && control.tolerance <= 0.5))
    throw std::invalid_argument("interface: step tolerance must lie in (0, 0.5]");
  if (!(control.plate_tolerance >= 0.0 && control.plate_tolerance <= 0.5))
    throw std::invalid_argument("interface: the plate's step tolerance must lie in (0, 0.5] (0: the tolerance)");
  if (control.scheme == Scheme::multirate && control.fixed_step > 0.0)
    throw std::invalid_argument("interface: the multirate scheme chooses its own steps: it takes no fixed step");
  if (!(contacts.friction >= 0.0)) throw std::invalid_argument("interface: friction must be >= 0");
  if (contacts.friction > 0.0 && !(contacts.tanh_velocity_scale > 0.0))
    throw std::invalid_argument("interface: tanh_velocity_scale must be > 0");
  if (plate_) {
    const auto& pm = plate_->material();
    plate_modulus_ = grain_plate_modulus(grain_material, pm, contacts.plate_contact);
    u_.assign(static_cast<std::size_t>(plate_->dof_count()), 0.0);
    v_ = u_;
  }
  double mean_radius = 0.0;
  for (const auto& g : grains_) {
    if (!(g.radius > 0.0 && g.mass > 0.0 && g.inertia > 0.0))
      throw std::invalid_argument("interface: every grain needs radius, mass and inertia > 0");
    mean_radius += g.radius;
  }
  if (!grains_.empty()) mean_radius /= static_cast<double>(grains_.size());
  skin_ = 0.2 * mean_radius;
  if (plate_ && contacts.plate_contact == PlateContactModel::rigid_layers)
    check_grains_over_nodes(grains_, plate_->element_width(), plate_->mesh().length_x, skin_);
  const std::size_t n = grains_.size();
  conservative_.resize(n);
  friction_.resize(n);
  dashpot_.resize(n);
  drive_.resize(n);
  book_plate_dofs();
  build_pairs();
  compute_forces(0.0);
  if (control.scheme == Scheme::newmark_rk4) {
    if (!plate_) throw std::invalid_argument("interface: the newmark_rk4 scheme needs a plate");
    if (dem::needs_history(grain_model_))
      throw std::invalid_argument("interface: the newmark_rk4 scheme takes no grain contact with a tangential history "
                                  "(its RK4 stages would advance the history four times a step)");
    if (!(control.reltol > 0.0 && control.abstol >= 0.0 && control.max_iterations >= 1))
      throw std::invalid_argument("interface: newmark_rk4 needs reltol > 0, abstol >= 0 and max_iterations >= 1");
    make_newmark();
  }
}

void GranularPlate::set_drive(ForcePulse pulse) {
  for (const int g : pulse.grains)
    if (g < 0 || static_cast<std::size_t>(g) >= grains_.size())
      throw std::out_of_range("interface: driven grain index out of range");
  if (!(pulse.duration > 0.0)) throw std::invalid_argument("interface: force pulse duration must be > 0");
  pulse_ = std::move(pulse);
  compute_forces(0.0);
}

void GranularPlate::set_static_load(std::vector<int> grains, double force_x, double force_y) {
  for (const int g : grains)
    if (g < 0 || static_cast<std::size_t>(g) >= grains_.size())
      throw std::out_of_range("interface: loaded grain index out of range");
  loaded_ = std::move(grains);
  load_x_ = force_x;
  load_y_ = force_y;
  compute_forces(0.0);
}

void GranularPlate::set_plate_pulse(PlatePulse pulse) {
  if (!plate_) throw std::invalid_argument("interface: a plate pulse needs a plate");
  if (control_.scheme == Scheme::newmark_rk4)
    throw std::invalid_argument("interface: the newmark_rk4 scheme takes no pulse on the plate (its load at the step's "
                                "ends would not deliver a rectangular pulse's impulse)");
  if (pulse.forces.size() != u_.size())
    throw std::invalid_argument("interface: a plate pulse needs one force per degree of freedom");
  if (!(pulse.duration > 0.0)) throw std::invalid_argument("interface: plate pulse duration must be > 0");
  plate_pulse_ = std::move(pulse);
  book_plate_dofs();
}

double GranularPlate::plate_pulse_time(double t0, double t1) const {
  if (!plate_pulse_) return 0.0;
  return std::max(0.0, std::min(t1, plate_pulse_->duration) - std::max(t0, 0.0));
}

long GranularPlate::relax(double damping_time, double tolerance, long max_steps) {
  if (!(damping_time > 0.0)) throw std::invalid_argument("interface: relaxation damping time must be > 0");
  const auto kinetic = [&] {
    const Energies e = energies_without_strain();
    return e.grain_translation + e.grain_rotation + e.plate_kinetic;
  };
  // Frictionless while relaxing (the header says why): the grains' normal law alone, no friction at
  // the plate or the walls; the books of the edge's x velocities follow. Tangential springs start
  // from the static state unloaded.
  const dem::AnyContactModel grain_model = grain_model_;
  const double friction = contacts_.friction, wall_friction = walls_.friction;
  set_grain_model(normal_law_only(grain_model));
  contacts_.friction = walls_.friction = 0.0;
  std::fill(shear_.begin(), shear_.end(), dem::Vec3{});
  book_plate_dofs();
  refresh_forces();
  double largest = 0.0;
  long n = 0;
  for (; n < max_steps; ++n) {
    const double dt = step();
    const double keep = std::exp(-dt / damping_time);
    for (auto& g : grains_) g.vx *= keep, g.vy *= keep, g.spin *= keep;
    for (auto& v : v_) v *= keep;
    step_rates_.reset();
    restart_newmark();
    const double now = kinetic();
    largest = std::max(largest, now);
    if (n > 10 && now < tolerance * largest) break;
  }
  set_grain_model(grain_model);
  contacts_.friction = friction;
  walls_.friction = wall_friction;
  book_plate_dofs();
  if (n == max_steps)
    throw std::runtime_error("interface: the loaded packing did not come to rest in " + std::to_string(max_steps) +
                             " steps (Coulomb-tanh has no static friction: a packing free to spread creeps under a "
                             "static load unless side walls hold it)");
  for (auto& g : grains_) g.vx = g.vy = g.spin = 0.0;
  std::fill(v_.begin(), v_.end(), 0.0);
  time_ = 0.0;
  steps_ = plate_steps_ = 0;
  iterations_ = factorisations_ = 0;
  most_iterations_ = 0;
  friction_work_ = dashpot_work_ = boundary_work_ = drive_work_ = 0.0;
  max_plate_contact_radius_ = 0.0;
  refresh_forces();
  tangential_energy_origin_ = tangential_energy_;
  return n;
}

void GranularPlate::refresh_forces() {
  restart_newmark();
  build_pairs();
  compute_forces(0.0);
}

// Cell list over the packing's bounding box; a pair is listed while |x_i - x_j| < r_i + r_j + skin
// and the list is rebuilt once any grain has moved skin/2 (as the DEM engine does, docs/dem.md).
void GranularPlate::build_pairs() {
  // A touching pair stays listed (it is within the skin), so its history moves to its new slot.
  std::unordered_map<long long, dem::Vec3> history;
  const auto key = [n = static_cast<long long>(grains_.size())](const Pair& p) { return p.i * n + p.j; };
  for (std::size_t k = 0; k < shear_.size(); ++k)
    if (dem::norm2(shear_[k]) > 0.0) history.emplace(key(pairs_[k]), shear_[k]);
  pairs_.clear();
  shear_.clear();
  pair_facts_.clear();
  x_at_build_.resize(grains_.size());
  y_at_build_.resize(grains_.size());
  if (grains_.empty()) {
    tabulate_pairs();  // an empty table of the model's type
    return;
  }
  double x0 = inf, y0 = inf, x1 = -inf, y1 = -inf, r_max = 0.0;
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& g = grains_[i];
    x0 = std::min(x0, g.x), x1 = std::max(x1, g.x), y0 = std::min(y0, g.y), y1 = std::max(y1, g.y);
    r_max = std::max(r_max, g.radius);
    x_at_build_[i] = g.x;
    y_at_build_[i] = g.y;
  }
  if (!std::isfinite(x1 - x0) || !std::isfinite(y1 - y0))
    throw std::runtime_error("interface: a grain's position is no longer finite at t = " + std::to_string(time_) +
                             " s: the integration is unstable (a fixed step above a contact's stability limit?)");
  const double cell = 2.0 * r_max + skin_;
  const int nx = static_cast<int>((x1 - x0) / cell) + 1;
  const int ny = static_cast<int>((y1 - y0) / cell) + 1;
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  auto cell_of = [&](const Grain& g) {
    const int cx = std::min(static_cast<int>((g.x - x0) / cell), nx - 1);
    const int cy = std::min(static_cast<int>((g.y - y0) / cell), ny - 1);
    return std::pair{cx, cy};
  };
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto [cx, cy] = cell_of(grains_[i]);
    cells[static_cast<std::size_t>(cy * nx + cx)].push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& gi = grains_[i];
    const auto [cx, cy] = cell_of(gi);
    for (int oy = std::max(cy - 1, 0); oy <= std::min(cy + 1, ny - 1); ++oy)
      for (int ox = std::max(cx - 1, 0); ox <= std::min(cx + 1, nx - 1); ++ox)
        for (const int j : cells[static_cast<std::size_t>(oy * nx + ox)]) {
          if (j <= static_cast<int>(i)) continue;
          const auto& gj = grains_[static_cast<std::size_t>(j)];
          const double reach = gi.radius + gj.radius + skin_;
          const double dx = gi.x - gj.x, dy = gi.y - gj.y;
          if (dx * dx + dy * dy < reach * reach) pairs_.push_back({static_cast<int>(i), j});
        }
  }
  shear_.assign(pairs_.size(), dem::Vec3{});
  pair_facts_.assign(pairs_.size(), PairFacts{});
  tabulate_pairs();
  if (history.empty()) return;
  for (std::size_t k = 0; k < pairs_.size(); ++k)
    if (const auto it = history.find(key(pairs_[k])); it != history.end()) shear_[k] = it->second;
}

void GranularPlate::set_grain_model(const dem::AnyContactModel& model) {
  grain_model_ = model;
  step_rates_.reset();
  tabulate_pairs();
}

void GranularPlate::tabulate_pairs() {
  std::visit(
      [&]<class Model>(const Model& model) {
        if (!std::holds_alternative<dem::PairTable<Model>>(pair_table_)) pair_table_.emplace<dem::PairTable<Model>>();
        auto& table = std::get<dem::PairTable<Model>>(pair_table_).pairs;
        table.clear();
        pair_constants_.clear();
        for (const auto& p : pairs_) {
          const auto& gi = grains_[static_cast<std::size_t>(p.i)];
          const auto& gj = grains_[static_cast<std::size_t>(p.j)];
          PairConstants c;
          c.reach = gi.radius + gj.radius;
          c.mass = gi.mass * gj.mass / (gi.mass + gj.mass);
          c.radius = gi.radius * gj.radius / (gi.radius + gj.radius);
          if constexpr (hertz_law<Model>) {
            const double k = dem::HertzNormal::stiffness(model.normal.effective_modulus, c.radius);
            c.closing_factor = 1.25 * c.mass / k;
            if (pair_constants_.empty()) rate_scale_ = k / c.mass;
            const double ratio = k / c.mass / rate_scale_;
            c.rate_weight = ratio * ratio * ratio * ratio * ratio;
          }
          c.inverse_mass = 1.0 / gi.mass + 1.0 / gj.mass;
          pair_constants_.push_back(c);
          table.push_back(model.pair(c.mass, gi.radius, gj.radius));
        }
      },
      grain_model_);
}

bool GranularPlate::pairs_stale() const {
  const double limit = 0.25 * skin_ * skin_;
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const double dx = grains_[i].x - x_at_build_[i], dy = grains_[i].y - y_at_build_[i];
    if (!(dx * dx + dy * dy <= limit)) return true;  // moved, or no longer finite: build_pairs says which
  }
  return false;
}

// Each grain pair's rates for the step limit (dem/critical_step.hpp), the largest of each over the
// pairs that touch or close. A Hertz normal law is evaluated at the largest overlap a collision can
// reach (reach_energy): its omega^2 = (3/2)(k/m) delta_max^(1/2) grows with (k/m)^5 delta_max^(5/2), so
// the search keeps the pair with the largest of those ((k/m)^5 against the first listed pair's, so
// that nothing overflows, tabulated with the list) and takes one root, for that pair, at the end
// instead of a power per pair. The tangential and rolling laws are evaluated at the overlap and normal
// force now, on the slip's inertia 1/m_t = 1/m_i + 1/m_j + a_i^2/I_i + a_j^2/I_j (m/7 for two equal
// spheres with rotation) and the relative spin's 1/I_i + 1/I_j.
template <class Model>
void GranularPlate::note_pair_rates(const Model& model, const PairConstants& constants,
                                    const typename Model::Pair& law_pair, const Grain& gi, const Grain& gj,
                                    double overlap, double normal_velocity, double normal_force, double inverse_mt,
                                    RateSearch& search) const {
  if constexpr (hertz_law<Model>) {
    note_reach(constants, reach_energy(overlap, normal_velocity, constants.closing_factor), search);
  } else {
    const double m = constants.mass;
    const dem::ContactOscillator n = model.normal.oscillator(m, constants.radius, overlap);
    search.rates.normal_omega_squared = std::max(search.rates.normal_omega_squared, n.stiffness / m);
    search.rates.normal_beta = std::max(search.rates.normal_beta, n.damping / m);
  }
  if (overlap > 0.0) note_slip_rates(model, constants, law_pair, gi, gj, overlap, normal_force, inverse_mt, search);
}

void GranularPlate::note_reach(const PairConstants& constants, double reach_now, RateSearch& search) {
  if (const double x = constants.rate_weight * reach_now; x > search.largest) {
    search.largest = x;
    search.mass = constants.mass, search.radius = constants.radius, search.reach = reach_now;
  }
}

template <class Model>
void GranularPlate::note_slip_rates(const Model& model, const PairConstants& constants,
                                    const typename Model::Pair& law_pair, const Grain& gi, const Grain& gj,
                                    double overlap, double normal_force, double inverse_mt, RateSearch& search) const {
  if constexpr (Model::rotates) {
    if constexpr (Model::has_tangential) {
      // Coulomb-tanh is a dashpot mu |F_n| k_s at small slip (the 2021 paper, appendix 1, eq. 29b).
      const dem::ContactOscillator t = model.tangential.oscillator(constants.mass, constants.radius, overlap, normal_force);
      search.rates.tangential_omega_squared =
          std::max(search.rates.tangential_omega_squared, t.stiffness * inverse_mt);
      search.rates.tangential_beta = std::max(search.rates.tangential_beta, t.damping * inverse_mt);
    }
    if constexpr (Model::has_rolling) {
      // Below omega_reg the rolling torque is a dashpot mu_r R_eff |F_n| / omega_reg on the relative spin.
      if (contacts_.rotation) {
        const double beta = law_pair.rolling.lever * normal_force / model.rolling.regularising_spin_rate *
                            (1.0 / gi.inertia + 1.0 / gj.inertia);
        search.rates.rolling_beta = std::max(search.rates.rolling_beta, beta);
      }
    }
  }
}

template <class Model>
dem::PairRates GranularPlate::finish_rates(const Model& model, const RateSearch& search) const {
  dem::PairRates rates = search.rates;
  if constexpr (hertz_law<Model>) {
    if (search.largest > 0.0) {
      // The law's tangent stiffness and dashpot at the largest overlap a collision can reach.
      const dem::ContactOscillator n = model.normal.oscillator(search.mass, search.radius, std::pow(search.reach, 0.4));
      rates.normal_omega_squared = n.stiffness / search.mass;
      rates.normal_beta = n.damping / search.mass;
    }
  }
  return rates;
}

// The DEM engine's contact model in the plane (dem/contact/contact_model.hpp): its slip, lever arms
// and torques. The books split its force: the normal law's spring is conservative, the rest of the
// normal force is its dashpot, the tangential force and the torques go to friction (with a
// tangential spring's energy taken back out of it in energies()).
template <class Model>
void GranularPlate::add_grain_pair(const Model& model, const Pair& p, double d2, const PairConstants& constants,
                                   const typename Model::Pair& law_pair, double dt, Vec3& shear, PairFacts& facts,
                                   bool damps, RateSearch* search) {
  auto& gi = grains_[static_cast<std::size_t>(p.i)];
  auto& gj = grains_[static_cast<std::size_t>(p.j)];
  const double dx = gi.x - gj.x, dy = gi.y - gj.y;
  const double d = std::sqrt(d2);
  const double overlap = constants.reach - d;
  const double nx = dx / d, ny = dy / d;
  const auto& si = seen_[static_cast<std::size_t>(p.i)];
  const auto& sj = seen_[static_cast<std::size_t>(p.j)];
  const Vec3 relative{si.vx - sj.vx, si.vy - sj.vy, 0.0};
  const double vn = relative.x * nx + relative.y * ny;
  const dem::ContactPoint point{{nx, ny, 0.0}, overlap, vn, gi.radius, gj.radius};
  // The normal law's spring and dashpot apart (the books need both); its force is spring - dashpot v_n.
  const double spring = model.normal.spring(overlap, law_pair.normal);
  const double dashpot_coefficient = damps ? model.normal.dashpot_at(overlap, law_pair.normal) : 0.0;  // 0 without
  const dem::PairResult r =
      model.evaluate_with_normal_force(spring - dashpot_coefficient * vn, point, law_pair, relative,
                                       {0.0, 0.0, si.spin}, {0.0, 0.0, sj.spin}, dt, shear);
  const double dashpot_force = r.normal_force - spring;
  facts.d2 = d2, facts.d = d, facts.spring = spring, facts.dashpot = dashpot_coefficient;
  if constexpr (Model::rotates && Model::has_tangential)
    facts.inverse_slip_mass = inverse_slip_mass(constants, gi, gj, overlap);
  auto& ci = conservative_[static_cast<std::size_t>(p.i)];
  auto& cj = conservative_[static_cast<std::size_t>(p.j)];
  ci.fx += spring * nx, ci.fy += spring * ny, cj.fx -= spring * nx, cj.fy -= spring * ny;
  auto& di = dashpot_[static_cast<std::size_t>(p.i)];
  auto& dj = dashpot_[static_cast<std::size_t>(p.j)];
  di.fx += dashpot_force * nx, di.fy += dashpot_force * ny, dj.fx -= dashpot_force * nx, dj.fy -= dashpot_force * ny;
  contact_energy_ += Model::NormalLaw::energy_of_force(spring, overlap);
  if constexpr (Model::rotates) {
    const double fx = r.force.x - r.normal_force * nx, fy = r.force.y - r.normal_force * ny;
    auto& fi = friction_[static_cast<std::size_t>(p.i)];
    auto& fj = friction_[static_cast<std::size_t>(p.j)];
    fi.fx += fx, fi.fy += fy, fj.fx -= fx, fj.fy -= fy;
    fi.torque += r.torque_i.z;
    fj.torque += r.torque_j.z;
    if constexpr (Model::has_tangential) {
      const double stored = model.tangential.energy(overlap, gi.radius, gj.radius, shear);
      contact_energy_ += stored;
      tangential_energy_ += stored;
    }
  }
  if (search)
    note_pair_rates(model, constants, law_pair, gi, gj, overlap, vn, std::abs(r.normal_force), facts.inverse_slip_mass,
                    *search);
}

// add_grain_pair for the default contact, in three passes: the touching pairs' geometry and motion
// gathered into arrays, every contact evaluated in SIMD lanes, and the forces, torques, energies and
// rates added pair by pair (two pairs of a grain in one lane set would collide in its sums).
void GranularPlate::add_planar_pairs(const PlanarLaw& model, const std::vector<PlanarLaw::Pair>& table,
                                     std::size_t touching, bool damps, RateSearch* search) {
  PlanarScratch& s = planar_;
  s.hold(touching);
  for (std::size_t c = 0; c < touching; ++c) {
    const auto [k, d2] = touching_[c];
    const auto i = static_cast<std::size_t>(pairs_[k].i), j = static_cast<std::size_t>(pairs_[k].j);
    const auto &gi = grains_[i], &gj = grains_[j];
    s.d2[c] = d2, s.dx[c] = gi.x - gj.x, s.dy[c] = gi.y - gj.y;
    s.dvx[c] = seen_[i].vx - seen_[j].vx, s.dvy[c] = seen_[i].vy - seen_[j].vy;
    s.spin_i[c] = seen_[i].spin, s.spin_j[c] = seen_[j].spin;
    s.radius_i[c] = gi.radius, s.radius_j[c] = gj.radius, s.inertia_i[c] = gi.inertia, s.inertia_j[c] = gj.inertia;
    s.effective_radius[c] = table[k].normal.effective_radius, s.damping[c] = table[k].normal.damping;
    s.reach[c] = pair_constants_[k].reach, s.inverse_mass[c] = pair_constants_[k].inverse_mass;
    s.closing_factor[c] = pair_constants_[k].closing_factor;
  }
  evaluate_planar_contacts(model.normal, model.tangential, damps, contacts_.rotation,
                           {s.d2.data(), s.dx.data(), s.dy.data(), s.dvx.data(), s.dvy.data(), s.spin_i.data(),
                            s.spin_j.data(), s.radius_i.data(), s.radius_j.data(), s.inertia_i.data(),
                            s.inertia_j.data(), s.effective_radius.data(), s.damping.data(), s.reach.data(),
                            s.inverse_mass.data(), s.closing_factor.data()},
                           {s.distance.data(), s.nx.data(), s.ny.data(), s.overlap.data(), s.normal_velocity.data(),
                            s.spring.data(), s.dashpot.data(), s.tangential.data(), s.inverse_slip_mass.data(),
                            s.reach_energy.data()},
                           touching);
  for (std::size_t c = 0; c < touching; ++c) {
    const std::size_t k = touching_[c].pair;
    const auto i = static_cast<std::size_t>(pairs_[k].i), j = static_cast<std::size_t>(pairs_[k].j);
    const double nx = s.nx[c], ny = s.ny[c], overlap = s.overlap[c], spring = s.spring[c];
    const double dashpot_force = -s.dashpot[c] * s.normal_velocity[c];
    const double ft = s.tangential[c], fx = -ft * ny, fy = ft * nx;  // along t = (-n_y, n_x)
    auto &ci = conservative_[i], &cj = conservative_[j];
    ci.fx += spring * nx, ci.fy += spring * ny, cj.fx -= spring * nx, cj.fy -= spring * ny;
    if (damps) {
      auto &di = dashpot_[i], &dj = dashpot_[j];
      di.fx += dashpot_force * nx, di.fy += dashpot_force * ny;
      dj.fx -= dashpot_force * nx, dj.fy -= dashpot_force * ny;
    }
    auto &fi = friction_[i], &fj = friction_[j];
    fi.fx += fx, fi.fy += fy, fj.fx -= fx, fj.fy -= fy;
    const double arm_i = s.radius_i[c] - 0.5 * overlap, arm_j = s.radius_j[c] - 0.5 * overlap;
    fi.torque -= arm_i * ft;
    fj.torque -= arm_j * ft;
    contact_energy_ += dem::HertzNormal::energy_of_force(spring, overlap);
    auto& facts = pair_facts_[k];
    facts.d2 = s.d2[c], facts.d = s.distance[c], facts.spring = spring, facts.dashpot = s.dashpot[c];
    facts.inverse_slip_mass = s.inverse_slip_mass[c];
    if (search) {
      note_reach(pair_constants_[k], s.reach_energy[c], *search);
      note_slip_rates(model, pair_constants_[k], table[k], grains_[i], grains_[j], overlap,
                      std::abs(spring + dashpot_force), facts.inverse_slip_mass, *search);
    }
  }
}

// How far grain g presses into the deformed top edge at its contact point e [m] (> 0: touching).
double GranularPlate::plate_overlap(const Grain& g, const plate::ElasticPlate::EdgePoint& e) const {
  const double edge_y = e.shape_left * u_[static_cast<std::size_t>(2 * e.node_left + 1)] +
                        e.shape_right * u_[static_cast<std::size_t>(2 * e.node_right + 1)];
  return g.radius - (g.y - edge_y);
}

void GranularPlate::add_plate_contact(int index) {
  auto& g = grains_[static_cast<std::size_t>(index)];
  const auto& mesh = plate_->mesh();
  if (g.x < 0.0 || g.x > mesh.length_x) return;  // beyond the plate's ends
  const auto e = contact_point(g.x);
  const auto ya = static_cast<std::size_t>(2 * e.node_left + 1), yb = static_cast<std::size_t>(2 * e.node_right + 1);
  const double overlap = plate_overlap(g, e);
  if (overlap <= 0.0) return;
  // Hertz sphere on a flat: R* = r. Force = -grad of (2/5) k delta^(5/2) with
  // delta = r - y_g + sum_a N_a(x_g) u_a: on the grain +F_n along y and -F_n du_y/dx along x (the
  // tilt of the deformed edge), on node a -F_n N_a along y.
  // With rigid layers e names one node at weight 1: no tilt, and everything acts on that node.
  const double contact_radius = std::sqrt(g.radius * overlap);
  const double fn = plate_law().spring(overlap, {g.radius, 0.0});
  const double slope = (u_[yb] - u_[ya]) / plate_->element_width();
  auto& c = conservative_[static_cast<std::size_t>(index)];
  c.fy += fn;
  c.fx -= fn * slope;
  f_conservative_[ya] -= fn * e.shape_left;
  f_conservative_[yb] -= fn * e.shape_right;
  contact_energy_ += dem::HertzNormal::energy_of_force(fn, overlap);
  plate_normal_force_ += fn;
  max_plate_contact_radius_ = std::max(max_plate_contact_radius_, contact_radius);
  if (contacts_.friction <= 0.0) return;
  const auto xa = static_cast<std::size_t>(2 * e.node_left), xb = static_cast<std::size_t>(2 * e.node_right);
  // Slip of the grain's lowest point against the edge: v_x + w r - v_edge,x (z x (-r y) = r x).
  const double edge_vx = e.shape_left * plate_seen_[xa] + e.shape_right * plate_seen_[xb];
  const auto& seen = seen_[static_cast<std::size_t>(index)];
  const Vec3 slip{seen.vx + seen.spin * g.radius - edge_vx, 0.0, 0.0};
  const dem::CoulombTanhFriction friction{contacts_.friction, contacts_.tanh_velocity_scale};
  const dem::ContactPoint point{{0.0, 1.0, 0.0}, overlap, 0.0, g.radius, inf};
  Vec3 unused;
  const double ft = friction.force(point, {}, slip, fn, 0.0, unused).x;
  auto& f = friction_[static_cast<std::size_t>(index)];
  f.fx += ft;
  f.torque += g.radius * ft;  // (-r y) x (F_t x) = r F_t z
  f_friction_[xa] -= ft * e.shape_left;
  f_friction_[xb] -= ft * e.shape_right;
  plate_tangential_force_ -= ft;
}

// A grain whose lowest point is above this height neither touches the top edge nor comes within
// the skin of it (the edge lies nowhere above its highest node; the margin is twice the skin), so
// the contact and step-limit loops pass it by without locating it on the edge. Infinite while the
// edge is not finite, so that an unstable run still reaches every grain.
double GranularPlate::contact_ceiling() const {
  const int top = plate_->node(0, plate_->mesh().elements_y);
  double highest = -inf, sum = 0.0;
  for (int i = 0; i < plate_->nodes_x(); ++i) {
    const double uy = u_[static_cast<std::size_t>(2 * (top + i) + 1)];
    highest = std::max(highest, uy);
    sum += uy;
  }
  return std::isfinite(sum) ? highest + 2.0 * skin_ : inf;
}

plate::ElasticPlate::EdgePoint GranularPlate::contact_point(double x) const {
  return contacts_.plate_contact == PlateContactModel::rigid_layers ? plate_->top_edge_node(x)
                                                                    : plate_->top_edge_point(x);
}

// Velocity-dependent forces (friction, dashpots) at t + dt see the half-step velocity advanced by the
// old acceleration, v(t + dt/2) + (dt/2) a(t), which is v(t + dt) to O(dt^2). With the half-step
// velocity itself (as LAMMPS and the DEM engine do) they are first order, and so is the whole
// frictional run (measured: order 1.2 in the tolerance instead of 2).
// Without friction or dashpots nothing reads them but a dashpot of zero: they are the velocities.
void GranularPlate::compute_forces(double half_step, bool with_elastic, double slow_half_step) {
  seen_.resize(grains_.size());
  const bool damps = damped(), velocity_forces = rubbing() || damps;
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& g = grains_[i];
    if (!velocity_forces) {
      seen_[i] = {g.vx, g.vy, g.spin};
      continue;
    }
    const auto &c = conservative_[i], &f = friction_[i], &d = dashpot_[i], &w = drive_[i];
    seen_[i] = {g.vx + half_step * (c.fx + f.fx + d.fx + w.fx) / g.mass,
                g.vy + half_step * (c.fy + f.fy + d.fy + w.fy) / g.mass,
                contacts_.rotation ? g.spin + half_step * (c.torque + f.torque) / g.inertia : 0.0};
  }
  if (plate_ && contacts_.friction > 0.0) {
    // Friction's slip reads the top edge's x velocities only.
    plate_seen_.resize(v_.size());
    const auto& inverse_mass = plate_->inverse_mass();
    const auto& damping = plate_->damping();
    const int top = plate_->node(0, plate_->mesh().elements_y);
    const bool split = multirate() && !f_elastic_.empty();
    for (int i = 0; i < plate_->nodes_x(); ++i) {
      const auto d = static_cast<std::size_t>(2 * (top + i));
      const double force = f_conservative_.empty() ? 0.0 : f_conservative_[d] + f_friction_[d];
      // multirate: the contacts' substep, and the outer half kick of the internal forces and the
      // dashpot where it ends the outer step.
      plate_seen_[d] = plate_->fixed()[d] ? 0.0
                       : split ? v_[d] + (half_step * force + slow_half_step * (f_elastic_[d] - damping[d] * v_[d])) *
                                             inverse_mass[d]
                               : v_[d] + half_step * (force - damping[d] * v_[d]) * inverse_mass[d];
    }
  }
  std::fill(conservative_.begin(), conservative_.end(), Parts{});
  std::fill(friction_.begin(), friction_.end(), Parts{});
  std::fill(dashpot_.begin(), dashpot_.end(), Parts{});
  std::fill(drive_.begin(), drive_.end(), Parts{});
  contact_energy_ = 0.0;
  plate_normal_force_ = plate_tangential_force_ = 0.0;
  wall_force_[0] = wall_force_[1] = 0.0;
  tangential_energy_ = 0.0;
  std::visit(
      [&]<class Model>(const Model& model) {
        const auto& table = std::get<dem::PairTable<Model>>(pair_table_).pairs;
        // The touching pairs first, packed without a branch, so that the force loop takes no branch on
        // a pair's state and the roots of successive contacts overlap; an open contact forgets its
        // history. The pairs that close without touching are packed beside them for the step limit.
        touching_.resize(pairs_.size());
        closing_.resize(pairs_.size());
        std::size_t touching = 0, closing = 0;
        for (std::size_t k = 0; k < pairs_.size(); ++k) {
          const auto i = static_cast<std::size_t>(pairs_[k].i), j = static_cast<std::size_t>(pairs_[k].j);
          const auto &gi = grains_[i], &gj = grains_[j];
          const double dx = gi.x - gj.x, dy = gi.y - gj.y, reach = pair_constants_[k].reach;
          const double d2 = dx * dx + dy * dy;
          const double approach = (seen_[i].vx - seen_[j].vx) * dx + (seen_[i].vy - seen_[j].vy) * dy;
          const bool touches = d2 < reach * reach;
          touching_[touching] = {k, d2};
          closing_[closing] = {k, d2, approach};
          touching += touches ? 1 : 0;
          closing += !touches && approach < 0.0 ? 1 : 0;
          if constexpr (Model::needs_history)
            if (!touches) shear_[k] = Vec3{};
        }
        // The step limit's rates, at the velocities the forces see, for the scheme that steps by them
        // (newmark_rk4 evaluates forces within its step; its limits are taken from its state afresh).
        RateSearch search;
        RateSearch* const rates = control_.scheme == Scheme::newmark_rk4 ? nullptr : &search;
        if constexpr (std::is_same_v<Model, PlanarLaw>) {
          add_planar_pairs(model, table, touching, damps, rates);
        } else {
          for (std::size_t c = 0; c < touching; ++c) {
            const auto [k, d2] = touching_[c];
            add_grain_pair(model, pairs_[k], d2, pair_constants_[k], table[k], 2.0 * half_step, shear_[k],
                           pair_facts_[k], damps, rates);
          }
        }
        if (!rates) {
          step_rates_.reset();
          return;
        }
        for (std::size_t c = 0; c < closing; ++c) {
          const auto [k, d2, approach] = closing_[c];
          const double d = std::sqrt(d2);
          const auto& p = pairs_[k];
          note_pair_rates(model, pair_constants_[k], table[k], grains_[static_cast<std::size_t>(p.i)],
                          grains_[static_cast<std::size_t>(p.j)], pair_constants_[k].reach - d, approach / d, 0.0, 0.0,
                          search);
        }
        step_rates_ = finish_rates(model, search);
      },
      grain_model_);
  if (plate_) {
    // The elastic forces overwrite f_conservative_; friction acts on the top edge's x components
    // alone, so only that row of f_friction_ is cleared once it has been sized. multirate: the
    // elastic forces have their own array, and the contacts act on the top edge alone.
    if (multirate()) {
      if (with_elastic) slow_forces();
      if (f_conservative_.size() != u_.size())
        f_conservative_.assign(u_.size(), 0.0);
      else
        std::fill(f_conservative_.begin() + static_cast<std::ptrdiff_t>(subcycled_dof()), f_conservative_.end(), 0.0);
      plate_->add_top_row_forces(u_, f_conservative_);
    } else if (with_elastic) {
      plate_->elastic_forces(u_, f_conservative_);
    } else {
      f_conservative_.assign(u_.size(), 0.0);
    }
    if (f_friction_.size() != u_.size())
      f_friction_.assign(u_.size(), 0.0);
    else
      std::fill(f_friction_.begin() + 2 * plate_->node(0, plate_->mesh().elements_y), f_friction_.end(), 0.0);
    const double ceiling = contact_ceiling();
    for (std::size_t g = 0; g < grains_.size(); ++g)
      if (!(grains_[g].y - grains_[g].radius > ceiling)) add_plate_contact(static_cast<int>(g));
  }
  if (walls_.left || walls_.right)
    for (std::size_t g = 0; g < grains_.size(); ++g) add_wall_contacts(static_cast<int>(g));
  for (const int g : loaded_) {
    drive_[static_cast<std::size_t>(g)].fx += load_x_;
    drive_[static_cast<std::size_t>(g)].fy += load_y_;
  }
  if (pulse_ && time_ < pulse_->duration) {
    const double f = pulse_->peak * std::sin(std::numbers::pi * time_ / pulse_->duration);
    for (const int g : pulse_->grains) {
      drive_[static_cast<std::size_t>(g)].fx += f * pulse_->direction_x;
      drive_[static_cast<std::size_t>(g)].fy += f * pulse_->direction_y;
    }
  }
}

bool GranularPlate::rubbing() const {
  const bool grain_law_rubs = std::visit([](const auto& model) { return std::decay_t<decltype(model)>::rotates; },
                                         grain_model_);
  return grain_law_rubs || contacts_.friction > 0.0 || walls_.friction > 0.0;
}

// The plate's and the walls' contacts have no dashpot; the grains' normal law has one where its
// damping is positive at any overlap.
bool GranularPlate::damped() const {
  return std::visit([](const auto& model) { return model.normal.oscillator(1.0, 1.0, 1e-6).damping > 0.0; },
                    grain_model_);
}

// Half a kick (h = dt/2). The kinetic energy changes by exactly h F . (v + v')/2 in a kick, so the
// work of each non-conservative force is summed the same way and the energy balance closes to the
// conservative forces' integration error alone.
void GranularPlate::kick(double h, bool second_half, double plate_drift) {
  kick_grains(h);
  if (plate_) kick_plate(h, second_half, plate_drift, f_conservative_, f_friction_.data(), v_.size());
}

void GranularPlate::kick_grains(double h) {
  // The works are summed in locals (in the same order): stores through g could alias the members.
  // A kind of force that the scene does not have is exactly zero on every grain, and so is its work:
  // its sum is left out (three serial additions a grain that bound the loop).
  double friction_work = friction_work_, dashpot_work = dashpot_work_, drive_work = drive_work_;
  const bool rubs = rubbing(), damps = damped();
  const bool driven = !loaded_.empty() || pulse_.has_value();
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    auto& g = grains_[i];
    const auto &c = conservative_[i], &f = friction_[i], &d = dashpot_[i], &w = drive_[i];
    const double vx = g.vx, vy = g.vy, spin = g.spin;
    g.vx += h * (c.fx + f.fx + d.fx + w.fx) / g.mass;
    g.vy += h * (c.fy + f.fy + d.fy + w.fy) / g.mass;
    const double mx = 0.5 * (vx + g.vx), my = 0.5 * (vy + g.vy);
    if (rubs) friction_work -= h * (f.fx * mx + f.fy * my);
    if (damps) dashpot_work -= h * (d.fx * mx + d.fy * my);
    if (driven) drive_work += h * (w.fx * mx + w.fy * my);
    if (contacts_.rotation) {
      g.spin += h * (c.torque + f.torque) / g.inertia;
      if (rubs) friction_work -= h * f.torque * 0.5 * (spin + g.spin);
    }
  }
  friction_work_ = friction_work, dashpot_work_ = dashpot_work, drive_work_ = drive_work;
}

void GranularPlate::book_plate_dofs() {
  booked_.clear();
  if (!plate_) return;
  const auto& fixed = plate_->fixed();
  const auto& damping = plate_->damping();
  const int top = plate_->node(0, plate_->mesh().elements_y);
  for (std::size_t d = 0; d < fixed.size(); ++d) {
    const bool rubbed = contacts_.friction > 0.0 && d % 2 == 0 && d >= static_cast<std::size_t>(2 * top);
    const bool pulsed = plate_pulse_ && plate_pulse_->forces[d] != 0.0;
    if (!fixed[d] && (damping[d] > 0.0 || rubbed || pulsed)) booked_.push_back(d);
  }
}

// Every free degree of freedom but the booked ones (booked_: a dashpot, friction or a pulse, along
// the edges) takes v += h f / m in one pass without books, between the booked ones; those take their
// dashpot and their work after it. Held ones have inverse mass 0 and stay put. With drift > 0 the
// same pass moves the plate, u += drift v, on the velocity just kicked.
void GranularPlate::kick_plate(double h, bool second_half, double drift, const std::vector<double>& forces,
                               const double* friction, std::size_t end) {
  const auto& inverse_mass = plate_->inverse_mass();
  const auto& damping = plate_->damping();
  // The half kick spans [t, t + h] before the drift, [t - h, t] after it (time_ has moved on).
  const double on = second_half ? plate_pulse_time(time_ - h, time_) : plate_pulse_time(time_, time_ + h);
  const double* pulse = on > 0.0 ? plate_pulse_->forces.data() : nullptr;
  const double pulse_share = on / h;  // the pulse's mean force over the half kick, per unit force
  const double* fc = forces.data();
  const double* im = inverse_mass.data();
  double* v = v_.data();
  double* u = u_.data();
  // Friction and pulses act on booked degrees of freedom alone: the pass has the elastic and
  // contact forces only.
  const auto pass = [&](std::size_t from, std::size_t to) {
    if (drift > 0.0)
      for (std::size_t d = from; d < to; ++d) {
        v[d] += h * fc[d] * im[d];
        u[d] += drift * v[d];
      }
    else
      for (std::size_t d = from; d < to; ++d) v[d] += h * fc[d] * im[d];
  };
  const auto booked_end = std::lower_bound(booked_.begin(), booked_.end(), end);
  std::size_t from = 0;
  for (auto d = booked_.begin(); d != booked_end; ++d) pass(from, *d), from = *d + 1;
  pass(from, end);
  // The works are summed in locals (in the same order): stores through v could alias the members.
  double boundary_work = boundary_work_, friction_work = friction_work_, drive_work = drive_work_;
  for (auto booked = booked_.begin(); booked != booked_end; ++booked) {
    const std::size_t d = *booked;
    const double before = v[d];
    const double load = pulse ? pulse[d] * pulse_share : 0.0;
    const double rub = friction ? friction[d] : 0.0;
    const double force = fc[d] + rub + load;
    // The edge dashpots are diagonal: explicit in the first half kick, implicit in the second, so a
    // full step multiplies a free dashpot's velocity by (1 - h c/m)/(1 + h c/m), stable for any c.
    double dashpot_velocity = before;
    if (second_half) {
      v[d] = (before + h * force * im[d]) / (1.0 + h * damping[d] * im[d]);
      dashpot_velocity = v[d];
    } else {
      v[d] = before + h * (force - damping[d] * before) * im[d];
    }
    if (drift > 0.0) u[d] += drift * v[d];
    const double mean = 0.5 * (before + v[d]);
    boundary_work += h * damping[d] * dashpot_velocity * mean;
    friction_work -= h * rub * mean;
    drive_work += h * load * mean;
  }
  boundary_work_ = boundary_work, friction_work_ = friction_work, drive_work_ = drive_work;
}

double GranularPlate::inverse_slip_mass(const PairConstants& constants, const Grain& gi, const Grain& gj,
                                        double overlap) const {
  return constants.inverse_mass +
         (turning_inverse_mass(gi, gi.radius - 0.5 * overlap) + turning_inverse_mass(gj, gj.radius - 0.5 * overlap));
}

void GranularPlate::drift_grains(double h) {
  for (auto& g : grains_) {
    g.x += h * g.vx;
    g.y += h * g.vy;
  }
}

template <class Model>
dem::PairRates GranularPlate::grain_pair_rates(const Model& model) const {
  RateSearch search;
  const auto& table = std::get<dem::PairTable<Model>>(pair_table_).pairs;  // the model's (set_grain_model)
  for (std::size_t listed = 0; listed < pairs_.size(); ++listed) {
    const auto& p = pairs_[listed];
    const auto& gi = grains_[static_cast<std::size_t>(p.i)];
    const auto& gj = grains_[static_cast<std::size_t>(p.j)];
    const double dx = gi.x - gj.x, dy = gi.y - gj.y;
    const double d2 = dx * dx + dy * dy;
    const PairConstants& constants = pair_constants_[listed];
    const double reach = constants.reach;
    const double approach = (gi.vx - gj.vx) * dx + (gi.vy - gj.vy) * dy;
    if (d2 >= reach * reach && approach >= 0.0) continue;  // apart and not closing: no root, no division
    // A pair that touched at the last force evaluation at this very distance: what it computed then.
    const PairFacts& facts = pair_facts_[listed];
    const bool known = facts.d2 == d2;
    const double d = known ? facts.d : std::sqrt(d2);
    const double overlap = reach - d;
    const double vn = approach / d;
    if (overlap <= 0.0 && vn >= 0.0) continue;
    double fn = 0.0, inverse_mt = 0.0;
    if constexpr (Model::rotates) {
      if (overlap > 0.0) {
        // The normal law's force is its spring less its dashpot times v_n (hertz.hpp, hooke.hpp).
        fn = known ? std::abs(facts.spring - facts.dashpot * vn)
                   : std::abs(model.normal.force({{}, overlap, vn, gi.radius, gj.radius}, table[listed].normal));
        if constexpr (Model::has_tangential)
          inverse_mt = known ? facts.inverse_slip_mass : inverse_slip_mass(constants, gi, gj, overlap);
      }
    }
    note_pair_rates(model, constants, table[listed], gi, gj, overlap, vn, fn, inverse_mt, search);
  }
  return finish_rates(model, search);
}

StepLimits GranularPlate::current_limits() const {
  return limits_with(std::visit([&](const auto& model) { return grain_pair_rates(model); }, grain_model_));
}

StepLimits GranularPlate::next_limits() const { return step_rates_ ? limits_with(*step_rates_) : current_limits(); }

// The grain pairs' rates and the beads on the plate, whose Hertz limits take the same largest-reach
// trick. Coulomb-tanh limits fall with their beta alone.
StepLimits GranularPlate::limits_with(const dem::PairRates& pair_rates) const {
  StepLimits limits;
  const double omega_plate = plate_ ? plate_->max_frequency_bound() : 0.0;
  if (plate_) limits.plate = plate_->stable_time_step();
  const double mu_ks = contacts_.friction * contacts_.tanh_velocity_scale;
  // The forces see the predicted velocity (compute_forces), and the packing's collective modes
  // outrun a pair's (dem/critical_step.hpp): one oscillator of the pairs' largest rates scaled to them.
  const bool spin = contacts_.rotation;
  dem::PairRates normal_rates;
  normal_rates.normal_omega_squared = pair_rates.normal_omega_squared;
  normal_rates.normal_beta = pair_rates.normal_beta;
  if (normal_rates.normal_omega_squared > 0.0 || normal_rates.normal_beta > 0.0)
    limits.hertz = dem::hexagonal_packing_critical_step(normal_rates, spin);
  if (pair_rates.tangential_omega_squared > 0.0 || pair_rates.tangential_beta > 0.0 || pair_rates.rolling_beta > 0.0)
    limits.friction = dem::hexagonal_packing_critical_step(pair_rates, spin);
  // The packing's collective friction damping: a bead rubbing on its neighbours and on a wall or the
  // plate feels both, and the largest eigenvalue of a sum is at most the sum of theirs.
  dem::PairRates rubbing = pair_rates;
  rubbing.normal_omega_squared = rubbing.normal_beta = rubbing.tangential_omega_squared = 0.0;
  const double collective_friction = dem::hexagonal_collective(rubbing, spin).beta;
  const double wall_beta = tighten_with_walls(limits, collective_friction);
  double v2_max = 0.0;
  for (const auto& g : grains_) v2_max = std::max(v2_max, g.vx * g.vx + g.vy * g.vy);
  if (v2_max > 0.0) limits.travel = 0.5 * skin_ / std::sqrt(v2_max);
  if (!plate_) return limits;
  const auto& mass = plate_->mass();
  double plate_scale = 0.0, plate_largest = 0.0, plate_beta = 0.0;
  // newmark_rk4: the paper's criteria (eqs. 29a,b) with T (M + K dt^2/4)^-1 T^T bounded by sum N_a^2/M_a
  // (K is positive semi-definite) and cosh^-2 by 1: |lambda_1| < 1 is dt < 2/omega with
  // omega^2 = (3/2) k delta^(1/2) sum N_a^2/M_a, |lambda_2| < 1 is dt < 2/beta with
  // beta = mu k_s |N| sum N_a^2/M_a. The paper neglects the granule's own sensitivity; a bead lighter
  // than its node then blows up at that step (docs/interface.md, "Two schemes"), so the bead's
  // inverse mass (and r^2/I along the edge) is added to sum N_a^2/M_a.
  const bool newmark = control_.scheme == Scheme::newmark_rk4;
  double newmark_omega2 = 0.0;
  const double ceiling = contact_ceiling();
  for (const auto& g : grains_) {
    if (g.x < 0.0 || g.x > plate_->mesh().length_x || g.y - g.radius > ceiling) continue;
    const auto e = contact_point(g.x);
    const auto ya = static_cast<std::size_t>(2 * e.node_left + 1), yb = static_cast<std::size_t>(2 * e.node_right + 1);
    const double overlap = plate_overlap(g, e);
    if (overlap < -skin_) continue;
    const double vn = g.vy - (e.shape_left * v_[ya] + e.shape_right * v_[yb]);
    if (overlap <= 0.0 && vn >= 0.0) continue;
    // The edge moves with the nodes: 1/m_eff = 1/m_g + sum_a N_a^2 / M_a; the slip adds r^2/I with
    // rotation (2m/7 on a rigid wall; x and y masses of a node are equal).
    const double edge_inverse_mass =
        e.shape_left * e.shape_left / mass[ya] + e.shape_right * e.shape_right / mass[yb];
    const double inverse_m = 1.0 / g.mass + edge_inverse_mass;
    const double inverse_mt = inverse_m + turning_inverse_mass(g, g.radius);
    const double k = dem::HertzNormal::stiffness(plate_modulus_, g.radius);
    const double reach_now = reach_energy(overlap, vn, 1.25 / (inverse_m * k));
    if (newmark) {
      newmark_omega2 = std::max(newmark_omega2, 1.5 * k * std::pow(reach_now, 0.2) * inverse_m);  // delta_max^(1/2)
      if (mu_ks > 0.0 && overlap > 0.0)
        plate_beta = std::max(plate_beta, mu_ks * k * overlap * std::sqrt(overlap) * inverse_mt);
      continue;
    }
    if (plate_scale == 0.0) plate_scale = k * inverse_m;
    const double ratio = k * inverse_m / plate_scale;
    plate_largest = std::max(plate_largest, ratio * ratio * ratio * ratio * ratio * reach_now);
    if (mu_ks > 0.0 && overlap > 0.0) {
      const double fn = k * overlap * std::sqrt(overlap);
      plate_beta = std::max(plate_beta, mu_ks * fn * inverse_mt);
    }
  }
  if (newmark) {
    // |lambda_1| < 1 and |lambda_2| < 1 are the spring's and the dashpot's half-step Verlet limits.
    if (newmark_omega2 > 0.0)
      limits.hertz = std::min(limits.hertz, dem::verlet_critical_step(std::sqrt(newmark_omega2), 0.0));
    if (plate_beta > 0.0) limits.friction = std::min(limits.friction, dem::verlet_critical_step(0.0, plate_beta));
    return limits;
  }
  // The contact spring adds to the nodes' own stiffness: omega^2 <= omega_FE^2 + k_t / m_eff.
  if (plate_largest > 0.0) {
    const double omega2 = omega_plate * omega_plate + 1.5 * plate_scale * std::pow(plate_largest, 0.2);
    limits.hertz = std::min(limits.hertz, dem::predicted_velocity_critical_step(std::sqrt(omega2), 0.0));
  }
  // A grain on the plate also rubs on its neighbours and may rub on a wall: their dampings add.
  if (plate_beta > 0.0)
    limits.friction = std::min(limits.friction, dem::predicted_velocity_critical_step(
                                                    omega_plate, plate_beta + wall_beta + collective_friction));
  return limits;
}

// A bead on a wall is one oscillator against a fixed body: the wall couples no two beads, so the
// walls' operators are diagonal and their largest rate is the largest bead's, with no collective
// factor of their own. Its forces see the predicted velocity like every other (compute_forces), so
// its limits are predicted_velocity_critical_step's: the Hertz spring (3/2) k delta_max^(1/2) / m at
// the largest overlap the bead can reach, 2/omega; Coulomb-tanh a dashpot mu k_s |F_n| on the slip's
// inertia 1/m + r^2/I (1/m with rotation off; the wall does not move), whose damping adds to the packing's collective
// friction (`collective_friction`): 1/(beta_wall + collective). Returns beta_wall (0 without
// friction) for the plate's limit, where a bead may rub on the plate, a wall and its neighbours.
double GranularPlate::tighten_with_walls(StepLimits& limits, double collective_friction) const {
  if (!walls_.left && !walls_.right) return 0.0;
  const double mu_ks = walls_.friction * contacts_.tanh_velocity_scale;
  double omega2 = 0.0, beta = 0.0;
  for (const auto& g : grains_)
    for (const auto& [face, normal] : {std::pair{walls_.left, 1.0}, std::pair{walls_.right, -1.0}}) {
      if (!face) continue;
      const double overlap = wall_overlap(g, *face, normal);
      const double vn = normal * g.vx;  // > 0: leaving the wall
      if (overlap < -skin_ || (overlap <= 0.0 && vn >= 0.0)) continue;
      const double k = dem::HertzNormal::stiffness(walls_.modulus, g.radius);
      const double reach_now = reach_energy(overlap, vn, 1.25 * g.mass / k);
      omega2 = std::max(omega2, 1.5 * k * std::pow(reach_now, 0.2) / g.mass);
      if (mu_ks > 0.0 && overlap > 0.0) {
        const double inverse_mt = 1.0 / g.mass + turning_inverse_mass(g, g.radius);
        beta = std::max(beta, mu_ks * k * overlap * std::sqrt(overlap) * inverse_mt);
      }
    }
  if (omega2 > 0.0)
    limits.hertz = std::min(limits.hertz, dem::predicted_velocity_critical_step(std::sqrt(omega2), 0.0));
  if (beta > 0.0)
    limits.friction = std::min(limits.friction, dem::predicted_velocity_critical_step(0.0, beta + collective_friction));
  return beta;
}

double GranularPlate::step(double max_dt) { return step_with(next_limits(), max_dt); }

double GranularPlate::free_step(const StepLimits& limits) const {
  if (control_.fixed_step > 0.0) return control_.fixed_step;
  if (!multirate()) return substep_free(limits);
  // The outer step holds a whole number of the substeps the grains can take now, so that a substep
  // cut short to land on its end is rare.
  const double theta = control_.plate_tolerance > 0.0 ? control_.plate_tolerance : control_.tolerance;
  const double outer = std::min(theta * limits.plate, control_.max_step), inner = substep_free(limits);
  return inner < outer ? inner * std::floor(outer / inner) : outer;
}

double GranularPlate::substep_free(const StepLimits& limits) const {
  return std::min({control_.tolerance * limits.tightest(), limits.travel, control_.max_step});
}

double GranularPlate::step_with(const StepLimits& limits, double max_dt) {
  limits_ = limits;
  const double dt = std::min(free_step(limits), max_dt);
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::logic_error("interface: no time scale bounds the step (no plate, no contacts, no motion)");
  if (multirate()) return step_multirate(limits, dt);
  ++plate_steps_;
  if (control_.scheme == Scheme::newmark_rk4) {
    // On a ladder of steps theta T_FE 2^-k (unless fixed or cut to land on a time), so that the
    // factorisation of M + C dt/2 + K dt^2/4 serves many steps.
    const double ladder = control_.tolerance * limits_.plate;
    const bool on_ladder = control_.fixed_step <= 0.0 && dt < max_dt && dt < ladder;
    const double taken = step_newmark_rk4(on_ladder ? ladder * std::exp2(-std::ceil(std::log2(ladder / dt))) : dt);
    substep_min_ = substep_max_ = taken;
    return taken;
  }
  substep_min_ = substep_max_ = dt;
  kick(0.5 * dt, false, dt);  // and the plate's drift
  drift_grains(dt);
  time_ += dt;
  if (pairs_stale()) build_pairs();
  compute_forces(0.5 * dt);
  kick(0.5 * dt, true);
  ++steps_;
  return dt;
}

// The plate's internal forces but those of its top row of elements (and its edge dashpots and
// pulses) are the slow part, kicked at the outer step's ends; the contacts and the top row of
// elements are the fast part, integrated in substeps by the grains and the two top rows of nodes,
// each the step the single-rate scheme would take. The other nodes keep their velocity through the
// substeps and drift once, in the first outer kick's pass; the two top rows take their slow kicks
// with the first and the last substep's. The outer step is a fraction of the plate's own limit, so
// it resolves every oscillation of the slow part and resonates with no substep. With one substep
// this is the velocity-Verlet step.
double GranularPlate::step_multirate(const StepLimits& limits, double dt) {
  const std::size_t fast = subcycled_dof();
  kick_plate(0.5 * dt, false, dt, f_elastic_, nullptr, fast);
  const double end = time_ + dt;
  substep_min_ = inf, substep_max_ = 0.0;
  StepLimits now = limits;
  for (bool first = true; time_ < end; first = false) {
    if (!first) now = next_limits();
    const double h = substep(now, end, first ? dt : 0.0, dt);
    substep_min_ = std::min(substep_min_, h), substep_max_ = std::max(substep_max_, h);
  }
  kick_plate(0.5 * dt, true, 0.0, f_elastic_, nullptr, fast);
  ++plate_steps_;
  return dt;
}

void GranularPlate::slow_forces() {
  plate_->elastic_forces(u_, f_elastic_);
  plate_->add_top_row_forces(u_, f_elastic_, -1.0);
}

double GranularPlate::substep(const StepLimits& limits, double end, double opening, double outer) {
  const double left = end - time_;
  const double free = substep_free(limits);
  // Land on the outer step's end without a sliver: the last two substeps share what is left (a
  // substep within round-off of what is left is the last).
  const bool last = !(left > free * (1.0 + 1e-12));
  const double h = last ? left : left < 2.0 * free ? 0.5 * left : free;
  if (!(h > 0.0)) throw std::logic_error("interface: a multirate substep of no length");
  kick_grains(0.5 * h);
  kick_edge(0.5 * h, h, 0.5 * opening, false);
  drift_grains(h);
  time_ = last ? end : time_ + h;
  if (pairs_stale()) build_pairs();
  compute_forces(0.5 * h, false, last ? 0.5 * outer : 0.0);
  if (last) slow_forces();
  kick_grains(0.5 * h);
  kick_edge(0.5 * h, 0.0, last ? 0.5 * outer : 0.0, true);
  ++steps_;
  return h;
}

// The two top rows of nodes: the fast forces over h, and where the substep opens or closes the outer
// step the slow forces, a pulse on the plate and the edge dashpots over slow_h in the same kick
// (the dashpot explicit before the drift, implicit after it, as kick_plate), so that one substep is
// the velocity-Verlet step, books included. The booked degrees of freedom book their works.
void GranularPlate::kick_edge(double h, double drift, double slow_h, bool second_half) {
  const auto& inverse_mass = plate_->inverse_mass();
  const std::size_t fast = subcycled_dof();
  if (slow_h <= 0.0) {  // within the outer step: the fast forces alone, friction's work booked
    double friction_work = friction_work_;
    const bool rubs = contacts_.friction > 0.0;
    for (std::size_t d = fast; d < v_.size(); ++d) {
      const double before = v_[d];
      v_[d] += h * (f_conservative_[d] + f_friction_[d]) * inverse_mass[d];
      if (rubs) friction_work -= h * f_friction_[d] * 0.5 * (before + v_[d]);
      u_[d] += drift * v_[d];
    }
    friction_work_ = friction_work;
    return;
  }
  const auto& damping = plate_->damping();
  const double on = second_half ? plate_pulse_time(time_ - slow_h, time_) : plate_pulse_time(time_, time_ + slow_h);
  const double* pulse = on > 0.0 ? plate_pulse_->forces.data() : nullptr;
  const double pulse_share = on / slow_h;
  double boundary_work = boundary_work_, friction_work = friction_work_, drive_work = drive_work_;
  auto booked = std::lower_bound(booked_.begin(), booked_.end(), fast);
  for (std::size_t d = fast; d < v_.size(); ++d) {
    const double impulse = h * f_conservative_[d] + slow_h * f_elastic_[d];
    if (booked == booked_.end() || *booked != d) {
      v_[d] += impulse * inverse_mass[d];
      u_[d] += drift * v_[d];
      continue;
    }
    ++booked;
    const double before = v_[d], rub = f_friction_[d];
    const double load = pulse ? pulse[d] * pulse_share : 0.0;
    const double pushed = impulse + h * rub + slow_h * load;
    double dashpot_velocity = before;
    if (second_half) {
      v_[d] = (before + pushed * inverse_mass[d]) / (1.0 + slow_h * damping[d] * inverse_mass[d]);
      dashpot_velocity = v_[d];
    } else {
      v_[d] = before + (pushed - slow_h * damping[d] * before) * inverse_mass[d];
    }
    u_[d] += drift * v_[d];
    const double mean = 0.5 * (before + v_[d]);
    boundary_work += slow_h * damping[d] * dashpot_velocity * mean;
    friction_work -= h * rub * mean;
    drive_work += slow_h * load * mean;
  }
  boundary_work_ = boundary_work, friction_work_ = friction_work, drive_work_ = drive_work;
}

std::size_t GranularPlate::subcycled_dof() const {
  return static_cast<std::size_t>(2 * plate_->node(0, plate_->mesh().elements_y - 1));
}

double GranularPlate::step_towards(double t_end) {
  const double left = t_end - time_;
  const StepLimits limits = next_limits();
  const double free = free_step(limits);
  const double dt = step_with(limits, (left > free && left < 2.0 * free) ? 0.5 * left : left);
  if (t_end - time_ < 1e-9 * dt) time_ = t_end;  // round-off, not a step
  return dt;
}

void GranularPlate::advance_to(double t_end) {
  while (time_ < t_end) step_towards(t_end);
}

Energies GranularPlate::energies_without_strain() const {
  Energies e;
  for (const auto& g : grains_) {
    e.grain_translation += 0.5 * g.mass * (g.vx * g.vx + g.vy * g.vy);
    if (contacts_.rotation) e.grain_rotation += 0.5 * g.inertia * g.spin * g.spin;
  }
  if (plate_) {
    const auto& mass = plate_->mass();
    for (std::size_t d = 0; d < v_.size(); ++d) e.plate_kinetic += 0.5 * mass[d] * v_[d] * v_[d];
  }
  return e;
}

double participation_ratio(const std::vector<double>& energies) {
  double sum = 0.0, squares = 0.0;
  for (const double e : energies) sum += e, squares += e * e;
  return squares > 0.0 ? sum * sum / squares : 0.0;
}

std::vector<double> GranularPlate::grain_energies() const {
  std::vector<double> held(grains_.size(), 0.0);
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& g = grains_[i];
    held[i] = 0.5 * g.mass * (g.vx * g.vx + g.vy * g.vy);
    if (contacts_.rotation) held[i] += 0.5 * g.inertia * g.spin * g.spin;
  }
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const auto& p = pairs_[k];
    const auto& gi = grains_[static_cast<std::size_t>(p.i)];
    const auto& gj = grains_[static_cast<std::size_t>(p.j)];
    const double overlap = gi.radius + gj.radius - std::hypot(gi.x - gj.x, gi.y - gj.y);
    if (overlap <= 0.0) continue;
    const double half =
        0.5 * std::visit([&](const auto& model) { return model.energy(overlap, gi.radius, gj.radius, shear_[k]); },
                         grain_model_);
    held[static_cast<std::size_t>(p.i)] += half;
    held[static_cast<std::size_t>(p.j)] += half;
  }
  add_wall_energies(held);
  if (!plate_) return held;
  for (std::size_t i = 0; i < grains_.size(); ++i) {
    const auto& g = grains_[i];
    if (g.x < 0.0 || g.x > plate_->mesh().length_x) continue;  // beyond the plate's ends (add_plate_contact)
    const double overlap = plate_overlap(g, contact_point(g.x));
    if (overlap > 0.0) held[i] += plate_law().energy(overlap, {g.radius, 0.0});
  }
  return held;
}

Energies GranularPlate::energies() const {
  Energies e;
  for (const auto& g : grains_) {
    e.grain_translation += 0.5 * g.mass * (g.vx * g.vx + g.vy * g.vy);
    if (contacts_.rotation) e.grain_rotation += 0.5 * g.inertia * g.spin * g.spin;
  }
  e.contact = contact_energy_;
  if (plate_) {
    const auto& mass = plate_->mass();
    for (std::size_t d = 0; d < v_.size(); ++d) e.plate_kinetic += 0.5 * mass[d] * v_[d] * v_[d];
    e.plate_strain = plate_->strain_energy(u_);
  }
  e.friction_work = friction_work_ - (tangential_energy_ - tangential_energy_origin_);
  e.dashpot_work = dashpot_work_;
  e.boundary_work = boundary_work_;
  e.drive_work = drive_work_;
  return e;
}

int GranularPlate::grain_contacts() const {
  int n = 0;
  for (const auto& p : pairs_) {
    const auto& gi = grains_[static_cast<std::size_t>(p.i)];
    const auto& gj = grains_[static_cast<std::size_t>(p.j)];
    const double reach = gi.radius + gj.radius;
    if (std::hypot(gi.x - gj.x, gi.y - gj.y) < reach) ++n;
  }
  return n;
}

}  // namespace sedwave::forward::interface
