// Every compiled contact combination in both engines' terms. Each is read from keys by the one
// reader (as a scene file or `sedwave dem` gives them); in the time-domain engine two grains at rest
// carry the closed-form normal force and energy, and one contact evaluation the closed-form
// tangential force and rolling torque; the linear engine's blocks (normal stiffness and dashpot,
// tangential spring and dashpot) match finite differences of the force laws at a static overlap, and
// laws it cannot hold are refused. Then the closed forms of the Hertz-Mindlin tangential spring.
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "dem_test_support.hpp"
#include "sedwave/forward/dem/contact/read_contact.hpp"
#include "sedwave/forward/dem/contact/tanh_over_x.hpp"

namespace sedwave::forward::dem {
namespace {

using testing::make_grain;


constexpr double kE = 1e4, kNu = 0.3, kFriction = 0.5, kGammaT = 2.0, kKt = 300.0, kTanhScale = 100.0;
constexpr double kRollingFriction = 0.1, kRollingRegularisation = 0.01, kRestitution = 0.8;

/// Keys from maps, as a scene table gives them.
class MapKeys final : public ContactKeySource {
 public:
  MapKeys(std::map<std::string, std::string> choices, std::map<std::string, double> numbers)
      : choices_(std::move(choices)), numbers_(std::move(numbers)) {}
  std::optional<std::string> choice(std::string_view selector, const std::vector<std::string>& names) override {
    const auto it = choices_.find(std::string(selector));
    if (it == choices_.end()) return std::nullopt;
    if (std::find(names.begin(), names.end(), it->second) == names.end()) fail("unknown " + it->second);
    return it->second;
  }
  std::optional<double> number(const ContactKey& k) override {
    const auto it = numbers_.find(std::string(k.key));
    return it == numbers_.end() ? std::nullopt : std::optional(it->second);
  }
  [[noreturn]] void fail(const std::string& why) override { throw std::invalid_argument(why); }

