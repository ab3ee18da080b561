#include "alloycolor/model/physical_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <sstream>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/physical_kernel.h"

namespace alloycolor {

namespace {

struct KindName {
  TermKind kind;
  const char* name;
};
constexpr KindName kKindNames[] = {{TermKind::kDrude, "drude"},
                                   {TermKind::kLorentz, "lorentz"},
                                   {TermKind::kCriticalPoint, "cp"},
                                   {TermKind::kRiouxGap, "rioux-gap"},
                                   {TermKind::kRiouxEdge, "rioux-edge"}};

std::string Trim(const std::string& text) {
  const size_t b = text.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const size_t e = text.find_last_not_of(" \t");
  return text.substr(b, e - b + 1);
}

}  // namespace

const char* TermKindName(TermKind kind) {
  for (const auto& k : kKindNames) {
    if (k.kind == kind) return k.name;
  }
  return "?";
}

TermKind TermKindFromName(const std::string& name) {
  for (const auto& k : kKindNames) {
    if (name == k.name) return k.kind;
  }
  throw Error("unknown term kind '" + name + "' (drude, lorentz, cp, rioux-gap, rioux-edge)");
}

std::vector<TermKind> ParseInterbandTerms(const std::string& text) {
  std::vector<TermKind> kinds;
  const std::string all = Trim(text);
  if (all.empty() || all == "none") return kinds;
  std::stringstream in(all);
  std::string part;
  while (std::getline(in, part, ',')) {
    const std::string name = Trim(part);
    if (name.empty()) throw Error("terms '" + text + "': empty term kind");
    const TermKind kind = TermKindFromName(name);
    if (kind == TermKind::kDrude) {
      throw Error("terms '" + text +
                  "': the drude term is always there; list interband "
                  "terms only (lorentz, cp, rioux-gap, rioux-edge)");
    }
    kinds.push_back(kind);
  }
  if (all.back() == ',') throw Error("terms '" + text + "': empty term kind");
  if (kinds.size() > static_cast<size_t>(kPhysicalMaxInterbandTerms)) {
    throw Error("terms '" + text + "': at most " + std::to_string(kPhysicalMaxInterbandTerms) +
                " interband terms");
  }
  return kinds;
}

std::string InterbandTermsText(const std::vector<TermKind>& kinds) {
  if (kinds.empty()) return "none";
  std::string text;
  for (size_t i = 0; i < kinds.size(); ++i)
    text += (i ? "," : "") + std::string(TermKindName(kinds[i]));
  return text;
}

PhysicalLayout::PhysicalLayout(std::vector<TermKind> interband, int degree)
    : interband_(std::move(interband)), degree_(degree) {
  if (degree_ < 0 || degree_ > kPhysicalMaxDegree) {
    throw Error("physical model: degree must lie in 0.." + std::to_string(kPhysicalMaxDegree));
  }
  if (interband_.size() > static_cast<size_t>(kPhysicalMaxInterbandTerms)) {
    throw Error("physical model: at most " + std::to_string(kPhysicalMaxInterbandTerms) +
                " interband terms");
  }
  auto add = [&](int term, const char* name, ParameterMap map, int reference) {
    parameters_.push_back({term, term_kind(term), name, map, reference});
  };
  term_offset_.push_back(0);
  add(0, "eps_inf", ParameterMap::kOnePlusPositive, -1);
  add(0, "wp_eV", ParameterMap::kPositive, -1);
  add(0, "gamma_eV", ParameterMap::kPositive, -1);
  // The centre of the latest term of each kind, for ordering.
  std::vector<std::pair<TermKind, int>> last_centre;
  for (int t = 1; t <= static_cast<int>(interband_.size()); ++t) {
    const TermKind kind = interband_[t - 1];
    if (kind == TermKind::kDrude) throw Error("physical model: one drude term only");
    term_offset_.push_back(num_parameters());
    add(t, "A", ParameterMap::kPositive, -1);
    int below = -1;
    for (const auto& [k, index] : last_centre) {
      if (k == kind) below = index;
    }
    const int centre = num_parameters();
    add(t, "E0_eV", below < 0 ? ParameterMap::kPositive : ParameterMap::kAbove, below);
    last_centre.emplace_back(kind, centre);
    if (kind == TermKind::kRiouxGap) add(t, "Eg_eV", ParameterMap::kAbove, centre);
    add(t, "G_eV", ParameterMap::kPositive, -1);
    if (kind == TermKind::kCriticalPoint) add(t, "phi_rad", ParameterMap::kFree, -1);
  }
}

int PhysicalLayout::Find(int term, const std::string& name) const {
  for (int k = 0; k < num_parameters(); ++k) {
    if (parameters_[k].term == term && name == parameters_[k].name) return k;
  }
  return -1;
}

const PhysicalModel* PhysicalModel::From(const AlloyModel* model) {
  return dynamic_cast<const PhysicalModel*>(model);
}

PhysicalModel::PhysicalModel(const Dataset& dataset, double lambda_min_nm, double lambda_max_nm,
                             PhysicalLayout layout, std::vector<double> coeffs,
                             std::vector<double> covariance)
    : layout_(std::move(layout)), coeffs_(std::move(coeffs)), covariance_(std::move(covariance)) {
  SetCommon(dataset, lambda_min_nm, lambda_max_nm);
  Validate(dataset.manifest_path);
}

namespace {

// Reads a number, naming the field.
double FieldNumber(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw Error(where + ": expected a number");
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw Error(where + ": not a finite number");
  return v;
}

const nlohmann::json& FieldAt(const nlohmann::json& obj, const char* key,
                              const std::string& where) {
  if (!obj.is_object() || !obj.contains(key)) {
    throw Error(where + ": missing field '" + key + "'");
  }
  return obj.at(key);
}

std::string MapText(const PhysicalLayout& layout, const PhysicalParameter& p) {
  switch (p.map) {
    case ParameterMap::kPositive:
      return "pos(r)";
    case ParameterMap::kOnePlusPositive:
      return "1 + pos(r)";
    case ParameterMap::kFree:
      return "r";
    case ParameterMap::kAbove: {
      const PhysicalParameter& ref = layout.parameters()[p.reference];
      return std::string("terms[") + std::to_string(ref.term) + "]." + ref.name + " + pos(r)";
    }
  }
  return "";
}

}  // namespace

PhysicalModel::PhysicalModel(const nlohmann::json& doc, const std::string& source) {
  ReadCommon(doc);
  const std::string p = "parameters";
  const nlohmann::json& params = FieldAt(doc, "parameters", "model");
  const nlohmann::json& degree_field = FieldAt(params, "degree", p);
  if (!degree_field.is_number_integer()) throw Error(p + ".degree: expected an integer");
  const int degree = degree_field.get<int>();
  if (degree < 0 || degree > kPhysicalMaxDegree) {
    throw Error(p + ".degree: must lie in 0.." + std::to_string(kPhysicalMaxDegree));
  }
  const nlohmann::json& terms = FieldAt(params, "terms", p);
  if (!terms.is_array() || terms.empty()) throw Error(p + ".terms: expected a non-empty array");
  std::vector<TermKind> interband;
  for (size_t t = 0; t < terms.size(); ++t) {
    const std::string where = p + ".terms[" + std::to_string(t) + "].kind";
    const nlohmann::json& kind = FieldAt(terms[t], "kind", where.substr(0, where.size() - 5));
    if (!kind.is_string()) throw Error(where + ": expected a string");
    TermKind k;
    try {
      k = TermKindFromName(kind.get<std::string>());
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
    if ((t == 0) != (k == TermKind::kDrude)) {
      throw Error(where + ": the first term, and only it, must be drude");
    }
    if (t > 0) interband.push_back(k);
  }
  if (interband.size() > static_cast<size_t>(kPhysicalMaxInterbandTerms)) {
    throw Error(p + ".terms: at most " + std::to_string(kPhysicalMaxInterbandTerms) +
                " interband terms");
  }
  layout_ = PhysicalLayout(interband, degree);
  const int nb = layout_.basis_size();
  coeffs_.assign(layout_.num_coefficients(), 0.0);
  for (int t = 0; t < layout_.num_terms(); ++t) {
    const std::string tw = p + ".terms[" + std::to_string(t) + "]";
    const nlohmann::json& list = FieldAt(terms[t], "parameters", tw);
    const int first = layout_.term_offset(t);
    const int count =
        (t + 1 < layout_.num_terms() ? layout_.term_offset(t + 1) : layout_.num_parameters()) -
        first;
    if (!list.is_array() || static_cast<int>(list.size()) != count) {
      throw Error(tw + ".parameters: expected " + std::to_string(count) + " entries");
    }
    for (int i = 0; i < count; ++i) {
      const PhysicalParameter& spec = layout_.parameters()[first + i];
      const std::string pw = tw + ".parameters[" + std::to_string(i) + "]";
      const nlohmann::json& name = FieldAt(list[i], "name", pw);
      if (!name.is_string() || name.get<std::string>() != spec.name) {
        throw Error(pw + ".name: expected '" + spec.name + "'");
      }
      const nlohmann::json& c = FieldAt(list[i], "coefficients", pw);
      if (!c.is_array() || static_cast<int>(c.size()) != nb) {
        throw Error(pw + ".coefficients: expected " + std::to_string(nb) + " numbers");
      }
      for (int d = 0; d < nb; ++d) {
        coeffs_[(first + i) * nb + d] =
            FieldNumber(c[d], pw + ".coefficients[" + std::to_string(d) + "]");
      }
    }
  }
  covariance_.clear();
  if (params.contains("covariance")) {
    const nlohmann::json& cov = params.at("covariance");
    if (!cov.is_array()) throw Error(p + ".covariance: expected an array");
    for (size_t i = 0; i < cov.size(); ++i) {
      covariance_.push_back(FieldNumber(cov[i], p + ".covariance[" + std::to_string(i) + "]"));
    }
  }
  Validate(source);
  CheckWidths(source);
}

std::string PhysicalModel::NarrowestPole(double* width, double* x_at) const {
  // Every pole's width at kWidthChecks compositions across the range (the polynomials are
  // of degree 6 at most: a dip narrower than the steps is not possible without the
  // neighbouring steps coming near it too), where its centre lies among the model's photon
  // energies.
  constexpr int kWidthChecks = 256;
  const double omega_lo = OmegaEvFromLambdaNm(lambda_max_nm());
  const double omega_hi = OmegaEvFromLambdaNm(lambda_min_nm());
  std::string field;
  *width = HUGE_VAL;
  *x_at = x_min();
  double values[kPhysicalMaxParameters];
  for (int i = 0; i <= kWidthChecks; ++i) {
    const double x = x_min() + (x_max() - x_min()) * i / kWidthChecks;
    ValuesAt(x, coeffs_.data(), values);
    for (int t = 1; t < layout_.num_terms(); ++t) {
      const TermKind kind = layout_.term_kind(t);
      if (kind != TermKind::kLorentz && kind != TermKind::kCriticalPoint) continue;
      const int o = layout_.term_offset(t);  // A, E0, G[, phi]
      const double e0 = values[o + 1], g = values[o + 2];
      if (!(e0 >= omega_lo && e0 <= omega_hi) || !(g < *width)) continue;
      *width = g;
      *x_at = x;
      field = "parameters.terms[" + std::to_string(t) + "].parameters[2] (G_eV)";
    }
  }
  return field;
}

void PhysicalModel::CheckWidths(const std::string& source) const {
  double width = 0, x = 0;
  const std::string field = NarrowestPole(&width, &x);
  if (field.empty() || width >= kPhysicalMinWidthEv) return;
  throw Error(source + ": " + field + ": the width falls to " + FormatNumber(width) +
              " eV at x = " + FormatNumber(x) + ", the line's centre among the model's " +
              "wavelengths; a Lorentz or critical-point line needs " +
              FormatNumber(kPhysicalMinWidthEv) +
              " eV at least there (narrower, it is a pole between the wavelengths any colour "
              "is computed on, and the colour swings from one composition to the next)");
}

void PhysicalModel::Validate(const std::string& source) const {
  const std::string where = source + ": physical model: ";
  const size_t nc = static_cast<size_t>(layout_.num_coefficients());
  if (coeffs_.size() != nc) {
    throw Error(where + "parameters: expected " + std::to_string(nc) + " coefficients");
  }
  for (double c : coeffs_) {
    if (!std::isfinite(c) || std::abs(c) > 1e6) {
      throw Error(where + "parameters: coefficient out of range");
    }
  }
  if (!covariance_.empty() && covariance_.size() != nc * nc) {
    throw Error(where + "parameters.covariance: expected " + std::to_string(nc * nc) + " values");
  }
  for (double c : covariance_) {
    if (!std::isfinite(c)) throw Error(where + "parameters.covariance: not finite");
  }
  if (!(x_max() > x_min())) throw Error(where + "x_range must not be empty");
  if (!(lambda_min_nm() > 0)) throw Error(where + "lambda_range_nm must be positive");
}

double PhysicalModel::BasisArgument(double x_atomic) const {
  return CompositionArgument(x_atomic, x_min(), x_max());
}

void PhysicalModel::AddWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) AddWarning(w);
}

