#include "alloycolor/model/smooth_model.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/interpolation.h"
#include "hermite_bound_model.h"

namespace alloycolor {
namespace {

// Node bracket of wavelength l on the grid (clamped to it) and the weight of the upper node.
struct NodeBracket {
  size_t lo, hi;
  double t;
};

NodeBracket BracketOf(const std::vector<double>& grid, double l) {
  l = std::clamp(l, grid.front(), grid.back());
  size_t hi = std::upper_bound(grid.begin(), grid.end(), l) - grid.begin();
  hi = std::clamp<size_t>(hi, 1, grid.size() - 1);
  return {hi - 1, hi, (l - grid[hi - 1]) / (grid[hi] - grid[hi - 1])};
}

}  // namespace

const SmoothModel* SmoothModel::From(const AlloyModel* model) {
  return dynamic_cast<const SmoothModel*>(model);
}

const char* SmoothSpaceName(SmoothSpace space) {
  return space == SmoothSpace::kLogEps ? "log_eps" : "eps";
}

std::array<double, 2> PartsFromEps(SmoothSpace space, std::complex<double> eps) {
  if (space == SmoothSpace::kEps) return {eps.real(), eps.imag()};
  const std::complex<double> passive(eps.real(), std::max(eps.imag(), 0.0));
  return {std::log(std::max(std::abs(passive), 1e-12)), std::arg(passive)};
}

std::complex<double> EpsFromParts(SmoothSpace space, double part1, double part2) {
  if (space == SmoothSpace::kEps) return {part1, part2};
  static const double kMaxLogAbs = 2 * std::log(kMaxOpticalConstant);
  return std::polar(std::exp(std::min(part1, kMaxLogAbs)), std::clamp(part2, 0.0, kPi));
}

SmoothModel::SmoothModel(const Dataset& dataset, std::vector<double> grid_nm,
                         std::vector<double> knots_x, SmoothSpace space,
                         std::vector<std::vector<double>> part1,
                         std::vector<std::vector<double>> part2, double smoothing)
    : grid_nm_(std::move(grid_nm)),
      knots_x_(std::move(knots_x)),
      space_(space),
      part1_(std::move(part1)),
      part2_(std::move(part2)),
      smoothing_(smoothing) {
  if (grid_nm_.size() < 2) throw Error("smooth model: the grid needs two wavelengths");
  SetCommon(dataset, grid_nm_.front(), grid_nm_.back());
  Validate(dataset.manifest_path);
}

SmoothModel::SmoothModel(const nlohmann::json& doc, const std::string& source) {
  ReadCommon(doc);
  const auto& p = doc.at("parameters");
  if (p.is_object() && p.contains("coefficients") && !p.contains("knots_x")) {
    throw Error(source +
                ": parameters: a smooth model of the earlier form (Legendre polynomials of "
                "ln gamma, ln wp^2), which this version no longer reads: refit it with "
                "`alloycolor fit --method smooth`");
  }
  const char* field = "";
  try {
    field = "lambda_nm";
    grid_nm_ = p.at(field).get<std::vector<double>>();
    field = "knots_x";
    knots_x_ = p.at(field).get<std::vector<double>>();
    field = "space";  // absent in files of before the logarithm: eps
    const std::string space = p.value(field, std::string("eps"));
    if (space == "log_eps") {
      space_ = SmoothSpace::kLogEps;
    } else if (space != "eps") {
      throw Error(source + ": parameters.space: \"" + space + "\" is neither eps nor log_eps");
    }
    const bool log = space_ == SmoothSpace::kLogEps;
    field = log ? "ln_abs_eps" : "eps1";
    part1_ = p.at(field).get<std::vector<std::vector<double>>>();
    field = log ? "arg_eps_rad" : "eps2";
    part2_ = p.at(field).get<std::vector<std::vector<double>>>();
    field = "smoothing";
    smoothing_ = p.at(field).get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(source + ": parameters." + field + ": " + e.what());
  }
  Validate(source);
}

void SmoothModel::Validate(const std::string& source) {
  const std::string where = source + ": smooth model: parameters.";
  if (grid_nm_.size() < 2) throw Error(where + "lambda_nm: needs two wavelengths");
  for (size_t j = 0; j < grid_nm_.size(); ++j) {
    if (!std::isfinite(grid_nm_[j]) || grid_nm_[j] <= 0 ||
        (j > 0 && !(grid_nm_[j] > grid_nm_[j - 1]))) {
      throw Error(where + "lambda_nm: must be positive and increasing (entry " + std::to_string(j) +
                  ")");
    }
  }
  if (grid_nm_.front() < lambda_min_nm() || grid_nm_.back() > lambda_max_nm()) {
    throw Error(where + "lambda_nm: runs outside the model's wavelength range");
  }
  const size_t k = knots_x_.size();
  if (k < 2 || k > static_cast<size_t>(kSmoothMaxKnots)) {
    throw Error(where + "knots_x: expected 2.." + std::to_string(kSmoothMaxKnots) + " knots");
  }
  for (size_t c = 0; c < k; ++c) {
    if (!std::isfinite(knots_x_[c]) || (c > 0 && !(knots_x_[c] > knots_x_[c - 1])) ||
        knots_x_[c] < x_min() || knots_x_[c] > x_max()) {
      throw Error(where + "knots_x: must increase inside x_range (entry " + std::to_string(c) +
                  ")");
    }
  }
  if (!(smoothing_ >= 0 && std::isfinite(smoothing_))) {
    throw Error(where + "smoothing: must be finite and >= 0");
  }
  // |eps| <= kMaxOpticalConstant^2 keeps n, k within what the readers accept.
  const double max_abs = kMaxOpticalConstant * kMaxOpticalConstant;
  const auto check = [&](const std::vector<std::vector<double>>& v, const char* name, double lo,
                         double hi, const char* bound) {
    if (v.size() != grid_nm_.size()) {
      throw Error(where + name + ": one row per wavelength expected");
    }
    for (size_t j = 0; j < v.size(); ++j) {
      const std::string row = where + name + "[" + std::to_string(j) + "]: ";
      if (v[j].size() != k) throw Error(row + "expected " + std::to_string(k) + " values");
      for (double e : v[j]) {
        if (!std::isfinite(e) || std::abs(e) > max_abs) throw Error(row + "value out of range");
        if (e < lo || e > hi) throw Error(row + bound);
      }
    }
  };
  if (space_ == SmoothSpace::kLogEps) {
    check(part1_, "ln_abs_eps", -HUGE_VAL, std::log(max_abs), "|eps| out of range");
    check(part2_, "arg_eps_rad", 0, kPi, "arg eps outside [0, pi] (not passive)");
  } else {
    check(part1_, "eps1", -HUGE_VAL, HUGE_VAL, "");
    check(part2_, "eps2", 0, HUGE_VAL, "eps2 < 0 (not passive)");
  }
  slope1_.assign(grid_nm_.size(), std::vector<double>(k));
  slope2_.assign(grid_nm_.size(), std::vector<double>(k));
  for (size_t j = 0; j < grid_nm_.size(); ++j) {
    PchipSlopes(knots_x_.data(), part1_[j].data(), k, slope1_[j].data());
    PchipSlopes(knots_x_.data(), part2_[j].data(), k, slope2_[j].data());
  }
}

std::unique_ptr<BoundModel> SmoothModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  // Each knot's values and slopes interpolated in wavelength as Permittivity interpolates
  // its results (the Hermite sum is linear in them).
  const size_t k = knots_x_.size(), m = lambda_nm.size();
  std::vector<HermiteBoundModel::Knot> knots;
  for (size_t c = 0; c < k; ++c) {
    std::vector<double> e1(m), e2(m), d1(m), d2(m);
    for (size_t i = 0; i < m; ++i) {
      const NodeBracket b = BracketOf(grid_nm_, lambda_nm[i]);
      const auto lerp = [&](const std::vector<std::vector<double>>& v) {
        return v[b.lo][c] + (v[b.hi][c] - v[b.lo][c]) * b.t;
      };
      e1[i] = lerp(part1_);
      e2[i] = lerp(part2_);
      d1[i] = lerp(slope1_);
      d2[i] = lerp(slope2_);
    }
    knots.push_back({std::move(e1), std::move(e2), std::move(d1), std::move(d2)});
  }
  return std::make_unique<HermiteBoundModel>(lambda_nm, knots_x_, std::move(knots), false,
                                             space_ == SmoothSpace::kLogEps
                                                 ? HermiteBoundModel::Output::kFromLog
                                                 : HermiteBoundModel::Output::kEps);
}

