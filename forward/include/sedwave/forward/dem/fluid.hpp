#pragma once
// A still pore fluid around the grains: the hydrodynamic forces that act where grains meet
// (lubrication) and on each grain as a whole (drag, buoyancy). docs/fluid.md has the equations, the
// dimensionless groups and the measured effect; the engine evaluates nothing of this unless a run
// asks for a fluid (EngineSettings::fluid): a dry run executes a force loop without any of it.
//
// Normal lubrication (squeeze film). Two spheres of radii r_i, r_j a gap h apart, approaching at
// v_n, push the fluid out of the gap; to leading order in h / R the force on each is
//   F = -6 pi mu R_eff^2 v_n / h,   R_eff = r_i r_j / (r_i + r_j)
// along the line of centres (Reynolds lubrication between spheres: Jeffrey & Onishi 1984, J. Fluid
// Mech. 139, 261, the singular term of X^A_11; Kim & Karrila 1991, "Microhydrodynamics", sec. 9.3).
// For two equal spheres of radius a this is the familiar (3/2) pi mu a^2 v_n / h. It is regularised
// as DEM codes for immersed grains do (Ball & Melrose 1995, Adv. Colloid Interface Sci. 59, 19;
// LAMMPS pair lubricate's inner cut-off; Marzougui, Chareyre & Chauchat 2015, Granular Matter 17,
// 297):
//   - below the roughness gap h_r (asperities touch) the force is that at h_r, also while the grains
//     overlap: in contact the film between the asperities keeps acting as a dashpot of
//     6 pi mu R_eff^2 / h_r beside the contact's own;
//   - beyond the outer cut-off h_c it is zero (the far field belongs to drag; at h ~ R the
//     leading-order term is no longer accurate).
// The tangential and rotational lubrication terms, which grow only as ln(R/h), are not modelled.
//
// Drag (still fluid, porosity-corrected Stokes drag). A grain of radius r moving at v through fluid
// at rest feels F = -6 pi mu r f(eps) v. Alone, f = 1 (Stokes). In a packing of porosity eps the
// Richardson & Zaki (1954, Trans. Inst. Chem. Eng. 32, 35) hindered-settling law v_s = v_t eps^n,
// n = 4.65 at small Reynolds numbers, balanced against the buoyant weight in the mixture, gives
// f = eps^(1 - n) = eps^-3.65; Di Felice (1994, Int. J. Multiphase Flow 20, 153) finds eps^-3.7 in
// the same limit.
//
// Buoyancy: -rho_f (4/3 pi r^3) g on every free grain under gravity g.
//
// Units: the engine's (any consistent set). Scene files give the dimensionless groups
// (experiment/scene.hpp): mu_hat = mu d / sqrt(kappa m), h_r / d, h_c / d.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sedwave/forward/dem/vec3.hpp"

namespace sedwave::forward::dem {

enum class DragLaw {
  none,            ///< no drag (lubrication only)
  stokes,          ///< f = 1: an isolated sphere
  richardson_zaki  ///< f = porosity^(1 - 4.65)
};

/// The drag laws by the names scene files and `sedwave dem` use, the default first.
inline constexpr std::array<std::pair<std::string_view, DragLaw>, 3> kDragLaws{
    {{"richardson_zaki", DragLaw::richardson_zaki}, {"stokes", DragLaw::stokes}, {"none", DragLaw::none}}};
[[nodiscard]] std::string_view drag_law_name(DragLaw law);
/// The law of a name in kDragLaws; std::invalid_argument for any other name.
[[nodiscard]] DragLaw drag_law_of(std::string_view name);
/// The names of kDragLaws, in its order.
[[nodiscard]] std::vector<std::string> drag_law_names();

struct FluidSpec {
  double viscosity = 0.0;   ///< mu [mass / (length time)]
  double density = 0.0;     ///< rho_f [mass / length^3] (buoyancy)
  double roughness = 0.0;   ///< h_r: the lubrication force is that at h_r for smaller gaps [length]
  double cutoff = 0.0;      ///< h_c: no lubrication for gaps >= h_c [length]; h_c > h_r
  bool lubrication = true;  ///< the squeeze-film force between grains
  DragLaw drag = DragLaw::richardson_zaki;
  double porosity = 0.4;    ///< eps of the drag correction, in (0, 1)

