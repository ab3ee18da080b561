#include "alloycolor/render/composition_table.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <memory>
#include <sstream>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/units.h"

namespace alloycolor::render {
namespace {

constexpr double kSameX = 1e-12;

// Weights of the cubic through nodes 0, 1, 2, 3 at position t.
void LagrangeWeights(double t, double w[4]) {
  w[0] = -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0;
  w[1] = t * (t - 2.0) * (t - 3.0) / 2.0;
  w[2] = -t * (t - 1.0) * (t - 3.0) / 2.0;
  w[3] = t * (t - 1.0) * (t - 2.0) / 6.0;
}

// The first node and the weights of the four nodes that interpolate x in a segment.
int SegmentWeights(const CompositionSegment& seg, double x, double w[4]) {
  const double step = (seg.x_hi - seg.x_lo) / seg.intervals;
  const double u = std::clamp((x - seg.x_lo) / step, 0.0, static_cast<double>(seg.intervals));
  const int cell = std::min(static_cast<int>(u), seg.intervals - 1);
  const int first = std::clamp(cell - 1, 0, seg.intervals - 3);
  LagrangeWeights(u - first, w);
  return seg.first_node + first;
}

double SegmentNode(double x_lo, double x_hi, int intervals, int i) {
  return i == intervals ? x_hi : x_lo + i * (x_hi - x_lo) / intervals;
}

// X, Y, Z at the table's mu nodes, read from the renderer's own table at its nodes.
std::vector<double> Row(const DirectReflection& direct, int mu_nodes) {
  const ReflectionTable table(direct, mu_nodes);
  std::vector<double> row(3 * static_cast<std::size_t>(mu_nodes));
  for (int m = 0; m < mu_nodes; ++m) {
    const color::XYZ c = table.At(static_cast<double>(m) / (mu_nodes - 1));
    row[3 * m] = c.X;
    row[3 * m + 1] = c.Y;
    row[3 * m + 2] = c.Z;
  }
  return row;
}

color::XYZ RowAt(const double* row, int mu_nodes, double mu) {
  const double t = std::clamp(mu, 0.0, 1.0) * (mu_nodes - 1);
  const int i = std::min(static_cast<int>(t), mu_nodes - 2);
  const double f = t - i;
  const double* a = row + 3 * i;
  return {a[0] + f * (a[3] - a[0]), a[1] + f * (a[4] - a[1]), a[2] + f * (a[5] - a[2])};
}

struct ColourError {
  double de00 = 0.0;
  int srgb8 = 0;
};

void Accumulate(const color::XYZ& exact, const color::XYZ& table, const color::XYZ& white,
                ColourError* error) {
  error->de00 = std::max(error->de00, color::DeltaE00(color::LabFromXYZ(exact, white),
                                                      color::LabFromXYZ(table, white)));
  const auto a = color::SRGB8FromLinear(color::LinearSRGBFromXYZ(exact));
  const auto b = color::SRGB8FromLinear(color::LinearSRGBFromXYZ(table));
  for (int c = 0; c < 3; ++c) error->srgb8 = std::max(error->srgb8, std::abs(a[c] - b[c]));
}

class Builder {
 public:
  Builder(const AlloyModel& model, const std::vector<color::Colorimeter>& colorimeters,
          const CompositionTableOptions& options)
      : model_(model),
        colorimeters_(colorimeters),
        options_(options),
        threads_(ThreadCount(options.threads)) {}

  CompositionTable Build() {
    CheckOptions();
    CompositionTable table;
    table.roughness = options_.roughness;
    table.sigma_angles_deg = options_.sigma_angles_deg;
    const std::vector<double> breaks = Breakpoints();
    table.mu_nodes = ChooseMuNodes(breaks, &table.tolerance_met);
    table.rough_mu_nodes = std::max(2, options_.rough_mu_intervals) + 1;
    ChooseSegments(breaks, &table);
    FillTables(&table);
    MeasureErrors(&table);
    FillSpectra(&table);
    return table;
  }

 private:
  void CheckOptions() const {
    if (colorimeters_.empty()) throw Error("composition table: no illuminant given");
    if (options_.roughness.empty() || options_.roughness.front() != 0.0) {
      throw Error("composition table: the first roughness must be 0 (a polished surface)");
    }
    for (double a : options_.roughness) {
      if (!(a >= 0.0 && a <= kMaxRoughness)) {
        std::ostringstream msg;
        msg << "composition table: roughness " << a << " lies outside 0-" << kMaxRoughness;
        throw Error(msg.str());
      }
    }
    if (!(options_.tolerance_de00 > 0.0)) {
      throw Error("composition table: the tolerance must be above 0");
    }
    for (double a : options_.sigma_angles_deg) {
      if (!(a >= 0.0 && a <= 90.0)) throw Error("composition table: sigma angle outside 0-90");
    }
    if (!(model_.x_max() > model_.x_min())) {
      throw Error("composition table: the model's composition range is empty");
    }
  }

