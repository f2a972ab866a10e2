#include "sedwave/sediment/reflection.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sedwave::sediment {

namespace {

using C = std::complex<double>;

/// A medium at one frequency, in slowness form: everything below is divided by the powers of omega
/// the plane waves share, so only slownesses [s/m], densities and moduli/omega^0 remain.
struct PreparedMedium {
  bool fluid = true;
  C p_slowness_squared;  ///< s_p^2 = (1/c_p + i alpha_p/omega)^2
  C s_slowness_squared;  ///< s_s^2 (solids)
  C shear_modulus;       ///< mu = rho / s_s^2 [Pa] (solids; 0 in a fluid)
  double density = 0.0;
  double impedance_scale = 0.0;  ///< rho c_p: brings displacement rows to the size of stress rows
  [[nodiscard]] int waves() const { return fluid ? 1 : 2; }
};

PreparedMedium prepare(const AcousticMedium& m, double omega) {
  PreparedMedium r;
  r.fluid = m.is_fluid();
  r.density = m.density;
  r.impedance_scale = m.density * m.compressional_speed;
  const C sp(1.0 / m.compressional_speed, m.compressional_attenuation / omega);
  r.p_slowness_squared = sp * sp;
  if (!r.fluid) {
    const C ss(1.0 / m.shear_speed, m.shear_attenuation / omega);
    r.s_slowness_squared = ss * ss;
    r.shear_modulus = m.density / r.s_slowness_squared;
  }
  return r;
}

/// q = sqrt(s^2 - p^2), Im q >= 0 (and Re q >= 0 when real): the branch that decays or propagates
/// away from the interface it leaves (a negative zero imaginary part must not flip it).
C vertical_slowness(const C& slowness_squared, double p_squared) {
  C q = std::sqrt(slowness_squared - p_squared);
  if (q.imag() < 0.0 || (q.imag() == 0.0 && q.real() < 0.0)) q = -q;
  return q;
}

/// The vertical slownesses of a medium's waves (P, then SV in a solid) at horizontal slowness p.
struct VerticalSlownesses {
  C q[2];
};

VerticalSlownesses vertical_slownesses(const PreparedMedium& m, double p_squared) {
  VerticalSlownesses v;
  v.q[0] = vertical_slowness(m.p_slowness_squared, p_squared);
  if (!m.fluid) v.q[1] = vertical_slowness(m.s_slowness_squared, p_squared);
  return v;
}

/// What one plane wave of unit potential contributes at an interface, per power of omega:
/// {u_z, sigma_zz, u_x, sigma_xz}. `wave` 0 is P (phi), 1 is SV (psi); direction +1 downgoing,
/// -1 upgoing. From u = grad phi + curl(psi y): u_x = phi_x - psi_z, u_z = phi_z + psi_x, and
/// Hooke's law with lambda + 2 mu = rho / s_p^2.
struct WaveContribution {
  C row[4];
};

WaveContribution contribution(const PreparedMedium& m, const VerticalSlownesses& v, double p, int wave,
                              double direction) {
  const C i(0.0, 1.0);
  const C q = direction * v.q[wave];
  const double p_squared = p * p;
  WaveContribution w;
  if (wave == 0) {
    w.row[0] = i * q;
    w.row[1] = -(m.density - 2.0 * m.shear_modulus * p_squared);
    w.row[2] = i * p;
    w.row[3] = -2.0 * m.shear_modulus * p * q;
  } else {
    w.row[0] = i * p;
    w.row[1] = -2.0 * m.shear_modulus * p * q;
    w.row[2] = -i * q;
    w.row[3] = m.shear_modulus * (v.q[1] * v.q[1] - p_squared);
  }
  return w;
}

/// The interface's reflection and transmission matrices, entry [to wave][from wave]:
/// rd, td for waves incident from above; ru, tu from below.
struct InterfaceMatrices {
  C rd[2][2]{}, td[2][2]{}, ru[2][2]{}, tu[2][2]{};
};

/// Solves A X = B for n x n A (n <= 4) and m right-hand sides by Gaussian elimination with partial
/// pivoting; X replaces B. Throws std::domain_error for a singular A.
void solve_small(C (&a)[4][4], C (&b)[4][4], int n, int m) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r) {
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    }
    if (a[pivot][col] == C(0.0)) throw std::domain_error("reflection: singular interface conditions");
    if (pivot != col) {
      for (int k = 0; k < n; ++k) std::swap(a[col][k], a[pivot][k]);
      for (int k = 0; k < m; ++k) std::swap(b[col][k], b[pivot][k]);
    }
    const C inverse = 1.0 / a[col][col];
    for (int r = col + 1; r < n; ++r) {
      const C factor = a[r][col] * inverse;
      if (factor == C(0.0)) continue;
      for (int k = col; k < n; ++k) a[r][k] -= factor * a[col][k];
      for (int k = 0; k < m; ++k) b[r][k] -= factor * b[col][k];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    const C inverse = 1.0 / a[r][r];
    for (int k = 0; k < m; ++k) {
      C sum = b[r][k];
      for (int c = r + 1; c < n; ++c) sum -= a[r][c] * b[c][k];
      b[r][k] = sum * inverse;
    }
  }
}

