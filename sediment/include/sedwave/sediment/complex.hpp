#pragma once
// A complex number over any real scalar type T (double or ceres::Jet), for poroelastic and
// grain-contact wave numbers. std::complex<T> is specified for float, double and long double only,
// so automatic differentiation through complex algebra needs its own small type.
#include <cmath>

namespace sedwave::sediment {

template <typename T>
struct Complex {
  T re;
  T im;

  Complex() : re(0.0), im(0.0) {}
  Complex(const T& real) : re(real), im(0.0) {}  // NOLINT: a real is a complex number
  Complex(const T& real, const T& imag) : re(real), im(imag) {}

  friend Complex operator+(const Complex& a, const Complex& b) { return {a.re + b.re, a.im + b.im}; }
  friend Complex operator-(const Complex& a, const Complex& b) { return {a.re - b.re, a.im - b.im}; }
  friend Complex operator-(const Complex& a) { return {-a.re, -a.im}; }
  friend Complex operator*(const Complex& a, const Complex& b) {
    return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
  }
  friend Complex operator/(const Complex& a, const Complex& b) {
    const T n = b.re * b.re + b.im * b.im;
    return {(a.re * b.re + a.im * b.im) / n, (a.im * b.re - a.re * b.im) / n};
  }
  // Real scalars of type T without a detour through Complex (half the multiplications).
  friend Complex operator*(const Complex& a, const T& s) { return {a.re * s, a.im * s}; }
  friend Complex operator*(const T& s, const Complex& a) { return {a.re * s, a.im * s}; }
  friend Complex operator/(const Complex& a, const T& s) { return {a.re / s, a.im / s}; }
};

template <typename T>
Complex<T> conj(const Complex<T>& z) {
  return {z.re, -z.im};
}

/// |z|, without overflow for the moduli met here (|z| << 1e150).
template <typename T>
T abs(const Complex<T>& z) {
  using std::sqrt;
  return sqrt(z.re * z.re + z.im * z.im);
}

/// Principal square root (Re >= 0), stable on both half-planes: the larger of |re| and the root's
/// component is formed without cancellation.
template <typename T>
Complex<T> sqrt(const Complex<T>& z) {
  using std::sqrt;
  const T m = abs(z);
  if (z.re >= T(0.0)) {
    const T r = sqrt((m + z.re) / T(2.0));
    if (r == T(0.0)) return {T(0.0), T(0.0)};
    return {r, z.im / (T(2.0) * r)};
  }
  T s = sqrt((m - z.re) / T(2.0));
  if (z.im < T(0.0)) s = -s;
  return {z.im / (T(2.0) * s), s};
}

/// e^z = e^{re} (cos im + i sin im).
template <typename T>
Complex<T> exp(const Complex<T>& z) {
  using std::exp;
  const T m = exp(z.re);
  using std::cos;
  using std::sin;
  return {m * cos(z.im), m * sin(z.im)};
}

/// e^{i phase} times magnitude: polar form.
template <typename T>
Complex<T> polar(const T& magnitude, const T& phase) {
  using std::cos;
  using std::sin;
  return {magnitude * cos(phase), magnitude * sin(phase)};
}

}  // namespace sedwave::sediment
