#include "alloycolor/color/match.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <functional>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"

namespace alloycolor::color {
namespace {

constexpr double kRefineTolerance = 1e-10;  // Brent's bracket, atomic fraction
constexpr double kBisectTolerance = 1e-9;   // tolerance window edges
// Two refined minima closer than this (atomic fraction) are one.
constexpr double kSameMinimum = 1e-6;

bool Finite(const Lab& lab) {
  return std::isfinite(lab.L) && std::isfinite(lab.a) && std::isfinite(lab.b);
}

std::string ModelName(const AlloyModel& model) {
  return (model.source().empty() ? std::string() : model.source() + ": ") + "the " +
         model.method() + " model";
}

// The minimum of f on [lo, hi] by Brent's method (parabolic interpolation safeguarded by
// golden-section steps; Brent 1973, ch. 5), to kRefineTolerance in x; the ends of the
// bracket count too, so that a minimum at the model's range is found there. *f_min
// receives f at the minimum.
double BrentMinimum(const std::function<double(double)>& f, double lo, double hi, double* f_min) {
  constexpr double kGolden = 0.3819660112501051;  // (3 - sqrt 5) / 2
  double a = lo, b = hi;
  double x = a + kGolden * (b - a), w = x, v = x;
  double fx = f(x), fw = fx, fv = fx;
  double d = 0, e = 0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double m = 0.5 * (a + b);
    const double tol = 1e-12 * std::abs(x) + kRefineTolerance / 3;
    if (std::abs(x - m) <= 2 * tol - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol) {
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0)
        p = -p;
      else
        q = -q;
      const double e_before = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * e_before) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < 2 * tol || b - u < 2 * tol) d = m >= x ? tol : -tol;
        golden = false;
      }
    }
    if (golden) {
      e = x >= m ? a - x : b - x;
      d = kGolden * e;
    }
    const double u = std::abs(d) >= tol ? x + d : x + (d > 0 ? tol : -tol);
    const double fu = f(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  double best_x = x, best_f = fx;
  for (const double end : {lo, hi}) {
    const double f_end = f(end);
    if (f_end < best_f) best_x = end, best_f = f_end;
  }
  *f_min = best_f;
  return best_x;
}

// Indices of the local minima of a scan (ends included); a flat run counts once.
std::vector<size_t> LocalMinima(const std::vector<double>& d) {
  std::vector<size_t> minima;
  const size_t n = d.size();
  for (size_t i = 0; i < n; ++i) {
    const bool below_left = i == 0 || d[i] < d[i - 1];
    const bool below_right = i + 1 == n || d[i] <= d[i + 1];
    if (below_left && below_right) minima.push_back(i);
  }
  return minima;
}

// Scans, refines and keeps the minima within margin of the best, best first. `consider`
// (null: every point) marks the scan points whose minima may be kept.
std::vector<Match> Minimise(const std::vector<double>& scan_x, const std::vector<double>& scan_d,
                            const std::function<double(double)>& exact, double margin,
                            const std::string& what, const std::vector<char>* consider = nullptr) {
  std::vector<size_t> minima;
  for (const size_t i : LocalMinima(scan_d)) {
    if (consider == nullptr || (*consider)[i]) minima.push_back(i);
  }
  // A model whose colour swings back and forth (a crafted file: interband widths near a
  // pole) has hundreds of minima; the kMaxRefinedMinima lowest of the scan are refined, so
  // that the work is bounded whatever the model.
  if (minima.size() > kMaxRefinedMinima) {
    std::nth_element(minima.begin(), minima.begin() + kMaxRefinedMinima, minima.end(),
                     [&](size_t a, size_t b) { return scan_d[a] < scan_d[b]; });
    minima.resize(kMaxRefinedMinima);
  }
  std::vector<Match> found;
  for (const size_t i : minima) {
    const double lo = scan_x[i == 0 ? 0 : i - 1];
    const double hi = scan_x[std::min(i + 1, scan_x.size() - 1)];
    Match m;
    // The square of the distance: smooth where the target lies on the model's curve (the
    // distance itself has a corner there), with the same minimum.
    double d2 = 0;
    m.x_atomic = BrentMinimum(
        [&](double x) {
          const double d = exact(x);
          return d * d;
        },
        lo, hi, &d2);
    if (!std::isfinite(d2)) continue;
    m.de00 = std::sqrt(d2);  // the objective; the caller renames it for spectra
    found.push_back(m);
  }
  if (found.empty()) throw Error(what + ": the distance to the target is not finite anywhere");
  std::sort(found.begin(), found.end(),
            [](const Match& a, const Match& b) { return a.de00 < b.de00; });
  std::vector<Match> kept;
  for (const Match& m : found) {
    if (m.de00 > found.front().de00 + margin) break;
    const bool repeat = std::any_of(kept.begin(), kept.end(), [&](const Match& k) {
      return std::abs(k.x_atomic - m.x_atomic) < kSameMinimum;
    });
    if (!repeat) kept.push_back(m);
  }
  return kept;
}

