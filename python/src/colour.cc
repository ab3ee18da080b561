// The bindings of colour: colours of models and spectra (color/material_color.h, sweep.h),
// from colour to composition and tolerance windows (color/match.h).
#include <pybind11/stl.h>

#include <complex>
#include <map>
#include <utility>

#include "alloycolor/color/match.h"
#include "alloycolor/color/material_color.h"
#include "alloycolor/color/sweep.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/setting.h"
#include "bindings.h"

namespace alloycolor::python {
namespace {

// ---- colour ----------------------------------------------------------------------------

struct ColorArrays {
  py::array_t<double> xyz, lab, linear_srgb, paper_rgb, sigma;
  py::array_t<std::uint8_t> srgb8;
};

py::dict ColorDict(ColorArrays& c, bool with_sigma) {
  py::dict d;
  d["xyz"] = c.xyz;
  d["lab"] = c.lab;
  d["linear_srgb"] = c.linear_srgb;
  d["srgb8"] = c.srgb8;
  d["paper_rgb"] = c.paper_rgb;
  d["sigma"] = with_sigma ? py::object(c.sigma) : py::object(py::none());
  return d;
}

ColorArrays MakeColorArrays(py::ssize_t count) {
  ColorArrays c;
  c.xyz = py::array_t<double>({count, py::ssize_t{3}});
  c.lab = py::array_t<double>({count, py::ssize_t{3}});
  c.linear_srgb = py::array_t<double>({count, py::ssize_t{3}});
  c.paper_rgb = py::array_t<double>({count, py::ssize_t{3}});
  c.srgb8 = py::array_t<std::uint8_t>({count, py::ssize_t{3}});
  c.sigma = py::array_t<double>(count);
  return c;
}

struct ColorPointers {
  double *xyz, *lab, *lin, *paper, *sigma;
  std::uint8_t* srgb8;
};

ColorPointers Pointers(ColorArrays& c) {
  return {c.xyz.mutable_data(),       c.lab.mutable_data(),   c.linear_srgb.mutable_data(),
          c.paper_rgb.mutable_data(), c.sigma.mutable_data(), c.srgb8.mutable_data()};
}

void Store(const color::ColorResult& r, std::size_t i, const ColorPointers& p) {
  const double xyz[3] = {r.xyz.X, r.xyz.Y, r.xyz.Z};
  const double lab[3] = {r.lab.L, r.lab.a, r.lab.b};
  const double lin[3] = {r.linear_srgb.r, r.linear_srgb.g, r.linear_srgb.b};
  const double paper[3] = {r.paper_rgb.r, r.paper_rgb.g, r.paper_rgb.b};
  for (int c = 0; c < 3; ++c) {
    p.xyz[3 * i + c] = xyz[c];
    p.lab[3 * i + c] = lab[c];
    p.lin[3 * i + c] = lin[c];
    p.paper[3 * i + c] = paper[c];
    p.srgb8[3 * i + c] = r.srgb8[c];
  }
}

// Colours of a model at x[i] seen at angle[i] (1-D arrays of one length). Compositions are
// grouped by angle; an angle with many compositions uses ColorSweep's XYZ table
// (BuildTableFor: error at most color::kSweepTableTolerance, checked while it is built)
// unless exact is asked for, as `alloycolor sweep` does.
py::dict ModelColors(const AlloyModel& model, const Array& x_in, const Array& angle_in,
                     const std::string& illuminant, int observer_deg, bool sigma, bool exact) {
  if (x_in.size() != angle_in.size()) throw Error("color: x and angle_deg differ in length");
  const std::vector<double> xs = ToVector(x_in), angles = ToVector(angle_in);
  for (double a : angles) CheckAngleDeg("angle_deg", a);
  for (double x : xs) model.CheckInRange(x);
  const bool with_sigma = sigma && model.HasUncertainty();
  ColorArrays arrays = MakeColorArrays(static_cast<py::ssize_t>(xs.size()));
  const ColorPointers p = Pointers(arrays);
  RunInterruptible(
      [&](const CancelCheck& cancel) {
        const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
        std::map<double, std::vector<std::size_t>> by_angle;
        for (std::size_t i = 0; i < xs.size(); ++i) by_angle[angles[i]].push_back(i);
        for (const auto& [angle, indices] : by_angle) {
          color::ColorSweep sweep(colorimeter, model, angle);
          double lo = xs[indices[0]], hi = lo;
          for (std::size_t i : indices) lo = std::min(lo, xs[i]), hi = std::max(hi, xs[i]);
          sweep.BuildTableFor(indices.size(), lo, hi, exact);
          for (std::size_t k = 0; k < indices.size(); ++k) {
            // A one-sigma takes draws: each is a step; a table's colours, a block of them.
            if (with_sigma || k % 4096 == 0) cancel();
            const std::size_t i = indices[k];
            const color::XYZ xyz = sweep.has_table() ? sweep.XYZAt(xs[i]) : sweep.ExactXYZ(xs[i]);
            Store(color::ColorFromXYZ(colorimeter, xyz), i, p);
            p.sigma[i] = with_sigma ? color::DeltaE00Sigma(colorimeter, model, xs[i], angle) : 0.0;
          }
        }
      },
      !with_sigma && xs.size() <= 64);  // a few colours: well under a millisecond
  return ColorDict(arrays, with_sigma);
}

py::dict SpectrumColors(const NkSpectrum& nk, const Array& angle_in, const std::string& illuminant,
                        int observer_deg) {
  const std::vector<double> angles = ToVector(angle_in);
  for (double a : angles) CheckAngleDeg("angle_deg", a);
  ColorArrays arrays = MakeColorArrays(static_cast<py::ssize_t>(angles.size()));
  const ColorPointers p = Pointers(arrays);
  RunInterruptible([&](const CancelCheck& cancel) {
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    const std::vector<std::complex<double>> index = color::IndexOnGrid(colorimeter, nk);
    for (std::size_t i = 0; i < angles.size(); ++i) {
      if (i % 4096 == 0) cancel();
      Store(color::ColorFromXYZ(colorimeter, color::MaterialXYZ(colorimeter, index, angles[i])), i,
            p);
    }
  });
  return ColorDict(arrays, false);
}

// ---- from colour to composition ------------------------------------------------------------

// What `work` returns; an Error it throws named as `alloycolor match` names its target's
// option ("hex: ...", the package's keyword), unless the message names it already.
template <typename Work>
auto NamedTarget(const std::string& name, const Work& work) {
  try {
    return work();
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(name + ":", 0) == 0) throw;
    throw Error(name + ": " + what);
  }
}

// The best match for each target colour (rows of an (N, 3) CIELAB array), with the number
// of local minima within the margin and, with all_minima, every one of them.
py::dict ModelMatch(const AlloyModel& model, const Array& lab_in, const std::string& target,
                    double angle_deg, const std::string& illuminant, int observer_deg,
                    double target_sigma, double margin, bool sigma, bool all_minima) {
  if (lab_in.ndim() != 2 || lab_in.shape(1) != 3) {
    throw Error("match: the targets must be an (N, 3) array of CIELAB L*, a*, b*");
  }
  CheckAngleDeg("angle_deg", angle_deg);
  const py::ssize_t n = lab_in.shape(0);
  // Before the work: each target as the program checks its --lab, --xyz or --hex.
  for (py::ssize_t i = 0; i < n; ++i) {
    const double* row = lab_in.data() + 3 * i;
    NamedTarget(target, [&] { return color::CheckTargetLab({row[0], row[1], row[2]}), 0; });
  }
  py::array_t<double> x(n), x_sigma(n), de00(n), lab({n, py::ssize_t{3}});
  py::array_t<bool> reachable(n);
  py::array_t<int> minima(n);
  std::vector<std::vector<color::Match>> every(all_minima ? n : 0);
  const double* in = lab_in.data();
  double *px = x.mutable_data(), *ps = x_sigma.mutable_data(), *pd = de00.mutable_data(),
         *pl = lab.mutable_data();
  bool* pr = reachable.mutable_data();
  int* pm = minima.mutable_data();
  RunInterruptible([&](const CancelCheck& cancel) {
    color::MatchOptions options;
    options.angle_deg = angle_deg;
    options.target_sigma_de00 = target_sigma;
    options.margin = margin;
    options.with_sigma = sigma;
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer_deg);
    // Without the one-sigma, blocks of targets over the cores, a matcher each (a matcher's
    // sweep has scratch space, so one is not shared between threads).
    constexpr int kBlock = 2048;
    ParallelFor(static_cast<int>(n), kBlock, !sigma && n >= 2 * kBlock ? ThreadCount(0) : 1,
                [&](int begin, int end) {
                  const color::ColourMatcher matcher(colorimeter, model, options);
                  for (py::ssize_t i = begin; i < end; ++i) {
                    cancel();
                    std::vector<color::Match> found =
                        matcher.Find({in[3 * i], in[3 * i + 1], in[3 * i + 2]});
                    const color::Match& best = found.front();
                    px[i] = best.x_atomic;
                    ps[i] = best.x_sigma;
                    pd[i] = best.de00;
                    pl[3 * i] = best.lab.L;
                    pl[3 * i + 1] = best.lab.a;
                    pl[3 * i + 2] = best.lab.b;
                    pr[i] = best.de00 <= color::kReachableDeltaE00;
                    pm[i] = static_cast<int>(found.size());
                    if (all_minima) every[i] = std::move(found);
                  }
                });
  });
  py::dict d;
  d["x"] = x;
  d["x_sigma"] = x_sigma;
  d["de00"] = de00;
  d["lab"] = lab;
  d["reachable"] = reachable;
  d["n_minima"] = minima;
  if (all_minima) {
    py::list lists;
    for (const auto& found : every) {
      py::list rows;
      for (const color::Match& m : found) {
        py::dict r;
        r["x_atomic"] = m.x_atomic;
        r["x_sigma"] = m.x_sigma;
        r["de00"] = m.de00;
        rows.append(r);
      }
      lists.append(rows);
    }
    d["matches"] = lists;
  }
  return d;
}

