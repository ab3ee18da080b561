#include "alloycolor/model/sample_models.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/simd.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"
#include "alloycolor/model/interpolation.h"
#include "alloycolor/model/optics.h"
#include "hermite_bound_model.h"

namespace alloycolor {
namespace {

std::complex<double> EpsOf(const NkSpectrum& nk, double lambda_nm) {
  const std::complex<double> i = NkAt(nk, lambda_nm);
  return i * i;
}

// EpsOf at each of lambda_nm.
std::vector<std::complex<double>> EpsOn(const NkSpectrum& nk,
                                        const std::vector<double>& lambda_nm) {
  std::vector<std::complex<double>> eps = NkOn(nk, lambda_nm);
  for (std::complex<double>& e : eps) e = e * e;
  return eps;
}

std::complex<double> Lerp(const std::complex<double>& a, const std::complex<double>& b, double t) {
  return a + (b - a) * t;
}

// Index pair (lo, hi) and weight t such that x = x_lo + t (x_hi - x_lo), among the given
// sorted compositions; outside the range, the two nearest (t < 0 or t > 1).
struct Bracket {
  size_t lo, hi;
  double t;
};
Bracket FindBracket(const std::vector<double>& xs, double x) {
  const size_t n = xs.size();
  size_t hi = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
  hi = std::clamp<size_t>(hi, 1, n - 1);
  const size_t lo = hi - 1;
  return {lo, hi, (x - xs[lo]) / (xs[hi] - xs[lo])};
}

// DrudePermittivity(omega, EffectiveMassRatio(n_e, mass), GammaEvFromTauFs(tau)) with
// tau and mass interpolated linearly at t between two samples, on arrays, with one
// division: wp^2 / (omega^2 + gamma^2) = c tau^2 / (mass ((omega tau)^2 + hbar^2)),
// c = kPlasmaEv2M3 n_e.
ALLOYCOLOR_SIMD_CLONES
void PaperDrude(size_t m, double t, double c, const double* __restrict tau_lo,
                const double* __restrict tau_hi, const double* __restrict mass_lo,
                const double* __restrict mass_hi, const double* __restrict omega,
                const double* __restrict inv_omega, double* __restrict eps1,
                double* __restrict eps2) {
  const double hbar = kHbarEvFs, hbar2 = kHbarEvFs * kHbarEvFs;
  for (size_t i = 0; i < m; ++i) {
    const double tau = tau_lo[i] + (tau_hi[i] - tau_lo[i]) * t;
    const double mass = mass_lo[i] + (mass_hi[i] - mass_lo[i]) * t;
    const double wt = omega[i] * tau;
    const double inv = 1.0 / (mass * (wt * wt + hbar2));
    eps1[i] = 1.0 - c * tau * tau * inv;
    eps2[i] = c * hbar * tau * inv * inv_omega[i];
  }
}

// The paper model bound to a grid (SampleModel::Bind). Per wavelength it keeps every
// sample's eps and the compositions, tau and m* of the samples that can be inverted there,
// so Permittivity repeats PaperAt with the same arithmetic and none of the per-wavelength
// interpolation, inversion or allocation. At a wavelength where every sample is
// invertible (for metals, all of the visible) a composition between two samples is one
// pass of PaperDrude over the grid; the other wavelengths take the scalar path.
class BoundPaperModel : public BoundModel {
 public:
  struct Invertible {  // the samples invertible at one wavelength, sorted by x
    std::vector<double> xs, taus, masses;
  };
  BoundPaperModel(std::vector<double> lambda_nm, std::vector<double> node_x,
                  std::vector<Complex<double>> node_eps, std::vector<Invertible> invertible,
                  AlloySystem system, double x_min, double x_max)
      : BoundModel(std::move(lambda_nm)),
        node_x_(std::move(node_x)),
        node_eps_(std::move(node_eps)),
        invertible_(std::move(invertible)),
        system_(std::move(system)),
        x_min_(x_min),
        x_max_(x_max) {
    const size_t m = this->lambda_nm().size(), nodes = node_x_.size();
    for (double l : this->lambda_nm()) {
      omega_ev_.push_back(OmegaEvFromLambdaNm(l));
      inv_omega_ev_.push_back(1.0 / omega_ev_.back());
    }
    // Node-major tau and m* at the regular wavelengths (1 elsewhere, never read).
    taus_.assign(nodes * m, 1.0);
    masses_.assign(nodes * m, 1.0);
    for (size_t i = 0; i < m; ++i) {
      const Invertible& inv = invertible_[i];
      bool regular = inv.xs.size() == nodes && nodes >= 2;
      for (size_t j = 0; regular && j < nodes; ++j) {
        regular = inv.taus[j] > 0 && inv.masses[j] > 0;
      }
      all_.push_back(inv.xs.size() == nodes);
      if (!regular) {
        irregular_.push_back(i);
        continue;
      }
      for (size_t j = 0; j < nodes; ++j) {
        taus_[j * m + i] = inv.taus[j];
        masses_[j * m + i] = inv.masses[j];
      }
    }
  }

