#pragma once
// A thin elastic plate loaded in its own plane (plane stress), discretised by bilinear quadrilaterals
// on a structured rectangular mesh with lumped (row-sum) mass, for explicit central differences.
//
// Geometry: the plate covers [0, length_x] x [-length_y, 0]; its top edge y = 0 is the interface the
// grains press on. Node (i, j), i = 0..nx, j = 0..ny, sits at (i a, -length_y + j b) with a = length_x/nx,
// b = length_y/ny; its index is j (nx + 1) + i and its degrees of freedom are 2 index (x) and
// 2 index + 1 (y). Units: any consistent set (SI at the scene's boundary); thickness t is the plate's
// out-of-plane size, so forces are [force] and stiffnesses [force/length] per node.
//
// The plate holds no state: the integrator (interface/granular_plate.hpp) owns displacements and
// velocities and asks the plate for forces, masses, dashpots, constraints and energies.
#include <Eigen/Dense>
#include <vector>

namespace sedwave::forward::plate {

struct PlateMaterial {
  double youngs_modulus;  ///< E
  double poisson_ratio;   ///< nu, in [0, 0.5)
  double density;         ///< rho [mass/length^3]
  double thickness;       ///< t, the out-of-plane size [length]
};

/// Plane-stress wave speeds: dilatational sqrt(E/(rho (1 - nu^2))) and shear sqrt(E/(2 rho (1 + nu))).
[[nodiscard]] double dilatational_speed(const PlateMaterial& m);
[[nodiscard]] double shear_speed(const PlateMaterial& m);

/// What holds an edge: nothing, both displacements, or Lysmer-Kuhlemeyer dashpots (normal rho c_L t,
/// tangential rho c_S t per unit length, lumped to the nodes) that absorb waves arriving normally.
enum class EdgeCondition { free, clamped, absorbing };

struct PlateEdges {
  EdgeCondition top = EdgeCondition::free;  ///< y = 0: the interface
  EdgeCondition bottom = EdgeCondition::clamped;
  EdgeCondition left = EdgeCondition::absorbing;
  EdgeCondition right = EdgeCondition::absorbing;
};

struct PlateMesh {
  int elements_x;
  int elements_y;
  double length_x;
  double length_y;
};

class ElasticPlate {
 public:
  ElasticPlate(const PlateMaterial& material, const PlateMesh& mesh, const PlateEdges& edges);

  [[nodiscard]] int nodes_x() const { return mesh_.elements_x + 1; }
  [[nodiscard]] int nodes_y() const { return mesh_.elements_y + 1; }
  [[nodiscard]] int node_count() const { return nodes_x() * nodes_y(); }
  [[nodiscard]] int dof_count() const { return 2 * node_count(); }
  [[nodiscard]] int node(int i, int j) const { return j * nodes_x() + i; }
  [[nodiscard]] double element_width() const { return a_; }   ///< a (along x)
  [[nodiscard]] double element_height() const { return b_; }  ///< b (along y)
  [[nodiscard]] double node_x(int node_index) const { return a_ * (node_index % nodes_x()); }
  [[nodiscard]] double node_y(int node_index) const { return -mesh_.length_y + b_ * (node_index / nodes_x()); }
  [[nodiscard]] const PlateMaterial& material() const { return material_; }
  [[nodiscard]] const PlateMesh& mesh() const { return mesh_; }

  /// Lumped mass of each degree of freedom (the same for x and y of a node).
  [[nodiscard]] const std::vector<double>& mass() const { return mass_; }
  /// Lumped Lysmer-Kuhlemeyer dashpot of each degree of freedom (zero away from absorbing edges).
  [[nodiscard]] const std::vector<double>& damping() const { return damping_; }
  /// 1 where a degree of freedom is held at zero displacement, else 0.
  [[nodiscard]] const std::vector<char>& fixed() const { return fixed_; }
  /// 1/mass of each degree of freedom, 0 where it is held: a kick v += h f / m without a division
  /// that leaves a held degree of freedom where it is.
  [[nodiscard]] const std::vector<double>& inverse_mass() const { return inverse_mass_; }
  /// Holds one more degree of freedom at zero (symmetry planes, tests).
  void fix(int node_index, int component);