void PhysicalModel::ValuesAt(double x_atomic, const double* coeffs, double* values) const {
  double basis[kPhysicalMaxDegree + 1];
  LegendreBasis(BasisArgument(x_atomic), layout_.degree(), basis);
  double raw[kPhysicalMaxParameters];
  PhysicalRawFromCoefficients(layout_, coeffs, basis, raw);
  PhysicalValuesFromRaw(layout_, raw, values);
}

void PhysicalModel::PermittivityOnGrid(const double* values, std::size_t m, const double* omega_ev,
                                       double* eps1, double* eps2) const {
  kernel::PhysicalPermittivityOnGrid(layout_, values, m, omega_ev, eps1, eps2);
  if (kernel::AllUsable(m, eps1, eps2)) return;
  for (std::size_t i = 0; i < m; ++i) {
    const Complex<double> e = PhysicalPermittivity(layout_, values, omega_ev[i]);
    eps1[i] = e.re;
    eps2[i] = e.im;
  }
}

std::vector<std::complex<double>> PhysicalModel::Evaluate(double x_atomic,
                                                          const std::vector<double>& lambda_nm,
                                                          const double* coeffs) const {
  CheckLambda(lambda_nm);
  double values[kPhysicalMaxParameters];
  ValuesAt(x_atomic, coeffs, values);
  const std::size_t m = lambda_nm.size();
  std::vector<double> omega(m), eps1(m), eps2(m);
  for (std::size_t i = 0; i < m; ++i) omega[i] = OmegaEvFromLambdaNm(lambda_nm[i]);
  PermittivityOnGrid(values, m, omega.data(), eps1.data(), eps2.data());
  std::vector<std::complex<double>> eps(m);
  // A non-finite part stays so: every output refuses it by name.
  for (std::size_t i = 0; i < m; ++i) eps[i] = {eps1[i], eps2[i]};
  return eps;
}

