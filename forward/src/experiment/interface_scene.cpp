#include "sedwave/forward/experiment/interface_scene.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string_view>
#include <toml.hpp>

#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/dem/contact/coulomb_tanh.hpp"
#include "sedwave/forward/dem/contact/hertz.hpp"
#include "sedwave/forward/dem/contact/hooke.hpp"
#include "sedwave/forward/dem/contact/keys.hpp"
#include "sedwave/forward/dem/contact/read_contact.hpp"
#include "sedwave/forward/units.hpp"
#include "sedwave/io/toml_table.hpp"

namespace sedwave::forward::experiment {
namespace {

using Section = io::Table<InterfaceSceneError>;
using Range = io::Range;

// Physical ranges (docs/interface.md, "Limits"): what a laboratory solid, bead or strike can be, so
// that no value reaches the solver where it would overflow or name the wrong cause. One range per
// quantity: the plate and the beads bound a modulus or a density alike.
const Range kModulus = Range::closed(1e3, 2e12, "Pa");        // soft gels .. diamond (1.2e12 Pa)
const Range kDensity = Range::closed(1.0, 3e4, "kg/m^3");     // aerogels .. osmium (22 590 kg/m^3)
const Range kSize = Range::closed(1e-6, 10.0, "m");           // plate sizes and thickness, bead radius
const Range kSpacing = Range::closed(0.0, 10.0, "m");         // gap, lift
const Range kCount = Range::closed(1, 1e5);                   // elements and grains along one side
const Range kForce = Range::closed(0.0, 1e6, "N");
const Range kRunTime = Range::above(0.0, 1e3, "s");

// Shared by the keys and the command line's overrides.
Range strike_speed_range() { return Range::above(0.0, 1e4, "m/s"); }
Range tolerance_range() { return Range::above(0.0, 0.5); }
/// A key the DEM's contacts declare (dem/contact/keys.hpp): the same bounds as in DEM scenes.
Range dem_key_range(const dem::ContactKey& k) {
  Range range = k.bounds;
  range.unit = k.unit;
  return range;
}
const Range kPoisson = dem_key_range(dem::keys::poisson_ratio);

Range fixed_step_range(double duration) { return Range::closed(0.0, duration, "s (at most run.duration; 0: adaptive)"); }

void check_override(double x, const std::string& option, const Range& range) {
  if (!range.contains(x))
    throw std::invalid_argument(option + " " + io::shortest(x) + ": accepted range " + range.describe());
}

plate::EdgeCondition edge(Section& s, const std::string& key, plate::EdgeCondition fallback) {
  const std::string names[] = {"free", "clamped", "absorbing"};
  const std::string chosen = s.choice(key, names[static_cast<int>(fallback)], {"free", "clamped", "absorbing"});
  return chosen == "free" ? plate::EdgeCondition::free
                          : (chosen == "clamped" ? plate::EdgeCondition::clamped : plate::EdgeCondition::absorbing);
}

void read_plate(Section s, InterfaceScene& scene) {
  auto& m = scene.plate_material;
  m.youngs_modulus = s.number("youngs_modulus", m.youngs_modulus, kModulus);
  m.poisson_ratio = s.number("poisson_ratio", m.poisson_ratio, kPoisson);
  m.density = s.number("density", m.density, kDensity);
  m.thickness = s.number("thickness", m.thickness, kSize);
  auto& mesh = scene.mesh;
  mesh.length_x = s.number("length_x", mesh.length_x, kSize);
  mesh.length_y = s.number("length_y", mesh.length_y, kSize);
  mesh.elements_x = s.integer<int>("elements_x", mesh.elements_x, kCount);
  mesh.elements_y = s.integer<int>("elements_y", mesh.elements_y, kCount);
  scene.contacts.plate_contact = s.choice("contact", "interpolated", {"interpolated", "rigid_layers"}) == "rigid_layers"
                                     ? interface::PlateContactModel::rigid_layers
                                     : interface::PlateContactModel::interpolated;
  Section edges = s.sub("edges");
  scene.edges.top = edge(edges, "top", scene.edges.top);
  scene.edges.bottom = edge(edges, "bottom", scene.edges.bottom);
  scene.edges.left = edge(edges, "left", scene.edges.left);
  scene.edges.right = edge(edges, "right", scene.edges.right);
  edges.finish();
  s.finish();
}

std::string metres(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g m", x);
  return text;
}

void read_packing(Section s, InterfaceScene& scene) {
  auto& p = scene.packing;
  p.rows = s.integer<int>("rows", 10, kCount);
  p.columns = s.integer<int>("columns", 20, kCount);
  p.radius = s.number("radius", 2.5e-3, kSize);
  p.density = s.number("density", 7850.0, kDensity);
  p.gap = s.number("gap", 0.0, kSpacing);
  p.lift = s.number("lift", 0.0, kSpacing);
  p.orientation = s.choice("orientation", "rows_parallel", {"rows_parallel", "rows_perpendicular"}) == "rows_parallel"
                      ? interface::HexOrientation::rows_parallel
                      : interface::HexOrientation::rows_perpendicular;
  scene.packing_load = s.number("precompression", 0.0, kForce);
  scene.relaxation_time = s.number("relaxation_time", scene.relaxation_time, Range::above(0.0, 1.0, "s"));
  if (scene.packing_load > 0.0 && scene.edges.top != plate::EdgeCondition::clamped &&
      scene.edges.bottom != plate::EdgeCondition::clamped && scene.edges.left != plate::EdgeCondition::clamped &&
      scene.edges.right != plate::EdgeCondition::clamped)
    s.fail_key("precompression", "a static load needs a clamped plate edge to hold it (plate.edges)");
  scene.grain_material.youngs_modulus = s.number("youngs_modulus", scene.grain_material.youngs_modulus, kModulus);
  scene.grain_material.poisson_ratio =
      s.number("poisson_ratio", scene.grain_material.poisson_ratio, kPoisson);
  // Centred on the plate unless placed.
  const double span = interface::hex_packing_width(p);
  p.x_offset = s.number("x_offset", 0.5 * (scene.mesh.length_x - span), Range{});
  if (p.x_offset < 0.0 || p.x_offset + span > scene.mesh.length_x)
    s.fail_key("x_offset", "the packing (" + metres(span) + " wide) must lie over the plate (" +
                               metres(scene.mesh.length_x) + ")");
  s.finish();
}

void read_walls(Section s, InterfaceScene& scene) {
  auto& w = scene.walls;
  const std::string sides = s.choice("sides", "none", {"none", "both", "left", "right"});
  w.left = sides == "both" || sides == "left";
  w.right = sides == "both" || sides == "right";
  if (!w.left && !w.right) {
    for (const char* key : {"gap", "youngs_modulus", "poisson_ratio", "friction"})
      if (s.has(key)) s.fail_key(key, "sets the side walls, and walls.sides is none (give \"both\", \"left\" or \"right\")");
    s.finish();
    return;
  }
  w.gap = s.number("gap", 0.0, kSpacing);
  w.youngs_modulus = s.number("youngs_modulus", scene.plate_material.youngs_modulus, kModulus);
  w.poisson_ratio = s.number("poisson_ratio", scene.plate_material.poisson_ratio, kPoisson);
  w.friction = s.number("friction", scene.contacts.friction, dem_key_range(dem::keys::friction));
  const auto& p = scene.packing;
  const double left = p.x_offset - w.gap, right = p.x_offset + interface::hex_packing_width(p) + w.gap;
  if ((w.left && left < 0.0) || (w.right && right > scene.mesh.length_x))
    s.fail_key("gap", "the walls (at x = " + metres(left) + " and " + metres(right) + ") must stand over the plate (0 .. " +
                          metres(scene.mesh.length_x) + "; packing.x_offset places the packing)");
  s.finish();
}

/// The [contact] table as a source for dem::read_contact: the DEM scenes' keys and bounds, with the
/// interface's defaults: a Hertz law of the packing's youngs_modulus and poisson_ratio, Coulomb-tanh
/// (k_s 1000 s/m) when there is friction, no dashpot.
class InterfaceContactKeys final : public dem::ContactKeySource {
 public:
  InterfaceContactKeys(Section& s, const interface::GrainMaterial& grain) : s_(s), grain_(grain) {}
  std::optional<std::string> choice(std::string_view selector, const std::vector<std::string>& names) override {
    const std::string key(selector);
    if (s_.has(key)) {
      std::string chosen = s_.choice(key, "", std::set<std::string>(names.begin(), names.end()));
      if (selector == "law") law_ = chosen;
      return chosen;
    }
    if (selector == "law") return law_;
    if (selector == "tangential" && friction_ > 0.0) return std::string(dem::CoulombTanhFriction::name);
    return std::nullopt;
  }
  std::optional<double> number(const dem::ContactKey& k) override {
    const std::string key(k.key);
    if (s_.has(key)) {
      const std::optional<double> x = s_.optional_number(key, dem_key_range(k));
      if (key == dem::keys::friction.key) friction_ = x.value_or(0.0);
      return x;
    }
    // The grains' material, unless the table gives the chosen law's stiffness itself.
    const std::string_view stiffness =
        law_ == dem::HookeNormal::name ? dem::HookeNormal::kn_key.key : dem::HertzNormal::modulus_key.key;
    const bool stiffness_given = s_.has(std::string(stiffness));
    if (key == dem::keys::youngs_modulus.key && !stiffness_given) return grain_.youngs_modulus;
    if (key == dem::keys::poisson_ratio.key && !stiffness_given) return grain_.poisson_ratio;
    if (key == dem::CoulombTanhFriction::velocity_scale_key.key) return kDefaultVelocityScale;
    return std::nullopt;
  }
  [[noreturn]] void fail(const std::string& why) override { s_.fail_table(why); }

