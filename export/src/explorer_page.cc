#include "alloycolor/export/explorer_page.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "alloycolor/color/material_color.h"
#include "alloycolor/color/suggest.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/markup.h"
#include "alloycolor/core/parallel.h"
#include "alloycolor/render/composition_table.h"
#include "alloycolor/render/renderer.h"
#include "alloycolor/render/shading.h"
#include "explorer_assets.h"

namespace alloycolor::exports {
namespace {

constexpr int kMirrorEnvironmentWidth = 512;
constexpr int kRoughEnvironmentWidth = 256;

// A spectrum drawn beside the prediction: a measured training sample, or the model at a
// training composition when the model file keeps no spectra.
struct ExploreSample {
  double x_atomic;
  std::string label;
  bool measured;
  std::vector<double> lambda_nm, n, k, r_normal;
};

// Studio light, one per roughness: render::LatLongRadiance on width x height.
struct EnvironmentMap {
  int width, height;
  std::vector<float> texels;
};

struct PageInputs {
  const AlloyModel* model = nullptr;
  std::string source;
  int observer_deg = 2;
  const render::CompositionTable* table = nullptr;
  std::vector<std::string> finish_names;  // one per table roughness
  std::vector<ExploreSample> samples;
  std::string samples_note;
  render::NormalMap sphere, ring;
  std::vector<EnvironmentMap> environment_maps;
  std::string generator;
  // Where to measure next (color/suggest.h, under the first illuminant) and the samples the
  // fit found suspect, marked on the composition chart.
  std::vector<color::Suggestion> suggestions;
};

using nlohmann::json;

std::string Base64(const std::vector<std::uint8_t>& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

void PutLE(std::uint32_t v, int bytes, std::vector<std::uint8_t>* out) {
  for (int b = 0; b < bytes; ++b) out->push_back(static_cast<std::uint8_t>(v >> (8 * b)));
}

template <typename Range>
std::string Float32Base64(const Range& values) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(values.size() * 4);
  for (double v : values) {
    const float f = std::isfinite(v) ? static_cast<float>(v) : 0.0f;
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    PutLE(bits, 4, &bytes);
  }
  return Base64(bytes);
}

// Coverage as uint8 for every pixel; then x, y of the normal as int16 for the covered ones.
json TileJson(const render::NormalMap& map) {
  std::vector<std::uint8_t> coverage, normals;
  const std::size_t pixels = map.coverage.size();
  for (std::size_t p = 0; p < pixels; ++p) {
    const int c = static_cast<int>(std::lround(255.0 * map.coverage[p]));
    coverage.push_back(static_cast<std::uint8_t>(std::clamp(c, 0, 255)));
    if (c <= 0) continue;
    for (int axis = 0; axis < 2; ++axis) {
      const long q = std::lround(32767.0 * std::clamp(map.normal[3 * p + axis], -1.0f, 1.0f));
      PutLE(static_cast<std::uint32_t>(static_cast<std::uint16_t>(static_cast<std::int16_t>(q))), 2,
            &normals);
    }
  }
  return {{"size", map.size}, {"coverage", Base64(coverage)}, {"normals", Base64(normals)}};
}

json EnvironmentJson(const std::vector<EnvironmentMap>& maps) {
  json out = json::array();
  for (const auto& m : maps) {
    const std::vector<float>& map = m.texels;
    float top = 0.0f;
    for (float v : map) top = std::max(top, v);
    std::vector<std::uint8_t> bytes;
    for (float v : map) {
      const long q = top > 0.0f ? std::lround(65535.0 * std::max(0.0f, v) / top) : 0;
      PutLE(static_cast<std::uint32_t>(q), 2, &bytes);
    }
    out.push_back({{"width", m.width},
                   {"height", m.height},
                   {"scale", top / 65535.0},
                   {"texels", Base64(bytes)}});
  }
  return out;
}

json TableJson(const render::CompositionTable& t) {
  json segments = json::array();
  for (const auto& s : t.segments) segments.push_back({s.x_lo, s.x_hi, s.intervals, s.first_node});
  json illuminants = json::array();
  for (const auto& ill : t.illuminants) {
    json xyz = json::array();
    for (const auto& r : ill.xyz) xyz.push_back(Float32Base64(r));
    json entry = {
        {"name", ill.illuminant}, {"white", {ill.white.X, ill.white.Y, ill.white.Z}}, {"xyz", xyz}};
    if (!ill.sigma_de00.empty()) entry["sigma"] = Float32Base64(ill.sigma_de00);
    illuminants.push_back(entry);
  }
  return {{"segments", segments},
          {"nodes", t.x_nodes.size()},
          {"mu_nodes", t.mu_nodes},
          {"rough_mu_nodes", t.rough_mu_nodes},
          {"roughness", t.roughness},
          {"illuminants", illuminants},
          {"sigma_angles_deg", t.sigma_angles_deg},
          {"lambda_nm", t.lambda_nm},
          {"n", Float32Base64(t.n)},
          {"k", Float32Base64(t.k)},
          {"r", Float32Base64(t.r_normal)},
          {"max_de00", t.max_de00},
          {"max_srgb8_difference", t.max_srgb8_difference},
          {"check_points", t.check_points},
          {"tolerance_met", t.tolerance_met}};
}

// The XYZ -> linear sRGB matrix of colorimetry.h, column by column.
json SRGBMatrixJson() {
  json m = json::array({json::array(), json::array(), json::array()});
  const color::XYZ unit[3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  double rows[3][3];
  for (int c = 0; c < 3; ++c) {
    const color::RGB column = color::LinearSRGBFromXYZ(unit[c]);
    rows[0][c] = column.r;
    rows[1][c] = column.g;
    rows[2][c] = column.b;
  }
  for (int r = 0; r < 3; ++r) m[r] = {rows[r][0], rows[r][1], rows[r][2]};
  return m;
}

// page with each @KEY@ replaced by values.at(KEY), in one pass, so that a value is never
// read as a key.
std::string FillTemplate(std::string_view page,
                         const std::map<std::string_view, std::string_view>& values) {
  std::string out;
  std::size_t at = 0;
  for (std::size_t open; (open = page.find('@', at)) != page.npos;) {
    const std::size_t close = page.find('@', open + 1);
    out += page.substr(at, open - at);
    out += values.at(page.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  out += page.substr(at);
  return out;
}

std::string Format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

std::string FinishName(double alpha) {
  if (alpha == 0.0) return "polished";
  if (alpha <= 0.25) return "satin";
  if (alpha <= 0.5) return "matte";
  return "rough";
}

ExploreSample SampleFromIndex(double x, const std::string& label, bool measured,
                              const std::vector<double>& lambda_nm,
                              const std::vector<std::complex<double>>& index) {
  ExploreSample s{x, label, measured, lambda_nm, {}, {}, color::ReflectanceSpectrum(index, 0.0)};
  for (const auto& nk : index) {
    s.n.push_back(nk.real());
    s.k.push_back(nk.imag());
  }
  return s;
}

std::string Percent(double x) { return Format("%.4g", 100.0 * x) + " at%"; }

// The spectra drawn beside the prediction: measured when the data set is at hand
// (options.data) or the model keeps them (paper, eps-linear); else the model at the
// training compositions.
std::vector<ExploreSample> Samples(const ExplorerOptions& o, const AlloyModel& model,
                                   const render::CompositionTable& table, std::string* note) {
  std::vector<ExploreSample> samples;
  const double lo = table.lambda_nm.front(), hi = table.lambda_nm.back();
  const auto in_range = [&](const std::vector<double>& lambda, const std::vector<double>& n,
                            const std::vector<double>& k, double x, const std::string& label) {
    std::vector<double> l2;
    std::vector<std::complex<double>> index;
    for (std::size_t i = 0; i < lambda.size(); ++i) {
      if (lambda[i] < lo - 1e-9 || lambda[i] > hi + 1e-9) continue;
      l2.push_back(lambda[i]);
      index.emplace_back(n[i], k[i]);
    }
    if (l2.size() >= 2) samples.push_back(SampleFromIndex(x, label, true, l2, index));
  };
  const std::string a = model.system().a.symbol;
  if (o.data != nullptr) {
    for (const Sample& s : o.data->samples) {
      in_range(s.nk.lambda_nm, s.nk.n, s.nk.k, s.x_atomic,
               "measured " + a + " " + Percent(s.x_atomic) + " (" + s.file + ")");
    }
    *note = "Measured spectra from the data set " + o.data_name + ".";
    return samples;
  }
  const nlohmann::json params = model.ToJson()["parameters"];
  if (params.contains("samples") && params["samples"].is_array()) {
    for (const auto& s : params["samples"]) {
      in_range(s["lambda_nm"].get<std::vector<double>>(), s["n"].get<std::vector<double>>(),
               s["k"].get<std::vector<double>>(), s["x"].get<double>(),
               "measured " + a + " " + Percent(s["x"].get<double>()) + " (" +
                   s["source"].get<std::string>() + ")");
    }
    *note = "Measured spectra as kept in the model file.";
    return samples;
  }
  for (const TrainingSample& t : model.training_samples()) {
    samples.push_back(SampleFromIndex(t.x_atomic,
                                      "the model at the training composition " + a + " " +
                                          Percent(t.x_atomic) + " (" + t.file + ")",
                                      false, table.lambda_nm,
                                      model.Index(t.x_atomic, table.lambda_nm)));
  }
  *note = "The " + model.method() +
          " model file keeps no spectra: the dotted lines are the model at its training "
          "compositions, not the measurements (give the data set to draw those).";
  return samples;
}

std::string PageHtml(const PageInputs& in) {
  const AlloyModel& model = *in.model;
  const AlloySystem& system = model.system();
  json training = json::array();
  for (const TrainingSample& s : model.training_samples()) {
    training.push_back({{"x", s.x_atomic}, {"file", s.file}});
  }
  json suspects = json::array();
  for (const SampleNote& n : model.suspect_samples()) {
    suspects.push_back({{"x", n.x_atomic}, {"file", n.file}, {"reason", n.reason}});
  }
  json suggestions = json::array();
  for (const color::Suggestion& s : in.suggestions) {
    json entry = {{"x", s.x_atomic}};
    if (std::isfinite(s.sigma)) entry["sigma"] = s.sigma;
    suggestions.push_back(entry);
  }
  json samples = json::array();
  for (const ExploreSample& s : in.samples) {
    samples.push_back({{"x", s.x_atomic},
                       {"label", s.label},
                       {"measured", s.measured},
                       {"lambda_nm", s.lambda_nm},
                       {"n", s.n},
                       {"k", s.k},
                       {"r", s.r_normal}});
  }
  const json data = {{"format", "alloycolor-explorer"},
                     {"version", 1},
                     {"generator", in.generator},
                     {"system",
                      {{"a", system.a.symbol},
                       {"b", system.b.symbol},
                       {"mass_a", system.a.atomic_mass},
                       {"mass_b", system.b.atomic_mass}}},
                     {"method", model.method()},
                     {"source", in.source},
                     {"observer", in.observer_deg},
                     {"x_range", {model.x_min(), model.x_max()}},
                     {"training", training},
                     {"has_sigma", model.HasUncertainty()},
                     {"no_error_bar", model.NoErrorBarReason()},
                     {"suspects", suspects},
                     {"suggestions", suggestions},
                     {"srgb_matrix", SRGBMatrixJson()},
                     {"table", TableJson(*in.table)},
                     {"finishes", in.finish_names},
                     {"samples", samples},
                     {"samples_note", in.samples_note},
                     {"tiles", {{"sphere", TileJson(in.sphere)}, {"ring", TileJson(in.ring)}}},
                     {"environment", EnvironmentJson(in.environment_maps)}};
  // A name that is not valid UTF-8 is shown with U+FFFD rather than refused.
  const std::string data_text =
      EscapeJsonForScript(data.dump(-1, ' ', false, json::error_handler_t::replace));
  const std::string title =
      EscapeXml("alloycolor explorer: " + system.Name() + ", " + model.method());
  const std::string system_name = EscapeXml(system.Name());
  return FillTemplate(explorer::kPageHtml, {{"TITLE", title},
                                            {"SYSTEM", system_name},
                                            {"STYLE", explorer::kPageCss},
                                            {"DATA", data_text},
                                            {"COLOUR_JS", explorer::kColourJs},
                                            {"INPUT_JS", explorer::kInputJs},
                                            {"APP_JS", explorer::kAppJs}});
}

}  // namespace

void CheckExplorerOptions(const ExplorerOptions& o, OptionSpelling spelling) {
  const std::string dashes = spelling == OptionSpelling::kFlag ? "--" : "";
  if (o.size < kExplorerMinSize || o.size > kExplorerMaxSize) {
    throw Error(dashes + "size: " + std::to_string(o.size) + " lies outside " +
                std::to_string(kExplorerMinSize) + "-" + std::to_string(kExplorerMaxSize) +
                " pixels");
  }
  if (!(o.tolerance_de00 >= kExplorerMinTolerance && o.tolerance_de00 <= kExplorerMaxTolerance)) {
    throw Error(dashes + "tolerance: " + Format("%g", o.tolerance_de00) +
                " lies outside 0.0001-0.5 (dE00)");
  }
  if (o.roughness.empty()) throw Error(dashes + "roughness: no finish given");
  for (double r : o.roughness) {
    if (!(r >= 0.0 && r <= render::kMaxRoughness)) {
      throw Error(dashes + "roughness: " + Format("%g", r) + " lies outside 0-1 (GGX alpha)");
    }
  }
  if (o.threads < 0) throw Error(dashes + "threads: " + std::to_string(o.threads) + " is negative");
}

ExplorerPage BuildExplorerPage(const AlloyModel& model,
                               const std::vector<color::Colorimeter>& colorimeters,
                               const ExplorerOptions& o) {
  CheckExplorerOptions(o);
  if (colorimeters.empty()) throw Error("explorer: no illuminant");
  for (const color::Colorimeter& c : colorimeters) {
    if (c.observer_deg() != colorimeters.front().observer_deg()) {
      throw Error("explorer: the illuminants are given for two observers");
    }
  }
  render::CompositionTableOptions table_options;
  table_options.roughness = o.roughness;
  std::sort(table_options.roughness.begin(), table_options.roughness.end());
  table_options.roughness.erase(
      std::unique(table_options.roughness.begin(), table_options.roughness.end()),
      table_options.roughness.end());
  if (table_options.roughness.front() != 0.0) {
    table_options.roughness.insert(table_options.roughness.begin(), 0.0);
  }
  table_options.tolerance_de00 = o.tolerance_de00;
  table_options.threads = o.threads;
  table_options.cancel = o.cancel;
  const render::CompositionTable table =
      render::BuildCompositionTable(model, colorimeters, table_options);

  PageInputs in;
  in.model = &model;
  in.source = o.source;
  in.observer_deg = colorimeters.front().observer_deg();
  in.table = &table;
  for (double r : table.roughness) in.finish_names.push_back(FinishName(r));
  in.samples = Samples(o, model, table, &in.samples_note);
  CheckCancel(o.cancel);
  in.sphere = render::TraceNormals(render::Shape::kSphere, o.size);
  in.ring = render::TraceNormals(render::Shape::kRing, o.size);
  for (double r : table.roughness) {
    CheckCancel(o.cancel);
    // A rough finish blurs the light tent, so its map can be coarser.
    const int width = r > 0.0 ? kRoughEnvironmentWidth : kMirrorEnvironmentWidth;
    in.environment_maps.push_back(
        {width, width / 2,
         render::LatLongRadiance(render::Lighting::kStudio, r, width, width / 2, o.threads)});
  }
  in.generator = std::string("alloycolor ") + ALLOYCOLOR_VERSION;
  color::SuggestOptions suggest;
  suggest.count = 3;
  ThreadBudget threads(o.threads);
  suggest.threads = &threads;
  suggest.cancel = o.cancel;
  in.suggestions = color::SuggestCompositions(colorimeters.front(), model, suggest).suggestions;

  ExplorerPage page;
  page.html = PageHtml(in);
  page.compositions = static_cast<int>(table.x_nodes.size());
  page.angles = table.mu_nodes;
  page.illuminants = static_cast<int>(table.illuminants.size());
  page.finishes = static_cast<int>(table.roughness.size());
  page.check_points = table.check_points;
  page.max_de00 = table.max_de00;
  page.max_srgb8_difference = table.max_srgb8_difference;
  page.tolerance_met = table.tolerance_met;
  return page;
}

}  // namespace alloycolor::exports