  void Permittivity(double x, double* eps1, double* eps2) const override {
    const size_t m = lambda_nm().size();
    const Bracket all = FindBracket(node_x_, x);
    const double n_e = FreeElectronDensityM3(x, system_);
    const bool between = all.t >= 0 && all.t <= 1;
    if (between) {
      PaperDrude(m, all.t, kPlasmaEv2M3 * n_e, &taus_[all.lo * m], &taus_[all.hi * m],
                 &masses_[all.lo * m], &masses_[all.hi * m], omega_ev_.data(), inv_omega_ev_.data(),
                 eps1, eps2);
      for (size_t i : irregular_) Scalar(x, n_e, all, i, eps1, eps2);
    } else {
      for (size_t i = 0; i < m; ++i) Scalar(x, n_e, all, i, eps1, eps2);
    }
  }

 private:
  // PaperAt at wavelength i.
  void Scalar(double x, double n_e, const Bracket& all, size_t i, double* eps1,
              double* eps2) const {
    const Invertible& inv = invertible_[i];
    const bool inside = x >= x_min_ && x <= x_max_;
    double tau, mass;
    if (inv.xs.empty()) {
      const size_t m = lambda_nm().size();
      const Complex<double>& lo = node_eps_[all.lo * m + i];
      const Complex<double>& hi = node_eps_[all.hi * m + i];
      const Complex<double> e = all.t == 0.0   ? lo
                                : all.t == 1.0 ? hi
                                               : Complex<double>{lo.re + (hi.re - lo.re) * all.t,
                                                                 lo.im + (hi.im - lo.im) * all.t};
      eps1[i] = e.re;
      eps2[i] = e.im;
      return;
    }
    if (inv.xs.size() == 1) {
      tau = inv.taus[0];
      mass = inv.masses[0];
    } else {
      const Bracket b = all_[i] ? all : FindBracket(inv.xs, x);
      if (inside && (b.t < 0 || b.t > 1)) {
        const size_t nearest = b.t < 0 ? b.lo : b.hi;
        tau = inv.taus[nearest];
        mass = inv.masses[nearest];
      } else {
        tau = inv.taus[b.lo] + (inv.taus[b.hi] - inv.taus[b.lo]) * b.t;
        mass = inv.masses[b.lo] + (inv.masses[b.hi] - inv.masses[b.lo]) * b.t;
        if (!(tau > 0) || !(mass > 0)) {
          const size_t nearest = b.t < 0.5 ? b.lo : b.hi;
          tau = inv.taus[nearest];
          mass = inv.masses[nearest];
        }
      }
    }
    const Complex<double> e =
        DrudePermittivity(omega_ev_[i], EffectiveMassRatio(n_e, mass), GammaEvFromTauFs(tau));
    eps1[i] = e.re;
    eps2[i] = e.im;
  }

