// Joint Ceres fit of the "physical" model (model/physical_model.h) to all samples of a
// data set: one Drude term plus interband terms, every parameter a polynomial of degree D
// in composition, all samples and wavelengths in one problem.
//
// Cost: 1/2 the sum over samples i and wavelengths j of |eps_model(x_i, w_j) - eps_ij|^2 /
// |eps_ij|^2 (real and imaginary parts), over every finite point: eps_inf and the
// interband terms represent eps1 > 1, so no point contradicts the model.
//
// Start. (1) Each end sample (lowest and highest composition, normally the pure
// elements) is fitted alone (degree 0). eps is linear in eps_inf, wp^2 and each term's
// strength (a critical point's A cos phi, A sin phi), so a grid search over the other
// parameters (gamma around the pointwise inversion, eq. 11, 12, at the longest
// wavelength; each term's centre on 12 energies across the range, width on 4, a
// rioux-gap's Eg - E0 on 3) solves for those by weighted linear least squares from a
// cached Gram matrix; the best combinations with distinct centres are refined by Ceres.
// (2) Joint starts: the straight line between the ends' polynomials r, and quadratics
// through the ends and the middle sample's own fits (grid search with each centre kept
// near the span of the ends' centres, so the terms keep their roles). Every start runs
// kRaceIterations; the lowest cost goes on to convergence. Bounds: the phases' coefficients
// in [-pi, pi], the constant coefficients of positive parameters in [0, an upper limit]
// (energies up to 3 times the range's highest photon energy). They keep the solver out of
// flat regions where pos(r) is 0 and act as a mild prior: on measured data whose
// decomposition into terms is poorly determined (Cu-Zn) the bounded fit has a higher
// training cost than an unbounded one but predicts held-out samples better.
//
// Covariance: ceres::Covariance (dense SVD) of all coefficients, scaled by the residual
// variance sum r^2 / (residuals - coefficients) times (1 + rho) / (1 - rho), rho the
// residuals' lag-1 autocorrelation along wavelength (0 <= rho <= 0.99): a smooth misfit
// carries less information than the number of residuals says (AR(1) effective sample
// size). When the Jacobian is rank-deficient the pseudo-inverse is used
// (null_space_rank = -1) and the fit statistics say so.
// Linear algebra is Eigen's dense normal Cholesky, single-threaded, so the same inputs
// give the same bytes.
#ifndef ALLOYCOLOR_FIT_PHYSICAL_FIT_H_
#define ALLOYCOLOR_FIT_PHYSICAL_FIT_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/model/physical_model.h"

namespace alloycolor::fit {

// End-sample fits one job may reuse: every leave-one-out fold of a data set (the
// prediction error's, `validate`'s, auto's) keeps the same end samples and fits them
// alike, and a fit is deterministic. Thread-safe; made by MakeEndSampleFits.
struct EndSampleFits;
std::shared_ptr<EndSampleFits> MakeEndSampleFits();

struct PhysicalFitOptions {
  // Fit range; both 0: the samples' common range within 300-1000 nm, or, when that is
  // shorter than 200 nm (infrared data), the whole common range.
  double lambda_from_nm = 0;
  double lambda_to_nm = 0;
  double lambda_step_nm = 0;  // 0: 5 nm, or (to - from) / 200 for infrared data
  int degree = 2;             // reduced to (number of compositions - 1) when larger
  // Interband terms, comma-separated (lorentz, cp, rioux-gap, rioux-edge), "none" for
  // the Drude term alone, or "auto": none for infrared data; otherwise each of
  // kAutoTerms is fitted to the end samples and the lowest cost wins.
  std::string terms = "auto";
  int max_iterations = 500;
  bool covariance = true;
  // Warm start: a model fitted to data with the same end compositions (the parent of a
  // leave-one-out fold). With the same degree, its terms and coefficients are the one
  // start (no end-sample fits, no race); otherwise it is ignored.
  const PhysicalModel* start = nullptr;
  // false: no check for leaving physics (below) — for the model of a leave-one-out fold,
  // which only predicts its held-out samples and is never written or shown.
  bool check_physics = true;
  EndSampleFits* end_fits = nullptr;  // may be null: the end samples fitted afresh
  std::function<void(const std::string& message)> progress;  // may be empty
  CancelCheck cancel;  // may be empty: called between the solver's iterations (core/progress.h)
};

// The candidates "auto" tries on visible data.
inline const char* const kAutoTerms[] = {"rioux-gap,rioux-edge", "cp,cp",
                                         "lorentz,lorentz,lorentz"};

struct PhysicalFitResult {
  std::unique_ptr<PhysicalModel> model;
  std::string terms;  // the interband terms used ("none" for Drude only)
};

// More compositions than kPhysicalMaxCompositions (a composition-spread library): the fit
// takes the samples of that many, spread evenly by rank with the ends, and says so in a
// warning (and a progress line).
inline constexpr int kPhysicalMaxCompositions = 100;

// Throws Error when the data set has fewer than two compositions, when the samples share
// no wavelength range or do not cover the requested one (naming the sample), or for a
// bad option (naming it).
// A fit that leaves physics anywhere inside its composition and wavelength ranges (eps2 < 0,
// n or k above 50 or 1.5 times the data's largest) or does not converge is refitted one
// degree lower, down to 1, with a warning naming what happened; still unphysical at
// degree 1 it is an Error naming where.
PhysicalFitResult FitPhysical(const Dataset& dataset, const PhysicalFitOptions& options);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_PHYSICAL_FIT_H_