std::vector<std::complex<double>> PhysicalModel::Permittivity(
    double x_atomic, const std::vector<double>& lambda_nm) const {
  return Evaluate(x_atomic, lambda_nm, coeffs_.data());
}

namespace {

// The physical model on a grid: its photon energies once, then per composition the
// parameter values and the kernel.
class BoundPhysicalModel : public BoundModel {
 public:
  BoundPhysicalModel(const PhysicalModel& model, std::vector<double> lambda_nm)
      : BoundModel(std::move(lambda_nm)), model_(model) {
    for (double l : this->lambda_nm()) omega_ev_.push_back(OmegaEvFromLambdaNm(l));
  }
  void Permittivity(double x_atomic, double* eps1, double* eps2) const override {
    double values[kPhysicalMaxParameters];
    model_.ValuesAt(x_atomic, model_.coeffs().data(), values);
    const std::size_t m = omega_ev_.size();
    kernel::PhysicalPermittivityOnGrid(model_.layout(), values, m, omega_ev_.data(), eps1, eps2);
    if (kernel::AllUsable(m, eps1, eps2)) return;
    // Where the kernel gives up, the straightforward way; an unusable value is refused.
    model_.PermittivityOnGrid(values, m, omega_ev_.data(), eps1, eps2);
    for (std::size_t i = 0; i < m; ++i) {
      if (!UsablePermittivity(eps1[i], eps2[i])) {
        model_.FailUnusable(x_atomic, lambda_nm()[i], {eps1[i], eps2[i]}, false);
      }
    }
  }