  std::vector<double> node_x_;
  std::vector<Complex<double>> node_eps_;  // node-major: node_eps_[node * m + i]
  std::vector<Invertible> invertible_;     // per wavelength
  std::vector<bool> all_;                  // every sample invertible at wavelength i
  std::vector<size_t> irregular_;          // wavelengths PaperDrude does not cover
  std::vector<double> taus_, masses_;      // node-major, as node_eps_
  std::vector<double> omega_ev_, inv_omega_ev_;
  AlloySystem system_;
  double x_min_, x_max_;
};

}  // namespace

std::unique_ptr<BoundModel> SampleModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  const size_t m = lambda_nm.size();
  std::vector<double> node_x;
  std::vector<Complex<double>> node_eps;
  for (const Node& node : nodes_) {
    node_x.push_back(node.x);
    for (const std::complex<double>& e : EpsOn(node.nk, lambda_nm)) {
      node_eps.push_back({e.real(), e.imag()});
    }
  }
  if (kind_ != Kind::kPaper) {
    // Per wavelength, the scheme's slopes through the samples' eps1 and eps2.
    const size_t n = nodes_.size();
    std::vector<HermiteBoundModel::Knot> knots(n);
    const bool linear = kind_ == Kind::kEpsLinear;  // evaluated as lines: no slopes
    for (HermiteBoundModel::Knot& k : knots) {
      k.eps1.resize(m);
      k.eps2.resize(m);
      if (linear) continue;
      k.slope1.resize(m);
      k.slope2.resize(m);
    }
    std::vector<double> y1(n), y2(n), d1(n), d2(n);
    for (size_t i = 0; i < m; ++i) {
      for (size_t j = 0; j < n; ++j) {
        y1[j] = knots[j].eps1[i] = node_eps[j * m + i].re;
        y2[j] = knots[j].eps2[i] = node_eps[j * m + i].im;
      }
      if (linear) continue;
      if (kind_ == Kind::kEpsPchip) {
        PchipSlopes(node_x.data(), y1.data(), n, d1.data());
        PchipSlopes(node_x.data(), y2.data(), n, d2.data());
      } else {
        NaturalSplineSlopes(node_x.data(), y1.data(), n, d1.data());
        NaturalSplineSlopes(node_x.data(), y2.data(), n, d2.data());
      }
      for (size_t j = 0; j < n; ++j) {
        knots[j].slope1[i] = d1[j];
        knots[j].slope2[i] = d2[j];
      }
    }
    return std::make_unique<HermiteBoundModel>(
        lambda_nm, std::move(node_x), std::move(knots), linear,
        kind_ == Kind::kEpsSpline ? HermiteBoundModel::Output::kPassive
                                  : HermiteBoundModel::Output::kEps);
  }
  std::vector<BoundPaperModel::Invertible> invertible(m);
  for (size_t i = 0; i < m; ++i) {
    const double omega = OmegaEvFromLambdaNm(lambda_nm[i]);
    for (size_t j = 0; j < nodes_.size(); ++j) {
      const Complex<double>& e = node_eps[j * m + i];
      if (!DrudeInvertible(e.re, e.im)) continue;
      const DrudePoint p = InvertDrude(omega, e.re, e.im);
      invertible[i].xs.push_back(nodes_[j].x);
      invertible[i].taus.push_back(TauFsFromGammaEv(p.gamma_ev));
      invertible[i].masses.push_back(
          EffectiveMassRatio(FreeElectronDensityM3(nodes_[j].x, system()), p.wp2_ev2));
    }
  }
  return std::make_unique<BoundPaperModel>(lambda_nm, std::move(node_x), std::move(node_eps),
                                           std::move(invertible), system(), x_min(), x_max());
}

SampleModel::SampleModel(Kind kind, const Dataset& dataset) : kind_(kind) {
  // One node per composition: the replicates' mean there (SamplesAtComposition's, found
  // among the samples in order of composition rather than by a pass over all of them).
  try {
    std::vector<const Sample*> sorted;
    for (const Sample& s : dataset.samples) sorted.push_back(&s);
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const Sample* a, const Sample* b) { return a->x_atomic < b->x_atomic; });
    size_t first = 0;
    for (double x : DistinctCompositions(dataset)) {
      while (first < sorted.size() && sorted[first]->x_atomic < x - kSameComposition) ++first;
      std::vector<const Sample*> at;
      for (size_t i = first; i < sorted.size() && sorted[i]->x_atomic <= x + kSameComposition;
           ++i) {
        at.push_back(sorted[i]);
      }
      std::sort(at.begin(), at.end());  // in the data set's order, as SamplesAtComposition
      nodes_.push_back({x, MeanSpectrum(at)});
    }
  } catch (const Error& e) {
    throw Error(dataset.manifest_path + ": " + e.what());
  }
  const WavelengthRange range = CommonRange(dataset);
  SetCommon(dataset, range.lo_nm, range.hi_nm);
  try {
    Validate();
  } catch (const Error& e) {  // name the data set at fault
    throw Error(dataset.manifest_path + ": " + e.what());
  }
  Diagnose();
}

