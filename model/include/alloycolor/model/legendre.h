// Legendre polynomials of composition over a training range: the basis in which the
// physical model (physical_model.h) writes each oscillator parameter as a function of x.
#ifndef ALLOYCOLOR_MODEL_LEGENDRE_H_
#define ALLOYCOLOR_MODEL_LEGENDRE_H_

namespace alloycolor {

// The argument of the Legendre polynomials for composition x over the training range
// [x_lo, x_hi]: u = 2 (x - x_lo) / (x_hi - x_lo) - 1, so u runs over [-1, 1].
inline double CompositionArgument(double x, double x_lo, double x_hi) {
  return 2.0 * (x - x_lo) / (x_hi - x_lo) - 1.0;
}

// P_0..P_degree at u (Bonnet's recursion).
inline void LegendreBasis(double u, int degree, double* p) {
  p[0] = 1.0;
  if (degree >= 1) p[1] = u;
  for (int d = 2; d <= degree; ++d) {
    p[d] = ((2.0 * d - 1.0) * u * p[d - 1] - (d - 1.0) * p[d - 2]) / d;
  }
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_LEGENDRE_H_
