// From colour to composition: the compositions of an alloy whose colour (or reflectance)
// is closest to a target, and the composition window within which the colour stays
// within a given CIEDE2000 of an alloy's own.
//
// Matching. Colour need not be monotone in composition, so the target's difference
//   d(x) = DeltaE00(target, Lab(x))   (or, for a spectrum, RMS_lambda [R(x) - R_target])
// is scanned over the model's range (colour read from a ColorSweep table, sweep.h): of
// `scan_points` evenly spaced compositions, the ends and each one where the colour has moved
// kColourScanStep CIEDE2000 along its path since the last kept (or kColourScanGap of the
// range; a spectrum's scan keeps them all). Every local minimum of the scan (ends included)
// (the kMaxRefinedMinima lowest, where there are more) is refined by Brent's method (on d^2,
// smooth where d has a corner) on the exact model
// (ColorSweep::ExactXYZ) inside its two neighbouring scan intervals, and the minima within `margin`
// of the best are returned, best first. The scan computes CIEDE2000 only where a lower bound
// (DeltaE00LowerBound, colorimetry.h) leaves a point within reach of the best; its result is
// the full scan's.
//
// Error bar. The colour speed v(x) = |dLab/dx| in CIEDE2000 units per unit of x is
//   v(x) = DeltaE00(Lab(x - h), Lab(x + h)) / 2h,  h = 1e-5
// (one-sided at the ends of the range). A composition matched to a colour that is known
// to sigma_model (the model's colour one-sigma at x, DeltaE00Sigma in material_color.h)
// and sigma_target (the target measurement's, given) is known to
//   sigma_x = sqrt(sigma_model^2 + sigma_target^2) / v(x),
// first-order propagation of a colour error along the model's colour curve.
//
// Tolerance. Around x0, the window [x_low, x_high] is the largest interval containing x0
// in which max over (illuminant, angle) of DeltaE00(Lab(x0), Lab(x)) <= de00: walked out
// from x0 in steps of kToleranceStep and bisected to 1e-9 at the first step that leaves it;
// clipped at the model's range (and flagged). Units: x as atomic fraction of element a.
#ifndef ALLOYCOLOR_COLOR_MATCH_H_
#define ALLOYCOLOR_COLOR_MATCH_H_

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::color {

// A target farther than this from every composition is "not reachable".
inline constexpr double kReachableDeltaE00 = 1.0;
inline constexpr int kMatchScanPoints = 1001;
// The colour scan's spacing: finer than colours can be told apart, and at most 1/100 of
// the range.
inline constexpr double kColourScanStep = 0.1;
inline constexpr double kColourScanGap = 0.01;
// The step of the colour-speed difference and of the tolerance walk, in atomic fraction.
inline constexpr double kColourSpeedStep = 1e-5;
inline constexpr double kToleranceStep = 5e-4;
// The most local minima of the scan refined (the lowest): a bound on the work for a model
// whose colour swings back and forth, far more than any fitted model has.
inline constexpr std::size_t kMaxRefinedMinima = 32;

// The ranges every face takes for the settings of match and tolerance (the program's
// --target-sigma, --margin and --de, the Python package's target_sigma, margin and de),
// checked with NumberProblem so that a value is refused in the same words by both.
inline constexpr NumberRange kTargetSigmaRange{0, 100};
inline constexpr NumberRange kMatchMarginRange{0, 1000};
inline constexpr NumberRange kToleranceDeRange{1e-6, 100};

struct MatchOptions {
  double angle_deg = 0.0;
  int scan_points = kMatchScanPoints;  // at least 3
  // Other local minima whose distance lies within this of the best are returned too
  // (DeltaE00 for a colour, reflectance RMS for a spectrum).
  double margin = 1.0;
  double target_sigma_de00 = 0.0;  // one-sigma of the target's own measurement
  bool with_sigma = true;          // false: skip the model's uncertainty draws (faster)
};

struct Match {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double x_atomic = kNaN;
  double de00 = kNaN;              // CIEDE2000 left (NaN: a spectrum without colour)
  double reflectance_rms = kNaN;   // spectrum matches only
  double x_sigma = kNaN;           // one sigma of x_atomic (NaN: no uncertainty known)
  double model_sigma_de00 = kNaN;  // the model's colour one-sigma at x_atomic (NaN: none)
  double de00_per_x = kNaN;        // colour speed v(x) at x_atomic
  Lab lab{};                       // the model's colour at x_atomic
  bool at_range_end = false;       // the minimum lies at x_min or x_max
};

// The colour of the model at any composition and its distance to targets, prepared once
// (sweep table, Lab at the scan points) so that many targets cost little each.
class ColourMatcher {
 public:
  // Keeps references to colorimeter and model, which must outlive it. Throws Error when
  // the model does not cover the visible, the angle lies outside 0-90 degrees or the
  // options are out of range.
  ColourMatcher(const Colorimeter& colorimeter, const AlloyModel& model,
                const MatchOptions& options);
  ~ColourMatcher();

  // The minima of DeltaE00(target, Lab(x)) within options.margin of the best, best
  // first (never empty). Throws Error for a target CheckTargetLab refuses.
  std::vector<Match> Find(const Lab& target) const;
  // The same for a measured reflectance spectrum at the matcher's angle, by
  // reflectance RMS over the spectrum's wavelengths inside the model's range.
  // Throws Error naming `source` when the spectrum and the model share under two
  // wavelengths or a value is not finite.
  std::vector<Match> FindReflectance(const std::vector<double>& lambda_nm,
                                     const std::vector<double>& reflectance,
                                     const std::string& source) const;

  Lab LabAt(double x_atomic) const;
  // v(x), CIEDE2000 per unit of atomic fraction.
  double ColourSpeed(double x_atomic) const;

 private:
  void Finish(Match* match) const;

  const Colorimeter& colorimeter_;
  const AlloyModel& model_;
  MatchOptions options_;
  std::unique_ptr<ColorSweep> sweep_;
  std::vector<double> scan_x_;
  std::vector<Lab> scan_lab_;
  // Twice the largest DeltaE00 between neighbouring scan points: how far the distance to a
  // target may fall inside a minimum's bracket below its value at the scan point.
  double scan_slack_de00_ = 0.0;
  // The scan points as boxes, and blocks of kScanBlock of them, for DeltaE00LowerBound.
  static constexpr std::size_t kScanBlock = 16;
  std::vector<LabBox> scan_box_;
  std::vector<LabBox> block_box_;
};

// One target, one call.
std::vector<Match> MatchColour(const Colorimeter& colorimeter, const AlloyModel& model,
                               const Lab& target, const MatchOptions& options = {});

// What a target colour may be: L* in 0-kMaxTargetL, a* and b* within +-kMaxTargetAB (what
// any XYZ target within 0-kMaxTargetXYZ gives), X, Y, Z in 0-kMaxTargetXYZ (a perfect
// reflector has Y = 1; more is a measurement brighter than the white, up to twice).
inline constexpr double kMaxTargetL = 150.0;
inline constexpr double kMaxTargetAB = 600.0;
inline constexpr double kMaxTargetXYZ = 2.0;

// Throws Error ("the target L*a*b* ...: L* = ... lies outside 0-150") when a target lies
// outside those bounds or is not finite: the target is at fault, not the model.
void CheckTargetLab(const Lab& target);

// Targets given other ways, as CIELAB relative to the colorimeter's white:
// XYZ on the toolkit's scale (a perfect reflector has Y = 1); throws Error naming the
// value at fault when one is negative, not finite or above kMaxTargetXYZ;
Lab LabFromTargetXYZ(const Colorimeter& colorimeter, const XYZ& xyz);
// "#rrggbb" (or "rrggbb") as 8-bit sRGB values 0-255. Throws Error quoting the text and
// saying what is wrong: a character that is not a hex digit, a count other than six, a
// space, '#' twice, a list of colours.
std::array<int, 3> ParseHexColour(const std::string& text);
// That colour decoded and taken to XYZ with the IEC 61966-2-1 matrix without chromatic
// adaptation, the inverse of how the toolkit writes sRGB.
Lab LabFromHex(const Colorimeter& colorimeter, const std::string& hex);

struct ToleranceOptions {
  double de00 = 1.0;
  std::vector<double> angles_deg = {0.0};
};

struct ToleranceWindow {
  double x_atomic = 0.0;
  double x_low = 0.0, x_high = 0.0;
  bool clipped_low = false, clipped_high = false;  // the window reaches the model's range
  // The largest colour speed over the conditions at x_atomic, per unit of atomic fraction.
  double de00_per_x = 0.0;
  // Which illuminant and angle bound each side (empty when clipped).
  std::string limit_low, limit_high;
  // The model's own one-sigma colour uncertainty at x_atomic under the first colorimeter
  // and angle (DeltaE00Sigma), and the composition it amounts to at the colour speed there
  // (model_sigma_de00 / de00_per_x): how finely the model itself can tell compositions
  // apart. NaN without error bars (AlloyModel::NoErrorBarReason).
  double model_sigma_de00 = std::numeric_limits<double>::quiet_NaN();
  double x_sigma = std::numeric_limits<double>::quiet_NaN();
};

// The window around x_atomic for every colorimeter (illuminant, observer) and angle.
// Throws Error when x_atomic lies outside the model's range, de00 is not positive, no
// colorimeter or angle is given, or an angle lies outside 0-90 degrees.
ToleranceWindow Tolerance(const std::vector<Colorimeter>& colorimeters, const AlloyModel& model,
                          double x_atomic, const ToleranceOptions& options);

}  // namespace alloycolor::color

#endif  // ALLOYCOLOR_COLOR_MATCH_H_
