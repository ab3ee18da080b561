// The smooth fit's restricted marginal likelihood (smooth_solve.h): each node's terms at
// each candidate smoothing, and the most probable candidates with one noise level.
#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"
#include "alloycolor/fit/smooth_fit.h"
#include "smooth_solve.h"

namespace alloycolor::fit {
namespace smooth {

// The per-node candidates that maximise the evidence with one noise level: every node's
// best candidate at each noise level of a fine logarithmic scan across the range the
// candidates' own residuals span, then coordinate ascent (sigma^2 = sum Q / dof, every
// node's best again) from the best of the scan. Empty when the data leave no residual at
// any smoothing (eps linear in composition: every smoothing gives the same fit).
std::vector<size_t> MostProbableSmoothings(const EvidenceTerms& terms) {
  double q_lo = HUGE_VAL, q_hi = 0;
  for (const auto& node : terms.q) {
    for (double v : node) {
      if (v > 0) q_lo = std::min(q_lo, v);
      q_hi = std::max(q_hi, v);
    }
  }
  if (!(q_hi > 0)) return {};
  // One node's share of the degrees of freedom.
  const double per_dof = static_cast<double>(terms.q.size()) / terms.Dof();
  const double lo = std::log(q_lo * per_dof) - 2, hi = std::log(q_hi * per_dof) + 2;
  std::vector<size_t> best_choice;
  double best = -HUGE_VAL;
  constexpr int kSteps = 400;
  for (int step = 0; step <= kSteps; ++step) {
    std::vector<size_t> choice = terms.BestAt(std::exp(lo + (hi - lo) * step / kSteps));
    const double total = terms.Total(choice);
    if (total > best) {
      best = total;
      best_choice = std::move(choice);
    }
  }
  for (int round = 0; round < 50; ++round) {
    std::vector<size_t> choice =
        terms.BestAt(std::max(terms.SumQ(best_choice) / terms.Dof(), 1e-300));
    const double total = terms.Total(choice);
    if (!(total > best)) break;
    best = total;
    best_choice = std::move(choice);
  }
  return best_choice;
}

}  // namespace smooth

double SmoothingLogEvidence(const Dataset& dataset, const std::vector<double>& grid_nm,
                            const std::vector<double>& smoothing_per_node) {
  using smooth::AssembleAtCompositions;
  using smooth::Compositions;
  using smooth::EvidenceTerms;
  using smooth::GridData;
  using smooth::PrepareData;
  if (smoothing_per_node.size() != grid_nm.size()) {
    throw Error("smoothing evidence: one smoothing per wavelength needed");
  }
  const GridData g = PrepareData(dataset, grid_nm);
  const std::vector<char> all(g.x.size(), 1);
  const std::vector<double> compositions = Compositions(g, all);
  if (compositions.size() < 3 || g.x.size() < 3) {
    throw Error(dataset.manifest_path + ": the smoothing evidence needs three compositions");
  }
  const EvidenceTerms terms(AssembleAtCompositions(g, all, compositions), smoothing_per_node);
  std::vector<size_t> choice(grid_nm.size());
  for (size_t j = 0; j < choice.size(); ++j) choice[j] = j;
  return terms.Total(choice);
}

}  // namespace alloycolor::fit
