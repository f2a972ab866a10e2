#pragma once
// A channel scene file (TOML): everything that defines one acoustic simulation, so that a run or a
// table can be reproduced from the file alone. Annotated example: data/scenes/thesis_w3.toml;
// reference: docs/scenes.md.
//
// Units: dimensionless throughout (lengths in mean grain diameters, the grain density and the
// contact stiffness as given; drive frequency and dashpot as omega_hat and gamma_hat).
// Every key is checked: an unknown key, a wrong type or an impossible value is an error naming the
// file, line and key; nothing is silently ignored.
#include <filesystem>
#include <optional>
#include <string>

#include "sedwave/forward/channel/acoustic.hpp"
#include "sedwave/forward/channel/geometry.hpp"
#include "sedwave/forward/channel/periodic_cell.hpp"
#include "sedwave/forward/channel/preparation.hpp"
#include "sedwave/forward/dem/contact/contact_model.hpp"
#include "sedwave/forward/experiment/engine.hpp"
#include "sedwave/forward/linear/settings.hpp"

namespace sedwave::forward::experiment {

/// Error in a scene file: "FILE:LINE: key 'a.b': why" (toml11's own message for syntax errors).
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ChannelScene {
  std::filesystem::path path;   ///< where it was read from (relative paths inside resolve from here)
  std::string text;             ///< the file verbatim, stored in every output for provenance
  channel::ChannelGeometry geometry;
  /// A LAMMPS data file (atom_style sphere) to use instead of generating the column; types
  /// 1 = flow grains, 2 = lower wall, 3 = upper wall (the thesis's convention).
  std::optional<std::filesystem::path> import_lammps_data;
  /// Build the channel from a periodic cell of tiling->cell_grains grains ([geometry.periodic_cell],
  /// periodic_cell.hpp): geometry.n_grains / cell_grains copies, the ends frozen into the walls.
  std::optional<channel::CellTiling> tiling;
  /// Contact law; its damping (restitution or gamma) is the one used while preparing. Driven runs
  /// replace it by DriveSettings::gamma_hat.
  dem::ContactSpec contact;
  channel::PreparationSettings preparation;
  channel::DriveSettings drive;
  EngineKind engine = EngineKind::time_domain;
  linear::LinearSettings linear;  ///< used when engine == linear
};

/// Reads and validates a scene. Throws SceneError.
[[nodiscard]] ChannelScene read_scene(const std::filesystem::path& path);

/// Parses scene text (for tests and for tables that store their scene); `origin` names it in errors.
[[nodiscard]] ChannelScene parse_scene(const std::string& text, const std::string& origin);

}  // namespace sedwave::forward::experiment