  DirectReflection Direct(int c, double x) const {
    return DirectReflection(colorimeters_[c], color::IndexOnGrid(colorimeters_[c], model_, x), 0.0);
  }

  std::vector<double> Breakpoints() const {
    std::vector<double> breaks = {model_.x_min()};
    for (const TrainingSample& s : model_.training_samples()) {
      if (s.x_atomic > model_.x_min() + kSameX && s.x_atomic < model_.x_max() - kSameX) {
        breaks.push_back(s.x_atomic);
      }
    }
    breaks.push_back(model_.x_max());
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end(),
                             [](double a, double b) { return b - a <= kSameX; }),
                 breaks.end());
    return breaks;
  }

  // Doubles the mu intervals until linear interpolation in mu meets the tolerance at the
  // breakpoints and at the middle of every segment, or the limit is reached.
  int ChooseMuNodes(const std::vector<double>& breaks, bool* met) const {
    std::vector<double> xs = breaks;
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
      xs.push_back(0.5 * (breaks[b] + breaks[b + 1]));
    }
    const int limit = std::max(2, options_.max_mu_intervals);
    for (int intervals = std::min(limit, std::max(2, options_.min_mu_intervals));; intervals *= 2) {
      const int mu_nodes = intervals + 1;
      std::vector<double> worst(xs.size() * colorimeters_.size(), 0.0);
      ParallelFor(static_cast<int>(worst.size()), 1, threads_, [&](int lo, int hi) {
        CheckCancel(options_.cancel);
        for (int task = lo; task < hi; ++task) {
          const int c = task % static_cast<int>(colorimeters_.size());
          const DirectReflection direct = Direct(c, xs[task / colorimeters_.size()]);
          const std::vector<double> row = Row(direct, mu_nodes);
          ColourError error;
          for (int m = 0; m < intervals; ++m) {
            const double mu = (m + 0.5) / intervals;
            Accumulate(direct.FresnelXYZ(mu), RowAt(row.data(), mu_nodes, mu),
                       colorimeters_[c].White(), &error);
          }
          worst[task] = error.de00;
        }
      });
      if (*std::max_element(worst.begin(), worst.end()) <= options_.tolerance_de00) {
        return mu_nodes;
      }
      if (2 * intervals > limit) {
        *met = false;
        return mu_nodes;
      }
    }
  }

  // Smooth-surface rows at the nodes of one segment, for every colorimeter:
  // rows[c][node * 3 * mu_nodes + ...].
  std::vector<std::vector<double>> SegmentRows(double x_lo, double x_hi, int intervals,
                                               int mu_nodes) const {
    std::vector<std::vector<double>> rows(colorimeters_.size());
    for (auto& r : rows) r.resize(static_cast<std::size_t>(intervals + 1) * 3 * mu_nodes);
    const int nc = static_cast<int>(colorimeters_.size());
    ParallelFor((intervals + 1) * nc, 1, threads_, [&](int lo, int hi) {
      CheckCancel(options_.cancel);
      for (int task = lo; task < hi; ++task) {
        const int c = task % nc, i = task / nc;
        const std::vector<double> row =
            Row(Direct(c, SegmentNode(x_lo, x_hi, intervals, i)), mu_nodes);
        std::copy(row.begin(), row.end(),
                  rows[c].begin() + static_cast<std::size_t>(i) * row.size());
      }
    });
    return rows;
  }

  // Largest dE00 at the segment's interval midpoints (at the mu nodes).
  double SegmentMidpointError(double x_lo, double x_hi, int intervals, int mu_nodes,
                              const std::vector<std::vector<double>>& rows) const {
    const CompositionSegment seg{x_lo, x_hi, intervals, 0};
    const int nc = static_cast<int>(colorimeters_.size());
    std::vector<double> worst(static_cast<std::size_t>(intervals) * nc, 0.0);
    ParallelFor(intervals * nc, 1, threads_, [&](int lo, int hi) {
      CheckCancel(options_.cancel);
      for (int task = lo; task < hi; ++task) {
        const int c = task % nc, i = task / nc;
        const double x = x_lo + (i + 0.5) * (x_hi - x_lo) / intervals;
        const DirectReflection direct = Direct(c, x);
        double w[4];
        const int first = SegmentWeights(seg, x, w);
        ColourError error;
        for (int m = 0; m < mu_nodes; ++m) {
          double xyz[3] = {0.0, 0.0, 0.0};
          for (int q = 0; q < 4; ++q) {
            const double* p = &rows[c][(static_cast<std::size_t>(first + q) * mu_nodes + m) * 3];
            for (int k = 0; k < 3; ++k) xyz[k] += w[q] * p[k];
          }
          Accumulate(direct.FresnelXYZ(static_cast<double>(m) / (mu_nodes - 1)),
                     {xyz[0], xyz[1], xyz[2]}, colorimeters_[c].White(), &error);
        }
        worst[task] = error.de00;
      }
    });
    return *std::max_element(worst.begin(), worst.end());
  }

  void ChooseSegments(const std::vector<double>& breaks, CompositionTable* table) const {
    table->illuminants.resize(colorimeters_.size());
    for (std::size_t c = 0; c < colorimeters_.size(); ++c) {
      table->illuminants[c].illuminant = colorimeters_[c].illuminant();
      table->illuminants[c].white = colorimeters_[c].White();
      table->illuminants[c].xyz.resize(options_.roughness.size());
    }
    const int per_unit = std::max(1, options_.min_intervals_per_unit_x);
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
      const double lo = breaks[b], hi = breaks[b + 1];
      const int limit =
          std::max(3, static_cast<int>(std::ceil(options_.max_intervals_per_unit_x * (hi - lo))));
      int intervals =
          std::min(limit, std::max(3, static_cast<int>(std::ceil(per_unit * (hi - lo)))));
      std::vector<std::vector<double>> rows;
      for (;;) {
        rows = SegmentRows(lo, hi, intervals, table->mu_nodes);
        if (SegmentMidpointError(lo, hi, intervals, table->mu_nodes, rows) <=
            options_.tolerance_de00) {
          break;
        }
        if (2 * intervals > limit) {
          table->tolerance_met = false;
          break;
        }
        intervals *= 2;
      }
      table->segments.push_back({lo, hi, intervals, static_cast<int>(table->x_nodes.size())});
      for (int i = 0; i <= intervals; ++i) {
        table->x_nodes.push_back(SegmentNode(lo, hi, intervals, i));
      }
      for (std::size_t c = 0; c < colorimeters_.size(); ++c) {
        auto& dst = table->illuminants[c].xyz[0];
        dst.insert(dst.end(), rows[c].begin(), rows[c].end());
      }
    }
  }

  // Rough tables and the colour uncertainty at every node.
  void FillTables(CompositionTable* table) const {
    const int nodes = static_cast<int>(table->x_nodes.size());
    const int nc = static_cast<int>(colorimeters_.size());
    const int nr = static_cast<int>(options_.roughness.size());
    const int na = static_cast<int>(options_.sigma_angles_deg.size());
    const std::size_t row_size = 3 * static_cast<std::size_t>(table->rough_mu_nodes);
    const bool sigma = model_.HasUncertainty() && na > 0;
    for (auto& ill : table->illuminants) {
      for (int r = 1; r < nr; ++r) ill.xyz[r].resize(nodes * row_size);
      if (sigma) ill.sigma_de00.resize(static_cast<std::size_t>(nodes) * na);
    }
    ParallelFor(nodes * nc, 1, threads_, [&](int lo, int hi) {
      CheckCancel(options_.cancel);
      for (int task = lo; task < hi; ++task) {
        const int c = task % nc, i = task / nc;
        IlluminantTable& ill = table->illuminants[c];
        const double x = table->x_nodes[i];
        if (nr > 1) {
          const DirectReflection direct = Direct(c, x);
          for (int r = 1; r < nr; ++r) {
            const std::vector<double> row =
                Row(direct.WithRoughness(options_.roughness[r]), table->rough_mu_nodes);
            std::copy(row.begin(), row.end(), ill.xyz[r].begin() + i * row_size);
          }
        }
        if (sigma) {
          const std::vector<double> s =
              color::DeltaE00Sigma(colorimeters_[c], model_, x, options_.sigma_angles_deg);
          for (int a = 0; a < na; ++a) {
            ill.sigma_de00[static_cast<std::size_t>(i) * na + a] = std::max(0.0, s[a]);
          }
        }
      }
    });
  }

  // The errors of the final table at every node and midpoint in x and in mu.
  void MeasureErrors(CompositionTable* table) const {
    std::vector<double> xs;
    for (const CompositionSegment& seg : table->segments) {
      for (int i = 0; i <= seg.intervals; ++i) {
        xs.push_back(SegmentNode(seg.x_lo, seg.x_hi, seg.intervals, i));
        if (i < seg.intervals) {
          xs.push_back(seg.x_lo + (i + 0.5) * (seg.x_hi - seg.x_lo) / seg.intervals);
        }
      }
    }
    const int nc = static_cast<int>(colorimeters_.size());
    const int mu_checks = 2 * (table->mu_nodes - 1) + 1;
    std::vector<ColourError> errors(xs.size() * nc);
    ParallelFor(static_cast<int>(errors.size()), 4, threads_, [&](int lo, int hi) {
      CheckCancel(options_.cancel);
      for (int task = lo; task < hi; ++task) {
        const int c = task % nc;
        const double x = xs[task / nc];
        const DirectReflection direct = Direct(c, x);
        for (int m = 0; m < mu_checks; ++m) {
          const double mu = static_cast<double>(m) / (mu_checks - 1);
          Accumulate(direct.FresnelXYZ(mu), InterpolateCompositionTable(*table, c, 0, x, mu),
                     colorimeters_[c].White(), &errors[task]);
        }
      }
    });
    for (const ColourError& e : errors) {
      table->max_de00 = std::max(table->max_de00, e.de00);
      table->max_srgb8_difference = std::max(table->max_srgb8_difference, e.srgb8);
    }
    table->check_points = static_cast<int>(errors.size()) * mu_checks;
  }

  void FillSpectra(CompositionTable* table) const {
    const double lo = std::max(kColourTableMinNm, model_.lambda_min_nm());
    const double hi = std::min(kColourTableMaxNm, model_.lambda_max_nm());
    for (double l = std::ceil(lo / kGridStepNm - 1e-9) * kGridStepNm; l <= hi + 1e-9;
         l += kGridStepNm) {
      table->lambda_nm.push_back(std::min(l, hi));
    }
    const std::size_t nl = table->lambda_nm.size();
    const int nodes = static_cast<int>(table->x_nodes.size());
    table->n.resize(nodes * nl);
    table->k.resize(nodes * nl);
    table->r_normal.resize(nodes * nl);
    ParallelFor(nodes, 4, threads_, [&](int begin, int end) {
      CheckCancel(options_.cancel);
      for (int i = begin; i < end; ++i) {
        const auto index = model_.Index(table->x_nodes[i], table->lambda_nm);
        const std::vector<double> r = color::ReflectanceSpectrum(index, 0.0);
        for (std::size_t l = 0; l < nl; ++l) {
          table->n[i * nl + l] = index[l].real();
          table->k[i * nl + l] = index[l].imag();
          table->r_normal[i * nl + l] = r[l];
        }
      }
    });
  }

  const AlloyModel& model_;
  const std::vector<color::Colorimeter>& colorimeters_;
  const CompositionTableOptions& options_;
  int threads_;
};

}  // namespace

