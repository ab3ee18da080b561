// The "physical" model: a Drude term plus interband terms whose parameters are smooth
// functions of composition, fitted jointly to all samples (fit/physical_fit.h); this class
// only evaluates it. Photon energies w in eV (hbar w), time convention exp(-i w t), so
// eps2 > 0 for absorption.
//
//   eps(w, x) = eps_inf(x) - wp(x)^2 / (w (w + i gamma(x)))  +  sum_j eps_j(w, x)
//
// Interband term kinds (A >= 0 dimensionless, energies E and widths G in eV, c = w + i G):
//  - "lorentz": Lorentz oscillator (Lorentz-Drude model of Rakic et al., Appl. Opt. 37,
//      5271 (1998), with the strength A = f_j wp^2 / E0^2):
//        A E0^2 / (E0^2 - w^2 - i w G)
//  - "cp": critical point of Etchegoin, Le Ru & Meyer, J. Chem. Phys. 125, 164705 (2006),
//      eq. 2 written in energies (A_i / lambda_i -> A E0, 1 / gamma_i -> G):
//        A E0 [ e^{i phi} / (E0 - w - i G) + e^{-i phi} / (E0 + w + i G) ]
//  - "rioux-gap": transitions between parabolic bands with an absorption onset at E0 and a
//      gap Eg > E0, the first interband term of Rioux et al., Adv. Opt. Mater. 2, 176 (2014)
//      (as in the authors' published code), with r = sqrt(Eg - E0):
//        A / c^2 [ -sqrt(c - Eg) atan(r / sqrt(c - Eg)) - sqrt(c + Eg) atanh(r / sqrt(c + Eg))
//                  + 2 sqrt(Eg) atanh(r / sqrt(Eg)) - (r / 2) ln(1 - c^2 / E0^2) ]
//      (each product sqrt(z) atan(r / sqrt(z)) is even in sqrt(z), so the branch of the
//      root does not matter; the cuts of atan, atanh and ln are never reached for G > 0);
//  - "rioux-edge": the second term of Rioux et al. 2014, an onset at E0 without a gap:
//        -A ln(1 - c^2 / E0^2) / (2 c^2)
// The shipped Au-Ag set is reproduced by drude + rioux-gap + rioux-edge to 5e-6 in n, k.
//
// Composition dependence. Every parameter p is a function of a polynomial
//   r_p(x) = sum_d c_pd P_d(u),  u = 2 (x - x_lo) / (x_hi - x_lo) - 1
// (Legendre P_0..P_D, x_lo, x_hi the training range) through a map that keeps it physical:
//   eps_inf = 1 + pos(r);  wp, gamma, A, G, the first E0 of each kind = pos(r);
//   the k-th E0 of a kind = the (k-1)-th E0 of that kind + pos(r) (centres stay ordered);
//   Eg = E0 + pos(r);  phi = r (radians, kept in [-pi, pi] by the fit's bounds),
// with pos(r) = (r + sqrt(r^2 + s^2)) / 2, s = kPhysicalPositiveScale: a smooth positive
// part, equal to r to within s^2 / (4 r) for r >> s. The parameters are polynomials in x
// themselves, not in ln x: Nordheim's rule makes the alloy scattering rate quadratic,
// gamma = (1-x) gamma_b + x gamma_a + C x (1-x), and band energies move about linearly
// with composition (the shipped Au-Ag set is quadratic in the raw parameters too).
//
// The terms themselves, templated on the scalar, with their gradients: physical_terms.h.
// The model evaluates them over a wavelength grid in SIMD lanes (physical_kernel.h): its
// exact colour per composition is the parameters' polynomials once and the kernel.
#ifndef ALLOYCOLOR_MODEL_PHYSICAL_MODEL_H_
#define ALLOYCOLOR_MODEL_PHYSICAL_MODEL_H_

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/legendre.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/model/physical_terms.h"