std::vector<double> SmoothModel::FittedCoefficients() const {
  std::vector<double> all;
  for (size_t j = 0; j < grid_nm_.size(); ++j) {
    all.insert(all.end(), part1_[j].begin(), part1_[j].end());
    all.insert(all.end(), part2_[j].begin(), part2_[j].end());
  }
  return all;
}

void SmoothModel::AddWarnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) AddWarning(w);
}

std::vector<std::complex<double>> SmoothModel::Permittivity(
    double x_atomic, const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  const size_t k = knots_x_.size();
  const double* kx = knots_x_.data();
  std::vector<std::complex<double>> eps(lambda_nm.size());
  for (size_t i = 0; i < lambda_nm.size(); ++i) {
    const NodeBracket b = BracketOf(grid_nm_, lambda_nm[i]);
    // The two parts at the bracketing nodes, linear in wavelength between them.
    const auto at = [&](size_t j) {
      return std::complex<double>(HermiteAt(kx, part1_[j].data(), slope1_[j].data(), k, x_atomic),
                                  HermiteAt(kx, part2_[j].data(), slope2_[j].data(), k, x_atomic));
    };
    const std::complex<double> lo = at(b.lo), hi = at(b.hi), parts = lo + (hi - lo) * b.t;
    eps[i] = EpsFromParts(space_, parts.real(), parts.imag());
  }
  return eps;
}

nlohmann::json SmoothModel::ParametersJson() const {
  nlohmann::json p;
  const bool log = space_ == SmoothSpace::kLogEps;
  p["basis"] = log ? "per wavelength node, ln|eps| and arg eps (radians) each the PCHIP "
                     "(Fritsch-Butland) curve through their values at knots_x; linear in "
                     "wavelength between nodes; eps = exp(ln_abs_eps + i arg_eps_rad)"
                   : "per wavelength node, eps1 and eps2 each the PCHIP (Fritsch-Butland) "
                     "curve through their values at knots_x; linear in wavelength between "
                     "nodes";
  p["space"] = SmoothSpaceName(space_);
  p["lambda_nm"] = grid_nm_;
  p["knots_x"] = knots_x_;
  p[log ? "ln_abs_eps" : "eps1"] = part1_;
  p[log ? "arg_eps_rad" : "eps2"] = part2_;
  p["smoothing"] = smoothing_;
  return p;
}

}  // namespace alloycolor