/// The boundary conditions between `above` and `below`: continuity of u_z and sigma_zz; of u_x and
/// sigma_xz between solids; sigma_xz = 0 on a solid facing a fluid (it slips). Unknowns: the waves
/// leaving the interface (upgoing above, downgoing below).
InterfaceMatrices interface_matrices(const PreparedMedium& above, const VerticalSlownesses& va,
                                     const PreparedMedium& below, const VerticalSlownesses& vb, double p) {
  const int na = above.waves(), nb = below.waves(), n = na + nb;
  int rows[4] = {0, 1, 2, 3};  // u_z, sigma_zz, u_x, sigma_xz
  if (n == 3) rows[2] = 3;     // one solid: no u_x continuity, its shear stress vanishes
  const double scale = above.impedance_scale;
  const auto entry = [&](const WaveContribution& w, int r) {
    const int row = rows[r];
    return (row == 0 || row == 2) ? w.row[row] * scale : w.row[row];
  };
  C a[4][4]{}, b[4][4]{};
  for (int k = 0; k < na; ++k) {
    const WaveContribution up = contribution(above, va, p, k, -1.0);
    const WaveContribution down = contribution(above, va, p, k, +1.0);
    for (int r = 0; r < n; ++r) {
      a[r][k] = entry(up, r);
      b[r][k] = -entry(down, r);  // incident from above
    }
  }
  for (int k = 0; k < nb; ++k) {
    const WaveContribution down = contribution(below, vb, p, k, +1.0);
    const WaveContribution up = contribution(below, vb, p, k, -1.0);
    for (int r = 0; r < n; ++r) {
      a[r][na + k] = -entry(down, r);
      b[r][na + k] = entry(up, r);  // incident from below
    }
  }
  solve_small(a, b, n, n);
  InterfaceMatrices m;
  for (int j = 0; j < na; ++j) {  // from above: [R_D; T_D]
    for (int k = 0; k < na; ++k) m.rd[k][j] = b[k][j];
    for (int k = 0; k < nb; ++k) m.td[k][j] = b[na + k][j];
  }
  for (int j = 0; j < nb; ++j) {  // from below: [T_U; R_U]
    for (int k = 0; k < na; ++k) m.tu[k][j] = b[k][na + j];
    for (int k = 0; k < nb; ++k) m.ru[k][j] = b[na + k][na + j];
  }
  return m;
}

/// Rayleigh's coefficient between two fluids, from above: (rho_b q_a - rho_a q_b) / (rho_b q_a + rho_a q_b).
C fluid_reflection(const PreparedMedium& above, const C& qa, const PreparedMedium& below, const C& qb) {
  const C za = below.density * qa, zb = above.density * qb;
  return (za - zb) / (za + zb);
}

/// A reflection matrix of 1 x 1 (fluid) or 2 x 2 (solid) entries.
struct ReflectionMatrix {
  C r[2][2]{};
  int n = 1;
};