// `points` evenly spaced compositions over [lo, hi] (one where the range is a point).
std::vector<double> UniformScan(double lo, double hi, int points) {
  const int n = hi > lo ? points : 1;
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = i + 1 == n ? hi : lo + (hi - lo) * i / (n - 1);
  return x;
}

void CheckAngle(double angle_deg) {
  if (!(angle_deg >= 0.0 && angle_deg <= 90.0)) {
    throw Error("angle of incidence " + FormatNumber(angle_deg) + " degrees lies outside 0-90");
  }
}

// v(x) of the header from the colour at any composition, one-sided at the range's ends.
double ColourSpeedOf(const std::function<Lab(double)>& lab_at, double x_atomic,
                     const AlloyModel& model) {
  const double h = kColourSpeedStep;
  const double lo = std::max(model.x_min(), x_atomic - h);
  const double hi = std::min(model.x_max(), x_atomic + h);
  if (!(hi > lo)) return 0.0;
  return DeltaE00(lab_at(lo), lab_at(hi)) / (hi - lo);
}

}  // namespace

ColourMatcher::ColourMatcher(const Colorimeter& colorimeter, const AlloyModel& model,
                             const MatchOptions& options)
    : colorimeter_(colorimeter), model_(model), options_(options) {
  CheckAngle(options.angle_deg);
  if (options.scan_points < 3 || options.scan_points > 10000000) {
    throw Error("match: " + std::to_string(options.scan_points) +
                " scan points; give 3 to 10000000");
  }
  if (!(options.margin >= 0.0) || !std::isfinite(options.margin)) {
    throw Error("match: margin " + FormatNumber(options.margin) + " is not a number >= 0");
  }
  if (!(options.target_sigma_de00 >= 0.0) || !std::isfinite(options.target_sigma_de00)) {
    throw Error("match: target sigma " + FormatNumber(options.target_sigma_de00) +
                " is not a number >= 0");
  }
  sweep_ = std::make_unique<ColorSweep>(colorimeter, model, options.angle_deg);
  const double lo = model.x_min(), hi = model.x_max();
  // The table serves the scan alone: it may cost no more than the scan's exact evaluations
  // (else, or failing, exact evaluation).
  if (hi > lo) sweep_->BuildTable(lo, hi, kSweepTableTolerance, options.scan_points);
  const std::vector<double> uniform = UniformScan(lo, hi, options.scan_points);
  // The colour scan: the first and last of the uniform scan and each point where the colour
  // has moved kColourScanStep along its path since the last one kept, or kColourScanGap in x.
  double path = 0;
  Lab previous_lab{};
  for (size_t i = 0; i < uniform.size(); ++i) {
    const Lab lab = LabFromXYZ(sweep_->XYZAt(uniform[i]), colorimeter.White());
    if (i > 0) path += DeltaE00(previous_lab, lab);
    previous_lab = lab;
    if (i == 0 || i + 1 == uniform.size() || path >= kColourScanStep ||
        uniform[i] - scan_x_.back() >= kColourScanGap * (hi - lo)) {
      scan_x_.push_back(uniform[i]);
      scan_lab_.push_back(lab);
      path = 0;
    }
  }
  const size_t n = scan_x_.size();
  for (size_t i = 0; i + 1 < n; ++i) {
    scan_slack_de00_ = std::max(scan_slack_de00_, 2 * DeltaE00(scan_lab_[i], scan_lab_[i + 1]));
  }
  for (size_t i = 0; i < n; ++i) {
    scan_box_.push_back(LabBox::Of(scan_lab_[i]));
    if (i % kScanBlock == 0) {
      block_box_.push_back(scan_box_.back());
    } else {
      block_box_.back().Add(scan_lab_[i]);
    }
  }
}

