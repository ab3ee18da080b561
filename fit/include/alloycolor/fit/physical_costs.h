// Cost function of the physical fit (physical_fit.h): the relative misfit of the model's
// eps at every wavelength of one sample, differentiated by ceres::Jet through the same
// templated physics the model evaluates (model/physical_model.h).
//
// Residuals, for each wavelength i of the sample:
//   (eps_model(w_i, x) - eps_i) / |eps_i|, real and imaginary parts.
// The parameter block is the model's coefficients (parameter-major, c[k nb + d]). Every
// parameter value depends on the polynomials r_k = sum_d c_kd P_d(u) only, so Jets over
// the r_k (at most kPhysicalMaxParameters of them) give the values' derivatives once per
// sample; each term, which depends on at most 4 values, is differentiated at each
// wavelength with a Jet of 4; the chain rule joins them, and d/dc_kd = P_d(u) d/dr_k.
#ifndef ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_
#define ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_

#include <ceres/ceres.h>

#include <algorithm>
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
      : layout_(layout),
        basis_(basis, basis + layout.basis_size()),
        omega_ev_(std::move(omega_ev)) {
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
    // The parameter values as Jets over the r_k, once per sample.
    using Jet = ceres::Jet<double, kJet>;
    Jet raw_jet[kJet], values[kJet];
    for (int k = 0; k < np; ++k) raw_jet[k] = Jet(raw[k], k);
    PhysicalValuesFromRaw(layout_, raw_jet, values);
    // Each term depends on its own few parameters: differentiate it with a small Jet over
    // them, then chain to the r_k through values[].v.
    using TermJet = ceres::Jet<double, 4>;
    const int nb = layout_.basis_size();
    const int nc = layout_.num_coefficients();
    double* jac = jacobians[0];
    double dre[kPhysicalMaxParameters], dim[kPhysicalMaxParameters];
    for (size_t i = 0; i < omega_ev_.size(); ++i) {
      double eps_re = 0, eps_im = 0;
      std::fill(dre, dre + np, 0.0);
      std::fill(dim, dim + np, 0.0);
      for (int t = 0; t < layout_.num_terms(); ++t) {
        const int o = layout_.term_offset(t);
        const int size = layout_.term_size(t);
        TermJet v[4];
        for (int j = 0; j < size; ++j) v[j] = TermJet(values[o + j].a, j);
        const Complex<TermJet> e = TermPermittivity(layout_.term_kind(t), v, omega_ev_[i]);
        eps_re += e.re.a;
        eps_im += e.im.a;
        for (int j = 0; j < size; ++j) {
          const Jet& value = values[o + j];
          for (int k = 0; k < np; ++k) {
            dre[k] += e.re.v[j] * value.v[k];
            dim[k] += e.im.v[j] * value.v[k];
          }
        }
      }
      residuals[2 * i] = (eps_re - eps1_[i]) * inv_abs_[i];
      residuals[2 * i + 1] = (eps_im - eps2_[i]) * inv_abs_[i];
      if (!std::isfinite(residuals[2 * i]) || !std::isfinite(residuals[2 * i + 1])) return false;
      double* row_re = jac + (2 * i) * nc;
      double* row_im = row_re + nc;
      for (int k = 0; k < np; ++k) {
        const double a = dre[k] * inv_abs_[i];
        const double b = dim[k] * inv_abs_[i];
        for (int d = 0; d < nb; ++d) {
          row_re[k * nb + d] = a * basis_[d];
          row_im[k * nb + d] = b * basis_[d];
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
inline ceres::CostFunction* CreatePhysicalSampleCost(const PhysicalLayout& layout,
                                                     const double* basis,
                                                     std::vector<double> omega_ev,
                                                     const std::vector<std::complex<double>>& eps) {
  const int np = layout.num_parameters();
  if (np <= 4) return new PhysicalSampleCost<4>(layout, basis, std::move(omega_ev), eps);
  if (np <= 8) return new PhysicalSampleCost<8>(layout, basis, std::move(omega_ev), eps);
  if (np <= 16) return new PhysicalSampleCost<16>(layout, basis, std::move(omega_ev), eps);
  return new PhysicalSampleCost<kPhysicalMaxParameters>(layout, basis, std::move(omega_ev), eps);
}

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_
