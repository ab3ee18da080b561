// The bound model (alloy_model.h) of every method that interpolates eps across composition
// at each wavelength of the grid: eps-linear, eps-pchip, eps-spline (sample_models.h) and
// smooth (smooth_model.h). Each eps1, eps2 is a piecewise cubic in x in Hermite form
// through knots: per knot, its value and its slope on either side (the two differ only
// for the straight lines of eps-linear, which has a kink at every sample). At x the
// interval and its four Hermite weights are found once; every wavelength then costs two
// four-term sums over contiguous arrays, which the compiler vectorises (simd.h).
//
// Equal to HermiteAt (interpolation.h) and to the linear interpolation of the samples
// to rounding; beyond the first and last knot, the straight line with the end slope.
#ifndef ALLOYCOLOR_MODEL_SRC_HERMITE_BOUND_MODEL_H_
#define ALLOYCOLOR_MODEL_SRC_HERMITE_BOUND_MODEL_H_

#include <vector>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

class HermiteBoundModel : public BoundModel {
 public:
  // Arrays over the grid at one knot.
  struct Knot {
    std::vector<double> eps1, eps2;
    std::vector<double> slope1_below, slope2_below;  // on the interval ending at the knot
    std::vector<double> slope1_above, slope2_above;  // on the interval starting there
  };
  // `linear`: every slope the secant of its interval (eps-linear), evaluated as
  // lo + (hi - lo) t exactly as the scalar path. `passive`: eps2 held at 0 from below (a
  // natural spline can undershoot between samples; the other schemes cannot).
  HermiteBoundModel(std::vector<double> lambda_nm, std::vector<double> knots_x,
                    std::vector<Knot> knots, bool linear, bool passive = false);

  void Permittivity(double x_atomic, double* eps1, double* eps2) const override;

  // A knot with slopes equal on both sides.
  static Knot KnotOf(std::vector<double> eps1, std::vector<double> eps2,
                     std::vector<double> slope1, std::vector<double> slope2);

 private:
  std::vector<double> knots_x_;
  std::vector<Knot> knots_;
  bool linear_, passive_;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SRC_HERMITE_BOUND_MODEL_H_
