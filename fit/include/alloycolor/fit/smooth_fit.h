// Joint Ceres fit of the "smooth" model (model/smooth_model.h) to all samples of a data
// set: at every node of a wavelength grid, eps1 and eps2 are PCHIP curves of composition
// through values at knots, and all nodes are fitted in one problem.
//
// Knots: the training compositions, or kSmoothMaxKnots-at-most of them spread by quantile
// when there are more. Cost (1/2 the sum of squares of):
//  - data: (eps_model(x_i, w_j) - eps_i(w_j)) / |eps_i(w_j)|, real and imaginary parts, for
//    every sample i and node j: relative error, so every sample and wavelength counts alike;
//  - roughness: smoothing * integral of (d^2 eps / du^2)^2 du per node (u = x scaled to
//    [0, 1]), on the knot values' second divided differences, relative to the node's RMS
//    |eps|. After the solve a knot's eps2 below 0 (only strong smoothing of near-zero
//    data gives one) is set to 0: passive, and PCHIP keeps eps2 >= 0 between the knots.
// With the smoothing 0 and knots at the samples the fit interpolates them (eps-pchip); as
// it grows the curves tend to the least-squares straight line: a regression that does not
// chase each sample's scatter. The smoothing is chosen from the data by
// leave-one-composition-out cross-validation over the interior compositions (ten groups
// of them when there are more than twenty), scored by the left-out samples' normal-incidence
// reflectance error. With fewer than three interior compositions two left-out errors
// cannot decide, and the restricted marginal likelihood (REML) chooses among the same
// candidates, one for each wavelength node: the penalised fit read as a Gaussian model
// (the roughness a prior on the curve, its strength free per node, where the curvature
// across composition differs) with one relative noise level for all nodes, which weighs
// every sample, the ends too. With three samples or fewer the smoothing is 0 (with one
// interior composition the evidence cannot tell noise from curvature: for one node it
// does not depend on the smoothing at all).
//
// The space: the curves run through eps1 and eps2, or through ln|eps| and arg eps
// (model/smooth_model.h: geometric interpolation, for samples whose |eps| differ by orders
// of magnitude or of which one is not metallic). Both are fitted as above, each with its
// own choice of smoothing and form, and ln eps is kept where its left-out RMS reflectance
// error over the interior compositions (the cross-validation's, or with fewer folds that
// of the chosen smoothing) is at least a third below that of eps; eps otherwise, and
// without an interior composition. In ln eps the misfit is relative as it stands, and the
// roughness penalty acts on ln|eps| and arg eps.
//
// The second form (fit/gp_regression.h): a Gaussian process across composition, one kernel
// for all nodes, sampled at kSmoothMaxKnots even knots. The cross-validation's folds score
// it (only where they choose the smoothing), and it replaces the PCHIP form where its
// left-out reflectance error is more than 10 % below the best smoothing's: with dense samples of a
// smooth alloy series it uses them all (the PCHIP form sees only each interval's neighbours); with
// few or scattered samples the PCHIP form stays. A given smoothing keeps the PCHIP form.
// Above kSmoothMaxGpCompositions compositions (a composition-spread library) the Gaussian
// process is not tried: its cost grows as the cube of their number, and the PCHIP form's
// knots already smooth across so many samples.
//
// Dense series (more compositions than knots): each node's two parts are independent
// least-squares problems, each fitted on its own (Ceres, dense normal Cholesky).
#ifndef ALLOYCOLOR_FIT_SMOOTH_FIT_H_
#define ALLOYCOLOR_FIT_SMOOTH_FIT_H_

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/model/smooth_model.h"

namespace alloycolor::fit {

inline constexpr int kSmoothMaxGpCompositions = 100;

struct SmoothFitOptions {
  std::vector<double> grid_nm;  // empty: DefaultGrid(dataset)
  double smoothing = -1;        // < 0: chosen by cross-validation
  int max_knots = 24;           // at most kSmoothMaxKnots
  int max_iterations = 50;
  // The space of the curves; empty: eps, or ln eps where it predicts the left-out
  // compositions better by a third.
  std::optional<SmoothSpace> space;
  const SmoothModel* start = nullptr;  // refit: start from this model's eps at the knots
  ProgressCallback progress;           // may be empty
  ProgressCallback details;            // may be empty: each candidate's cross-validation
  CancelCheck cancel;  // may be empty: called before each solve and node (core/progress.h)
};

// The candidates cross-validation tries.
const std::vector<double>& SmoothingCandidates();

struct CrossValidationRow {
  double smoothing;
  double rms;              // RMS relative eps error on the left-out samples
  double rms_reflectance;  // RMS normal-incidence reflectance error there (the score)
};

struct EvidenceRow {
  double smoothing;
  int nodes;  // the wavelengths where it is the most probable
};

struct SmoothFitResult {
  std::unique_ptr<SmoothModel> model;
  // Whichever chose the smoothing; both empty when it was given or there were too few samples.
  std::vector<CrossValidationRow> cross_validation;
  std::vector<EvidenceRow> evidence;
  // The marginal likelihood's smoothing at each node of the grid (the model's smoothing()
  // is their median); empty where it did not choose.
  std::vector<double> smoothing_per_node;
  // The Gaussian-process form's leave-one-out errors (as CrossValidationRow); -1 when it
  // was not scored (no cross-validation).
  double gp_rms = -1, gp_rms_reflectance = -1;
};

// Throws Error when the data set has fewer than two compositions or a sample does not
// cover the grid, naming what is missing.
SmoothFitResult FitSmooth(const Dataset& dataset, const SmoothFitOptions& options);

// The restricted log marginal likelihood, up to a constant that depends only on the data,
// of a smoothing at each node of grid_nm, knots at the compositions and one relative noise
// level profiled out: how the fit weighs one choice of smoothings against another.
double SmoothingLogEvidence(const Dataset& dataset, const std::vector<double>& grid_nm,
                            const std::vector<double>& smoothing_per_node);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SMOOTH_FIT_H_