 private:
  const PhysicalModel& model_;
  std::vector<double> omega_ev_;
};

}  // namespace

std::unique_ptr<BoundModel> PhysicalModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  return std::make_unique<BoundPhysicalModel>(*this, lambda_nm);
}

std::vector<std::vector<std::complex<double>>> PhysicalModel::PermittivityDraws(
    double x_atomic, const std::vector<double>& lambda_nm, int count, std::uint32_t seed) const {
  if (prediction_error().present()) {
    return AlloyModel::PermittivityDraws(x_atomic, lambda_nm, count, seed);
  }
  if (covariance_.empty()) return {};
  const int nc = layout_.num_coefficients();
  Eigen::Map<const Eigen::MatrixXd> c(covariance_.data(), nc, nc);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (c + c.transpose()));
  const Eigen::MatrixXd root =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<std::vector<std::complex<double>>> draws;
  Eigen::VectorXd z(nc);
  std::vector<double> coeffs(nc);
  for (int s = 0; s < count; ++s) {
    for (int d = 0; d < nc; ++d) z[d] = normal(rng);
    const Eigen::VectorXd delta = root * z;
    for (int d = 0; d < nc; ++d) coeffs[d] = coeffs_[d] + delta[d];
    draws.push_back(Evaluate(x_atomic, lambda_nm, coeffs.data()));
  }
  return draws;
}