ColourMatcher::~ColourMatcher() = default;

Lab ColourMatcher::LabAt(double x_atomic) const {
  return LabFromXYZ(sweep_->ExactXYZ(x_atomic), colorimeter_.White());
}

double ColourMatcher::ColourSpeed(double x_atomic) const {
  return ColourSpeedOf([this](double x) { return LabAt(x); }, x_atomic, model_);
}

void ColourMatcher::Finish(Match* m) const {
  m->lab = LabAt(m->x_atomic);
  const double span = model_.x_max() - model_.x_min();
  m->at_range_end = std::abs(m->x_atomic - model_.x_min()) <= 1e-9 * std::max(span, 1.0) ||
                    std::abs(m->x_atomic - model_.x_max()) <= 1e-9 * std::max(span, 1.0);
  m->de00_per_x = ColourSpeed(m->x_atomic);
  double sigma2 = options_.target_sigma_de00 * options_.target_sigma_de00;
  bool known = options_.target_sigma_de00 > 0;
  if (options_.with_sigma && model_.HasUncertainty()) {
    const double s = DeltaE00Sigma(colorimeter_, model_, m->x_atomic, options_.angle_deg);
    if (s >= 0) {
      m->model_sigma_de00 = s;
      sigma2 += s * s;
      known = true;
    }
  }
  if (known) {
    m->x_sigma = m->de00_per_x > 0 ? std::sqrt(sigma2) / m->de00_per_x
                                   : std::numeric_limits<double>::infinity();
  }
}

void CheckTargetLab(const Lab& target) {
  const std::string lab = "the target L*a*b* " + FormatNumber(target.L) + "," +
                          FormatNumber(target.a) + "," + FormatNumber(target.b);
  if (!Finite(target)) throw Error(lab + " is not finite");
  if (!(target.L >= 0 && target.L <= kMaxTargetL)) {
    throw Error(lab + ": L* = " + FormatNumber(target.L) + " lies outside 0-" +
                FormatNumber(kMaxTargetL) + " (100 is a perfect white reflector)");
  }
  for (const double v : {target.a, target.b}) {
    if (!(std::abs(v) <= kMaxTargetAB)) {
      throw Error(lab + ": " + (v == target.a ? "a* = " : "b* = ") + FormatNumber(v) +
                  " lies outside -" + FormatNumber(kMaxTargetAB) + " to " +
                  FormatNumber(kMaxTargetAB) + " (no colour lies that far from grey)");
    }
  }
}

