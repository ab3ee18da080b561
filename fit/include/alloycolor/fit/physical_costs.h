// Cost function of the physical fit (physical_fit.h): the relative misfit of the model's
// eps at every wavelength of one sample, through the same physics the model evaluates
// (model/physical_terms.h), in the wavelength kernel (model/physical_kernel.h).
//
// Residuals, for each wavelength i of the sample:
//   (eps_model(w_i, x) - eps_i) / |eps_i|, real and imaginary parts.
// The parameter block is the model's coefficients (parameter-major, c[k nb + d]). Every
// parameter value depends on the polynomials r_k = sum_d c_kd P_d(u) only: Jets over the
// r_k (at most kPhysicalMaxParameters of them) give the values' derivatives dv_j / dr_k
// once per sample (the maps of physical_model.h); the terms' hand-written gradients
// d eps / dv_j (physical_terms.h) come from the kernel for all wavelengths at once; the
// chain rule joins them, and d/dc_kd = P_d(u) d/dr_k. Where the kernel gives up (its
// approximations' range, physical_kernel.h) the same gradients are taken one wavelength at
// a time with the C library's functions.
#ifndef ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_
#define ALLOYCOLOR_FIT_PHYSICAL_COSTS_H_

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <utility>
#include <vector>

#include "alloycolor/model/physical_kernel.h"
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
    const size_t m = omega_ev_.size(), np = static_cast<size_t>(layout_.num_parameters());
    scratch_.resize(2 * m * (2 * np + 1));  // eps, d eps / dv_j, d eps / dr_k
    // Which r_k each value depends on: its own, and through a reference (a centre above
    // another, Eg above E0) that one's.
    for (int j = 0; j < layout_.num_parameters(); ++j) {
      for (int k = j; k >= 0; k = layout_.parameters()[k].reference) {
        depends_.push_back({j, k});
        if (layout_.parameters()[k].map != ParameterMap::kAbove) break;
      }
    }
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int np = layout_.num_parameters();
    const size_t m = omega_ev_.size();
    double raw[kPhysicalMaxParameters];
    PhysicalRawFromCoefficients(layout_, parameters[0], basis_.data(), raw);
    double* e1 = scratch_.data();
    double* e2 = e1 + m;
    if (jacobians == nullptr || jacobians[0] == nullptr) {
      // The cost alone (the line search's, the step's).
      double values[kPhysicalMaxParameters];
      PhysicalValuesFromRaw(layout_, raw, values);
      kernel::PhysicalPermittivityOnGrid(layout_, values, m, omega_ev_.data(), e1, e2);
      for (size_t i = 0; i < m; ++i) {
        if (!std::isfinite(e1[i]) || !std::isfinite(e2[i])) {
          const Complex<double> e = PhysicalPermittivity(layout_, values, omega_ev_[i]);
          e1[i] = e.re;
          e2[i] = e.im;
        }
      }
      return Residuals(e1, e2, residuals);
    }
    // The line search asks for the Jacobian at its step, and the minimizer again at the
    // same point when it takes the step: the second time, the first's answer.
    const int nc = layout_.num_coefficients();
    const size_t rows = 2 * m;
    if (cached_ && std::equal(parameters[0], parameters[0] + nc, cached_at_.begin())) {
      std::copy(cached_residuals_.begin(), cached_residuals_.end(), residuals);
      std::copy(cached_jacobian_.begin(), cached_jacobian_.end(), jacobians[0]);
      return true;
    }
    cached_ = false;
    // The parameter values and dv_j / dr_k, once per sample.
    using Jet = ceres::Jet<double, kJet>;
    Jet raw_jet[kJet], value_jet[kJet];
    for (int k = 0; k < np; ++k) raw_jet[k] = Jet(raw[k], k);
    PhysicalValuesFromRaw(layout_, raw_jet, value_jet);
    double values[kPhysicalMaxParameters];
    for (int j = 0; j < np; ++j) values[j] = value_jet[j].a;
    // eps and d eps / dv_j at every wavelength.
    double* g1 = e2 + m;
    double* g2 = g1 + np * m;
    kernel::PhysicalGradientOnGrid(layout_, values, m, omega_ev_.data(), e1, e2, g1, g2);
    if (!AllFinite(2 * m * (np + 1), e1)) GradientOneByOne(values, e1, e2, g1, g2);
    if (!Residuals(e1, e2, residuals)) return false;
    // d eps / dr_k at every wavelength: the chain rule through the values, one
    // (value, r) pair at a time over all wavelengths.
    double* d1 = g2 + np * m;
    double* d2 = d1 + np * m;
    std::fill(d1, d1 + 2 * np * m, 0.0);
    for (const auto& [j, k] : depends_) {
      const double dv = value_jet[j].v[k];
      const double* a1 = g1 + j * m;
      const double* a2 = g2 + j * m;
      double* b1 = d1 + k * m;
      double* b2 = d2 + k * m;
      for (size_t i = 0; i < m; ++i) {
        b1[i] += a1[i] * dv;
        b2[i] += a2[i] * dv;
      }
    }
    // Then d/dc_kd = P_d(u) d/dr_k, relative to |eps_i|.
    const int nb = layout_.basis_size();
    double* jac = jacobians[0];
    for (size_t i = 0; i < m; ++i) {
      double* row_re = jac + (2 * i) * nc;
      double* row_im = row_re + nc;
      for (int k = 0; k < np; ++k) {
        const double a = d1[k * m + i] * inv_abs_[i];
        const double b = d2[k * m + i] * inv_abs_[i];
        for (int d = 0; d < nb; ++d) {
          row_re[k * nb + d] = a * basis_[d];
          row_im[k * nb + d] = b * basis_[d];
        }
      }
    }
    cached_at_.assign(parameters[0], parameters[0] + nc);
    cached_residuals_.assign(residuals, residuals + rows);
    cached_jacobian_.assign(jac, jac + rows * static_cast<size_t>(nc));
    cached_ = true;
    return true;  // Ceres checks the Jacobian's values itself
  }

 private:
  static bool AllFinite(size_t n, const double* v) {
    int bad = 0;
#pragma omp simd reduction(| : bad)
    for (size_t i = 0; i < n; ++i) bad |= !(std::abs(v[i]) <= kMaxFinite);  // NaN fails too
    return bad == 0;
  }
  static constexpr double kMaxFinite = 1.7976931348623157e308;

  bool Residuals(const double* e1, const double* e2, double* residuals) const {
    for (size_t i = 0; i < omega_ev_.size(); ++i) {
      residuals[2 * i] = (e1[i] - eps1_[i]) * inv_abs_[i];
      residuals[2 * i + 1] = (e2[i] - eps2_[i]) * inv_abs_[i];
    }
    return AllFinite(2 * omega_ev_.size(), residuals);
  }

  // The kernel's gradient the straightforward way, one wavelength at a time.
  void GradientOneByOne(const double* values, double* e1, double* e2, double* g1,
                        double* g2) const {
    const size_t m = omega_ev_.size();
    for (size_t i = 0; i < m; ++i) {
      e1[i] = e2[i] = 0.0;
      for (int t = 0; t < layout_.num_terms(); ++t) {
        const int o = layout_.term_offset(t);
        const TermGradient<double> g =
            TermGradientAt(layout_.term_kind(t), values + o, omega_ev_[i]);
        e1[i] += g.value.re;
        e2[i] += g.value.im;
        for (int j = 0; j < layout_.term_size(t); ++j) {
          g1[(o + j) * m + i] = g.d[j].re;
          g2[(o + j) * m + i] = g.d[j].im;
        }
      }
    }
  }

  const PhysicalLayout layout_;
  const std::vector<double> basis_;
  const std::vector<double> omega_ev_;
  std::vector<double> eps1_, eps2_, inv_abs_;
  std::vector<std::pair<int, int>> depends_;  // (value j, raw k) where dv_j / dr_k may be != 0
  // eps and its gradient: Ceres evaluates one problem's blocks on one thread (the fits set
  // num_threads = 1), so one scratch per cost is enough.
  mutable std::vector<double> scratch_;
  // The last Jacobian evaluation: where, and what it gave.
  mutable bool cached_ = false;
  mutable std::vector<double> cached_at_, cached_residuals_, cached_jacobian_;
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
