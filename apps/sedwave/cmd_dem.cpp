// `sedwave dem`: runs a packing from a LAMMPS data file (atom_style sphere) with the DEM engine,
// with walls chosen by atom type, checkpoints and restarts, dumps and a final-state file. Under
// mpirun the grains are shared among the ranks (see docs/dem.md, "The sedwave dem command").
#include <mpi.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "option_checks.hpp"
#include "mpi_session.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/dem/contact/read_contact.hpp"
#include "sedwave/forward/dem/engine.hpp"
#include "sedwave/forward/dem/gather.hpp"
#include "sedwave/forward/dem/h5md.hpp"
#include "sedwave/forward/dem/lammps_io.hpp"
#include "sedwave/forward/parallel/collectives.hpp"
#include "sedwave/io/fingerprint.hpp"
#include "sedwave/version.hpp"

namespace sedwave::app {
namespace {

namespace dem = forward::dem;

struct DemOptions {
  std::string data;
  std::int64_t steps = 0;
  std::string boundary = "ppf";
  /// Contact laws by name and their keys' values, by key (docs/dem.md lists them).
  std::optional<std::string> law, tangential, rolling;
  std::map<std::string, std::optional<double>, std::less<>> contact;
  std::vector<double> gravity;
  /// A still pore fluid (dem/fluid.hpp), in the data file's units; none without --fluid-viscosity.
  struct Fluid {
    std::optional<double> viscosity, density, roughness, cutoff, porosity;
    std::optional<std::string> drag, lubrication;
  } fluid;
  std::optional<double> dt, skin;
  std::string newton = "on";
  std::vector<int> frozen_types;
  std::vector<std::string> wiggles;
  std::string checkpoint;
  std::int64_t checkpoint_every = 0;
  bool restart = false;
  std::string dump;
  std::int64_t dump_every = 0;
  std::string h5md;
  std::int64_t h5md_every = 0;
  std::string final_state;
  double progress_seconds = 10.0;
  bool quiet = false;
  bool allow_changed_inputs = false;
};

/// "ppf" or "p p f" (LAMMPS's boundary command): p periodic; f, s or m open.
std::array<bool, 3> parse_boundary(std::string text) {
  std::erase(text, ' ');
  if (text.size() != 3 || text.find_first_not_of("pfsm") != std::string::npos)
    throw std::invalid_argument("--boundary '" + text + "': expected three letters p (periodic) or f (open), e.g. ppf");
  return {text[0] == 'p', text[1] == 'p', text[2] == 'p'};
}

/// Accepts the numbers within `bounds` (CLI11's Range includes both ends).
CLI::Validator within(const io::Range& bounds) {
  const std::string range = bounds.describe();
  return CLI::Validator(
      [bounds, range](const std::string& text) -> std::string {
        double x = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
        const bool ok = error == std::errc{} && end == text.data() + text.size() && bounds.contains(x);
        return ok ? std::string{} : "value " + text + " not in the accepted range " + range;
      },
      range);
}

/// (low, high], or (low, inf).
CLI::Validator half_open_range(double low, double high) { return within({low, high, true, std::isinf(high)}); }

/// The value of a contact option, by key (none when not given).
std::optional<double> given(const DemOptions& o, std::string_view key) {
  const auto it = o.contact.find(key);
  return it == o.contact.end() ? std::nullopt : it->second;
}

/// The contact options as a source for dem::read_contact, which reads a scene's [contact] the same
/// way. An option the chosen laws do not read is refused (e.g. --kt without a tangential law).
class OptionContactKeys final : public dem::ContactKeySource {
 public:
  explicit OptionContactKeys(const DemOptions& o) : o_(o) {}
  std::optional<std::string> choice(std::string_view selector, const std::vector<std::string>& /*names*/) override {
    if (selector == "law") return o_.law;
    return selector == "tangential" ? o_.tangential : o_.rolling;  // CLI11 checked the names
  }
  std::optional<double> number(const dem::ContactKey& k) override {
    asked_.insert(std::string(k.key));
    return given(o_, k.key);  // CLI11 checked the bounds
  }
  [[noreturn]] void fail(const std::string& why) override { throw std::invalid_argument("contact options: " + why); }
  /// Refuses options that no chosen law read.
  void require_all_read(const dem::ContactSpec& spec) const {
    for (const dem::ContactKey* k : dem::all_contact_keys())
      if (given(o_, k->key) && !asked_.count(std::string(k->key)))
        throw std::invalid_argument("--" + std::string(k->option) + " does not apply to " + dem::describe(spec));
  }

