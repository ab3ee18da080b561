#include "alloycolor/model/smooth_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <random>

#include "alloycolor/core/error.h"
#include "alloycolor/core/units.h"

namespace alloycolor {
namespace {

// Largest sum of |coefficients| of ln gamma or ln wp^2 at a node (see Validate).
constexpr double kMaxLogSum = 100.0;

}  // namespace

SmoothModel::SmoothModel(const Dataset& dataset, std::vector<double> grid_nm, int degree,
                         std::vector<std::vector<double>> coeffs,
                         std::vector<std::vector<double>> covariance)
    : grid_nm_(std::move(grid_nm)),
      degree_(degree),
      coeffs_(std::move(coeffs)),
      covariance_(std::move(covariance)) {
  if (grid_nm_.size() < 2) throw Error("smooth model: the grid needs two wavelengths");
  SetCommon(dataset, grid_nm_.front(), grid_nm_.back());
  Validate(dataset.manifest_path);
}

SmoothModel::SmoothModel(const nlohmann::json& doc, const std::string& source) {
  ReadCommon(doc);
  const auto& p = doc.at("parameters");
  const char* field = "";
  try {
    field = "degree";
    degree_ = p.at(field).get<int>();
    field = "lambda_nm";
    grid_nm_ = p.at(field).get<std::vector<double>>();
    field = "coefficients";
    coeffs_ = p.at(field).get<std::vector<std::vector<double>>>();
    field = "covariance";
    covariance_ = p.value(field, std::vector<std::vector<double>>{});
  } catch (const nlohmann::json::exception& e) {
    throw Error(source + ": parameters." + field + ": " + e.what());
  }
  Validate(source);
}

void SmoothModel::Validate(const std::string& source) const {
  const std::string where = source + ": smooth model: ";
  if (degree_ < 0 || degree_ > kSmoothMaxDegree) {
    throw Error(where + "degree must lie in 0.." + std::to_string(kSmoothMaxDegree));
  }
  if (grid_nm_.size() < 2) throw Error(where + "lambda_nm needs two wavelengths");
  for (size_t j = 0; j < grid_nm_.size(); ++j) {
    if (!std::isfinite(grid_nm_[j]) || grid_nm_[j] <= 0 ||
        (j > 0 && !(grid_nm_[j] > grid_nm_[j - 1]))) {
      throw Error(where + "lambda_nm must be positive and increasing (entry " +
                  std::to_string(j) + ")");
    }
  }
  const size_t nc = 2 * static_cast<size_t>(basis_size());
  if (coeffs_.size() != grid_nm_.size()) {
    throw Error(where + "coefficients: one row per wavelength expected");
  }
  for (size_t j = 0; j < coeffs_.size(); ++j) {
    if (coeffs_[j].size() != nc) {
      throw Error(where + "coefficients[" + std::to_string(j) + "]: expected " +
                  std::to_string(nc) + " values");
    }
    for (double c : coeffs_[j]) {
      if (!std::isfinite(c) || std::abs(c) > 700) {
        throw Error(where + "coefficients[" + std::to_string(j) + "]: value out of range");
      }
    }
    // Inside the training range |P_d(u)| <= 1, so |ln gamma| and |ln wp^2| are at most
    // the sums of |coefficients|; bounding those keeps gamma, wp^2, their products and eps
    // finite (e^100 ~ 3e43).
    for (size_t part = 0; part < 2; ++part) {
      double sum = 0;
      for (size_t d = 0; d < nc / 2; ++d) sum += std::abs(coeffs_[j][part * nc / 2 + d]);
      if (sum > kMaxLogSum) {
        throw Error(where + "coefficients[" + std::to_string(j) + "]: value out of range (" +
                    (part == 0 ? "ln gamma" : "ln wp2") + " could exceed " +
                    std::to_string(static_cast<int>(kMaxLogSum)) + ")");
      }
    }
  }
  if (!covariance_.empty()) {
    if (covariance_.size() != grid_nm_.size()) {
      throw Error(where + "covariance: one matrix per wavelength expected");
    }
    for (size_t j = 0; j < covariance_.size(); ++j) {
      if (covariance_[j].size() != nc * nc) {
        throw Error(where + "covariance[" + std::to_string(j) + "]: expected " +
                    std::to_string(nc * nc) + " values");
      }
      for (double c : covariance_[j]) {
        if (!std::isfinite(c)) {
          throw Error(where + "covariance[" + std::to_string(j) + "]: not finite");
        }
      }
    }
  }
  if (!(x_max() > x_min())) throw Error(where + "x_range must not be empty");
}

namespace {

class BoundSmoothModel : public BoundModel {
 public:
  BoundSmoothModel(const SmoothModel& model, std::vector<double> lambda_nm)
      : BoundModel(std::move(lambda_nm)), model_(model), nb_(model.basis_size()) {
    const std::vector<double>& nodes = model.grid_nm();
    const std::vector<std::vector<double>>& coeffs = model.coeffs();
    const int nc = 2 * nb_;
    const std::vector<double>& grid = this->lambda_nm();
    coeffs_.resize(grid.size() * nc);
    omega_ev_.resize(grid.size());
    // Interpolated in wavelength exactly as SmoothModel::Permittivity does.
    for (size_t i = 0; i < grid.size(); ++i) {
      const double l = std::clamp(grid[i], nodes.front(), nodes.back());
      size_t hi = std::upper_bound(nodes.begin(), nodes.end(), l) - nodes.begin();
      hi = std::clamp<size_t>(hi, 1, nodes.size() - 1);
      const size_t lo = hi - 1;
      const double t = (l - nodes[lo]) / (nodes[hi] - nodes[lo]);
      for (int d = 0; d < nc; ++d) {
        const double c_lo = coeffs[lo][d], c_hi = coeffs[hi][d];
        coeffs_[i * nc + d] = t == 0.0 ? c_lo : t == 1.0 ? c_hi : c_lo + (c_hi - c_lo) * t;
      }
      omega_ev_[i] = OmegaEvFromLambdaNm(grid[i]);
    }
  }