std::vector<Match> ColourMatcher::Find(const Lab& target) const {
  CheckTargetLab(target);
  // DeltaE00 is needed only at scan points where it may come within the margin of the
  // best (and at their neighbours, which decide whether they are minima): a point whose
  // lower bound exceeds reach = an upper bound of the best + the margin + the most the
  // colour changes over a bracket of two scan intervals cannot hold a match. The bounds are
  // taken for blocks of points first, then for the points of the blocks within reach. The
  // result is that of the full scan.
  const size_t n = scan_lab_.size();
  const auto block_of = [n](size_t b) {
    return std::pair{b * kScanBlock, std::min(n, (b + 1) * kScanBlock)};
  };
  std::vector<double> block_bound(block_box_.size());
  size_t closest = 0;
  for (size_t b = 0; b < block_box_.size(); ++b) {
    block_bound[b] = DeltaE00LowerBound(target, block_box_[b]);
    if (block_bound[b] < block_bound[closest]) closest = b;
  }
  double nearest = std::numeric_limits<double>::infinity();
  for (auto [i, end] = block_of(closest); i < end; ++i) {
    nearest = std::min(nearest, DeltaE00(target, scan_lab_[i]));
  }
  const double reach = nearest + options_.margin + scan_slack_de00_;
  std::vector<double> d(n, std::numeric_limits<double>::infinity());
  std::vector<char> candidate(n, 0);
  for (size_t b = 0; b < block_box_.size(); ++b) {
    if (block_bound[b] > reach) continue;
    for (auto [i, end] = block_of(b); i < end; ++i) {
      if (DeltaE00LowerBound(target, scan_box_[i]) > reach) continue;
      candidate[i] = 1;
      for (size_t j = i == 0 ? 0 : i - 1; j <= std::min(i + 1, n - 1); ++j) {
        if (std::isinf(d[j])) d[j] = DeltaE00(target, scan_lab_[j]);
      }
    }
  }
  const auto exact = [&](double x) { return DeltaE00(target, LabAt(x)); };
  std::vector<Match> matches =
      Minimise(scan_x_, d, exact, options_.margin, ModelName(model_), &candidate);
  for (Match& m : matches) Finish(&m);
  return matches;
}

std::vector<Match> ColourMatcher::FindReflectance(const std::vector<double>& lambda_nm,
                                                  const std::vector<double>& reflectance,
                                                  const std::string& source) const {
  if (lambda_nm.size() != reflectance.size()) {
    throw Error(source + ": " + std::to_string(lambda_nm.size()) + " wavelengths but " +
                std::to_string(reflectance.size()) + " reflectances");
  }
  std::vector<double> grid, target;
  for (size_t i = 0; i < lambda_nm.size(); ++i) {
    if (!std::isfinite(reflectance[i]) || !std::isfinite(lambda_nm[i])) {
      throw Error(source + ": the reflectance at row " + std::to_string(i + 1) + " is not finite");
    }
    if (lambda_nm[i] >= model_.lambda_min_nm() - 1e-9 &&
        lambda_nm[i] <= model_.lambda_max_nm() + 1e-9) {
      grid.push_back(std::clamp(lambda_nm[i], model_.lambda_min_nm(), model_.lambda_max_nm()));
      target.push_back(reflectance[i]);
    }
  }
  if (grid.size() < 2) {
    throw Error(source + " and " + ModelName(model_) + " share under two wavelengths (the model " +
                "covers " + FormatNumber(model_.lambda_min_nm()) + "-" +
                FormatNumber(model_.lambda_max_nm()) + " nm)");
  }
  const auto rms = [&](double x) {
    const std::vector<double> r = ReflectanceSpectrum(model_.Index(x, grid), options_.angle_deg);
    double sum2 = 0;
    for (size_t i = 0; i < r.size(); ++i) sum2 += (r[i] - target[i]) * (r[i] - target[i]);
    return std::sqrt(sum2 / r.size());
  };
  const std::vector<double> scan =
      UniformScan(model_.x_min(), model_.x_max(), options_.scan_points);
  std::vector<double> d(scan.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = rms(scan[i]);
  // The margin is a colour difference; for spectra the same number of reflectance percent.
  std::vector<Match> matches = Minimise(scan, d, rms, options_.margin / 100.0, source);
  // The target's own colour, where it covers what the colorimeter needs.
  bool coloured = false;
  Lab target_lab{};
  if (lambda_nm.front() <= std::max(380.0, colorimeter_.lambda_nm().front()) + 1e-9 &&
      lambda_nm.back() >= std::min(780.0, colorimeter_.lambda_nm().back()) - 1e-9) {
    std::vector<double> r(colorimeter_.lambda_nm().size());
    for (size_t i = 0; i < r.size(); ++i) {
      const double l = std::clamp(colorimeter_.lambda_nm()[i], lambda_nm.front(), lambda_nm.back());
      const size_t j = std::min<size_t>(
          std::upper_bound(lambda_nm.begin(), lambda_nm.end(), l) - lambda_nm.begin(),
          lambda_nm.size() - 1);
      const size_t i0 = j == 0 ? 0 : j - 1;
      const double t =
          lambda_nm[j] > lambda_nm[i0] ? (l - lambda_nm[i0]) / (lambda_nm[j] - lambda_nm[i0]) : 0.0;
      r[i] = reflectance[i0] + t * (reflectance[j] - reflectance[i0]);
    }
    target_lab = LabFromXYZ(colorimeter_.ReflectanceToXYZ(r), colorimeter_.White());
    coloured = Finite(target_lab);
  }
  for (Match& m : matches) {
    m.reflectance_rms = m.de00;
    Finish(&m);
    m.de00 = coloured ? DeltaE00(target_lab, m.lab) : Match::kNaN;
  }
  return matches;
}

std::vector<Match> MatchColour(const Colorimeter& colorimeter, const AlloyModel& model,
                               const Lab& target, const MatchOptions& options) {
  return ColourMatcher(colorimeter, model, options).Find(target);
}

Lab LabFromTargetXYZ(const Colorimeter& colorimeter, const XYZ& xyz) {
  const std::string text =
      "XYZ " + FormatNumber(xyz.X) + "," + FormatNumber(xyz.Y) + "," + FormatNumber(xyz.Z);
  const char* names[] = {"X", "Y", "Z"};
  const double values[] = {xyz.X, xyz.Y, xyz.Z};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(values[i])) throw Error(text + ": " + names[i] + " is not finite");
    if (values[i] < 0) {
      throw Error(text + ": " + names[i] + " = " + FormatNumber(values[i]) +
                  " is negative (tristimulus values are >= 0)");
    }
    if (values[i] > kMaxTargetXYZ) {
      throw Error(text + ": " + names[i] + " = " + FormatNumber(values[i]) + " lies above " +
                  FormatNumber(kMaxTargetXYZ) +
                  " (on this scale a perfect reflector has Y = 1: divide values on the 0-100 "
                  "scale by 100)");
    }
  }
  return LabFromXYZ(xyz, colorimeter.White());
}