/// Everything below an interface seen from above it, given the reflection matrix `below` of what lies
/// under the lower medium's bottom, already carried through that medium (E R E):
///   R_D + T_U R~ (I - R_U R~)^{-1} T_D.
ReflectionMatrix add_interface(const InterfaceMatrices& m, int na, const ReflectionMatrix& below) {
  const int nb = below.n;
  // X = (I - R_U R~)^{-1} T_D, from (I - R_U R~) X = T_D.
  C g[2][2]{};
  for (int i = 0; i < nb; ++i) {
    for (int j = 0; j < nb; ++j) {
      C s = (i == j) ? C(1.0) : C(0.0);
      for (int k = 0; k < nb; ++k) s -= m.ru[i][k] * below.r[k][j];
      g[i][j] = s;
    }
  }
  C x[2][2]{};
  if (nb == 1) {
    for (int j = 0; j < na; ++j) x[0][j] = m.td[0][j] / g[0][0];
  } else {
    const C det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    for (int j = 0; j < na; ++j) {
      x[0][j] = (g[1][1] * m.td[0][j] - g[0][1] * m.td[1][j]) / det;
      x[1][j] = (g[0][0] * m.td[1][j] - g[1][0] * m.td[0][j]) / det;
    }
  }
  ReflectionMatrix out;
  out.n = na;
  for (int i = 0; i < na; ++i) {
    for (int j = 0; j < na; ++j) {
      C s = m.rd[i][j];
      for (int k = 0; k < nb; ++k) {
        C rx(0.0);
        for (int l = 0; l < nb; ++l) rx += below.r[k][l] * x[l][j];
        s += m.tu[i][k] * rx;
      }
      out.r[i][j] = s;
    }
  }
  return out;
}

/// E R E: the reflection matrix at a layer's bottom carried to its top, E = diag(e^{i omega q h}).
void carry_through_layer(ReflectionMatrix& r, const VerticalSlownesses& v, double omega, double thickness) {
  C phase[2];
  for (int k = 0; k < r.n; ++k) phase[k] = std::exp(C(0.0, omega * thickness) * v.q[k]);
  for (int i = 0; i < r.n; ++i) {
    for (int j = 0; j < r.n; ++j) r.r[i][j] *= phase[i] * phase[j];
  }
}

void check_medium(const AcousticMedium& m, const std::string& what) {
  const auto fail = [&](const char* field, double value, const char* need) {
    std::ostringstream msg;
    msg << "reflection: " << what << ": " << field << " = " << value << " (" << need << ")";
    throw std::invalid_argument(msg.str());
  };
  if (!(std::isfinite(m.compressional_speed) && m.compressional_speed > 0.0)) {
    fail("compressional speed [m/s]", m.compressional_speed, "finite and positive");
  }
  if (!(std::isfinite(m.density) && m.density > 0.0)) fail("density [kg/m^3]", m.density, "finite and positive");
  if (!(std::isfinite(m.compressional_attenuation) && m.compressional_attenuation >= 0.0)) {
    fail("compressional attenuation [Np/m]", m.compressional_attenuation, "finite and not negative");
  }
  if (!(std::isfinite(m.shear_speed) && m.shear_speed >= 0.0)) {
    fail("shear speed [m/s]", m.shear_speed, "finite and not negative; 0 for a fluid");
  }
  if (!(std::isfinite(m.shear_attenuation) && m.shear_attenuation >= 0.0)) {
    fail("shear attenuation [Np/m]", m.shear_attenuation, "finite and not negative");
  }
}

double horizontal_slowness(const LayeredHalfspace& seabed, double grazing_angle) {
  if (!(grazing_angle >= 0.0 && grazing_angle <= std::numbers::pi / 2.0)) {
    std::ostringstream msg;
    msg << "reflection: grazing angle " << grazing_angle << " rad outside [0, pi/2]";
    throw std::invalid_argument(msg.str());
  }
  return std::cos(grazing_angle) / seabed.water.compressional_speed;
}

double omega_of(double frequency_hz) {
  if (!(std::isfinite(frequency_hz) && frequency_hz > 0.0)) {
    throw std::invalid_argument("reflection: frequency " + std::to_string(frequency_hz) +
                                " Hz (finite and positive needed)");
  }
  return 2.0 * std::numbers::pi * frequency_hz;
}

}  // namespace