 private:
  std::map<std::string, std::string> choices_;
  std::map<std::string, double> numbers_;
};

struct Combination {
  std::string normal, tangential, rolling;
};

std::vector<Combination> every_combination() {
  std::vector<Combination> out;
  for (const std::string& n : normal_law_names())
    for (const std::string& t : tangential_law_names())
      for (const std::string& r : rolling_law_names()) out.push_back({n, t, r});
  return out;
}

/// A value for every key of every law: each combination reads those of its parts (friction
/// without a tangential law is refused, as a scene's would be).
ContactSpec spec_of(const Combination& c) {
  std::map<std::string, double> values{
      {"youngs_modulus", kE}, {"poisson_ratio", kNu}, {"restitution", kRestitution}, {"gamma_t", kGammaT},
      {"kt", kKt}, {"tanh_velocity_scale", kTanhScale}, {"rolling_friction", kRollingFriction},
      {"rolling_regularisation", kRollingRegularisation}};
  if (c.tangential != "none") values["friction"] = kFriction;
  MapKeys keys({{"law", c.normal}, {"tangential", c.tangential}, {"rolling", c.rolling}}, values);
  return read_contact(keys);
}

std::string name_of(const Combination& c) { return c.normal + "+" + c.tangential + "+" + c.rolling; }

// Closed forms for grains of radius 0.5 (R_eff = 1/4) of identical material E, nu.
constexpr double kRadius = 0.5, kEffectiveRadius = 0.25;
double shear_modulus() { return kE / (2.0 * (1.0 + kNu)); }
double hooke_kn() { return 4.0 * shear_modulus() / (3.0 * (1.0 - kNu)); }  // LAMMPS example scripts
double hertz_modulus() { return kE / (2.0 * (1.0 - kNu * kNu)); }           // E* of two equal grains

double closed_form_normal_force(const std::string& law, double overlap) {
  if (law == "hooke") return hooke_kn() * overlap;
  return 4.0 / 3.0 * hertz_modulus() * std::sqrt(kEffectiveRadius) * std::pow(overlap, 1.5);  // Hertz 1882
}
double closed_form_energy(const std::string& law, double overlap) {
  if (law == "hooke") return 0.5 * hooke_kn() * overlap * overlap;
  return 8.0 / 15.0 * hertz_modulus() * std::sqrt(kEffectiveRadius) * std::pow(overlap, 2.5);
}
/// Mindlin's no-slip stiffness 8 G* sqrt(R delta), 1/G* = 2 (2 - nu) / G.
double mindlin_kt(double overlap) {
  return 8.0 * shear_modulus() / (2.0 * (2.0 - kNu)) * std::sqrt(kEffectiveRadius * overlap);
}

TEST(ContactCombinations, EveryChoiceOfEachListIsOneCompiledModel) {
  const std::vector<Combination> all = every_combination();
  EXPECT_EQ(all.size(), std::variant_size_v<AnyContactModel>);
  std::set<std::size_t> alternatives;
  std::set<std::string> descriptions;
  for (const Combination& c : all) {
    const ContactSpec spec = spec_of(c);
    alternatives.insert(make_contact_model(spec).index());
    descriptions.insert(describe(spec));
  }
  EXPECT_EQ(alternatives.size(), all.size());
  EXPECT_EQ(descriptions.size(), all.size());
}

TEST(ContactCombinations, TwoGrainsAtRestCarryTheClosedFormForceAndEnergy) {
  constexpr double overlap = 0.01;
  for (const Combination& c : every_combination()) {
    SCOPED_TRACE(name_of(c));
    EngineSettings s;
    s.box.periodic = {false, false, false};
    s.contact = spec_of(c);
    Engine engine(MPI_COMM_SELF, s, std::vector<Grain>{make_grain(0, {0, 0, 0}), make_grain(1, {0, 0, 1.0 - overlap})});
    const Vec3 f = engine.grains().force[testing::local_index(engine.grains(), 1)];
    const double expected = closed_form_normal_force(c.normal, overlap);
    EXPECT_NEAR(f.z, expected, 1e-12 * expected);
    EXPECT_EQ(f.x, 0.0);
    EXPECT_EQ(f.y, 0.0);
    const double energy = closed_form_energy(c.normal, overlap);
    EXPECT_NEAR(engine.elastic_energy(), energy, 1e-12 * energy);
  }
}

/// The tangential force of the first step of a contact sliding at speed v along x (no spin), and the
/// rolling torque of one spinning about y at rate w, against each law's closed form.
TEST(ContactCombinations, OneContactEvaluationMatchesTheClosedForms) {
  constexpr double overlap = 0.01, v = 1e-3, w = 0.02, dt = 1e-3, m_eff = 0.25;
  for (const Combination& c : every_combination()) {
    SCOPED_TRACE(name_of(c));
    std::visit(
        [&](const auto& model) {
          const ContactPoint point{{0, 0, 1}, overlap, 0.0, kRadius, kRadius};
          const auto pair = model.pair(m_eff, kRadius, kRadius);
          Vec3 shear;
          const PairResult r = model.evaluate(point, pair, {v, 0, 0}, {0, w, 0}, {}, dt, shear);
          const double fn = closed_form_normal_force(c.normal, overlap);
          EXPECT_NEAR(r.normal_force, fn, 1e-12 * fn);
          double ft = 0.0;  // along x
          if (c.tangential == "spring_history") ft = -(kKt * v * dt + m_eff * kGammaT * v);
          if (c.tangential == "mindlin") ft = -(mindlin_kt(overlap) * v * dt + m_eff * kGammaT * v);
          if (c.tangential == "coulomb_tanh") ft = -kFriction * fn * std::tanh(kTanhScale * v);
          // The rolling slip of spin w about y at the contact point adds to v (arm r - delta/2).
          if (c.tangential != "none" && w != 0.0) {
            const Vec3 slip = Vec3{v, 0, 0} + cross(Vec3{0, 0, 1}, (kRadius - 0.5 * overlap) * Vec3{0, w, 0});
            const double s = slip.x;
            if (c.tangential == "spring_history") ft = -(kKt * s * dt + m_eff * kGammaT * s);
            if (c.tangential == "mindlin") ft = -(mindlin_kt(overlap) * s * dt + m_eff * kGammaT * s);
            if (c.tangential == "coulomb_tanh") ft = -kFriction * fn * std::tanh(kTanhScale * std::abs(s)) * (s > 0 ? 1 : -1);
          }
          ASSERT_LT(std::abs(ft), kFriction * fn);  // sticking: no Coulomb cap in these closed forms
          EXPECT_NEAR(r.force.x, ft, 1e-12 * fn);
          EXPECT_NEAR(r.force.z, fn, 1e-12 * fn);
          // Rolling: mu_r R_eff |F_n| tanh(w / w_reg) against the relative spin (Ai et al. 2011, model A).
          const double rolling = c.rolling == "constant_torque"
                                     ? -kRollingFriction * kEffectiveRadius * fn * std::tanh(w / kRollingRegularisation)
                                     : 0.0;
          const double lever = -(kRadius - 0.5 * overlap) * r.force.x;  // torque about y of F_t at the arm
          if (c.tangential == "none" && c.rolling == "none") {
            EXPECT_EQ(r.torque_i.y, 0.0);
          }
          EXPECT_NEAR(r.torque_i.y, rolling + lever, 1e-12 * fn);
        },
        make_contact_model(spec_of(c)));
  }
}

/// Central difference of f at x with step h.
template <class F>
double derivative(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

TEST(ContactCombinations, LinearBlocksAreDerivativesOfTheForceLaws) {
  constexpr double overlap = 0.01, m_eff = 0.3, mu_force = 1e9;
  for (const Combination& c : every_combination()) {
    SCOPED_TRACE(name_of(c));
    const AnyContactModel model = make_contact_model(spec_of(c));
    if (!linearised(model)) {
      EXPECT_THROW((void)tangential_block(model, overlap, kRadius, kRadius), std::invalid_argument);
      continue;
    }
    std::visit(
        [&](const auto& m) {
          const auto pair = m.pair(m_eff, kRadius, kRadius);
          const auto normal_force = [&](double delta, double v_n) {
            return m.normal.force(ContactPoint{{0, 0, 1}, delta, v_n, kRadius, kRadius}, pair.normal);
          };
          const ContactOscillator n = m.normal.oscillator(m_eff, kEffectiveRadius, overlap);
          const double k_fd = derivative([&](double d) { return normal_force(d, 0.0); }, overlap, 1e-6 * overlap);
          EXPECT_NEAR(n.stiffness, k_fd, 1e-6 * k_fd);
          const double c_fd = -derivative([&](double v) { return normal_force(overlap, v); }, 0.0, 1e-3);
          EXPECT_NEAR(n.damping, c_fd, 1e-9 * c_fd);

          using Model = std::decay_t<decltype(m)>;
          const std::optional<TangentialBlock> t = tangential_block(model, overlap, kRadius, kRadius);
          ASSERT_EQ(t.has_value(), Model::has_tangential);
          if constexpr (Model::has_tangential) {
            const ContactPoint point{{0, 0, 1}, overlap, 0.0, kRadius, kRadius};
            // Spring: the force of a shear displacement s at rest; dashpot: of a slip speed with dt = 0.
            const auto spring = [&](double s) {
              Vec3 shear{s, 0, 0};
              return m.tangential.force(point, pair.tangential, {}, mu_force, 1e-3, shear).x;
            };
            const auto dashpot = [&](double v) {
              Vec3 shear;
              return m.tangential.force(point, pair.tangential, {v, 0, 0}, mu_force, 0.0, shear).x;
            };
            const double kt_fd = -derivative(spring, 0.0, 1e-6);
            EXPECT_NEAR(t->stiffness, kt_fd, 1e-9 * kt_fd);
            EXPECT_NEAR(t->damping_per_mass * m_eff, -derivative(dashpot, 0.0, 1e-6), 1e-9);
            EXPECT_EQ(t->friction, kFriction);
          }
        },
        model);
  }
}

TEST(ContactReader, DefaultsAreTheThesisContactAndFrictionSelectsTheHistorySpring) {
  MapKeys plain({}, {{"kn", 726.0}});
  const ContactSpec hooke = read_contact(plain);
  EXPECT_EQ(describe(hooke), "hooke");
  MapKeys frictional({}, {{"kn", 700.0}, {"friction", 0.3}});
  const AnyContactModel model = make_contact_model(read_contact(frictional));
  const auto& m = std::get<ContactModel<HookeNormal, TangentialSpringHistory>>(model);
  EXPECT_DOUBLE_EQ(m.tangential.kt, 200.0);  // 2/7 kn, the one default
}

TEST(ContactReader, RefusesKeysThatNoChosenLawReads) {
  ContactSpec s;
  s["kn"] = 726.0;
  s["tanh_velocity_scale"] = 3.0;
  EXPECT_THROW((void)make_contact_model(s), std::invalid_argument);
  MapKeys hertz_spring({{"law", "hertz"}, {"tangential", "spring_history"}}, {{"youngs_modulus", kE}, {"friction", 0.3}});
  EXPECT_THROW((void)read_contact(hertz_spring), std::invalid_argument);  // kt has no default without kn
  MapKeys friction_without_law({{"tangential", "none"}}, {{"kn", 726.0}, {"friction", 0.3}});
  EXPECT_THROW((void)read_contact(friction_without_law), std::invalid_argument);
}

// ---- Hertz-Mindlin tangential spring -----------------------------------------------------------

TEST(Mindlin, StiffnessFollowsTheContactRadiusAtMindlinsRatioToHertz) {
  const MindlinTangential law = MindlinTangential::from(ContactValues(spec_of({"hertz", "mindlin", "none"})), 0.0);
  const HertzNormal hertz{hertz_modulus(), 0.0};
  for (const double overlap : {1e-4, 1e-3, 1e-2}) {
    const double kt = law.stiffness(overlap, kEffectiveRadius);
    EXPECT_NEAR(kt, mindlin_kt(overlap), 1e-12 * kt);
    // kt / kn = 2 (1 - nu) / (2 - nu) at every overlap (Mindlin 1949; Di Renzo & Di Maio 2004).
    const double kn = hertz.oscillator(1.0, kEffectiveRadius, overlap).stiffness;
    EXPECT_NEAR(kt / kn, 2.0 * (1.0 - kNu) / (2.0 - kNu), 1e-12);
  }
  EXPECT_NEAR(law.energy(0.01, kRadius, kRadius, {1e-4, 0, 0}), 0.5 * mindlin_kt(0.01) * 1e-8, 1e-20);
}

TEST(Mindlin, SlidesAtTheCoulombLimit) {
  const MindlinTangential law = MindlinTangential::from(ContactValues(spec_of({"hertz", "mindlin", "none"})), 0.0);
  const ContactPoint point{{0, 0, 1}, 0.01, 0.0, kRadius, kRadius};
  Vec3 shear{1.0, 0, 0};  // far beyond the spring length that mu F_n can hold
  const double fn = 2.0;
  const Vec3 f = law.force(point, law.pair(0.25, kRadius, kRadius), {}, fn, 1e-3, shear);
  EXPECT_NEAR(f.x, -kFriction * fn, 1e-12);
  EXPECT_NEAR(shear.x, kFriction * fn / mindlin_kt(0.01), 1e-12);  // the spring that carries the limit
}

TEST(Mindlin, EngineFirstStepOfASlidingPairIsTheSpringOverOneStep) {
  constexpr double overlap = 0.01, v = 1e-3;
  EngineSettings s;
  s.box.periodic = {false, false, false};
  s.contact = spec_of({"hertz", "mindlin", "none"});
  s.contact.erase("gamma_t");
  std::vector<Grain> grains{make_grain(0, {0, 0, 0}), make_grain(1, {0, 0, 1.0 - overlap})};
  grains[1].velocity.x = v;
  Engine engine(MPI_COMM_SELF, s, grains);
  const Vec3 f = engine.grains().force[testing::local_index(engine.grains(), 1)];
  EXPECT_NEAR(f.x, -mindlin_kt(overlap) * v * engine.time_step(), 1e-12);
}

// Coulomb-tanh's tanh(x)/x against long double's tanh over 0 to 40 (both branches, the seam at
// 0.625 and the saturation past 19.1), within 2.5 ulp (5.6e-16 relative): std::tanh's own worst on
// this grid is 3.9e-16. A slip that is not a number gives a force that is not one.
/// A tanh(x)/x form against long double's tanh over 1e-12 < x < 40: its worst relative error, and
/// where; then the values every form must give exactly.
void expect_tanh_over_x_to_round_off(double (*form)(double)) {
  EXPECT_EQ(form(0.0), 1.0);
  double worst = 0.0, at = 0.0;
  for (double x = 1e-12; x < 40.0; x *= 1.00002) {
    const auto exact = static_cast<double>(std::tanh(static_cast<long double>(x)) / static_cast<long double>(x));
    if (const double error = std::abs(form(x) - exact) / exact; error > worst) worst = error, at = x;
  }
  EXPECT_LT(worst, 2.5 * std::numeric_limits<double>::epsilon()) << "at x = " << at;
  EXPECT_DOUBLE_EQ(form(1e3), 1e-3);  // tanh is 1 in double precision
  EXPECT_TRUE(std::isnan(form(std::numeric_limits<double>::quiet_NaN())));
}

TEST(TanhOverX, MatchesLongDoubleTanhToRoundOff) { expect_tanh_over_x_to_round_off(tanh_over_x); }

TEST(TanhOverX, TheLanesFormMatchesLongDoubleTanhToRoundOff) {
  // Without a branch (both forms and a select, e^{2x} by exp_in_lanes): the same accuracy.
  expect_tanh_over_x_to_round_off(tanh_over_x_in_lanes);
}

TEST(TanhOverX, TheLanesExponentialMatchesLongDoubleExpOverItsRange) {
  // Its range in tanh_over_x_in_lanes: e^y for 1.25 <= y <= 40, and from 0 by its construction.
  double worst = 0.0, at = 0.0;
  for (double y = 0.0; y <= 40.0; y += 1.0 / 4096.0) {
    const auto exact = static_cast<double>(std::exp(static_cast<long double>(y)));
    if (const double error = std::abs(exp_in_lanes(y) - exact) / exact; error > worst) worst = error, at = y;
  }
  EXPECT_LT(worst, 2.0 * std::numeric_limits<double>::epsilon()) << "at y = " << at;
  EXPECT_EQ(exp_in_lanes(0.0), 1.0);
}

}  // namespace
}  // namespace sedwave::forward::dem
