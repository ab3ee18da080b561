// The Fresnel step of the colour chain on arrays over wavelength (ColorSweep::ExactXYZ):
// from eps1, eps2 to R = (Rs + Rp) / 2 (eq. 2-4, 13, 14) and the three weighted sums that
// give XYZ (eq. 5), in plain loops the compiler vectorises and builds for AVX2 too
// (core/simd.h). The same arithmetic as FresnelReflectance and NormalReflectance of
// IndexFromPermittivity(eps), rearranged to need fewer divisions (and at oblique incidence
// with N^2 = eps itself rather than the square of its root): equal to rounding.
#ifndef ALLOYCOLOR_COLOR_REFLECTANCE_ARRAYS_H_
#define ALLOYCOLOR_COLOR_REFLECTANCE_ARRAYS_H_

#include <cstddef>

namespace alloycolor::color {

// sums[q] = sum over i of w[q][i] R(eps1[i] + i eps2[i]) at incidence cos_psi (in [0, 1];
// `normal`: exactly 0 degrees).
void ReflectanceSums(std::size_t m, const double* eps1, const double* eps2, double cos_psi,
                     bool normal, const double* wx, const double* wy, const double* wz,
                     double sums[3]);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_REFLECTANCE_ARRAYS_H_