// The tolerance window around each composition.
py::dict ModelTolerance(const AlloyModel& model, const Array& x_in, double de00,
                        const std::vector<double>& angles_deg,
                        const std::vector<std::string>& illuminants, int observer_deg) {
  const std::vector<double> xs = ToVector(x_in);
  for (double a : angles_deg) CheckAngleDeg("angles_deg", a);
  const py::ssize_t n = static_cast<py::ssize_t>(xs.size());
  py::array_t<double> low(n), high(n), speed(n);
  py::array_t<bool> clipped_low(n), clipped_high(n);
  double *pl = low.mutable_data(), *ph = high.mutable_data(), *ps = speed.mutable_data();
  bool *pcl = clipped_low.mutable_data(), *pch = clipped_high.mutable_data();
  RunInterruptible([&](const CancelCheck& cancel) {
    std::vector<color::Colorimeter> colorimeters;
    for (const std::string& name : illuminants) {
      colorimeters.push_back(GetColorimeter(name, observer_deg));
    }
    color::ToleranceOptions options;
    options.de00 = de00;
    options.angles_deg = angles_deg;
    for (py::ssize_t i = 0; i < n; ++i) {
      cancel();
      const color::ToleranceWindow w = color::Tolerance(colorimeters, model, xs[i], options);
      pl[i] = w.x_low;
      ph[i] = w.x_high;
      ps[i] = w.de00_per_x / 100.0;
      pcl[i] = w.clipped_low;
      pch[i] = w.clipped_high;
    }
  });
  py::dict d;
  d["x_low"] = low;
  d["x_high"] = high;
  d["de00_per_at_percent"] = speed;
  d["clipped_low"] = clipped_low;
  d["clipped_high"] = clipped_high;
  return d;
}

}  // namespace

void BindColour(py::module_& m, SpectrumClass& spectrum, ModelClass& model) {
  m.def("illuminants", &color::IlluminantNames);
  m.def("_lab_from_hex", [](const std::string& hex, const std::string& illuminant, int observer) {
    const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer);
    const color::Lab lab = NamedTarget("hex", [&] { return color::LabFromHex(colorimeter, hex); });
    return std::vector<double>{lab.L, lab.a, lab.b};
  });
  m.def("_lab_from_xyz",
        [](double X, double Y, double Z, const std::string& illuminant, int observer) {
          const color::Colorimeter& colorimeter = GetColorimeter(illuminant, observer);
          const color::Lab lab = NamedTarget("xyz", [&] {
            return color::LabFromTargetXYZ(colorimeter, {X, Y, Z});
          });
          return std::vector<double>{lab.L, lab.a, lab.b};
        });
  spectrum.def("_color", &SpectrumColors);
  model.def("_color", &ModelColors).def("_match", &ModelMatch).def("_tolerance", &ModelTolerance);
}

}  // namespace alloycolor::python