CompositionTable BuildCompositionTable(const AlloyModel& model,
                                       const std::vector<color::Colorimeter>& colorimeters,
                                       const CompositionTableOptions& options) {
  return Builder(model, colorimeters, options).Build();
}

color::XYZ InterpolateCompositionTable(const CompositionTable& table, int illuminant, int roughness,
                                       double x_atomic, double mu) {
  const auto& segments = table.segments;
  std::size_t s = 0;
  while (s + 1 < segments.size() && x_atomic > segments[s].x_hi) ++s;
  double w[4];
  const int first = SegmentWeights(segments[s], x_atomic, w);
  const std::vector<double>& xyz = table.illuminants[illuminant].xyz[roughness];
  const int mu_nodes = table.MuNodes(roughness);
  const std::size_t row_size = 3 * static_cast<std::size_t>(mu_nodes);
  color::XYZ sum{0.0, 0.0, 0.0};
  for (int q = 0; q < 4; ++q) {
    const color::XYZ c = RowAt(&xyz[(first + q) * row_size], mu_nodes, mu);
    sum.X += w[q] * c.X;
    sum.Y += w[q] * c.Y;
    sum.Z += w[q] * c.Z;
  }
  return sum;
}

std::vector<float> LatLongRadiance(Lighting lighting, double roughness_alpha, int width, int height,
                                   int threads) {
  if (width < 1 || height < 1) throw Error("environment map: empty size");
  const Environment environment(lighting);
  std::unique_ptr<PrefilteredEnvironment> prefiltered;
  if (roughness_alpha > 0.0) {
    prefiltered = std::make_unique<PrefilteredEnvironment>(environment, roughness_alpha,
                                                           ThreadCount(threads));
  }
  std::vector<float> texels(static_cast<std::size_t>(width) * height);
  for (int j = 0; j < height; ++j) {
    const double theta = (j + 0.5) * kPi / height;
    for (int i = 0; i < width; ++i) {
      const double phi = (i + 0.5) * 2.0 * kPi / width;
      const Vec3 w{std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi)};
      texels[static_cast<std::size_t>(j) * width + i] =
          static_cast<float>(prefiltered ? prefiltered->At(w) : environment.Radiance(w));
    }
  }
  return texels;
}

}  // namespace alloycolor::render
