#include "sedwave/forward/experiment/scene.hpp"

#include <cmath>
#include <set>
#include <toml.hpp>

#include "sedwave/io/toml_table.hpp"

#include "sedwave/forward/dem/contact/read_contact.hpp"

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::experiment {
namespace {

using namespace channel;  // a scene file is mostly the channel's settings

using Section = io::Table<SceneError>;
using Range = io::Range;

// Accepted ranges (docs/scenes.md lists them). Bounds beyond the physically possible keep runs
// affordable: a channel of more grains than kMaxGrains would not fit in memory.
constexpr double kMaxGrains = 1e8;
constexpr double kMaxPeriods = 1e6;
const std::string kDiameters = "d (mean grain diameters)";

double number_value_required(Section& s, const std::string& key, const Range& range) {
  return s.number_value(s.at(key), s.name(key), range);
}

void read_geometry(Section s, ChannelScene& scene, const std::filesystem::path& base) {
  ChannelGeometry& g = scene.geometry;
  if (s.has("import_lammps_data")) {
    scene.import_lammps_data = base / s.text("import_lammps_data", "");
  }
  g.n_grains = s.integer("grains", g.n_grains, Range::closed(1, kMaxGrains, "grains"));
  g.width = s.positive("width", g.width, kDiameters);
  g.density = s.positive("density", g.density);
  g.seed = s.integer("seed", g.seed, Range::closed(0, 1e15));
  // Random sequential addition jams near 0.38; above 0.3 placement slows to a crawl.
  g.initial_packing_fraction =
      s.number("initial_packing_fraction", g.initial_packing_fraction, Range::above(0.0, 0.3, "(volume fraction)"));
  Section sizes = s.sub("sizes");
  sizes.choice("distribution", "normal", {"normal"});
  g.sizes.mean = sizes.positive("mean", g.sizes.mean, kDiameters);
  g.sizes.sd = sizes.number("sd", g.sizes.sd, Range::non_negative(kDiameters));
  g.sizes.min = sizes.positive("min", g.sizes.min, kDiameters);
  g.sizes.max = sizes.positive("max", g.sizes.max, kDiameters);
  if (!(g.sizes.min <= g.sizes.mean)) sizes.fail_key("min", "must not exceed mean (" + io::shortest(g.sizes.mean) + ")");
  if (!(g.sizes.mean <= g.sizes.max)) sizes.fail_key("max", "must not be below mean (" + io::shortest(g.sizes.mean) + ")");
  sizes.finish();
  if (!(g.width >= g.sizes.max)) {
    s.fail_key("width", "must be at least the largest grain diameter (sizes.max = " + io::shortest(g.sizes.max) + ")");
  }
  Section walls = s.sub("walls");
  g.wall_diameter = walls.positive("diameter", g.wall_diameter, kDiameters);
  // Offsets are drawn with this standard deviation and kept within +-0.5 d.
  g.wall_roughness = walls.number("roughness", g.wall_roughness, Range::closed(0.0, 0.5, kDiameters));
  walls.finish();
  if (s.has("periodic_cell")) {
    Section cell = s.sub("periodic_cell");
    CellTiling t;
    t.cell_grains = cell.integer("grains", t.cell_grains, Range::closed(1, kMaxGrains, "grains"));
    t.wall_thickness = cell.positive("wall_thickness", t.wall_thickness, kDiameters);
    if (g.n_grains % t.cell_grains != 0) {
      cell.fail_key("grains", "the channel's " + std::to_string(g.n_grains) + " grains must be a whole number of cells of " +
                              std::to_string(t.cell_grains));
    }
    if (!(t.wall_thickness >= g.sizes.max)) {
      cell.fail_key("wall_thickness", "walls thinner than the largest grain (" + std::to_string(g.sizes.max) +
                                      ") would cut contacts of flow grains");
    }
    if (scene.import_lammps_data) cell.fail_key("grains", "a periodic cell is generated; it cannot be imported");
    cell.finish();
    scene.tiling = t;
  }
  s.finish();
}

/// The [contact] table as a source for dem::read_contact, which asks for the keys of the laws the
/// table selects (docs/scenes.md lists them).
class SceneContactKeys final : public dem::ContactKeySource {
 public:
  explicit SceneContactKeys(Section& s) : s_(s) {}
  std::optional<std::string> choice(std::string_view selector, const std::vector<std::string>& names) override {
    const std::string key(selector);
    if (!s_.has(key)) return std::nullopt;
    return s_.choice(key, "", std::set<std::string>(names.begin(), names.end()));
  }
  std::optional<double> number(const dem::ContactKey& k) override {
    io::Range range = k.bounds;  // the key's own unit note in messages
    range.unit = k.unit;
    return s_.optional_number(std::string(k.key), range);
  }
  [[noreturn]] void fail(const std::string& why) override { s_.fail_table(why); }

 private:
  Section& s_;
};

void read_contact(Section s, dem::ContactSpec& c) {
  SceneContactKeys keys(s);
  c = dem::read_contact(keys);
  s.finish();
}

void read_preparation(Section s, PreparationSettings& p) {
  p.pressure = s.positive("pressure", p.pressure);
  const std::string compression = s.choice("compression", "wall", {"wall", "affine", "pressure"});
  p.compression = compression == "wall" ? Compression::wall
                  : compression == "affine" ? Compression::affine
                                            : Compression::pressure;
  p.compression_speed =
      s.number("compression_speed", p.compression_speed, Range::above(0.0, 1.0, "d per binary collision time"));
  p.compression_strain_rate = s.number("compression_strain_rate", p.compression_strain_rate,
                                       Range::above(0.0, 0.1, "per binary collision time"));
  p.compression_damping = s.number("compression_damping", p.compression_damping, Range::non_negative());
  p.residual_force_tolerance = s.number("residual_force_tolerance", p.residual_force_tolerance,
                                        Range::open(0.0, 1.0, "of the mean contact force"));
  p.pressure_tolerance = s.number("pressure_tolerance", p.pressure_tolerance, Range::open(0.0, 1.0, "of P W^2"));
  p.max_compression_steps = s.integer("max_compression_steps", p.max_compression_steps, Range::closed(1, INFINITY, "steps"));
  p.max_relaxation_steps = s.integer("max_relaxation_steps", p.max_relaxation_steps, Range::closed(1, INFINITY, "steps"));
  p.newton_relaxation = s.boolean("newton_relaxation", p.newton_relaxation);
  p.newton_start_tolerance =
      s.number("newton_start_tolerance", p.newton_start_tolerance, Range::open(0.0, 1.0, "of the mean contact force"));
  s.finish();
}

void read_drive(Section s, DriveSettings& d) {
  d.axis = s.choice("axis", "z", {"z", "x"}) == "z" ? DriveAxis::longitudinal : DriveAxis::transverse;
  d.amplitude = s.number("amplitude", d.amplitude, Range::above(0.0, 1.0, kDiameters));
  const std::string signal = s.choice("signal", "sinusoid", {"sinusoid", "pulse", "chirp"});
  if (signal != "chirp" && s.has("sweep_periods")) s.fail_key("sweep_periods", "is for signal = \"chirp\"");
  if (signal != "sinusoid") {
    if (s.has("omega_hat")) s.fail_table("a " + signal + " spans omega_hat_min..omega_hat_max; 'omega_hat' is for signal = \"sinusoid\"");
    PulseBand band;
    if (signal == "chirp") {
      band.shape = BroadbandShape::log_chirp;
      band.sweep_periods = s.number("sweep_periods", band.sweep_periods, Range::closed(1.0, kMaxPeriods, "periods of omega_hat_min"));
    }
    band.omega_hat_min = s.positive("omega_hat_min", band.omega_hat_min);
    band.omega_hat_max = s.positive("omega_hat_max", band.omega_hat_max);
    band.frequencies = s.integer("frequencies", band.frequencies, Range::closed(1, 10000, "frequencies"));
    if (!(band.omega_hat_max > band.omega_hat_min)) s.fail_table("omega_hat_max must exceed omega_hat_min");
    d.pulse = band;
  } else {
    d.omega_hat = s.positive("omega_hat", d.omega_hat);
  }
  if (s.has("gamma_hat") && s.has("restitution")) s.fail_table("give 'gamma_hat' or 'restitution', not both");
  if (s.has("restitution")) {
    const double e = s.number("restitution", 0.9, Range::above(0.0, 1.0));
    d.gamma_hat = gamma_hat_from_restitution(e);
  } else {
    d.gamma_hat = s.number("gamma_hat", d.gamma_hat, Range::non_negative("(gamma / sqrt(kappa m))"));
  }
  d.far_end = s.choice("far_end", "absorbing", {"frozen", "absorbing"}) == "frozen" ? FarEnd::frozen : FarEnd::absorbing;
  d.far_wall = s.choice("far_wall", "frozen", {"frozen", "loaded"}) == "loaded" ? FarWall::loaded : FarWall::frozen;
  if (s.has("far_wall_mass")) {
    if (d.far_wall != FarWall::loaded) s.fail_table("far_wall_mass is for far_wall = \"loaded\"");
    d.far_wall_mass = s.positive("far_wall_mass", 1.0, "mean grain masses");
  }
  // At least a tenth of the column stays outside the absorbing layer to be measured.
  d.absorbing_fraction =
      s.number("absorbing_fraction", d.absorbing_fraction, Range::above(0.0, 0.9, "of the column length"));
  d.absorbing_strength = s.positive("absorbing_strength", d.absorbing_strength, "m omega");
  d.periods = s.number("periods", d.periods, Range::closed(0.0, kMaxPeriods, "periods (0: until echoes could return)"));
  // A lock-in needs a few samples per period to tell amplitude from phase.
  d.samples_per_period =
      s.integer("samples_per_period", d.samples_per_period, Range::closed(4, 1e6, "samples per period"));
  // The engine caps a step above the stability limit of a dense packing's collective modes (about
  // 0.3 collision times undamped, less with damping); a fraction beyond 0.1 asks for that cap.
  d.time_step_fraction =
      s.number("time_step_fraction", d.time_step_fraction, Range::above(0.0, 0.1, "of the binary collision time"));
  Section m = s.sub("measurement");
  d.layer_thickness = m.positive("layer_thickness", d.layer_thickness, kDiameters);
  d.skip_layers = m.integer("skip_layers", d.skip_layers, Range::closed(0, 1e6, "layers"));
  d.max_fit_depth = m.number("max_fit_depth", d.max_fit_depth, Range::non_negative(kDiameters + ", 0: no limit"));
  d.grain_probes = m.boolean("grain_probes", d.grain_probes);
  d.settle_periods = m.number("settle_periods", d.settle_periods, Range::closed(0.0, kMaxPeriods, "periods"));
  d.steady_extensions = m.integer("steady_extensions", d.steady_extensions, Range::closed(0, 100, "extensions"));
  m.finish();
  s.finish();
}

void read_linear(Section s, linear::LinearSettings& l) {
  l.ensemble = s.integer("ensemble", l.ensemble, Range::closed(1, 10000, "packings"));
  l.gap_search = s.positive("gap_search", l.gap_search, kDiameters);
  l.warn_state_changes = s.number("warn_state_changes", l.warn_state_changes, Range::above(0.0, 1.0, "of the contacts"));
  l.refuse_state_changes =
      s.number("refuse_state_changes", l.refuse_state_changes, Range::above(0.0, 1.0, "of the contacts"));
  s.finish();
}

/// The largest mu_hat a scene accepts (see read_fluid).
constexpr double kMaxViscosity = 0.1;

/// [fluid]: a still pore fluid during the drive, in the packing's dimensionless groups
/// (docs/fluid.md). Absent: dry.
std::optional<dem::FluidSpec> read_fluid(Section s) {
  dem::FluidSpec f;
  // mu_hat grows as mu / d (docs/fluid.md): water around gravel to clay is 4e-7 to 1e-3, glycerol (1400 x
  // water) around silt 0.08. Beyond 0.1 the film's dashpot dwarfs any contact's and shrinks the stable
  // time step with it: minutes of steps for a fluid no sediment holds.
  f.viscosity = number_value_required(s, "viscosity",
                                      Range::above(0.0, kMaxViscosity,
                                                   "mu_hat = mu d / sqrt(kappa m); water around sand is 5e-6 to "
                                                   "6e-5, glycerol around silt 0.08 (docs/fluid.md)"));
  f.roughness = number_value_required(s, "roughness", Range::positive(kDiameters + ": the smallest lubrication gap"));
  f.cutoff = number_value_required(s, "cutoff", Range::above(0.0, 1.0, kDiameters + ": no lubrication beyond this gap"));
  if (!(f.cutoff > f.roughness)) {
    s.fail_key("cutoff", "must exceed roughness (" + io::shortest(f.roughness) + "): accepted range (" +
                             io::shortest(f.roughness) + ", 1] " + kDiameters);
  }
  f.lubrication = s.boolean("lubrication", f.lubrication);
  const std::vector<std::string> drag_laws = dem::drag_law_names();
  f.drag = dem::drag_law_of(s.choice("drag", drag_laws.front(), {drag_laws.begin(), drag_laws.end()}));
  // 0 stands for the prepared packing's own porosity, resolved when the drive starts.
  f.porosity = s.number("porosity", 0.0, Range::open(0.0, 1.0, "(pore volume fraction; default: the packing's)"));
  if (s.has("porosity") && f.drag != dem::DragLaw::richardson_zaki) {
    s.fail_key("porosity", "is read by drag = \"richardson_zaki\" only");
  }
  f.density = 0.0;  // channel drives have no gravity, so no buoyancy
  s.finish();
  return f;
}

ChannelScene from_value(const toml::value& root, const std::string& origin, const std::filesystem::path& base) {
  ChannelScene scene;
  Section top(root, "", origin);
  top.allow_only({"title", "engine", "geometry", "contact", "preparation", "drive", "linear", "fluid"});
  top.text("title", "");
  scene.engine = engine_named(top.choice("engine", "time_domain", {"time_domain", "linear"}));  // the driven engines
  read_geometry(top.sub("geometry"), scene, base);
  read_contact(top.sub("contact"), scene.contact);
  read_preparation(top.sub("preparation"), scene.preparation);
  if (scene.tiling && scene.preparation.compression != Compression::affine) {
    // A periodic cell has no wall to lower: its box is strained instead.
    Section preparation = top.sub("preparation");
    if (preparation.has("compression")) {
      preparation.fail_key("compression", "a periodic cell ([geometry.periodic_cell]) is compressed affinely: use \"affine\"");
    }
    scene.preparation.compression = Compression::affine;
  }
  read_drive(top.sub("drive"), scene.drive);
  read_linear(top.sub("linear"), scene.linear);
  if (top.has("fluid")) scene.drive.fluid = read_fluid(top.sub("fluid"));
  if (const std::string refusal = engine_refusal(scene.engine, scene.drive); !refusal.empty()) {
    top.sub("drive").fail_table(refusal);
  }
  if (scene.drive.pulse && scene.drive.far_end != FarEnd::absorbing) {
    top.sub("drive").fail_table("far_end: a pulse needs far_end = \"absorbing\" (a frozen end sends the whole pulse "
                                "back through the layers being measured)");
  }
  top.finish();
  // Preparation damping (the thesis's), unless the scene chose a dashpot.
  const bool damped = scene.contact.has(dem::keys::restitution.key) || scene.contact.has(dem::keys::gamma.key) ||
                      scene.contact.has(dem::HookeNormal::gamma_n_key.key);
  if (!damped) scene.contact[std::string(dem::keys::restitution.key)] = 0.9;
  return scene;
}

}  // namespace

ChannelScene parse_scene(const std::string& text, const std::string& origin) {
  ChannelScene scene =
      from_value(io::parse<SceneError>(text, origin), origin, std::filesystem::path(origin).parent_path());
  scene.text = text;
  scene.path = origin;
  return scene;
}

ChannelScene read_scene(const std::filesystem::path& path) {
  return parse_scene(io::read_text<SceneError>(path, "scene file"), path.string());
}

}  // namespace sedwave::forward::experiment