  /// f -= K u: the elastic forces of displacement u added to f.
  void add_elastic_forces(const std::vector<double>& u, std::vector<double>& f) const;
  /// f = -K u: the elastic forces of displacement u written over f (sized to u), without a pass that
  /// clears f first. The same arithmetic as add_elastic_forces on a zeroed f.
  void elastic_forces(const std::vector<double>& u, std::vector<double>& f) const;
  /// f -= sign K_top u (sign 1 or -1), K_top the stiffness of the top row of elements alone (under
  /// the top edge): it touches the two top rows of nodes' entries of f and no other. (multirate
  /// integration, interface/granular_plate.hpp: the top row of elements is integrated with the contacts.)
  void add_top_row_forces(const std::vector<double>& u, std::vector<double>& f, double sign = 1.0) const;
  /// (1/2) u^T K u.
  [[nodiscard]] double strain_energy(const std::vector<double>& u) const;
  /// Largest undamped circular frequency of M^-1 K, bounded from above by the element eigenvalue
  /// theorem (Irons & Treharne 1971; Hughes 2000, sec. 9.2): omega_max <= max over elements of
  /// the largest omega of M_e^-1 K_e. All elements are the same rectangle, so one 8x8 problem.
  [[nodiscard]] double max_frequency_bound() const { return omega_bound_; }
  /// Central differences are stable for dt < 2/omega_max (undamped; the dashpots are integrated
  /// implicitly, interface/granular_plate.cpp, so they do not shrink it).
  [[nodiscard]] double stable_time_step() const { return 2.0 / omega_bound_; }
  /// The element stiffness matrix (nodes counter-clockwise from the lower left, x then y each).
  [[nodiscard]] const Eigen::Matrix<double, 8, 8>& element_stiffness() const { return element_stiffness_; }

  /// Top-edge (y = 0) interpolation at abscissa x in [0, length_x]: the two nodes of the edge
  /// segment and their linear shape functions (the bilinear element's restriction to that edge).
  struct EdgePoint {
    int node_left;
    int node_right;
    double shape_left;   ///< 1 - xi
    double shape_right;  ///< xi
  };
  [[nodiscard]] EdgePoint top_edge_point(double x) const;
  /// The top-edge node nearest abscissa x, at full weight (node_left = node_right, shapes 1 and 0):
  /// the node whose flat rigid layer carries a contact at x (a layer as wide as an element).
  [[nodiscard]] EdgePoint top_edge_node(double x) const;

 private:
  PlateMaterial material_;
  PlateMesh mesh_;
  double a_;
  double b_;
  Eigen::Matrix<double, 8, 8> element_stiffness_;
  /// element_stiffness_ with nodes ordered (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1): an
  /// element's 8 unknowns are then 4 consecutive values in each of its two node rows.
  Eigen::Matrix<double, 8, 8> row_stiffness_;
  /// The force on a node whose four elements all exist, -stencil_ times the displacements of its 3 x 3
  /// neighbourhood (rows below, level and above; in each, nodes left, centre, right, x then y).
  Eigen::Matrix<double, 2, 18> stencil_;
  /// The stencil's five distinct coefficients on the uniform mesh (elastic_plate.cpp says why they
  /// are all): diagonal (x, y) entries of the centre, axis and corner blocks, and the corners' one
  /// x-y coupling.
  struct NodeStencil {
    Eigen::Array2d centre, along_x, along_y, corner;
    double corner_coupling;
  };
  NodeStencil node_stencil_{};
  /// The force on a node of an edge, not a corner, from the two elements it has: -edge_stencil_ times
  /// its neighbourhood's two node rows (bottom and top edges, 3 nodes each) or three node rows (left
  /// and right edges, 2 nodes each), x then y. Order: bottom, top, left, right.
  Eigen::Matrix<double, 2, 12> edge_stencil_[4];
  static NodeStencil compact_stencil(const Eigen::Matrix<double, 2, 18>& stencil);
  enum class Accumulate { overwrite, subtract, add };  ///< f = -K u, f -= K u, f += K u
  /// K u of the plate's first `element_rows` rows of elements over the node rows from u's and f's
  /// first entries: the whole plate, or one row of elements taken as a plate of its own.
  template <Accumulate mode>
  void apply_stiffness(const double* u, double* f, int element_rows) const;
  std::vector<double> mass_;
  std::vector<double> inverse_mass_;
  std::vector<double> damping_;
  std::vector<char> fixed_;
  double omega_bound_ = 0.0;
};

}  // namespace sedwave::forward::plate
