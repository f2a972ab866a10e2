#pragma once
// Preparing the channel: compress the loose column by lowering the upper wall (with global viscous
// damping) until the grains carry the pressure P, then relax it to mechanical equilibrium with FIRE.
//
// Why both stages: damping alone never settles a frictionless column (it keeps creeping), and both
// the lock-in measurement and the linear-response engine need a truly static start. FIRE (Bitzek et
// al., PRL 97, 170201, 2006) is the standard minimiser for jammed packings: molecular dynamics whose
// velocities are steered along the force and zeroed whenever the power F.v turns negative.
//
// For frictionless packings FIRE only settles the column roughly (and the wall height to the
// pressure); Newton's method on the elastic energy (linear/static_equilibrium.hpp) then finishes the
// job in a few O(N) solves. FIRE's cost to a tight tolerance grows like N^2 in a long column (its
// slowest mode is a wave crossing the column); Newton's like N.
//
// With friction, FIRE runs to the tolerance at a frozen upper wall (a minimiser needs a fixed energy
// landscape); its height is then corrected by a secant iteration until the force the grains exert on
// it is P W^2 within the tolerance, and FIRE runs again. Pressure is force per area: the wall
// carries P W^2 in total, not P per wall grain.
//
// A z-periodic cell without walls (ChannelGeometry::periodic, the building block of long channels:
// periodic_cell.hpp) goes through the same stages with its length in the wall's place: the box is
// strained affinely during compression and corrected by the same secant iteration, and the force it
// carries is its contact virial over its length (PackingStats::virial_zz), the force across every
// cross-section.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "sedwave/forward/channel/contacts.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"

namespace sedwave::forward::channel {

/// How the loose column is brought to the pressure (stage 1).
enum class Compression {
  wall,      ///< the upper wall descends at compression_speed (the thesis's protocol)
  affine,    ///< every height shrinks at compression_strain_rate: O(N) for long columns
  pressure,  ///< the upper wall is a servo holding P W^2: compression_speed while the column is
             ///< loose, slowing as the grains take the load, backing off if they carry more
};

struct PreparationSettings {
  double pressure = 10.0;             ///< P [force / length^2] on the upper wall
  Compression compression = Compression::wall;
  /// Compression: the upper wall moves down at this speed, in mean diameters per binary collision
  /// time, until the grains push back with P W^2. A speed cap (rather than the constant force
  /// itself) keeps impacts gentle: a contact hit at speed v overlaps by about v t_col / pi.
  double compression_speed = 0.03;
  /// Global viscous drag during compression, in units of m pi / t_col of the mean grain. Off by
  /// default: the wall pushes a growing plug of grains, and drag on that plug (n c v) soon rivals the
  /// target force itself, ending compression long before the grains carry the pressure. The
  /// contact dashpots and FIRE remove the kinetic energy instead.
  double compression_damping = 0.0;
  /// Affine compression: the rate at which heights above the lower wall shrink, per binary
  /// collision time. Neighbours one diameter apart approach at this many diameters per t_col (the
  /// analogue of compression_speed), so a column of any length is compressed in about
  /// 0.5 / rate collision times (from the initial packing fraction 0.3), where the wall needs its
  /// length over its speed; a slower rate lets grains rearrange more on the way.
  double compression_strain_rate = 3e-4;
  double compression_step_fraction = 0.15;  ///< dt / binary collision time while compressing
  std::int64_t max_compression_steps = 5'000'000;
  double relaxation_step_fraction = 0.2;    ///< dt / binary collision time during FIRE
  double residual_force_tolerance = 1e-9;   ///< max |F| on a flow grain / mean contact force
  double pressure_tolerance = 1e-2;         ///< | wall force / (P W^2) - 1 |
  std::int64_t max_relaxation_steps = 2'000'000;
  int max_wall_corrections = 30;
  /// Finish with Newton's method (linear/static_equilibrium.hpp) once FIRE has brought the residual
  /// ratio below newton_start_tolerance (and the wall force within pressure_tolerance): the slowest
  /// modes of a long column, which FIRE relaxes in O(N) steps each costing O(N), are solved
  /// directly. Frictionless packings only; with friction FIRE does everything.
  bool newton_relaxation = true;
  double newton_start_tolerance = 1e-3;
  std::ostream* log = nullptr;              ///< progress lines (rank 0), or nullptr
};

struct PreparationReport {
  std::int64_t compression_steps = 0;
  std::int64_t relaxation_steps = 0;
  int wall_corrections = 0;
  int newton_iterations = 0;       ///< Newton steps tried (accepted or not)
  double wall_force = 0.0;         ///< force of the grains on the upper wall (a periodic cell: across a section)
  double target_wall_force = 0.0;  ///< P W^2
  double pressure = 0.0;           ///< wall_force / W^2
  double residual_ratio = 0.0;     ///< max |F| / mean contact force at the end
  bool converged = false;
  PackingStats stats;
};

struct PreparedChannel {
  dem::Box box;
  /// Grains at rest: all on rank 0 (empty elsewhere) as prepare_channel returns them; a tiled or
  /// read packing spread over the ranks.
  std::vector<dem::Grain> grains;
  PreparationReport report;
};

/// Newton's method for the last stage of a frictionless preparation: moves the free grains of
/// `grains` (a box with `rigid_bodies` frozen walls) to the nearest static equilibrium in at most
/// `max_iterations` trial steps, to max |F| / mean contact force below `residual_force_tolerance`,
/// and returns the steps taken; throws when it cannot. The solver is the linear engine's
/// (linear/newton_stage.hpp), which builds on the channel, so the caller hands it in.
using NewtonRelaxation = std::function<int(std::vector<dem::Grain>& grains, const dem::Box& box,
                                           const dem::ContactSpec& contact, int rigid_bodies,
                                           double residual_force_tolerance, int max_iterations)>;

/// Compresses and relaxes `start` (whose grains may be given on any rank). Collective over comm.
/// Without `newton` (an empty function) FIRE relaxes alone, as with newton_relaxation = false.
[[nodiscard]] PreparedChannel prepare_channel(MPI_Comm comm, const ChannelConfiguration& start,
                                              const dem::ContactSpec& contact, double width,
                                              const PreparationSettings& settings, const NewtonRelaxation& newton);

/// The box as rank 0 knows it, on every rank: scenes hold their grains (and so their box) on rank 0
/// only, and every rank must construct its engine with the same box (collective).
[[nodiscard]] dem::Box broadcast_box(MPI_Comm comm, dem::Box box);

/// One line per quantity, for logs and reports.
[[nodiscard]] std::string describe(const PreparationReport& report);

}  // namespace sedwave::forward::channel
