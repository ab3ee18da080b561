// Which of a data set's samples the rest of the series contradicts: an oxidised, rough or
// mislabelled film, fitted as if it were as good as the others, bends every model through
// it. After a fit, each sample (the two ends included) is weighed against the others, in
// the spirit of statsmodels' OLSInfluence: cheap measures for every sample, a refit
// without the suspects to say what they cost.
//
//  - Metallic where its neighbours are: a film whose eps1 >= 0 (n >= k) over most of the
//    compared wavelengths (380-780 nm where the sample and its neighbours cover it, else
//    their common range) while its neighbours' eps1 < 0 there is not the same kind of
//    material as them (Querry's zinc: n > k across the visible). The neighbours are the
//    nearest composition on each side, or for an end the next two; a sample with fewer
//    than two neighbours is not judged.
//  - Held out: each composition the model's folds hold out (AlloyModel::prediction_error,
//    its held_out list: 20 compositions at most) and each end, held out by fitting the
//    method without it, against its one-sigma there with the calibration taken from the
//    other folds only (externally studentized). For errors of a two-dimensional normal
//    law (the error bars' draws move eps along one complex direction), f = (e / sigma)^2
//    over the calibration's own mean from m folds follows Fisher's F(2, 2m), whose tail is
//    p = (1 + f / m)^-m; a sample is out of line where p < kSuspectTail and its error is a
//    miss worth doubting (above ΔE00 1, the in-sample miss). An end's one-sigma grows
//    with the extrapolation, so an end is rarely flagged this way: the metallic check and
//    the refit without the suspect are what single out a bad end.
// Held-out errors need colour (a colorimeter and data over the visible); infrared series
// are checked for metallic behaviour alone. Where a sample is found not metallic, the
// held-out check is made on the fit without it (one bad sample bends the fold of its
// neighbour), and its note says how the others' held-out error changes without it.
//
// The rule's false-alarm rate on honest scatter is measured by scripts/suspects.sh
// (docs/suspects.md) on series drawn from seeds the rule was not set on.
#ifndef ALLOYCOLOR_FIT_SUSPECTS_H_
#define ALLOYCOLOR_FIT_SUSPECTS_H_

#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::fit {

// The F tail below which a held-out error is out of line with the other folds': one in ten
// thousand. Held-out errors have heavier tails than the normal law the F test assumes
// (the scatter between films does not shrink with the gap as the interpolation error
// does): set first at one in two hundred, that tail flagged 3 of 281 honest samples of
// freshly drawn series (scripts/suspects_table.py, seed 101), each 7 to 13 times its
// one-sigma; the false-alarm rate of this tail is measured on other seeds
// (docs/suspects.md).
inline constexpr double kSuspectTail = 1e-4;

// The samples of `dataset` that `model` (built on it by BuildModel, with its folds) finds
// out of line, each with its check, figure and one-line reason (advice included), in the
// data set's order. Needs settings.colorimeter for the held-out check. Never throws for
// a sample it cannot judge: that sample is left unjudged.
std::vector<SampleNote> CheckSamples(const Dataset& dataset, const AlloyModel& model,
                                     const FitSettings& settings);

// The fraction of wavelengths where eps1 < 0 (n < k) in the sample's own data inside
// [lo_nm, hi_nm] (NaN where it has none there).
double MetallicFraction(const NkSpectrum& nk, double lo_nm, double hi_nm);

// The tail probability of Fisher's F(2, 2m) beyond f: (1 + f / m)^-m.
double FTailTwo(double f, double m);

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_SUSPECTS_H_