namespace alloycolor {

inline constexpr int kPhysicalMaxDegree = 6;
inline constexpr int kPhysicalMaxInterbandTerms = 6;
inline constexpr int kPhysicalMaxParameters = 3 + 4 * kPhysicalMaxInterbandTerms;
inline constexpr double kPhysicalPositiveScale = 1e-3;
// The narrowest Lorentz or critical-point line (G, eV) a model file may give where its
// centre lies among the model's photon energies, anywhere in its composition range: a
// width far below the 5 nm colour grid's spacing (0.01-0.05 eV) is a pole that the grid
// samples by chance (A E0 / G at the centre). Rioux et al.'s terms have logarithmic
// onsets, no pole, and no floor (fits of Au-Ag narrow them to 1e-7 eV where the data do
// not resolve them).
inline constexpr double kPhysicalMinWidthEv = 1e-3;

// "drude", "lorentz", "cp", "rioux-gap", "rioux-edge".
const char* TermKindName(TermKind kind);
// Throws Error naming the text for an unknown kind.
TermKind TermKindFromName(const std::string& name);
// Comma-separated interband kinds ("cp,cp", "rioux-gap,rioux-edge"); "" or "none": no
// interband term. Throws Error naming the text.
std::vector<TermKind> ParseInterbandTerms(const std::string& text);
std::string InterbandTermsText(const std::vector<TermKind>& kinds);

// How a parameter's value follows from its polynomial r.
enum class ParameterMap {
  kPositive,         // pos(r)
  kOnePlusPositive,  // 1 + pos(r)
  kAbove,            // value of parameter `reference` + pos(r)
  kFree,             // r
};

struct PhysicalParameter {
  int term;          // 0 is the Drude term
  TermKind kind;     // the term's kind
  const char* name;  // "eps_inf", "wp_eV", "gamma_eV", "A", "E0_eV", "Eg_eV", "G_eV", "phi_rad"
  ParameterMap map;
  int reference;  // for kAbove: index of the parameter this one lies above; else -1
};

// The terms of a model and the order of its parameters: the Drude term's eps_inf, wp_eV,
// gamma_eV, then each interband term's A, E0_eV, [Eg_eV,] G_eV, [phi_rad].
class PhysicalLayout {
 public:
  PhysicalLayout() : PhysicalLayout({}, 2) {}
  // Throws Error for a degree outside 0..kPhysicalMaxDegree or too many terms.
  PhysicalLayout(std::vector<TermKind> interband, int degree);

  int degree() const { return degree_; }
  int basis_size() const { return degree_ + 1; }
  const std::vector<TermKind>& interband() const { return interband_; }
  int num_terms() const { return 1 + static_cast<int>(interband_.size()); }
  TermKind term_kind(int term) const { return term == 0 ? TermKind::kDrude : interband_[term - 1]; }
  const std::vector<PhysicalParameter>& parameters() const { return parameters_; }
  int num_parameters() const { return static_cast<int>(parameters_.size()); }
  int num_coefficients() const { return num_parameters() * basis_size(); }
  // Index of the first parameter of a term, and the term's number of parameters.
  int term_offset(int term) const { return term_offset_[term]; }
  int term_size(int term) const {
    return (term + 1 < num_terms() ? term_offset_[term + 1] : num_parameters()) -
           term_offset_[term];
  }
  // Index of a term's parameter by name, or -1.
  int Find(int term, const std::string& name) const;

 private:
  std::vector<TermKind> interband_;
  int degree_;
  std::vector<PhysicalParameter> parameters_;
  std::vector<int> term_offset_;
};

// pos(r) of the header.
template <typename T>
T SoftPositive(const T& r) {
  using std::sqrt;
  return (r + sqrt(r * r + T(kPhysicalPositiveScale * kPhysicalPositiveScale))) * T(0.5);
}
// Its inverse: the r with SoftPositive(r) = value, for value > 0.
inline double SoftPositiveInverse(double value) {
  return value - kPhysicalPositiveScale * kPhysicalPositiveScale / (4.0 * value);
}

// Parameter values from the polynomials r (one per parameter, in layout order).
template <typename T>
void PhysicalValuesFromRaw(const PhysicalLayout& layout, const T* raw, T* values) {
  const auto& params = layout.parameters();
  for (size_t k = 0; k < params.size(); ++k) {
    switch (params[k].map) {
      case ParameterMap::kPositive:
        values[k] = SoftPositive(raw[k]);
        break;
      case ParameterMap::kOnePlusPositive:
        values[k] = T(1.0) + SoftPositive(raw[k]);
        break;
      case ParameterMap::kAbove:
        values[k] = values[params[k].reference] + SoftPositive(raw[k]);
        break;
      case ParameterMap::kFree:
        values[k] = raw[k];
        break;
    }
  }
}

// The polynomials r at a composition from the coefficients (parameter-major: c[k nb + d])
// and the basis P_d(u).
template <typename T>
void PhysicalRawFromCoefficients(const PhysicalLayout& layout, const T* coeffs, const double* basis,
                                 T* raw) {
  const int nb = layout.basis_size();
  for (int k = 0; k < layout.num_parameters(); ++k) {
    T r(0.0);
    for (int d = 0; d < nb; ++d) r += coeffs[k * nb + d] * basis[d];
    raw[k] = r;
  }
}

// One term of the header (the Drude term or an interband one) at photon energy w; v points
// at the term's parameters (layout order).
template <typename T>
Complex<T> TermPermittivity(TermKind kind, const T* v, double omega_ev) {
  if (kind == TermKind::kDrude) return DrudePermittivity(T(omega_ev), v[1] * v[1], v[2], v[0]);
  return InterbandPermittivity(kind, v, omega_ev);
}

// eps of the header from parameter values (layout order) at photon energy w: the
// straightforward evaluation, one wavelength at a time (PhysicalModel evaluates many at once
// through the kernel, equal to this to rounding).
template <typename T>
Complex<T> PhysicalPermittivity(const PhysicalLayout& layout, const T* values, double omega_ev) {
  Complex<T> eps{T(0.0), T(0.0)};
  for (int t = 0; t < layout.num_terms(); ++t) {
    eps = eps + TermPermittivity(layout.term_kind(t), values + layout.term_offset(t), omega_ev);
  }
  return eps;
}

// One parameter at one composition with its one-sigma uncertainty (0 without covariance).
struct PhysicalParameterValue {
  int term;
  TermKind kind;
  std::string name;
  double value;
  double sigma;
};

class PhysicalModel : public AlloyModel {
 public:
  // `model` as a physical model, or null when it is of another method.
  static const PhysicalModel* From(const AlloyModel* model);
  // coeffs: layout.num_coefficients() values, parameter-major; covariance (row-major,
  // may be empty) their covariance.
  PhysicalModel(const Dataset& dataset, double lambda_min_nm, double lambda_max_nm,
                PhysicalLayout layout, std::vector<double> coeffs, std::vector<double> covariance);
  PhysicalModel(const nlohmann::json& doc, const std::string& source);

