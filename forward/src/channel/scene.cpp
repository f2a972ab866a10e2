#include "sedwave/forward/channel/scene.hpp"

#include <cmath>
#include <toml.hpp>

#include "../io/toml_table.hpp"

#include "sedwave/forward/units.hpp"

namespace sedwave::forward::channel {
namespace {

using Section = toml_io::Table<SceneError>;

void read_geometry(Section s, ChannelScene& scene, const std::filesystem::path& base) {
  ChannelGeometry& g = scene.geometry;
  if (s.has("import_lammps_data")) {
    scene.import_lammps_data = base / s.text("import_lammps_data", "");
  }
  g.n_grains = static_cast<int>(s.integer("grains", g.n_grains));
  g.width = s.positive("width", g.width);
  g.density = s.positive("density", g.density);
  g.seed = static_cast<std::uint64_t>(s.integer("seed", static_cast<std::int64_t>(g.seed)));
  g.initial_packing_fraction = s.positive("initial_packing_fraction", g.initial_packing_fraction);
  Section sizes = s.sub("sizes");
  sizes.choice("distribution", "normal", {"normal"});
  g.sizes.mean = sizes.positive("mean", g.sizes.mean);
  g.sizes.sd = sizes.number("sd", g.sizes.sd);
  g.sizes.min = sizes.positive("min", g.sizes.min);
  g.sizes.max = sizes.positive("max", g.sizes.max);
  sizes.finish();
  Section walls = s.sub("walls");
  g.wall_diameter = walls.positive("diameter", g.wall_diameter);
  g.wall_roughness = walls.number("roughness", g.wall_roughness);
  walls.finish();
  if (s.has("periodic_cell")) {
    Section cell = s.sub("periodic_cell");
    CellTiling t;
    t.cell_grains = static_cast<int>(cell.integer("grains", t.cell_grains, 1));
    t.wall_thickness = cell.positive("wall_thickness", t.wall_thickness);
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

void read_contact(Section s, dem::ContactSpec& c, double density) {
  const std::string law = s.choice("law", "hooke", {"hooke", "hertz"});
  c.normal = law == "hooke" ? dem::NormalLawKind::hooke : dem::NormalLawKind::hertz;
  const std::optional<double> E = s.optional_number("youngs_modulus");
  const double nu = s.number("poisson_ratio", 2.0 / 7.0);
  c.restitution = s.optional_number("restitution");
  if (c.normal == dem::NormalLawKind::hooke) {
    // kn directly, or from E and nu with LAMMPS's example-script formula (units.hpp).
    if (s.has("kn") == E.has_value()) s.fail_table("give exactly one of 'kn' or 'youngs_modulus'");
    c.kn = E ? lammps_hooke_from_material(*E, nu, 0.5, grain_mass(density, 0.8)).kn : s.positive("kn", 0.0);
  } else {
    if (!E) s.fail_table("the Hertz law needs 'youngs_modulus' (and 'poisson_ratio')");
    c.effective_modulus = hertz_effective_modulus(*E, nu, *E, nu);
  }
  const double mu = s.number("friction", 0.0);
  if (mu > 0.0) {
    c.tangential = dem::TangentialLawKind::spring_history;
    c.friction = mu;
    c.kt = s.positive("kt", 2.0 / 7.0 * (c.kn > 0.0 ? c.kn : 1.0));
  }
  s.finish();
}

void read_preparation(Section s, PreparationSettings& p) {
  p.pressure = s.positive("pressure", p.pressure);
  const std::string compression = s.choice("compression", "wall", {"wall", "affine", "pressure"});
  p.compression = compression == "wall" ? Compression::wall
                  : compression == "affine" ? Compression::affine
                                            : Compression::pressure;
  p.compression_speed = s.positive("compression_speed", p.compression_speed);
  p.compression_strain_rate = s.positive("compression_strain_rate", p.compression_strain_rate);
  p.compression_damping = s.number("compression_damping", p.compression_damping);
  p.residual_force_tolerance = s.positive("residual_force_tolerance", p.residual_force_tolerance);
  p.pressure_tolerance = s.positive("pressure_tolerance", p.pressure_tolerance);
  p.max_compression_steps = s.integer("max_compression_steps", p.max_compression_steps);
  p.max_relaxation_steps = s.integer("max_relaxation_steps", p.max_relaxation_steps);
  p.newton_relaxation = s.boolean("newton_relaxation", p.newton_relaxation);
  p.newton_start_tolerance = s.positive("newton_start_tolerance", p.newton_start_tolerance);
  s.finish();
}

void read_drive(Section s, DriveSettings& d) {
  d.axis = s.choice("axis", "z", {"z", "x"}) == "z" ? DriveAxis::longitudinal : DriveAxis::transverse;
  d.amplitude = s.positive("amplitude", d.amplitude);
  const std::string signal = s.choice("signal", "sinusoid", {"sinusoid", "pulse", "chirp"});
  if (signal != "chirp" && s.has("sweep_periods")) s.fail_key("sweep_periods", "is for signal = \"chirp\"");
  if (signal != "sinusoid") {
    if (s.has("omega_hat")) s.fail_table("a " + signal + " spans omega_hat_min..omega_hat_max; 'omega_hat' is for signal = \"sinusoid\"");
    PulseBand band;
    if (signal == "chirp") {
      band.shape = BroadbandShape::log_chirp;
      band.sweep_periods = s.positive("sweep_periods", band.sweep_periods);
    }
    band.omega_hat_min = s.positive("omega_hat_min", band.omega_hat_min);
    band.omega_hat_max = s.positive("omega_hat_max", band.omega_hat_max);
    band.frequencies = static_cast<int>(s.integer("frequencies", band.frequencies, 1));
    if (!(band.omega_hat_max > band.omega_hat_min)) s.fail_table("omega_hat_max must exceed omega_hat_min");
    d.pulse = band;
  } else {
    d.omega_hat = s.positive("omega_hat", d.omega_hat);
  }
  if (s.has("gamma_hat") && s.has("restitution")) s.fail_table("give 'gamma_hat' or 'restitution', not both");
  if (s.has("restitution")) {
    const double e = s.positive("restitution", 0.9);
    d.gamma_hat = gamma_hat_from_restitution(e);
  } else {
    d.gamma_hat = s.number("gamma_hat", d.gamma_hat);
  }
  d.far_end = s.choice("far_end", "absorbing", {"frozen", "absorbing"}) == "frozen" ? FarEnd::frozen : FarEnd::absorbing;
  d.far_wall = s.choice("far_wall", "frozen", {"frozen", "loaded"}) == "loaded" ? FarWall::loaded : FarWall::frozen;
  if (s.has("far_wall_mass")) {
    if (d.far_wall != FarWall::loaded) s.fail_table("far_wall_mass is for far_wall = \"loaded\"");
    d.far_wall_mass = s.positive("far_wall_mass", 1.0);
  }
  d.absorbing_fraction = s.positive("absorbing_fraction", d.absorbing_fraction);
  d.absorbing_strength = s.positive("absorbing_strength", d.absorbing_strength);
  d.periods = s.number("periods", d.periods);
  d.samples_per_period = static_cast<int>(s.integer("samples_per_period", d.samples_per_period));
  d.time_step_fraction = s.positive("time_step_fraction", d.time_step_fraction);
  Section m = s.sub("measurement");
  d.layer_thickness = m.positive("layer_thickness", d.layer_thickness);
  d.skip_layers = static_cast<int>(m.integer("skip_layers", d.skip_layers));
  d.max_fit_depth = m.positive("max_fit_depth", d.max_fit_depth);
  d.grain_probes = m.boolean("grain_probes", d.grain_probes);
  d.settle_periods = m.number("settle_periods", d.settle_periods);
  d.steady_extensions = static_cast<int>(m.integer("steady_extensions", d.steady_extensions, 0));
  m.finish();
  s.finish();
}

void read_linear(Section s, linear::LinearSettings& l) {
  l.ensemble = static_cast<int>(s.integer("ensemble", l.ensemble, 1));
  l.gap_search = s.positive("gap_search", l.gap_search);
  l.warn_state_changes = s.positive("warn_state_changes", l.warn_state_changes);
  l.refuse_state_changes = s.positive("refuse_state_changes", l.refuse_state_changes);
  s.finish();
}

ChannelScene from_value(const toml::value& root, const std::string& origin, const std::filesystem::path& base) {
  ChannelScene scene;
  Section top(root, "", origin);
  top.allow_only({"title", "engine", "geometry", "contact", "preparation", "drive", "linear"});
  top.text("title", "");
  scene.engine = top.choice("engine", "time_domain", {"time_domain", "linear"}) == "linear" ? EngineKind::linear
                                                                                           : EngineKind::time_domain;
  read_geometry(top.sub("geometry"), scene, base);
  read_contact(top.sub("contact"), scene.contact, scene.geometry.density);
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
  if (scene.drive.pulse && scene.engine == EngineKind::linear) {
    top.sub("drive").fail_table("signal: the linear engine solves each frequency directly; a pulse is for the "
                                "time-domain engine");
  }
  if (scene.drive.pulse && scene.drive.far_end != FarEnd::absorbing) {
    top.sub("drive").fail_table("far_end: a pulse needs far_end = \"absorbing\" (a frozen end sends the whole pulse "
                                "back through the layers being measured)");
  }
  if (scene.engine == EngineKind::linear && scene.drive.far_end != FarEnd::absorbing) {
    top.sub("drive").fail_table("far_end: the linear engine computes the steady state, in which a frozen end "
                                         "reflects the whole wave: use far_end = \"absorbing\"");
  }
  top.finish();
  if (!scene.contact.restitution) scene.contact.restitution = 0.9;  // preparation damping (thesis)
  return scene;
}

}  // namespace

ChannelScene parse_scene(const std::string& text, const std::string& origin) {
  ChannelScene scene =
      from_value(toml_io::parse<SceneError>(text, origin), origin, std::filesystem::path(origin).parent_path());
  scene.text = text;
  scene.path = origin;
  return scene;
}

ChannelScene read_scene(const std::filesystem::path& path) {
  return parse_scene(toml_io::read_text<SceneError>(path, "scene file"), path.string());
}

}  // namespace sedwave::forward::channel
