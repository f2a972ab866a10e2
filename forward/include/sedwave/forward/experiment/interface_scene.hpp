#pragma once
// A granular-solid interface scene (docs/interface.md): the plate, the hexagonal packing on its top
// edge, the contacts, the drive at the packing's free end and what to record. SI units throughout
// (m, kg, s, Pa, N). Read by `sedwave interface`.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/forward/interface/granular_plate.hpp"
#include "sedwave/forward/plate/elastic_plate.hpp"

namespace sedwave::forward::experiment {

/// Error in an interface scene: "FILE:LINE: key 'a.b': why".
class InterfaceSceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The impulse on the packing's free end (its row farthest from the plate), towards the plate; or,
/// edge_impulse, a uniform line load on the plate's top edge under the driven beads' span (no beads:
/// the monolithic plate), into the plate, held for `duration`.
struct InterfaceDrive {
  enum class Kind { velocity, force, edge_impulse };
  Kind kind = Kind::velocity;
  double speed = 1.0;       ///< velocity: initial speed of the driven grains [m/s]
  double peak = 0.0;        ///< force: peak of the half-sine on each driven grain [N]
  double duration = 0.0;    ///< force, edge_impulse: its duration [s]
  double line_load = 0.0;   ///< edge_impulse: the load per unit length of edge [N/m]
  int width = 0;            ///< driven grains of the free row, centred on the plate (0: the whole row)
  /// The reference for the delay: no beads; the plate's top-edge nodes under the driven beads' span
  /// start with one speed towards the plate's inside, carrying the strike's kinetic energy.
  bool direct = false;
};

struct InterfaceRecording {
  double duration = 0.0;         ///< simulated time [s]
  double tolerance = 0.1;        ///< the adaptive step's theta (granular_plate.hpp)
  double fixed_step = 0.0;       ///< > 0: a fixed step [s] instead (for comparisons)
  double output_interval = 0.0;  ///< time between samples [s] (0: duration / 1000)
  int snapshots = 5;             ///< plate displacement snapshots, evenly spaced, the last at the end
  std::vector<double> probe_x;   ///< abscissae of the probes [m] (default: the plate's centre)
  double probe_depth = 0.0;      ///< depth of the probes below the interface [m] (0: the interface)
  double line_depth = 0.0;       ///< depth of the recorded line of nodes [m] (the wavenumber analysis)
  double arrival_fraction = 0.1; ///< arrival: first time |v| reaches this fraction of its maximum
  interface::Scheme scheme = interface::Scheme::velocity_verlet;
  double iteration_reltol = 1e-10;  ///< newmark_rk4: the fixed point's relative tolerance
  double iteration_abstol = 1e-9;   ///< newmark_rk4: and its absolute one [N]
  double plate_tolerance = 0.1;     ///< multirate: the outer step's theta (default: tolerance)
};

/// Rigid side walls at `gap` from the packing's outermost beads (docs/interface.md, "Side walls").
struct InterfaceWalls {
  bool left = false;
  bool right = false;
  double gap = 0.0;             ///< [m] from the packing's boundary to each wall's face
  double youngs_modulus = 0.0;  ///< [Pa] the walls' material (default: the plate's)
  double poisson_ratio = 0.0;
  double friction = 0.0;        ///< Coulomb coefficient along the walls (default: contact.friction)
};

struct InterfaceScene {
  std::filesystem::path path;
  std::string text;  ///< verbatim, kept in the run file
  plate::PlateMaterial plate_material{70e9, 0.33, 2700.0, 5e-3};
  plate::PlateMesh mesh{120, 40, 0.12, 0.04};
  plate::PlateEdges edges;
  interface::HexPacking packing;
  double packing_load = 0.0;       ///< static precompression [N] on each bead of the free row (0: none)
  double relaxation_time = 2e-5;   ///< damping time [s] of the relaxation under that load
  interface::GrainMaterial grain_material{200e9, 0.3};
  interface::InterfaceContacts contacts;
  InterfaceWalls walls;
  InterfaceDrive drive;
  InterfaceRecording recording;
};

/// The walls' contact with the beads (side_walls.hpp): placed about the packing, E* of bead and wall.
[[nodiscard]] interface::SideWalls side_walls(const InterfaceScene& scene);

InterfaceScene parse_interface_scene(const std::string& text, const std::string& origin);
InterfaceScene read_interface_scene(const std::filesystem::path& path);

/// Command-line overrides, checked against the ranges of the keys they replace (run.fixed_step: at
/// most run.duration); std::invalid_argument naming `option` and the range otherwise.
void override_speed(InterfaceScene& scene, double speed, const std::string& option);
void override_tolerance(InterfaceScene& scene, double tolerance, const std::string& option);
void override_fixed_step(InterfaceScene& scene, double step, const std::string& option);

}  // namespace sedwave::forward::experiment