std::array<int, 3> ParseHexColour(const std::string& text) {
  const std::string quoted = Quote(text, 40);
  const auto refuse = [&](const std::string& why) -> std::array<int, 3> {
    throw Error(quoted + " is not an sRGB colour '#rrggbb': " + why);
  };
  if (text.empty()) refuse("it is empty");
  if (text.find_first_of(" \t\r\n") != std::string::npos) {
    refuse("it holds a space (give the six digits alone)");
  }
  if (text.find_first_of(",;") != std::string::npos) {
    refuse("it holds a list (give one colour)");
  }
  std::string digits = text;
  if (digits.front() == '#') digits.erase(0, 1);
  if (digits.find('#') != std::string::npos) refuse("'#' comes once, first");
  for (const char c : digits) {
    if (!std::isxdigit(static_cast<unsigned char>(c))) {
      refuse(Quote(std::string(1, c)) + " is not a hexadecimal digit (0-9, a-f)");
    }
  }
  if (digits.size() != 6) {
    refuse(std::to_string(digits.size()) + " hexadecimal digit" + (digits.size() == 1 ? "" : "s") +
           ", not 6");
  }
  std::array<int, 3> rgb8{};
  for (int i = 0; i < 3; ++i) rgb8[i] = std::stoi(digits.substr(2 * i, 2), nullptr, 16);
  return rgb8;
}