  void Permittivity(double x_atomic, Complex<double>* eps) const override {
    double basis[kSmoothMaxDegree + 1];
    LegendreBasis(model_.BasisArgument(x_atomic), nb_ - 1, basis);
    for (size_t i = 0; i < omega_ev_.size(); ++i) {
      eps[i] = SmoothNodePermittivity(&coeffs_[i * 2 * nb_], basis, nb_, omega_ev_[i]);
    }
  }

 private:
  const SmoothModel& model_;
  int nb_;
  std::vector<double> coeffs_;    // per wavelength, 2 nb
  std::vector<double> omega_ev_;  // per wavelength
};

}  // namespace

std::unique_ptr<BoundModel> SmoothModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  return std::make_unique<BoundSmoothModel>(*this, lambda_nm);
}

std::vector<double> SmoothModel::FittedCoefficients() const {
  std::vector<double> all;
  for (const auto& node : coeffs_) all.insert(all.end(), node.begin(), node.end());
  return all;
}

double SmoothModel::BasisArgument(double x_atomic) const {
  return CompositionArgument(x_atomic, x_min(), x_max());
}

void SmoothModel::AddWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) AddWarning(w);
}

std::vector<std::complex<double>> SmoothModel::Evaluate(
    double x_atomic, const std::vector<double>& lambda_nm,
    const std::vector<std::vector<double>>& coeffs) const {
  CheckLambda(lambda_nm);
  const int nb = basis_size();
  double basis[kSmoothMaxDegree + 1];
  LegendreBasis(BasisArgument(x_atomic), degree_, basis);
  std::vector<std::complex<double>> eps(lambda_nm.size());
  std::vector<double> c(2 * nb);
  for (size_t i = 0; i < lambda_nm.size(); ++i) {
    const double l = std::clamp(lambda_nm[i], grid_nm_.front(), grid_nm_.back());
    size_t hi = std::upper_bound(grid_nm_.begin(), grid_nm_.end(), l) - grid_nm_.begin();
    hi = std::clamp<size_t>(hi, 1, grid_nm_.size() - 1);
    const size_t lo = hi - 1;
    const double t = (l - grid_nm_[lo]) / (grid_nm_[hi] - grid_nm_[lo]);
    const double* c_lo = coeffs[lo].data();
    const double* c_hi = coeffs[hi].data();
    const double* ci;
    if (t == 0.0) {
      ci = c_lo;
    } else if (t == 1.0) {
      ci = c_hi;
    } else {
      for (int d = 0; d < 2 * nb; ++d) c[d] = c_lo[d] + (c_hi[d] - c_lo[d]) * t;
      ci = c.data();
    }
    const Complex<double> e =
        SmoothNodePermittivity(ci, basis, nb, OmegaEvFromLambdaNm(lambda_nm[i]));
    if (!std::isfinite(e.re) || !std::isfinite(e.im)) {  // only far outside the x range
      throw Error("smooth model: eps is not finite at x = " + std::to_string(x_atomic) +
                  ", " + std::to_string(lambda_nm[i]) + " nm (extrapolated too far from " +
                  std::to_string(x_min()) + "-" + std::to_string(x_max()) + ")");
    }
    eps[i] = {e.re, e.im};
  }
  return eps;
}