SampleModel::SampleModel(Kind kind, const nlohmann::json& doc, const std::string& source)
    : kind_(kind) {
  ReadCommon(doc);
  const auto& params = doc.at("parameters");
  if (!params.is_object() || !params.contains("samples") || !params["samples"].is_array()) {
    throw Error(source + ": parameters.samples: expected an array");
  }
  const auto& samples = params["samples"];
  for (size_t i = 0; i < samples.size(); ++i) {
    const std::string where = source + ": parameters.samples[" + std::to_string(i) + "]";
    const auto& s = samples[i];
    try {
      Node node;
      node.x = s.at("x").get<double>();
      node.nk.source = s.at("source").get<std::string>();
      node.nk.lambda_nm = s.at("lambda_nm").get<std::vector<double>>();
      node.nk.n = s.at("n").get<std::vector<double>>();
      node.nk.k = s.at("k").get<std::vector<double>>();
      const size_t m = node.nk.lambda_nm.size();
      if (m < 2 || node.nk.n.size() != m || node.nk.k.size() != m) {
        throw Error(where + ": lambda_nm, n and k need the same length, at least 2");
      }
      for (size_t j = 0; j < m; ++j) {
        if (!std::isfinite(node.nk.lambda_nm[j]) || !(node.nk.lambda_nm[j] > 0) ||
            !(node.nk.n[j] >= 0 && node.nk.n[j] <= kMaxOpticalConstant) ||
            !(node.nk.k[j] >= 0 && node.nk.k[j] <= kMaxOpticalConstant) ||
            (j > 0 && !(node.nk.lambda_nm[j] > node.nk.lambda_nm[j - 1]))) {
          throw Error(where + ": bad row " + std::to_string(j));
        }
      }
      // The sample must hold eps over the whole stated range (no value made up past it).
      const double tolerance = 1e-9 * lambda_max_nm();
      if (node.nk.lambda_nm.front() > lambda_min_nm() + tolerance ||
          node.nk.lambda_nm.back() < lambda_max_nm() - tolerance) {
        throw Error(where + ".lambda_nm: covers " + FormatNumber(node.nk.lambda_nm.front()) + "-" +
                    FormatNumber(node.nk.lambda_nm.back()) +
                    " nm, not the whole lambda_range_nm [" + FormatNumber(lambda_min_nm()) + ", " +
                    FormatNumber(lambda_max_nm()) + "]");
      }
      nodes_.push_back(std::move(node));
    } catch (const nlohmann::json::exception& e) {
      throw Error(where + ": " + e.what());
    }
  }
  Validate();
}

void SampleModel::Validate() {
  if (nodes_.size() < 2) {
    throw Error("the " + method() + " model needs at least two samples, at distinct compositions" +
                (nodes_.size() == 1 ? "; all are at x = " + FormatNumber(nodes_[0].x) + " (" +
                                          nodes_[0].nk.source + ")"
                                    : std::string()));
  }
  for (size_t i = 1; i < nodes_.size(); ++i) {
    if (!(nodes_[i].x > nodes_[i - 1].x)) {
      throw Error("samples " + nodes_[i - 1].nk.source + " and " + nodes_[i].nk.source +
                  " are not at increasing compositions");
    }
  }
  if (!(lambda_min_nm() < lambda_max_nm())) {
    throw Error("the samples share no wavelength range");
  }
  node_x_.clear();
  for (const Node& node : nodes_) node_x_.push_back(node.x);
}