std::vector<PhysicalParameterValue> PhysicalModel::ParameterValues(double x_atomic) const {
  const int np = layout_.num_parameters();
  const int nc = layout_.num_coefficients();
  std::vector<double> values(np);
  ValuesAt(x_atomic, coeffs_.data(), values.data());
  std::vector<double> sigma(np, 0.0);
  if (!covariance_.empty()) {
    // d value / d coefficient by central differences (the maps are smooth).
    Eigen::MatrixXd jac(np, nc);
    std::vector<double> c = coeffs_;
    for (int j = 0; j < nc; ++j) {
      const double h = 1e-6 * std::max(1.0, std::abs(coeffs_[j]));
      c[j] = coeffs_[j] + h;
      std::vector<double> plus(np), minus(np);
      ValuesAt(x_atomic, c.data(), plus.data());
      c[j] = coeffs_[j] - h;
      ValuesAt(x_atomic, c.data(), minus.data());
      c[j] = coeffs_[j];
      for (int k = 0; k < np; ++k) jac(k, j) = (plus[k] - minus[k]) / (2 * h);
    }
    Eigen::Map<const Eigen::MatrixXd> cov(covariance_.data(), nc, nc);
    const Eigen::MatrixXd pc = jac * cov * jac.transpose();
    for (int k = 0; k < np; ++k) sigma[k] = std::sqrt(std::max(0.0, pc(k, k)));
  }
  std::vector<PhysicalParameterValue> out;
  for (int k = 0; k < np; ++k) {
    const PhysicalParameter& p = layout_.parameters()[k];
    double v = values[k];
    if (p.map == ParameterMap::kFree) v = std::remainder(v, 2.0 * kPi);  // a phase
    out.push_back({p.term, p.kind, p.name, v, sigma[k]});
  }
  return out;
}