std::vector<std::complex<double>> SmoothModel::Permittivity(
    double x_atomic, const std::vector<double>& lambda_nm) const {
  return Evaluate(x_atomic, lambda_nm, coeffs_);
}

std::vector<std::vector<std::complex<double>>> SmoothModel::PermittivityDraws(
    double x_atomic, const std::vector<double>& lambda_nm, int count,
    std::uint32_t seed) const {
  if (covariance_.empty()) return {};
  const int nc = 2 * basis_size();
  // Square roots of the node covariances (eigen-decomposition, negative rounding clamped).
  std::vector<Eigen::MatrixXd> roots;
  for (const auto& cov : covariance_) {
    // Cholesky factor; eigen-decomposition where the matrix is singular.
    Eigen::Map<const Eigen::MatrixXd> c(cov.data(), nc, nc);
    const Eigen::MatrixXd sym = 0.5 * (c + c.transpose());
    Eigen::LLT<Eigen::MatrixXd> llt(sym);
    if (llt.info() == Eigen::Success) {
      roots.push_back(llt.matrixL());
    } else {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sym);
      roots.push_back(eig.eigenvectors() *
                      eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal());
    }
  }
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<std::vector<std::complex<double>>> draws;
  std::vector<std::vector<double>> coeffs = coeffs_;
  Eigen::VectorXd z(nc);
  for (int s = 0; s < count; ++s) {
    // Independent draws per node, as the node covariances are estimated; fully correlated
    // draws overstated the held-out colour error 10-50 times on Au-Ag.
    for (size_t j = 0; j < coeffs.size(); ++j) {
      for (int d = 0; d < nc; ++d) z[d] = normal(rng);
      const Eigen::VectorXd delta = roots[j] * z;
      for (int d = 0; d < nc; ++d) coeffs[j][d] = coeffs_[j][d] + delta[d];
    }
    draws.push_back(Evaluate(x_atomic, lambda_nm, coeffs));
  }
  return draws;
}

nlohmann::json SmoothModel::ParametersJson() const {
  nlohmann::json p;
  p["basis"] = "legendre(u), u = 2 (x - x_range[0]) / (x_range[1] - x_range[0]) - 1";
  p["layout"] = "per wavelength: ln(gamma_eV) coefficients d=0..degree, then ln(wp2_eV2)";
  p["degree"] = degree_;
  p["lambda_nm"] = grid_nm_;
  p["coefficients"] = coeffs_;
  if (!covariance_.empty()) p["covariance"] = covariance_;
  return p;
}

}  // namespace alloycolor
