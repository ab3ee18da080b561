#include "alloycolor/export/blender_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <mutex>

#include "alloycolor/color/material_color.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/core/units.h"
#include "alloycolor/export/renderer_materials.h"
#include "alloycolor/render/composition_table.h"
#include "alloycolor/render/image.h"
#include "alloycolor/render/shading.h"

namespace alloycolor::exports {
namespace {

constexpr double kSample16 = 65535.0;

color::RGB Clamped(const color::RGB& c) {
  return {std::clamp(c.r, 0.0, 1.0), std::clamp(c.g, 0.0, 1.0), std::clamp(c.b, 0.0, 1.0)};
}

double ColumnX(const BlenderTable& t, double i) {
  return t.x_min + i * (t.x_max - t.x_min) / (t.columns - 1);
}

// Blender's Linear lookup with Extension EXTEND at column position i and row position m
// (texel units from the first centre), on the stored samples.
color::RGB Bilinear(const BlenderTable& t, double i, double m) {
  i = std::clamp(i, 0.0, t.columns - 1.0);
  m = std::clamp(m, 0.0, t.rows - 1.0);
  const int i0 = std::min(static_cast<int>(i), t.columns - 2);
  const int m0 = std::min(static_cast<int>(m), t.rows - 2);
  const double fi = i - i0, fm = m - m0;
  double out[3];
  for (int c = 0; c < 3; ++c) {
    const auto at = [&](int mm, int ii) { return t.rgb[(mm * t.columns + ii) * 3 + c]; };
    out[c] = (1 - fm) * ((1 - fi) * at(m0, i0) + fi * at(m0, i0 + 1)) +
             fm * ((1 - fi) * at(m0 + 1, i0) + fi * at(m0 + 1, i0 + 1));
  }
  return {out[0], out[1], out[2]};
}

// The largest errors of the lookup against direct evaluation (see the header).
void MeasureError(const color::Colorimeter& d65, const AlloyModel& model, int threads,
                  BlenderTable* t) {
  const color::XYZ white = d65.White();
  std::mutex mutex;
  // Column positions 0, 0.5, 1, ...: odd ones are midpoints.
  const int positions = 2 * t->columns - 1;
  ParallelFor(positions, 1, ThreadCount(threads), [&](int begin, int end) {
    for (int p = begin; p < end; ++p) {
      const double i = 0.5 * p;
      const render::DirectReflection direct(d65, color::IndexOnGrid(d65, model, ColumnX(*t, i)),
                                            0.0);
      double de00 = 0.0;
      int srgb8 = 0, points = 0;
      for (int q = 0; q < 2 * t->rows - 1; ++q) {
        if (p % 2 == 0 && q % 2 == 0) continue;  // a texel centre
        const double m = 0.5 * q;
        const color::RGB exact =
            Clamped(color::LinearSRGBFromXYZ(direct.FresnelXYZ(m / (t->rows - 1))));
        const color::RGB baked = Bilinear(*t, i, m);
        de00 = std::max(de00,
                        color::DeltaE00(color::LabFromXYZ(color::XYZFromLinearSRGB(exact), white),
                                        color::LabFromXYZ(color::XYZFromLinearSRGB(baked), white)));
        const auto a = color::SRGB8FromLinear(exact), b = color::SRGB8FromLinear(baked);
        for (int c = 0; c < 3; ++c) srgb8 = std::max(srgb8, std::abs(a[c] - b[c]));
        ++points;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      t->max_de00 = std::max(t->max_de00, de00);
      t->max_srgb8_difference = std::max(t->max_srgb8_difference, srgb8);
      t->check_points += points;
    }
  });
}

nlohmann::json RgbJson(const color::RGB& c) { return {c.r, c.g, c.b}; }

std::string FileName(const std::string& path) { return path.substr(path.find_last_of('/') + 1); }

}  // namespace

BlenderTable BuildBlenderTable(const color::Colorimeter& d65, const AlloyModel& model,
                               const BlenderTableOptions& options) {
  if (options.columns < 2 || options.rows < 2 || options.columns > 8192 || options.rows > 8192) {
    throw Error("blender-table: columns and rows must be 2-8192");
  }
  render::CompositionTableOptions table_options;
  table_options.roughness = {0.0};
  table_options.sigma_angles_deg = {};
  // The page keeps its size down with 128 intervals per unit x at most, which leaves a
  // long segment (Zn to Cu70Zn30) 1.5 CIEDE2000 off; the image is resampled anyway, so
  // the table may refine until it meets its tolerance.
  table_options.max_intervals_per_unit_x = 2048;
  table_options.threads = options.threads;
  const render::CompositionTable table = render::BuildCompositionTable(model, {d65}, table_options);

  BlenderTable t;
  t.system = model.system();
  t.x_min = model.x_min();
  t.x_max = model.x_max();
  t.columns = options.columns;
  t.rows = options.rows;
  t.rgb.resize(static_cast<std::size_t>(t.columns) * t.rows * 3);
  const double mu82 = std::cos(kF82AngleDeg * kPi / 180.0);
  for (int i = 0; i < t.columns; ++i) {
    const double x = i == t.columns - 1 ? t.x_max : ColumnX(t, i);
    for (int m = 0; m < t.rows; ++m) {
      const double mu = static_cast<double>(m) / (t.rows - 1);
      const color::RGB c = Clamped(
          color::LinearSRGBFromXYZ(render::InterpolateCompositionTable(table, 0, 0, x, mu)));
      const double q[3] = {c.r, c.g, c.b};
      for (int k = 0; k < 3; ++k) {
        t.rgb[(m * t.columns + i) * 3 + k] = std::round(q[k] * kSample16) / kSample16;
      }
    }
    // Unclamped, as renderer_materials.h reports them.
    const color::RGB f0 =
        color::LinearSRGBFromXYZ(render::InterpolateCompositionTable(table, 0, 0, x, 1.0));
    const color::RGB f82 =
        color::LinearSRGBFromXYZ(render::InterpolateCompositionTable(table, 0, 0, x, mu82));
    t.f0.push_back(f0);
    t.f82_tint.push_back({f82.r / SchlickFresnel(f0.r, mu82), f82.g / SchlickFresnel(f0.g, mu82),
                          f82.b / SchlickFresnel(f0.b, mu82)});
  }
  MeasureError(d65, model, options.threads, &t);
  return t;
}

std::vector<OutputFile> BlenderTableFiles(const BlenderTable& t, const std::string& prefix,
                                          const std::string& material,
                                          const std::string& generator) {
  const std::string png_path = prefix + ".alloy-table.png";
  render::ImageRGBA16 image(t.columns, t.rows);
  for (int m = 0; m < t.rows; ++m) {
    // The PNG's first row is the top: mu = 1.
    const int y = t.rows - 1 - m;
    for (int i = 0; i < t.columns; ++i) {
      std::uint16_t* p = image.Pixel(i, y);
      for (int c = 0; c < 3; ++c) {
        p[c] =
            static_cast<std::uint16_t>(std::lround(t.rgb[(m * t.columns + i) * 3 + c] * kSample16));
      }
      p[3] = 65535;
    }
  }
  const std::string png = render::DataPngBytes(
      image, {{"Software", generator}, {"Description", "linear sRGB reflection of " + material}});

  nlohmann::json f0 = nlohmann::json::array(), tint = nlohmann::json::array();
  for (int i = 0; i < t.columns; ++i) {
    f0.push_back(RgbJson(t.f0[i]));
    tint.push_back(RgbJson(t.f82_tint[i]));
  }
  const bool gold = IsGoldAlloy(t.system);
  const nlohmann::json doc = {
      {"format", "alloycolor blender-table 1"},
      {"material", material},
      {"system", t.system.Name()},
      {"elements", {t.system.a.symbol, t.system.b.symbol}},
      {"molar_masses_g_mol", {t.system.a.atomic_mass, t.system.b.atomic_mass}},
      {"composition", "x: atomic fraction of " + std::string(t.system.a.symbol)},
      {"x_range", {t.x_min, t.x_max}},
      {"karat", gold},
      {"gold_element", gold ? (std::string(t.system.a.symbol) == "Au" ? 0 : 1) : -1},
      {"image", FileName(png_path)},
      {"columns", t.columns},
      {"rows", t.rows},
      {"layout",
       "linear sRGB (Rec. 709, D65), 16-bit, clamped to [0, 1], colour space Non-Color; column i "
       "at x = x_min + i (x_max - x_min) / (columns - 1), row m from the bottom at mu = cos "
       "theta = m / (rows - 1); Blender reads u = (1/2 + i) / columns, v = (1/2 + m) / rows, "
       "Linear, Extension EXTEND"},
      {"colour", "D65, CIE 1931 2-degree observer, smooth surface (roughness 0)"},
      {"f0", f0},
      {"f82_tint", tint},
      {"lookup_error",
       {{"max_delta_e00", t.max_de00},
        {"max_srgb8_difference", t.max_srgb8_difference},
        {"check_points", t.check_points},
        {"against",
         "direct spectral evaluation between texel centres, bilinear lookup of the stored "
         "samples"}}},
      {"generator", generator}};
  return {{png_path, png}, {prefix + ".alloy-table.json", JsonText(doc, 2) + "\n"}};
}

}  // namespace alloycolor::exports