  std::string method() const override { return "physical"; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;
  // Bound to a grid: per composition the parameters' polynomials once, then eps over the
  // grid in the wavelength kernel (physical_kernel.h).
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;
  // The cross-validated prediction error where the fit estimated one (AlloyModel), else
  // draws of the coefficients from their covariance.
  bool HasUncertaintyTerms() const override {
    return AlloyModel::HasUncertaintyTerms() || !covariance_.empty();
  }
  std::vector<std::vector<std::complex<double>>> PermittivityDraws(
      double x_atomic, const std::vector<double>& lambda_nm, int count = kUncertaintyDraws,
      std::uint32_t seed = kUncertaintySeed) const override;

  const PhysicalLayout& layout() const { return layout_; }
  const std::vector<double>& coeffs() const { return coeffs_; }
  std::vector<double> FittedCoefficients() const override { return coeffs_; }
  const std::vector<double>& covariance() const { return covariance_; }
  double BasisArgument(double x_atomic) const;
  // Every parameter's value at x (layout order) from the coefficients (coeffs() or a draw
  // of them), into values[0..layout().num_parameters()).
  void ValuesAt(double x_atomic, const double* coeffs, double* values) const;
  // eps at the photon energies omega_ev[0..m) from parameter values, into eps1, eps2: the
  // kernel, or where it gives up (physical_kernel.h) PhysicalPermittivity at every one.
  void PermittivityOnGrid(const double* values, std::size_t m, const double* omega_ev, double* eps1,
                          double* eps2) const;
  // Every parameter's value at x, with one-sigma from the coefficients' covariance.
  std::vector<PhysicalParameterValue> ParameterValues(double x_atomic) const;
  // wp, gamma, tau, N_e, m*/m_e, eps_inf and each interband term's centre (eV and nm), gap
  // and width, with one-sigma from the covariance (first-order propagation).
  ParameterTable Parameters(const std::vector<double>& x_atomic) const override;
  // The narrowest width G of a Lorentz or critical-point line whose centre lies among the
  // model's photon energies, over the composition range, where, and the model file's field
  // that gives it ("" where there is none).
  std::string NarrowestPole(double* width_ev, double* x_atomic) const;
  // Adds fit diagnostics to warnings().
  void AddWarnings(const std::vector<std::string>& warnings);

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  void Validate(const std::string& source) const;
  // Throws Error naming the file and the field where a pole's width falls below
  // kPhysicalMinWidthEv (NarrowestPole; a model file's check; fits check it last of their
  // checks for leaving physics).
  void CheckWidths(const std::string& source) const;
  std::vector<std::complex<double>> Evaluate(double x_atomic, const std::vector<double>& lambda_nm,
                                             const double* coeffs) const;

  PhysicalLayout layout_;
  std::vector<double> coeffs_;
  std::vector<double> covariance_;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_PHYSICAL_MODEL_H_
