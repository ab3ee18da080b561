// Complex numbers as explicit real and imaginary parts, templated on the scalar, so that
// the same arithmetic runs with double and with ceres::Jet (std::complex<ceres::Jet> is
// not supported: its operations assume a floating-point scalar).
#ifndef ALLOYCOLOR_CORE_COMPLEX_H_
#define ALLOYCOLOR_CORE_COMPLEX_H_

#include <cmath>

namespace alloycolor {

template <typename T>
struct Complex {
  T re;
  T im;
};

template <typename T>
Complex<T> operator+(const Complex<T>& a, const Complex<T>& b) {
  return {a.re + b.re, a.im + b.im};
}
template <typename T>
Complex<T> operator-(const Complex<T>& a, const Complex<T>& b) {
  return {a.re - b.re, a.im - b.im};
}
template <typename T>
Complex<T> operator*(const Complex<T>& a, const Complex<T>& b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
template <typename T>
Complex<T> operator*(const T& s, const Complex<T>& a) {
  return {s * a.re, s * a.im};
}
template <typename T>
T Norm2(const Complex<T>& a) {
  return a.re * a.re + a.im * a.im;
}

// Principal square root, in the form that avoids cancellation for either sign of re.
template <typename T>
Complex<T> Sqrt(const Complex<T>& z) {
  using std::sqrt;
  const T r = sqrt(z.re * z.re + z.im * z.im);
  if (r == T(0)) return {T(0), T(0)};
  if (z.re >= T(0)) {
    const T t = sqrt((r + z.re) * T(0.5));
    return {t, z.im / (T(2) * t)};
  }
  const T t = sqrt((r - z.re) * T(0.5));
  const T abs_im = z.im < T(0) ? -z.im : z.im;
  return {abs_im / (T(2) * t), z.im < T(0) ? -t : t};
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_COMPLEX_H_
