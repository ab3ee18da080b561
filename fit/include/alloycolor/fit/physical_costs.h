// Cost function of the physical fit (physical_fit.h): the relative misfit of the model's
// eps at every wavelength of one sample, differentiated by ceres::Jet through the same
// templated physics the model evaluates (model/physical_model.h).
//
// Residuals, for each wavelength i of the sample:
//   (eps_model(w_i, x) - eps_i) / |eps_i|, real and imaginary parts.
// The parameter block is the model's coefficients (parameter-major, c[k nb + d]). Every
// parameter depends on its own polynomial r_k = sum_d c_kd P_d(u) only, so the Jets run
// over the r_k (at most kPhysicalMaxParameters of them) and the chain rule
// d/dc_kd = P_d(u) d/dr_k gives the coefficients' Jacobian.
#ifndef ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_
#define ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_

#include <ceres/ceres.h>

#include <cmath>
#include <complex>
#include <vector>

#include "alloycolor/model/physical_model.h"

namespace alloycolor::fit {

template <int kJet>
class PhysicalSampleCost : public ceres::CostFunction {
 public:
  PhysicalSampleCost(const PhysicalLayout& layout, const double* basis,
                     std::vector<double> omega_ev, const std::vector<std::complex<double>>& eps)
      : layout_(layout), basis_(basis, basis + layout.basis_size()), omega_ev_(std::move(omega_ev)) {
    for (const auto& e : eps) {
      eps1_.push_back(e.real());
      eps2_.push_back(e.imag());
      inv_abs_.push_back(1.0 / std::abs(e));
    }
    set_num_residuals(2 * static_cast<int>(omega_ev_.size()));
    mutable_parameter_block_sizes()->push_back(layout_.num_coefficients());
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int np = layout_.num_parameters();
    double raw[kPhysicalMaxParameters];
    PhysicalRawFromCoefficients(layout_, parameters[0], basis_.data(), raw);
    if (jacobians == nullptr || jacobians[0] == nullptr) {
      double values[kPhysicalMaxParameters];
      PhysicalValuesFromRaw(layout_, raw, values);
      for (size_t i = 0; i < omega_ev_.size(); ++i) {
        const Complex<double> e = PhysicalPermittivity(layout_, values, omega_ev_[i]);
        residuals[2 * i] = (e.re - eps1_[i]) * inv_abs_[i];
        residuals[2 * i + 1] = (e.im - eps2_[i]) * inv_abs_[i];
        if (!std::isfinite(residuals[2 * i]) || !std::isfinite(residuals[2 * i + 1])) {
          return false;
        }
      }
      return true;
    }
    using Jet = ceres::Jet<double, kJet>;
    Jet raw_jet[kJet], values[kJet];
    for (int k = 0; k < np; ++k) raw_jet[k] = Jet(raw[k], k);
    PhysicalValuesFromRaw(layout_, raw_jet, values);
    const int nb = layout_.basis_size();
    const int nc = layout_.num_coefficients();
    double* jac = jacobians[0];
    for (size_t i = 0; i < omega_ev_.size(); ++i) {
      const Complex<Jet> e = PhysicalPermittivity(layout_, values, omega_ev_[i]);
      residuals[2 * i] = (e.re.a - eps1_[i]) * inv_abs_[i];
      residuals[2 * i + 1] = (e.im.a - eps2_[i]) * inv_abs_[i];
      if (!std::isfinite(residuals[2 * i]) || !std::isfinite(residuals[2 * i + 1])) return false;
      double* row_re = jac + (2 * i) * nc;
      double* row_im = row_re + nc;
      for (int k = 0; k < np; ++k) {
        const double dre = e.re.v[k] * inv_abs_[i];
        const double dim = e.im.v[k] * inv_abs_[i];
        for (int d = 0; d < nb; ++d) {
          row_re[k * nb + d] = dre * basis_[d];
          row_im[k * nb + d] = dim * basis_[d];
        }
      }
    }
    return true;
  }

 private:
  const PhysicalLayout layout_;
  const std::vector<double> basis_;
  const std::vector<double> omega_ev_;
  std::vector<double> eps1_, eps2_, inv_abs_;
};

// The cost of one sample at basis P_d(u) (layout.basis_size() values): its eps at the
// photon energies omega_ev. Chooses the smallest Jet that holds the layout's parameters.
inline ceres::CostFunction* CreatePhysicalSampleCost(
    const PhysicalLayout& layout, const double* basis, std::vector<double> omega_ev,
    const std::vector<std::complex<double>>& eps) {
  const int np = layout.num_parameters();
  if (np <= 4) return new PhysicalSampleCost<4>(layout, basis, std::move(omega_ev), eps);
  if (np <= 8) return new PhysicalSampleCost<8>(layout, basis, std::move(omega_ev), eps);
  if (np <= 16) return new PhysicalSampleCost<16>(layout, basis, std::move(omega_ev), eps);
  return new PhysicalSampleCost<kPhysicalMaxParameters>(layout, basis, std::move(omega_ev), eps);
}

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_