 private:
  const DemOptions& o_;
  std::set<std::string> asked_;
};

dem::ContactSpec contact_spec(const DemOptions& o) {
  OptionContactKeys keys(o);
  const dem::ContactSpec spec = dem::read_contact(keys);
  keys.require_all_read(spec);
  return spec;
}

/// Walls from atom types: --frozen TYPE and --wiggle TYPE:AXIS:AMPLITUDE:PERIOD, one rigid body each.
std::vector<dem::RigidBody> make_walls(const DemOptions& o, std::map<int, std::int32_t>& body_of_type) {
  std::vector<dem::RigidBody> bodies;
  auto add = [&](int type, dem::BodyMotion motion, const std::string& name) {
    if (!body_of_type.emplace(type, static_cast<std::int32_t>(bodies.size()) + 1).second)
      throw std::invalid_argument("atom type " + std::to_string(type) + " is given to two walls");
    bodies.emplace_back(name, std::move(motion));
  };
  for (int type : o.frozen_types) add(type, dem::Frozen{}, "frozen type " + std::to_string(type));
  for (const std::string& spec : o.wiggles) {
    std::vector<std::string> parts;
    std::stringstream stream(spec);
    for (std::string part; std::getline(stream, part, ':');) parts.push_back(part);
    const bool axis_ok = parts.size() == 4 && parts[1].size() == 1 && parts[1].find_first_of("xyz") == 0;
    if (!axis_ok) throw std::invalid_argument("--wiggle '" + spec + "': expected TYPE:AXIS:AMPLITUDE:PERIOD, AXIS x, y or z");
    dem::Wiggle w;
    w.axis = parts[1][0] - 'x';
    int type = 0;
    try {
      type = std::stoi(parts[0]);
      w.amplitude = std::stod(parts[2]);
      w.period = std::stod(parts[3]);
    } catch (const std::logic_error&) {
      throw std::invalid_argument("--wiggle '" + spec + "': TYPE, AMPLITUDE and PERIOD must be numbers");
    }
    if (!(w.period > 0.0)) throw std::invalid_argument("--wiggle '" + spec + "': PERIOD must be positive");
    add(type, w, "wiggle type " + parts[0]);
  }
  return bodies;
}

bool exists_on_root(const std::string& path) {
  return forward::parallel::root_says(MPI_COMM_WORLD, [&] { return std::filesystem::exists(path); });
}

/// Writes a trajectory frame now and every `every` steps. After a restart the frames that the
/// interrupted run wrote past its checkpoint are cut away first (and no frame is written now), so the
/// file ends up as one uninterrupted run would have written it.
template <class Writer>
void add_trajectory(dem::Engine& engine, const std::string& path, std::int64_t every, bool restarted,
                    const MpiSession& mpi, std::size_t (*truncate)(const std::string&, std::int64_t)) {
  const bool append = restarted && exists_on_root(path);
  if (append && mpi.rank() == 0) truncate(path, engine.step_count());
  MPI_Barrier(MPI_COMM_WORLD);
  auto writer = std::make_shared<Writer>(path, append);
  if (!append) writer->write(engine);
  engine.add_step_callback(every, [writer](const dem::Engine& e) { writer->write(e); });
}

/// Shortest round-trip text of an optional number, "(none)" when absent.
std::string option_text(const std::optional<double>& x) {
  if (!x) return "(none)";
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, *x).ptr);
}

template <typename T>
std::string list_text(const std::vector<T>& values) {
  std::ostringstream text;
  for (std::size_t k = 0; k < values.size(); ++k) text << (k ? " " : "") << values[k];
  return values.empty() ? "(none)" : text.str();
}

/// What a checkpoint depends on, by option name: a restart with any of them changed would continue
/// another run than the one checkpointed. (--skin, --progress and the outputs change no physics.)
std::map<std::string, std::string> run_inputs(const DemOptions& o) {
  return {{"sedwave version", kVersion},
          {"data file", "hash " + io::file_fingerprint(o.data)},
          {"--boundary", o.boundary},
          {"--gravity", list_text(o.gravity)},
          {"--dt", option_text(o.dt)},
          {"--newton", o.newton},
          {"--frozen", list_text(o.frozen_types)},
          {"--wiggle", list_text(o.wiggles)}};
}