  /// Empty when the spec can be used, else why not (names the field and its accepted range).
  [[nodiscard]] std::string problem() const;
  /// Richardson-Zaki exponent n (small Reynolds numbers).
  static constexpr double richardson_zaki_exponent = 4.65;
  /// f(eps): the drag on a grain in the packing over the Stokes drag on the same grain alone.
  [[nodiscard]] double drag_factor() const {
    switch (drag) {
      case DragLaw::none: return 0.0;
      case DragLaw::stokes: return 1.0;
      case DragLaw::richardson_zaki: return std::pow(porosity, 1.0 - richardson_zaki_exponent);
    }
    return 0.0;
  }
  /// Drag coefficient c of a free grain of this radius: F = -c v.
  [[nodiscard]] double drag_coefficient(double radius) const {
    return 6.0 * std::numbers::pi * viscosity * radius * drag_factor();
  }
  /// Buoyant force on a grain of this radius under gravity g.
  [[nodiscard]] Vec3 buoyancy(double radius, const Vec3& gravity) const {
    return (-density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius) * gravity;
  }
  /// 6 pi mu R_eff^2 of grains of radii r_i, r_j: the film's dashpot times the gap.
  [[nodiscard]] double film_coefficient(double r_i, double r_j) const {
    const double r_eff = r_i * r_j / (r_i + r_j);
    return 6.0 * std::numbers::pi * viscosity * r_eff * r_eff;
  }
  /// Lubrication dashpot between grains of radii r_i, r_j at gap h (<= 0: overlapping): F = -c v_n.
  [[nodiscard]] double lubrication_coefficient(double gap, double r_i, double r_j) const {
    if (!lubrication || !(gap < cutoff)) return 0.0;
    return film_coefficient(r_i, r_j) / std::max(gap, roughness);
  }
  /// Largest gap at which grains interact through the fluid (0 without lubrication).
  [[nodiscard]] double interaction_gap() const { return lubrication ? cutoff : 0.0; }

  friend bool operator==(const FluidSpec&, const FluidSpec&) = default;
};

/// One line: "viscosity 0.001, roughness 0.001, cutoff 0.1, lubrication, drag richardson_zaki
/// (porosity 0.4: 28.3 x Stokes), density 0".
[[nodiscard]] std::string describe(const FluidSpec& f);

/// What the force loop needs of one listed pair's film, fixed by the pair's radii (tabulated with
/// the neighbour list: tabulate_films in force_loop.hpp). reach = r_i + r_j.
struct FilmPair {
  double film;     ///< 6 pi mu R_eff^2
  double reach2;   ///< reach^2
  double clamp;    ///< (reach + h_r)^2 - reach^2: below it the film sees the roughness gap
  double cut2;     ///< (reach + h_c)^2: no film from here on
};

/// The squeeze-film force as the force loop evaluates it, from the tabulated FilmPair of each
/// listed pair, so that per step a pair costs two clamps, a mask and a few products.
class LubricationEvaluator {
 public:
  LubricationEvaluator(const FluidSpec& f, std::span<const FilmPair> films)
      : roughness_(f.roughness), cutoff_(f.cutoff), films_(films) {}
  [[nodiscard]] static FilmPair pair(const FluidSpec& f, double r_i, double r_j) {
    const double reach = r_i + r_j;
    const double cut = reach + f.cutoff;
    return {f.film_coefficient(r_i, r_j), reach * reach, f.roughness * (2.0 * reach + f.roughness), cut * cut};
  }
  [[nodiscard]] const FilmPair& film(std::size_t k) const { return films_[k]; }
  [[nodiscard]] double roughness() const { return roughness_; }
  /// The force on i as a multiple of d = x_i - x_j, given the gap and (d . v_rel) / |d|^2
  /// (positive while separating): -lubrication_coefficient(gap) v_n / |d|.
  [[nodiscard]] double multiple_of_d(std::size_t k, double gap, double approach_over_r2) const {
    const double in_range = static_cast<double>(gap < cutoff_);
    return -in_range * films_[k].film / std::max(gap, roughness_) * approach_over_r2;
  }

 private:
  double roughness_;
  double cutoff_;
  std::span<const FilmPair> films_;
};

}  // namespace sedwave::forward::dem