  static constexpr double kDefaultVelocityScale = 1e3;  // [s/m]

 private:
  Section& s_;
  const interface::GrainMaterial& grain_;
  double friction_ = 0.0;
  std::string law_{dem::HertzNormal::name};
};

void read_contact(Section s, InterfaceScene& scene) {
  auto& c = scene.contacts;
  InterfaceContactKeys keys(s, scene.grain_material);
  const dem::ContactSpec spec = dem::read_contact(keys);
  c.grain_contact = spec;
  c.friction = spec.find(dem::keys::friction.key).value_or(0.0);
  c.restitution = spec.find(dem::keys::restitution.key).value_or(1.0);
  // The grain-plate contact is Coulomb-tanh whatever the grains' tangential law: its k_s.
  const std::string velocity_scale(dem::CoulombTanhFriction::velocity_scale_key.key);
  c.tanh_velocity_scale = spec.find(velocity_scale)
                              .value_or(s.number(velocity_scale, InterfaceContactKeys::kDefaultVelocityScale,
                                                 dem_key_range(dem::CoulombTanhFriction::velocity_scale_key)));
  c.rotation = s.boolean("rotation", true);
  s.finish();
}

void read_drive(Section s, InterfaceScene& scene) {
  auto& d = scene.drive;
  const std::string kind = s.choice("kind", "velocity", {"velocity", "force", "edge_impulse"});
  d.kind = kind == "force" ? InterfaceDrive::Kind::force
                           : (kind == "edge_impulse" ? InterfaceDrive::Kind::edge_impulse : InterfaceDrive::Kind::velocity);
  if (d.kind == InterfaceDrive::Kind::force) {
    d.peak = s.number_value(s.at("peak"), s.name("peak"), Range::above(0.0, 1e6, "N"));
    d.duration = s.number_value(s.at("duration"), s.name("duration"), kRunTime);
  } else if (d.kind == InterfaceDrive::Kind::edge_impulse) {
    // Up to 1e8 N/m: 2e10 Pa under a 5 mm plate, beyond any solid's strength (the plate is linear).
    d.line_load = s.number_value(s.at("line_load"), s.name("line_load"), Range::above(0.0, 1e8, "N/m"));
    d.duration = s.number_value(s.at("duration"), s.name("duration"), kRunTime);
  } else {
    d.speed = s.number("speed", d.speed, strike_speed_range());
  }
  d.width = s.integer<int>("width", 0, Range::closed(0, 1e5, "beads"));
  s.finish();
}

void read_recording(Section s, InterfaceScene& scene) {
  auto& r = scene.recording;
  r.duration = s.number_value(s.at("duration"), s.name("duration"), kRunTime);
  r.tolerance = s.number("tolerance", r.tolerance, tolerance_range());
  r.fixed_step = s.number("fixed_step", 0.0, fixed_step_range(r.duration));
  r.output_interval = s.number("output_interval", r.duration / 1000.0, Range::above(0.0, r.duration, "s"));
  r.snapshots = s.integer<int>("snapshots", r.snapshots, Range::closed(0, 1000));
  if (s.has("probe_x")) {
    const toml::value& v = s.at("probe_x");
    if (!v.is_array()) io::fail<InterfaceSceneError>(v, s.name("probe_x"), "must be an array of abscissae [m]", s.origin());
    for (const auto& x : v.as_array()) {
      const double value = s.number_value(x, s.name("probe_x"), Range::closed(0.0, scene.mesh.length_x, "m"));
      r.probe_x.push_back(value);
    }
  } else {
    r.probe_x = {0.5 * scene.mesh.length_x};
  }
  r.probe_depth = s.number("probe_depth", 0.0, Range::closed(0.0, scene.mesh.length_y, "m"));
  r.line_depth = s.number("line_depth", 0.0, Range::closed(0.0, scene.mesh.length_y, "m"));
  r.arrival_fraction = s.number("arrival_fraction", r.arrival_fraction, Range::open(0.0, 1.0));
  const std::string scheme = s.choice("scheme", "velocity_verlet", {"velocity_verlet", "newmark_rk4", "multirate"});
  r.scheme = scheme == "newmark_rk4" ? interface::Scheme::newmark_rk4
             : scheme == "multirate" ? interface::Scheme::multirate
                                     : interface::Scheme::velocity_verlet;
  r.plate_tolerance = s.number("plate_tolerance", r.tolerance, tolerance_range());
  if (r.scheme != interface::Scheme::multirate && s.has("plate_tolerance"))
    s.fail_key("plate_tolerance", "sets the multirate scheme's outer step, and run.scheme is " + scheme);
  if (r.scheme == interface::Scheme::multirate && r.fixed_step > 0.0)
    s.fail_key("fixed_step", "the multirate scheme (run.scheme) chooses its own outer steps and substeps: it takes "
                             "no fixed step");
  // Tolerances of the fixed point: below round-off's 1e-16 the iteration cannot stop, above 1e-2 it
  // is no iteration; a force of 1e6 N is the largest drive a scene takes.
  r.iteration_reltol = s.number("iteration_reltol", r.iteration_reltol, Range::closed(1e-15, 1e-2));
  r.iteration_abstol = s.number("iteration_abstol", r.iteration_abstol, Range::closed(0.0, 1e6, "N"));
  if (r.scheme != interface::Scheme::newmark_rk4 && (s.has("iteration_reltol") || s.has("iteration_abstol")))
    s.fail_key(s.has("iteration_reltol") ? "iteration_reltol" : "iteration_abstol",
               "sets the newmark_rk4 scheme's iteration, and run.scheme is " + scheme);
  s.finish();
}

InterfaceScene from_value(const toml::value& root, const std::string& origin) {
  InterfaceScene scene;
  Section top(root, "", origin);
  top.allow_only({"plate", "packing", "contact", "walls", "drive", "run"});
  read_plate(top.sub("plate"), scene);
  read_packing(top.sub("packing"), scene);
  if (scene.contacts.plate_contact == interface::PlateContactModel::rigid_layers) {
    // The beads that can touch the plate (within the neighbour list's skin, 0.2 r) sit over nodes:
    // those of the row on the plate, or of the chains' lowest layer (at most 1e5 beads to place).
    interface::HexPacking lowest = scene.packing;
    (lowest.orientation == interface::HexOrientation::rows_parallel ? lowest.rows : lowest.columns) = 1;
    try {
      interface::check_grains_over_nodes(interface::make_hex_packing(lowest), scene.mesh.length_x / scene.mesh.elements_x,
                                         scene.mesh.length_x, 0.2 * scene.packing.radius);
    } catch (const std::invalid_argument& e) {
      top.sub("plate").fail_key("contact", std::string(e.what()).substr(std::string("interface: ").size()) +
                                               " (the element width is plate.length_x / plate.elements_x; the beads "
                                               "sit at packing.x_offset + radius + k (2 radius + gap))");
    }
  }
  read_contact(top.sub("contact"), scene);
  read_walls(top.sub("walls"), scene);
  read_drive(top.sub("drive"), scene);
  if (!top.has("run")) top.fail_table("missing [run] (its duration is required)");
  read_recording(top.sub("run"), scene);
  if (scene.drive.kind == InterfaceDrive::Kind::edge_impulse && scene.recording.scheme == interface::Scheme::newmark_rk4)
    top.sub("run").fail_key("scheme", "newmark_rk4 takes no pulse on the plate (drive.kind = \"edge_impulse\"): its load "
                                      "at the step's ends would not deliver a rectangular pulse's impulse");
  if (scene.recording.scheme == interface::Scheme::newmark_rk4 && scene.contacts.grain_contact &&
      dem::needs_history(dem::make_contact_model(*scene.contacts.grain_contact)))
    top.sub("run").fail_key("scheme", "newmark_rk4 takes no grain contact with a tangential history (contact.tangential = \"" +
                                          scene.contacts.grain_contact->tangential +
                                          "\"): its RK4 stages would advance the history four times a step");
  if (scene.drive.kind == InterfaceDrive::Kind::edge_impulse && scene.packing_load > 0.0)
    top.sub("packing").fail_key("precompression", "drive.kind = \"edge_impulse\" strikes the plate alone: no beads to load");
  if (scene.drive.kind == InterfaceDrive::Kind::edge_impulse && (scene.walls.left || scene.walls.right))
    top.sub("walls").fail_key("sides", "drive.kind = \"edge_impulse\" strikes the plate alone: no beads to hold");
  // Coulomb-tanh has no static friction: beyond one row on the plate (or one chain standing on it),
  // the 60-degree contacts push the packing apart under a static load, and only walls hold it.
  if (scene.packing_load > 0.0 && scene.packing.rows > 1 && !(scene.walls.left && scene.walls.right))
    top.sub("packing").fail_key("precompression", "a static load spreads a packing of more than one row (chain) "
                                                  "sideways, as Coulomb-tanh has no static friction: hold it between "
                                                  "side walls (walls.sides = \"both\")");
  if (scene.drive.kind != InterfaceDrive::Kind::velocity && scene.drive.duration > scene.recording.duration) {
    Section drive = top.sub("drive");
    drive.fail_key("duration", "the pulse (" + io::shortest(scene.drive.duration) + " s) outlasts the run (run.duration = " +
                                   io::shortest(scene.recording.duration) + " s): most of its work would never be done");
  }
  top.finish();
  return scene;
}

}  // namespace

interface::SideWalls side_walls(const InterfaceScene& scene) {
  const auto& w = scene.walls;
  const auto& g = scene.grain_material;
  return interface::side_walls_around(scene.packing, w.gap, w.left, w.right,
                                      hertz_effective_modulus(g.youngs_modulus, g.poisson_ratio, w.youngs_modulus,
                                                              w.poisson_ratio),
                                      w.friction);
}

InterfaceScene parse_interface_scene(const std::string& text, const std::string& origin) {
  InterfaceScene scene = from_value(io::parse<InterfaceSceneError>(text, origin), origin);
  scene.text = text;
  scene.path = origin;
  return scene;
}

void override_speed(InterfaceScene& scene, double speed, const std::string& option) {
  check_override(speed, option, strike_speed_range());
  scene.drive.speed = speed;
}

void override_tolerance(InterfaceScene& scene, double tolerance, const std::string& option) {
  check_override(tolerance, option, tolerance_range());
  scene.recording.tolerance = tolerance;
}

void override_fixed_step(InterfaceScene& scene, double step, const std::string& option) {
  check_override(step, option, fixed_step_range(scene.recording.duration));
  if (!(step > 0.0)) throw std::invalid_argument(option + " must be > 0");
  if (scene.recording.scheme == interface::Scheme::multirate)
    throw std::invalid_argument("the multirate scheme (run.scheme) chooses its own steps: it takes no fixed step (" +
                                option + ")");
  scene.recording.fixed_step = step;
}

InterfaceScene read_interface_scene(const std::filesystem::path& path) {
  return parse_interface_scene(io::read_text<InterfaceSceneError>(path, "interface scene file"), path.string());
}

}  // namespace sedwave::forward::experiment