/// The fluid options, checked together: --fluid-viscosity, --fluid-roughness and --fluid-cutoff
/// make a fluid, the others refine it; none: dry.
std::optional<dem::FluidSpec> fluid_spec(const DemOptions& o) {
  const DemOptions::Fluid& f = o.fluid;
  const bool any = f.viscosity || f.density || f.roughness || f.cutoff || f.porosity || f.drag || f.lubrication;
  if (!any) return std::nullopt;
  for (const auto& [option, value] : {std::pair{"--fluid-viscosity", f.viscosity}, std::pair{"--fluid-roughness", f.roughness},
                                      std::pair{"--fluid-cutoff", f.cutoff}})
    if (!value) throw std::invalid_argument(std::string(option) + " is required with any --fluid-* option");
  dem::FluidSpec spec;
  spec.viscosity = *f.viscosity;
  spec.density = f.density.value_or(0.0);
  spec.roughness = *f.roughness;
  spec.cutoff = *f.cutoff;
  spec.lubrication = f.lubrication.value_or("on") == "on";
  if (f.drag) spec.drag = dem::drag_law_of(*f.drag);
  if (f.porosity && spec.drag != dem::DragLaw::richardson_zaki)
    throw std::invalid_argument("--fluid-porosity is read by --fluid-drag richardson_zaki only");
  spec.porosity = f.porosity.value_or(spec.porosity);
  if (!(spec.cutoff > spec.roughness))
    throw std::invalid_argument("--fluid-cutoff " + option_text(spec.cutoff) + ": accepted range (--fluid-roughness, inf) = (" +
                                option_text(spec.roughness) + ", inf)");
  if (const std::string why = spec.problem(); !why.empty()) throw std::invalid_argument("fluid options: " + why);
  return spec;
}

/// run_inputs, every contact option and the fluid.
std::map<std::string, std::string> checkpoint_inputs(const DemOptions& o) {
  std::map<std::string, std::string> inputs = run_inputs(o);
  const DemOptions::Fluid& f = o.fluid;
  inputs["--fluid-viscosity"] = option_text(f.viscosity);
  inputs["--fluid-density"] = option_text(f.density);
  inputs["--fluid-roughness"] = option_text(f.roughness);
  inputs["--fluid-cutoff"] = option_text(f.cutoff);
  inputs["--fluid-porosity"] = option_text(f.porosity);
  inputs["--fluid-drag"] = f.drag.value_or("(none)");
  inputs["--fluid-lubrication"] = f.lubrication.value_or("(none)");
  inputs["--law"] = o.law.value_or("(none)");
  inputs["--tangential"] = o.tangential.value_or("(none)");
  inputs["--rolling"] = o.rolling.value_or("(none)");
  for (const dem::ContactKey* k : dem::all_contact_keys())
    inputs["--" + std::string(k->option)] = option_text(given(o, k->key));
  return inputs;
}

/// Every file the run writes, checked against the data file and for a writable directory before
/// any step.
void check_dem_paths(const DemOptions& o) {
  std::vector<OutputPath> outputs;
  using io::OutputFormat;
  for (const auto& [option, path, format] : {std::tuple{"--checkpoint", &o.checkpoint, OutputFormat::seekable},
                                             std::tuple{"--dump", &o.dump, OutputFormat::text},
                                             std::tuple{"--h5md", &o.h5md, OutputFormat::seekable},
                                             std::tuple{"--final", &o.final_state, OutputFormat::text}}) {
    if (!path->empty()) outputs.push_back({option, *path, format});
  }
  check_outputs(outputs, {o.data}, "dem");
}

