#pragma once
// A complex number over any real scalar type T (double or ceres::Jet), for poroelastic and
// grain-contact wave numbers. std::complex<T> is specified for float, double and long double only,
// so automatic differentiation through complex algebra needs its own small type.
#include <cmath>
#include <numbers>

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

/// e^{i phase} times magnitude: polar form.
template <typename T>
Complex<T> polar(const T& magnitude, const T& phase) {
  using std::cos;
  using std::sin;
  return {magnitude * cos(phase), magnitude * sin(phase)};
}

// ---- Logarithms, exponentials and powers ------------------------------------------------------
// All use the principal branch, arg z in (-pi, pi].

/// Principal argument of z, in (-pi, pi].
template <typename T>
T arg(const Complex<T>& z) {
  using std::atan2;
  return atan2(z.im, z.re);
}

/// e^z = e^{re} (cos im + i sin im).
template <typename T>
Complex<T> exp(const Complex<T>& z) {
  using std::exp;
  return polar(T(exp(z.re)), z.im);
}

/// Principal logarithm ln|z| + i arg z (z != 0).
template <typename T>
Complex<T> log(const Complex<T>& z) {
  using std::log;
  return {log(abs(z)), arg(z)};
}

/// Principal power z^p = |z|^p e^{i p arg z} for a real exponent p (z != 0): the polar form keeps
/// one pow, one atan2 and one cos/sin pair, and is exact in p for Jets.
template <typename T>
Complex<T> pow(const Complex<T>& z, const T& p) {
  using std::exp;
  using std::log;
  // |z|^p from ln|z|^2 / 2: no square root, no overflow of |z|^2 for the moduli met here.
  const T log_modulus = log(z.re * z.re + z.im * z.im) / T(2.0);
  return polar(T(exp(p * log_modulus)), T(p * arg(z)));
}

/// (i x)^p for real x > 0 and real p: x^p e^{i p pi/2}, the fractional-derivative factor of
/// power-law (grain-shearing) memory functions, without a general complex power.
template <typename T>
Complex<T> pow_imaginary(double x, const T& p) {
  using std::pow;
  return polar(T(pow(x, p)), T(p * (std::numbers::pi / 2.0)));
}

}  // namespace sedwave::sediment
