// Models that keep the training samples' measured spectra and interpolate between them:
//
//  - "paper": the baseline of Kuboshima & Furukawa. At each wavelength, each sample's
//    eps is inverted to Drude parameters (eq. 11, 12): gamma = 1/tau and wp^2, hence
//    m*/m_e = kPlasmaEv2M3 N_e(x) / wp^2. tau and m* are interpolated linearly in x
//    between the neighbouring samples and eps rebuilt with eq. 7 (N_e(x) from
//    composition.h). Where a sample's inversion is undefined (eps1 >= 1 or eps2 <= 0) it
//    is skipped at those wavelengths (named in warnings()); where no sample can be
//    inverted, eps is interpolated linearly instead. Known samples are reproduced exactly.
//  - "eps-linear": eps interpolated linearly in x between neighbouring samples; the
//    obvious baseline the fitted models must beat.
//  - "eps-pchip": eps1 and eps2 each interpolated in x by a monotone cubic (PCHIP), and
//    "eps-spline": by a natural cubic spline (interpolation.h): the strongest simple rivals.
//    PCHIP stays between neighbouring samples; a natural spline can undershoot, and its
//    eps2 is held at 0 where it would (a negative eps2 is an amplifying medium).
//
// Replicates (several samples at one composition) make one node there: their mean
// (dataset.h MeanSpectrum, eps averaged), so the model passes between them.
// All interpolate each node's n, k linearly in wavelength. Outside the samples' x range
// they extrapolate linearly from the two nearest samples (the caller decides whether
// that is allowed).
#ifndef ALLOYCOLOR_MODEL_SAMPLE_MODELS_H_
#define ALLOYCOLOR_MODEL_SAMPLE_MODELS_H_

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

class SampleModel : public AlloyModel {
 public:
  enum class Kind { kPaper, kEpsLinear, kEpsPchip, kEpsSpline };

  // Throws Error when the data set has fewer than two compositions or no common
  // wavelength range.
  SampleModel(Kind kind, const Dataset& dataset);
  SampleModel(Kind kind, const nlohmann::json& doc, const std::string& source);

  std::string method() const override;
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;

  // "paper": the interpolated tau and m* turned back into gamma and wp^2 at x; otherwise
  // the inversion of eps.
  bool DrudeAt(double x_atomic, double lambda_nm, DrudePoint* out) const override;

  // Bound to a grid: every sample's eps there (and, for "paper", its inversion to tau and
  // m* wherever that is defined) computed once, so a composition costs the interpolation
  // in x and eq. 7 per wavelength. Equal to Permittivity to rounding.
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;

  // Drude parameters of the paper method at (x, lambda): false where undefined.
  struct TauMass {
    double tau_fs;
    double mass_ratio;  // m*/m_e
  };
  bool PaperTauMass(double x_atomic, double lambda_nm, TauMass* out) const;

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  struct Node {
    double x;
    NkSpectrum nk;
  };
  void Validate();
  void Diagnose();
  std::complex<double> PaperAt(double x, double lambda_nm) const;
  std::complex<double> EpsLinearAt(double x, double lambda_nm) const;
  std::vector<std::complex<double>> EpsLinearOn(double x,
                                                const std::vector<double>& lambda_nm) const;
  std::complex<double> EpsCubicAt(double x, double lambda_nm) const;

  Kind kind_;
  std::vector<Node> nodes_;     // sorted by x
  std::vector<double> node_x_;  // their compositions
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_SAMPLE_MODELS_H_