void SampleModel::Diagnose() {
  if (kind_ != Kind::kPaper) return;
  for (const Node& node : nodes_) {
    // Ranges (in the sample's own wavelengths within the model's range) where eq. 11, 12
    // are undefined.
    double start = -1, last = -1;
    std::string reason;
    auto flush = [&]() {
      if (start < 0) return;
      std::ostringstream msg;
      msg << node.nk.source << " (x = " << node.x << "): " << reason << " at " << start << "-"
          << last << " nm; the Drude inversion is undefined there and the paper "
          << "model skips this sample at those wavelengths";
      AddWarning(msg.str());
      start = -1;
    };
    for (size_t j = 0; j < node.nk.lambda_nm.size(); ++j) {
      const double l = node.nk.lambda_nm[j];
      if (l < lambda_min_nm() || l > lambda_max_nm()) continue;
      const double n = node.nk.n[j], k = node.nk.k[j];
      const double e1 = n * n - k * k, e2 = 2 * n * k;
      if (DrudeInvertible(e1, e2)) {
        flush();
        continue;
      }
      const std::string why = e1 >= 1 ? "eps1 >= 1" : "eps2 <= 0";
      if (start >= 0 && why != reason) flush();
      if (start < 0) start = l;
      reason = why;
      last = l;
    }
    flush();
  }
}

std::string SampleModel::method() const {
  switch (kind_) {
    case Kind::kPaper:
      return "paper";
    case Kind::kEpsLinear:
      return "eps-linear";
    case Kind::kEpsPchip:
      return "eps-pchip";
    case Kind::kEpsSpline:
      return "eps-spline";
  }
  return "";
}

std::vector<std::complex<double>> SampleModel::Permittivity(
    double x_atomic, const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  if (kind_ == Kind::kEpsLinear) return EpsLinearOn(x_atomic, lambda_nm);
  std::vector<std::complex<double>> eps(lambda_nm.size());
  for (size_t i = 0; i < lambda_nm.size(); ++i) {
    eps[i] = kind_ == Kind::kPaper ? PaperAt(x_atomic, lambda_nm[i])
                                   : EpsCubicAt(x_atomic, lambda_nm[i]);
  }
  return eps;
}

std::complex<double> SampleModel::EpsLinearAt(double x, double lambda_nm) const {
  const Bracket b = FindBracket(node_x_, x);
  if (b.t == 0.0) return EpsOf(nodes_[b.lo].nk, lambda_nm);
  if (b.t == 1.0) return EpsOf(nodes_[b.hi].nk, lambda_nm);
  return Lerp(EpsOf(nodes_[b.lo].nk, lambda_nm), EpsOf(nodes_[b.hi].nk, lambda_nm), b.t);
}

std::vector<std::complex<double>> SampleModel::EpsLinearOn(
    double x, const std::vector<double>& lambda_nm) const {
  // As EpsLinearAt at each wavelength, with the bracket found once.
  const Bracket b = FindBracket(node_x_, x);
  if (b.t == 1.0) return EpsOn(nodes_[b.hi].nk, lambda_nm);
  std::vector<std::complex<double>> eps = EpsOn(nodes_[b.lo].nk, lambda_nm);
  if (b.t == 0.0) return eps;
  const std::vector<std::complex<double>> hi = EpsOn(nodes_[b.hi].nk, lambda_nm);
  for (size_t i = 0; i < eps.size(); ++i) eps[i] = Lerp(eps[i], hi[i], b.t);
  return eps;
}

std::complex<double> SampleModel::EpsCubicAt(double x, double lambda_nm) const {
  // PCHIP's slopes at a node depend on its neighbours alone (at an end, on the two next to
  // it): the nodes from one before x's interval to one after it give the same curve there.
  // The natural spline's depend on every node.
  size_t first = 0, last = nodes_.size();
  if (kind_ == Kind::kEpsPchip) {
    const Bracket b = FindBracket(node_x_, x);
    first = b.lo > 0 ? b.lo - 1 : 0;
    last = std::min(nodes_.size(), b.hi + 2);
    if (first == 0) last = std::min(nodes_.size(), std::max<size_t>(last, 3));
    if (last == nodes_.size()) first = std::min(first, nodes_.size() >= 3 ? nodes_.size() - 3 : 0);
  }
  std::vector<double> xs, e1, e2;
  for (size_t i = first; i < last; ++i) {
    const std::complex<double> e = EpsOf(nodes_[i].nk, lambda_nm);
    xs.push_back(nodes_[i].x);
    e1.push_back(e.real());
    e2.push_back(e.imag());
  }
  const Interpolation scheme =
      kind_ == Kind::kEpsPchip ? Interpolation::kPchip : Interpolation::kNaturalSpline;
  const double eps2 = Interpolant(scheme, xs, e2)(x);
  // A natural spline can undershoot between samples: eps2 is held at 0 (passive).
  return {Interpolant(scheme, std::move(xs), e1)(x),
          kind_ == Kind::kEpsSpline && eps2 < 0.0 ? 0.0 : eps2};
}