int run_dem(const DemOptions& o, const MpiSession& mpi) {
  std::ostream& out = std::cout;
  const bool root = mpi.rank() == 0;
  // The options, checked alike on every rank: a mistake is told once.
  std::map<int, std::int32_t> body_of_type;
  std::vector<dem::RigidBody> bodies;
  dem::EngineSettings s;
  mpi.alike([&] {
    if (!o.dump.empty() && o.dump_every <= 0) throw std::invalid_argument("--dump needs --dump-every");
    if (!o.h5md.empty() && o.h5md_every <= 0) throw std::invalid_argument("--h5md needs --h5md-every");
    check_dem_paths(o);
    bodies = make_walls(o, body_of_type);
    s.box.periodic = parse_boundary(o.boundary);
    s.contact = contact_spec(o);
    if (!o.gravity.empty()) s.gravity = {o.gravity.at(0), o.gravity.at(1), o.gravity.at(2)};
    s.fluid = fluid_spec(o);
    s.checkpoint.inputs = checkpoint_inputs(o);
  });
  s.time_step = o.dt;
  if (o.skin) s.skin = *o.skin;
  s.newton = o.newton == "on";
  s.checkpoint.path = o.checkpoint;
  s.checkpoint.every = o.checkpoint_every;
  s.checkpoint.allow_changed_inputs = o.allow_changed_inputs;
  s.progress = {!o.quiet, o.progress_seconds, &out};

  // Each rank reads its share of the file's bytes; the engine then sends each grain to its slab's owner.
  dem::LammpsData data = dem::read_lammps_data(MPI_COMM_WORLD, o.data);
  for (dem::Grain& g : data.grains) {
    const auto it = body_of_type.find(g.group);
    if (it != body_of_type.end()) g.body = it->second;
  }
  const std::array<bool, 3> periodic = s.box.periodic;
  s.box = data.box;
  s.box.periodic = periodic;

  dem::Engine engine(MPI_COMM_WORLD, s, data.grains, std::move(bodies));
  data.grains = {};

  bool restarted = false;
  if (o.restart) {
    restarted = exists_on_root(o.checkpoint);
    if (restarted) engine.restore_checkpoint(o.checkpoint);
    if (root && !o.quiet)
      out << (restarted ? "dem: restarting from " + o.checkpoint + " at step " + std::to_string(engine.step_count())
                        : "dem: no checkpoint " + o.checkpoint + " yet: starting at step 0")
          << '\n';
  }
  if (root && !o.quiet)
    out << "dem: " << engine.n_global() << " grains, " << dem::describe(s.contact)
        << (s.fluid ? " in a fluid (" + dem::describe(*s.fluid) + ")" : std::string()) << ", time step "
        << engine.time_step() << " (" << engine.time_step_limits().summary() << "), " << mpi.size() << " rank(s)\n";

  if (!o.dump.empty())
    add_trajectory<dem::LammpsDumpWriter>(engine, o.dump, o.dump_every, restarted, mpi, dem::truncate_lammps_dump);
  if (!o.h5md.empty())
    add_trajectory<dem::H5mdWriter>(engine, o.h5md, o.h5md_every, restarted, mpi, dem::truncate_h5md);

  const std::int64_t remaining = o.steps - engine.step_count();
  if (remaining > 0) engine.run(remaining);
  else if (root && !o.quiet) out << "dem: already at step " << engine.step_count() << ": nothing to run\n";
  // A checkpoint of the final state (unless the periodic one just wrote it), so a later --restart
  // with more --steps continues from here.
  const bool just_written = o.checkpoint_every > 0 && engine.step_count() % o.checkpoint_every == 0;
  if (!o.checkpoint.empty() && remaining > 0 && !just_written) engine.write_checkpoint(o.checkpoint);

  if (!o.final_state.empty()) {
    std::vector<dem::Grain> grains = dem::gather_grains(engine);
    std::sort(grains.begin(), grains.end(), [](const dem::Grain& a, const dem::Grain& b) { return a.id < b.id; });
    if (root) dem::write_lammps_data(o.final_state, engine.domain().box(), grains);
  }
  const double kinetic = engine.kinetic_energy();
  if (root && !o.quiet)
    out << "dem: finished at step " << engine.step_count() << ", t = " << engine.time() << ", kinetic energy "
        << kinetic << '\n';
  return 0;
}

/// --law, --tangential, --rolling and one option per key of the contact laws (dem::read_contact).
void add_contact_options(CLI::App& cmd, DemOptions& o) {
  cmd.add_option("--law", o.law, "normal contact law: " + comma_separated(dem::normal_law_names()) + " (default hooke)")
      ->check(CLI::IsMember(dem::normal_law_names()));
  cmd.add_option("--tangential", o.tangential,
                 "tangential law: " + comma_separated(dem::tangential_law_names()) +
                     " (default spring_history with --friction, else none)")
      ->check(CLI::IsMember(dem::tangential_law_names()));
  cmd.add_option("--rolling", o.rolling, "rolling law: " + comma_separated(dem::rolling_law_names()) + " (default none)")
      ->check(CLI::IsMember(dem::rolling_law_names()));
  for (const dem::ContactKey* k : dem::all_contact_keys())
    cmd.add_option("--" + std::string(k->option), o.contact[std::string(k->key)], std::string(k->help))
        ->check(within(k->bounds));
}