ParameterTable PhysicalModel::Parameters(const std::vector<double>& xs) const {
  ParameterTable table;
  const std::string terms = layout_.interband().empty()
                                ? "drude only"
                                : "drude + " + InterbandTermsText(layout_.interband());
  std::ostringstream title;
  title << "physical model: " << terms << ", degree " << layout_.degree() << ", fitted "
        << lambda_min_nm() << "-" << lambda_max_nm() << " nm";
  table.notes.push_back(title.str());
  table.notes.push_back(
      "tau = hbar / gamma; m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2); " +
      std::string(HasUncertainty() ? "sigma from the fit's covariance" : "no covariance"));
  table.columns = {"wp_eV", "gamma_eV", "tau_fs", "N_e_m^-3", "m*/m_e", "eps_inf"};
  for (int t = 1; t < layout_.num_terms(); ++t) {
    const std::string p = "t" + std::to_string(t) + ":";
    const bool gap = layout_.term_kind(t) == TermKind::kRiouxGap;
    table.notes.push_back(
        p + " " + TermKindName(layout_.term_kind(t)) +
        (gap ? " (E0 absorption onset, Eg gap, G width)" : " (E0 centre, G width)"));
    table.columns.push_back(p + "E0_eV");
    table.columns.push_back(p + "E0_nm");
    if (gap) table.columns.push_back(p + "Eg_eV");
    table.columns.push_back(p + "G_eV");
  }
  for (double x : xs) {
    const std::vector<PhysicalParameterValue> values = ParameterValues(x);
    auto get = [&](int term, const char* name) {
      const PhysicalParameterValue& v = values[layout_.Find(term, name)];
      return ParameterTable::Quantity{v.value, v.sigma};
    };
    const auto wp = get(0, "wp_eV"), gamma = get(0, "gamma_eV");
    const double n_e = FreeElectronDensityM3(x, system());
    const double mass = EffectiveMassRatio(n_e, wp.value * wp.value);
    std::vector<ParameterTable::Quantity> row = {
        wp,
        gamma,
        {TauFsFromGammaEv(gamma.value), kHbarEvFs * gamma.sigma / (gamma.value * gamma.value)},
        {n_e, 0.0},
        {mass, 2.0 * mass * wp.sigma / wp.value},
        get(0, "eps_inf")};
    for (int t = 1; t < layout_.num_terms(); ++t) {
      const auto e0 = get(t, "E0_eV");
      row.push_back(e0);
      row.push_back({LambdaNmFromOmegaEv(e0.value), kHcEvNm * e0.sigma / (e0.value * e0.value)});
      if (layout_.term_kind(t) == TermKind::kRiouxGap) row.push_back(get(t, "Eg_eV"));
      row.push_back(get(t, "G_eV"));
    }
    table.x_atomic.push_back(x);
    table.rows.push_back(std::move(row));
  }
  return table;
}

nlohmann::json PhysicalModel::ParametersJson() const {
  const int nb = layout_.basis_size();
  const int nc = layout_.num_coefficients();
  nlohmann::json p;
  p["form"] =
      "eps(w, x) = eps_inf - wp^2 / (w (w + i gamma)) + sum of interband terms "
      "(alloycolor/model/physical_model.h), w in eV";
  p["basis"] = "legendre(u), u = 2 (x - x_range[0]) / (x_range[1] - x_range[0]) - 1";
  p["value"] =
      "each parameter = map(r), r(x) = sum_d coefficients[d] P_d(u); "
      "pos(r) = (r + sqrt(r^2 + s^2)) / 2";
  p["positive_part_scale"] = kPhysicalPositiveScale;
  p["degree"] = layout_.degree();
  // Every parameter's value and one-sigma at the training compositions, for readers.
  std::vector<std::vector<PhysicalParameterValue>> at_training;
  std::vector<double> training_x;
  for (const TrainingSample& s : training_samples()) {
    training_x.push_back(s.x_atomic);
    at_training.push_back(ParameterValues(s.x_atomic));
  }
  p["training_x"] = training_x;
  nlohmann::json terms = nlohmann::json::array();
  for (int t = 0; t < layout_.num_terms(); ++t) {
    nlohmann::json list = nlohmann::json::array();
    for (int k = 0; k < layout_.num_parameters(); ++k) {
      const PhysicalParameter& spec = layout_.parameters()[k];
      if (spec.term != t) continue;
      std::vector<double> c(coeffs_.begin() + k * nb, coeffs_.begin() + (k + 1) * nb);
      nlohmann::json entry = {
          {"name", spec.name}, {"map", MapText(layout_, spec)}, {"coefficients", c}};
      if (!covariance_.empty()) {
        std::vector<double> sigma(nb);
        for (int d = 0; d < nb; ++d) {
          const int i = k * nb + d;
          sigma[d] = std::sqrt(std::max(0.0, covariance_[static_cast<size_t>(i) * nc + i]));
        }
        entry["coefficient_sigma"] = sigma;
      }
      std::vector<double> value, value_sigma;
      for (const auto& row : at_training) {
        value.push_back(row[k].value);
        value_sigma.push_back(row[k].sigma);
      }
      entry["value_at_training_x"] = value;
      if (!covariance_.empty()) entry["sigma_at_training_x"] = value_sigma;
      list.push_back(entry);
    }
    terms.push_back({{"kind", TermKindName(layout_.term_kind(t))}, {"parameters", list}});
  }
  p["terms"] = terms;
  if (!covariance_.empty()) {
    p["covariance_layout"] =
        "row-major over all coefficients, terms and parameters in order, d = 0..degree";
    p["covariance"] = covariance_;
  }
  return p;
}

}  // namespace alloycolor
