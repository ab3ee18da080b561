// Interpolation across composition of values known at the samples' compositions, for the
// baselines that interpolate eps at each wavelength (sample_models.h):
//  - linear: the straight line between neighbouring samples;
//  - pchip: monotone piecewise cubic Hermite (Fritsch & Carlson, SIAM J. Numer. Anal. 17,
//    238 (1980)), slopes by the weighted harmonic mean of Fritsch & Butland (1984) as in
//    MATLAB's and SciPy's pchip, end slopes by the shape-preserving three-point formula:
//    no overshoot between samples, the shape of the data kept;
//  - natural cubic spline: C2 piecewise cubic with zero second derivative at the ends.
// Beyond the first and last composition every scheme continues as the straight line with
// its end slope. With two samples all three are the straight line.
#ifndef ALLOYCOLOR_MODEL_INTERPOLATION_H_
#define ALLOYCOLOR_MODEL_INTERPOLATION_H_

#include <vector>

namespace alloycolor {

enum class Interpolation { kLinear, kPchip, kNaturalSpline };

// A scheme fitted to (xs[i], ys[i]), xs strictly increasing, at least two points.
class Interpolant {
 public:
  Interpolant(Interpolation scheme, std::vector<double> xs, std::vector<double> ys);
  double operator()(double x) const;

 private:
  std::vector<double> xs_, ys_;
  std::vector<double> slopes_;  // dy/dx at each x (Hermite form of the cubic schemes)
  bool linear_ = false;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_INTERPOLATION_H_