/// --fluid-*: a still pore fluid around the grains (docs/fluid.md).
void add_fluid_options(CLI::App& cmd, DemOptions& o) {
  DemOptions::Fluid& f = o.fluid;
  cmd.add_option("--fluid-viscosity", f.viscosity, "pore fluid viscosity mu [mass/(length time)]; gives the run a fluid")
      ->check(within(io::Range::positive()));
  cmd.add_option("--fluid-roughness", f.roughness,
                 "smallest lubrication gap h_r [length]: the squeeze-film force at smaller gaps and overlaps is that at h_r")
      ->check(within(io::Range::positive()));
  cmd.add_option("--fluid-cutoff", f.cutoff, "no lubrication at gaps beyond h_c [length] (> --fluid-roughness)")
      ->check(within(io::Range::positive()));
  cmd.add_option("--fluid-density", f.density, "fluid density [mass/length^3] for buoyancy under --gravity (default 0)")
      ->check(within(io::Range::non_negative()));
  cmd.add_option("--fluid-drag", f.drag, "drag on each grain: richardson_zaki (default), stokes or none")
      ->check(CLI::IsMember(dem::drag_law_names()));
  cmd.add_option("--fluid-porosity", f.porosity, "porosity of the Richardson-Zaki drag correction (default 0.4)")
      ->check(within({0.0, 1.0, true, true}));
  cmd.add_option("--fluid-lubrication", f.lubrication, "the squeeze-film force between grains: on (default) or off")
      ->check(CLI::IsMember({"on", "off"}));
}

}  // namespace

Command add_dem_command(CLI::App& app) {
  auto o = std::make_shared<DemOptions>();
  CLI::App* cmd = app.add_subcommand(
      "dem", "Run a grain packing from a LAMMPS data file (atom_style sphere) with the DEM engine "
             "(contact laws chosen by --law, --tangential and --rolling; run under mpirun for several ranks)");
  cmd->add_option("data", o->data, "LAMMPS data file: id type diameter density x y z [+ Velocities]")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--steps", o->steps, "step number to reach (a restart runs only the steps left)")
      ->required()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--boundary", o->boundary, "periodicity along x y z, p or f each (LAMMPS boundary)")
      ->capture_default_str();
  add_contact_options(*cmd, *o);
  add_fluid_options(*cmd, *o);
  cmd->add_option("--gravity", o->gravity, "gravity gx,gy,gz")->delimiter(',')->expected(3);
  cmd->add_option("--dt", o->dt, "time step (default 0.01 binary collision time; refused above the "
                                 "stability limit)")
      ->check(half_open_range(0.0, INFINITY));
  cmd->add_option("--skin", o->skin, "neighbour skin (default 0.1 mean diameter)")
      ->check(half_open_range(0.0, INFINITY));
  cmd->add_option("--newton", o->newton,
                  "on: a pair across a periodic face or rank boundary is computed once and its reaction "
                  "sent back (LAMMPS newton on); off: computed on both sides")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--frozen", o->frozen_types, "atom TYPE forming a wall that does not move (repeatable)");
  cmd->add_option("--wiggle", o->wiggles,
                  "TYPE:AXIS:AMPLITUDE:PERIOD: atom type forming a wall moved by AMPLITUDE sin(2 pi t/PERIOD) "
                  "along AXIS x, y or z (LAMMPS fix move wiggle; repeatable)");
  auto* checkpoint = cmd->add_option("--checkpoint", o->checkpoint,
                                     "HDF5 checkpoint, replaced atomically every --every steps and at the end");
  cmd->add_option("--every", o->checkpoint_every, "steps between checkpoints")
      ->needs(checkpoint)
      ->check(half_open_range(0.0, INFINITY));
  cmd->add_flag("--restart", o->restart,
                "continue from --checkpoint if it exists (else start at step 0); finished steps are not redone; "
                "refused if the data file, a contact or wall option or the sedwave version differs from the "
                "checkpoint's")
      ->needs(checkpoint);
  cmd->add_flag("--allow-changed-inputs", o->allow_changed_inputs,
                "with --restart: continue even if the data file or options differ from the checkpoint's");
  auto* dump = cmd->add_option("--dump", o->dump, "LAMMPS text dump (id type radius x y z vx vy vz)");
  cmd->add_option("--dump-every", o->dump_every, "steps between dump frames")
      ->needs(dump)
      ->check(half_open_range(0.0, INFINITY));
  auto* h5md = cmd->add_option("--h5md", o->h5md,
                               "H5MD (HDF5) trajectory: position, velocity, id, species, radius, box");
  cmd->add_option("--h5md-every", o->h5md_every, "steps between H5MD frames")
      ->needs(h5md)
      ->check(half_open_range(0.0, INFINITY));
  cmd->add_option("--final", o->final_state,
                  "write the final state as a LAMMPS data file (17 digits: reads back bit for bit)");
  cmd->add_option("--progress", o->progress_seconds, "seconds between progress lines")->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "no progress lines or timing table");
  cmd->footer("Example: sedwave dem packing.data --steps 100000 --kn 725.9 --restitution 0.9 --frozen 2 "
              "--checkpoint run.h5 --every 10000 --restart --dump run.dump --dump-every 1000");
  return {cmd, [o]() {
    const MpiSession mpi;
    return mpi.run([&] { return run_dem(*o, mpi); });
  }};
}

}  // namespace sedwave::app