Lab LabFromHex(const Colorimeter& colorimeter, const std::string& hex) {
  const std::array<int, 3> rgb8 = ParseHexColour(hex);
  double channel[3];
  for (int i = 0; i < 3; ++i) channel[i] = SRGBDecode(rgb8[i] / 255.0);
  return LabFromXYZ(XYZFromLinearSRGB({channel[0], channel[1], channel[2]}), colorimeter.White());
}

ToleranceWindow Tolerance(const std::vector<Colorimeter>& colorimeters, const AlloyModel& model,
                          double x_atomic, const ToleranceOptions& options) {
  if (colorimeters.empty() || options.angles_deg.empty()) {
    throw Error("tolerance: give at least one illuminant and one angle");
  }
  if (!(options.de00 > 0) || !std::isfinite(options.de00)) {
    throw Error("tolerance: the colour difference " + FormatNumber(options.de00) +
                " is not a positive number");
  }
  if (!std::isfinite(x_atomic)) throw Error("tolerance: the composition is not finite");
  model.CheckInRange(x_atomic);
  for (const double a : options.angles_deg) CheckAngle(a);

  struct Condition {
    std::unique_ptr<ColorSweep> sweep;
    const Colorimeter* colorimeter;
    double angle_deg;
    Lab reference;
    Lab At(double x) const { return LabFromXYZ(sweep->ExactXYZ(x), colorimeter->White()); }
    std::string Name() const {
      return colorimeter->illuminant() + " at " + FormatNumber(angle_deg) + " degrees";
    }
  };
  std::vector<Condition> conditions;
  for (const Colorimeter& c : colorimeters) {
    for (const double a : options.angles_deg) {
      Condition k{std::make_unique<ColorSweep>(c, model, a), &c, a, {}};
      k.reference = k.At(x_atomic);
      if (!Finite(k.reference)) {
        throw Error(ModelName(model) + " gives no finite colour at x = " + FormatNumber(x_atomic));
      }
      conditions.push_back(std::move(k));
    }
  }
  // The largest difference from the reference over the conditions, and which one.
  const auto worst = [&](double x, size_t* which) {
    double w = 0;
    for (size_t i = 0; i < conditions.size(); ++i) {
      const double d = DeltaE00(conditions[i].reference, conditions[i].At(x));
      if (!(d <= w)) {  // NaN counts as outside
        w = std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
        if (which != nullptr) *which = i;
      }
    }
    return w;
  };
  ToleranceWindow window;
  window.x_atomic = x_atomic;
  for (const int direction : {-1, +1}) {
    const double end = direction < 0 ? model.x_min() : model.x_max();
    double inside = x_atomic;
    double& edge = direction < 0 ? window.x_low : window.x_high;
    bool clipped = true;
    size_t which = 0;
    while (direction * (end - inside) > 0) {
      const double next = direction < 0 ? std::max(end, inside - kToleranceStep)
                                        : std::min(end, inside + kToleranceStep);
      if (worst(next, &which) > options.de00) {
        double in = inside, out = next;
        while (std::abs(out - in) > kBisectTolerance) {
          const double mid = 0.5 * (in + out);
          (worst(mid, nullptr) > options.de00 ? out : in) = mid;
        }
        worst(out, &which);
        edge = in;
        clipped = false;
        break;
      }
      inside = next;
    }
    if (clipped) edge = end;
    (direction < 0 ? window.clipped_low : window.clipped_high) = clipped;
    (direction < 0 ? window.limit_low : window.limit_high) =
        clipped ? std::string() : conditions[which].Name();
  }
  for (const Condition& k : conditions) {
    window.de00_per_x = std::max(
        window.de00_per_x, ColourSpeedOf([&k](double x) { return k.At(x); }, x_atomic, model));
  }
  if (model.HasUncertainty()) {
    const double sigma =
        DeltaE00Sigma(colorimeters.front(), model, x_atomic, options.angles_deg.front());
    if (sigma >= 0) {
      window.model_sigma_de00 = sigma;
      if (window.de00_per_x > 0) window.x_sigma = sigma / window.de00_per_x;
    }
  }
  return window;
}

}  // namespace alloycolor::color
