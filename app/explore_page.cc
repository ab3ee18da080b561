#include "explore_page.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/composition.h"
#include "alloycolor/core/markup.h"
#include "explore_assets.h"

namespace alloycolor::app {
namespace {

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

json EnvironmentJson(const std::vector<ExplorePageInputs::EnvironmentMap>& maps) {
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

}  // namespace

std::string ExplorePageHtml(const ExplorePageInputs& in) {
  const AlloyModel& model = *in.model;
  const AlloySystem& system = model.system();
  json training = json::array();
  for (const TrainingSample& s : model.training_samples()) {
    training.push_back({{"x", s.x_atomic}, {"file", s.file}});
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
  return FillTemplate(explore::kPageHtml, {{"TITLE", title},
                                           {"SYSTEM", system_name},
                                           {"STYLE", explore::kPageCss},
                                           {"DATA", data_text},
                                           {"COLOUR_JS", explore::kColourJs},
                                           {"INPUT_JS", explore::kInputJs},
                                           {"APP_JS", explore::kAppJs}});
}

}  // namespace alloycolor::app
