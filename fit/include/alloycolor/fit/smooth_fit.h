// Joint Ceres fit of the "smooth" model (model/smooth_model.h) to all samples of a data
// set: at every node of a wavelength grid, ln gamma and ln wp^2 are Legendre polynomials
// of degree D in composition; all nodes are fitted in one problem.
//
// Cost (1/2 the sum of squares of):
//  - data:  (eps_model(x_i, w_j) - eps_i(w_j)) / |eps_i(w_j)|, real and imaginary parts,
//           for every sample i and node j where the sample is Drude-invertible (eps1 < 1,
//           eps2 > 0); relative error, so every sample and wavelength counts alike;
//  - curvature across wavelength: sqrt(mu) (c_{j-1} - 2 c_j + c_{j+1}) per coefficient;
//  - a weak ridge sqrt(rho) c_d on the d >= 1 coefficients, so nodes with few usable
//    samples stay determined.
// The start is the least-squares fit of the pointwise inversion (eq. 11, 12) in
// (ln gamma, ln wp^2); Ceres refines it on eps. D is chosen by leave-one-composition-out
// cross-validation over the interior samples unless fixed, scored by the left-out
// samples' normal-incidence reflectance error (what colour depends on) (a fold is fitted with degree
// D - 1, so it keeps the final fit's degrees of freedom). Covariance: ceres::Covariance of
// each node's coefficients on that node's data (the curvature prior left out, which is
// conservative), scaled by the larger of the data residual variance and the node's
// leave-one-out variance r^2 / (1 + h) (h the left-out composition's leverage in its fold):
// an interpolating fit has no residual to scale by, but it still errs between samples.
#ifndef ALLOYCOLOR_FIT_SMOOTH_FIT_H_
#define ALLOYCOLOR_FIT_SMOOTH_FIT_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "alloycolor/core/dataset.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit {

using ProgressCallback = std::function<void(const std::string& message)>;

struct SmoothFitOptions {
  std::vector<double> grid_nm;     // empty: DefaultGrid(dataset)
  int degree = -1;                 // < 0: chosen by leave-one-out cross-validation
  int max_degree = 6;              // largest degree cross-validation tries
  double smoothing = 1e-3;         // mu
  double ridge = 1e-8;             // rho
  int max_iterations = 100;
  bool covariance = true;
  const SmoothModel* start = nullptr;  // refit: start from these coefficients
  ProgressCallback progress;           // may be empty
};

struct CrossValidationRow {
  int degree;
  double rms;              // RMS relative eps error on the left-out samples
  double rms_reflectance;  // RMS normal-incidence reflectance error there (the score)
};

struct SmoothFitResult {
  std::unique_ptr<SmoothModel> model;
  std::vector<CrossValidationRow> cross_validation;  // empty when the degree was fixed
};

// Throws Error when the data set has fewer than two compositions, no common wavelength
// range, or no usable (Drude-invertible) data at some node, naming what is missing.
SmoothFitResult FitSmooth(const Dataset& dataset, const SmoothFitOptions& options);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SMOOTH_FIT_H_
