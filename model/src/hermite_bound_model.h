// The bound model (alloy_model.h) of every method that interpolates eps across composition
// at each wavelength of the grid: eps-linear, eps-pchip, eps-spline (sample_models.h) and
// smooth (smooth_model.h). Each eps1, eps2 is a piecewise cubic in x in Hermite form
// through knots (per knot its value and its slope), or for eps-linear the straight line
// between neighbouring knots. At x the interval and its weights are found once; every
// wavelength then costs two short sums over contiguous arrays, which the compiler
// vectorises (simd.h).
//
// Equal to HermiteAt (interpolation.h) and to the linear interpolation of the samples
// to rounding; beyond the first and last knot, the straight line with the end slope. The
// smooth model's curves may run through ln eps (smooth_model.h): the two sums are then
// ln|eps| and arg eps, and eps follows from them (EpsFromParts) wavelength by wavelength.
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
    std::vector<double> slope1, slope2;  // d eps / dx (empty for `linear`)
  };
  // What the sums are: eps; eps with eps2 held at 0 from below (a natural spline can
  // undershoot between samples; the other schemes cannot); ln|eps| and arg eps.
  enum class Output { kEps, kPassive, kFromLog };
  // `linear`: the straight line between neighbouring knots, evaluated as lo + (hi - lo) t
  // exactly as the scalar path (no slopes). Knot's eps1, eps2 hold ln|eps|, arg eps for
  // kFromLog.
  HermiteBoundModel(std::vector<double> lambda_nm, std::vector<double> knots_x,
                    std::vector<Knot> knots, bool linear, Output output = Output::kEps);

  void Permittivity(double x_atomic, double* eps1, double* eps2) const override;

 private:
  std::vector<double> knots_x_;
  std::vector<Knot> knots_;
  bool linear_;
  Output output_;

  void Finish(double* eps1, double* eps2) const;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SRC_HERMITE_BOUND_MODEL_H_