bool SampleModel::PaperTauMass(double x, double lambda_nm, TauMass* out) const {
  const double omega = OmegaEvFromLambdaNm(lambda_nm);
  // tau and m* of every sample that can be inverted at this wavelength.
  std::vector<double> xs, taus, masses;
  for (const Node& node : nodes_) {
    const std::complex<double> e = EpsOf(node.nk, lambda_nm);
    if (!DrudeInvertible(e.real(), e.imag())) continue;
    const DrudePoint p = InvertDrude(omega, e.real(), e.imag());
    xs.push_back(node.x);
    taus.push_back(TauFsFromGammaEv(p.gamma_ev));
    masses.push_back(EffectiveMassRatio(FreeElectronDensityM3(node.x, system()), p.wp2_ev2));
  }
  if (xs.empty()) return false;
  if (xs.size() == 1) {
    *out = {taus[0], masses[0]};
    return true;
  }
  Bracket b = FindBracket(xs, x);
  // Inside the samples' range but beyond the invertible ones: hold the nearest.
  const bool inside = x >= x_min() && x <= x_max();
  if (inside && (b.t < 0 || b.t > 1)) {
    const size_t nearest = b.t < 0 ? b.lo : b.hi;
    *out = {taus[nearest], masses[nearest]};
    return true;
  }
  const double tau = taus[b.lo] + (taus[b.hi] - taus[b.lo]) * b.t;
  const double mass = masses[b.lo] + (masses[b.hi] - masses[b.lo]) * b.t;
  if (!(tau > 0) || !(mass > 0)) {  // extrapolated past zero: hold the nearest
    const size_t nearest = b.t < 0.5 ? b.lo : b.hi;
    *out = {taus[nearest], masses[nearest]};
    return true;
  }
  *out = {tau, mass};
  return true;
}

std::complex<double> SampleModel::PaperAt(double x, double lambda_nm) const {
  TauMass tm;
  if (!PaperTauMass(x, lambda_nm, &tm)) return EpsLinearAt(x, lambda_nm);
  const double omega = OmegaEvFromLambdaNm(lambda_nm);
  const double wp2 = EffectiveMassRatio(FreeElectronDensityM3(x, system()), tm.mass_ratio);
  const Complex<double> e = DrudePermittivity(omega, wp2, GammaEvFromTauFs(tm.tau_fs));
  return {e.re, e.im};
}

bool SampleModel::DrudeAt(double x_atomic, double lambda_nm, DrudePoint* out) const {
  if (kind_ != Kind::kPaper) return AlloyModel::DrudeAt(x_atomic, lambda_nm, out);
  if (!(lambda_nm >= lambda_min_nm() - 1e-9 && lambda_nm <= lambda_max_nm() + 1e-9)) return false;
  TauMass tm;
  if (!PaperTauMass(x_atomic, lambda_nm, &tm)) return false;
  // m*/m_e = kPlasmaEv2M3 N_e / wp^2 is its own inverse in (m*/m_e, wp^2).
  *out = {GammaEvFromTauFs(tm.tau_fs),
          EffectiveMassRatio(FreeElectronDensityM3(x_atomic, system()), tm.mass_ratio)};
  return true;
}

nlohmann::json SampleModel::ParametersJson() const {
  nlohmann::json samples = nlohmann::json::array();
  for (const Node& node : nodes_) {
    samples.push_back({{"x", node.x},
                       {"source", node.nk.source},
                       {"lambda_nm", node.nk.lambda_nm},
                       {"n", node.nk.n},
                       {"k", node.nk.k}});
  }
  const char* interpolation =
      kind_ == Kind::kPaper       ? "tau and m* linear in x (eq. 11, 12, 7)"
      : kind_ == Kind::kEpsLinear ? "eps linear in x"
      : kind_ == Kind::kEpsPchip
          ? "eps1, eps2 monotone cubic (PCHIP) in x"
          : "eps1, eps2 natural cubic spline in x, eps2 held at 0 from below";
  return {{"interpolation", interpolation}, {"samples", samples}};
}

}  // namespace alloycolor