void check_layered_halfspace(const LayeredHalfspace& seabed) {
  check_medium(seabed.water, "water");
  if (seabed.water.compressional_attenuation != 0.0 || !seabed.water.is_fluid()) {
    throw std::invalid_argument("reflection: the water must be a lossless fluid (attenuation 0, shear speed 0)");
  }
  for (std::size_t i = 0; i < seabed.layers.size(); ++i) {
    const std::string name = "layer " + std::to_string(i + 1);
    check_medium(seabed.layers[i].medium, name);
    const double h = seabed.layers[i].thickness;
    if (!(std::isfinite(h) && h >= 0.0)) {
      throw std::invalid_argument("reflection: " + name + ": thickness = " + std::to_string(h) +
                                  " m (finite and not negative)");
    }
  }
  check_medium(seabed.halfspace, "half-space");
}

std::vector<std::complex<double>> reflection_coefficients(const LayeredHalfspace& seabed,
                                                          std::span<const double> grazing_angles,
                                                          double frequency_hz) {
  check_layered_halfspace(seabed);
  const double omega = omega_of(frequency_hz);
  // media[0] water, media[1..L] layers, media[L+1] half-space.
  std::vector<PreparedMedium> media;
  media.reserve(seabed.layers.size() + 2);
  media.push_back(prepare(seabed.water, omega));
  for (const MediumLayer& l : seabed.layers) media.push_back(prepare(l.medium, omega));
  media.push_back(prepare(seabed.halfspace, omega));
  std::vector<VerticalSlownesses> q(media.size());
  std::vector<std::complex<double>> out;
  out.reserve(grazing_angles.size());
  for (const double angle : grazing_angles) {
    const double p = horizontal_slowness(seabed, angle);
    const double p_squared = p * p;
    for (std::size_t j = 0; j < media.size(); ++j) q[j] = vertical_slownesses(media[j], p_squared);
    // Start at the deepest interface, then carry R up through each layer and across its top.
    std::size_t below = media.size() - 1;
    ReflectionMatrix r;
    const auto across = [&](std::size_t upper, std::size_t lower, const ReflectionMatrix* carried) {
      const PreparedMedium &a = media[upper], &b = media[lower];
      ReflectionMatrix next;
      if (a.fluid && b.fluid) {
        const C rd = fluid_reflection(a, q[upper].q[0], b, q[lower].q[0]);
        next.r[0][0] = carried ? (rd + carried->r[0][0]) / (1.0 + rd * carried->r[0][0]) : rd;
        return next;
      }
      const InterfaceMatrices m = interface_matrices(a, q[upper], b, q[lower], p);
      if (!carried) {
        next.n = a.waves();
        for (int i = 0; i < next.n; ++i) {
          for (int j = 0; j < next.n; ++j) next.r[i][j] = m.rd[i][j];
        }
        return next;
      }
      return add_interface(m, a.waves(), *carried);
    };
    r = across(below - 1, below, nullptr);
    for (std::size_t j = below - 1; j >= 1; --j) {
      carry_through_layer(r, q[j], omega, seabed.layers[j - 1].thickness);
      r = across(j - 1, j, &r);
    }
    out.push_back(r.r[0][0]);
  }
  return out;
}

std::complex<double> reflection_coefficient(const LayeredHalfspace& seabed, double grazing_angle, double frequency_hz) {
  return reflection_coefficients(seabed, std::span<const double>(&grazing_angle, 1), frequency_hz).front();
}

InterfaceWaves interface_waves(const AcousticMedium& water, const AcousticMedium& halfspace, double grazing_angle,
                               double frequency_hz) {
  const LayeredHalfspace seabed{water, {}, halfspace};
  check_layered_halfspace(seabed);
  const double omega = omega_of(frequency_hz);
  const double p = horizontal_slowness(seabed, grazing_angle);
  const PreparedMedium a = prepare(water, omega), b = prepare(halfspace, omega);
  const VerticalSlownesses qa = vertical_slownesses(a, p * p), qb = vertical_slownesses(b, p * p);
  const InterfaceMatrices m = interface_matrices(a, qa, b, qb, p);
  return {m.rd[0][0], m.td[0][0], b.fluid ? C(0.0) : m.td[1][0], qa.q[0], qb.q[0], b.fluid ? C(0.0) : qb.q[1]};
}

double bottom_loss_db(std::complex<double> reflection) { return -20.0 * std::log10(std::abs(reflection)); }

}  // namespace sedwave::sediment
