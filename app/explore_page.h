// The explorer page written by `alloycolor explore`: one self-contained HTML file (no
// network, no external script or font) in which a designer drags a composition slider and
// sees the metal. The program computes everything (render/composition_table.h: colour
// against composition and angle under each illuminant and roughness, the uncertainty, the
// spectra; render/renderer.h: the sphere's and ring's normals and coverage; the studio
// environment); the page only interpolates those tables and shades each pixel as the
// renderer does: XYZ = E(r) * table(x, mu), mu = n.z, r the mirror direction (E = 1 in
// uniform light), then linear sRGB with the program's matrix, the sRGB transfer curve and
// 8 bits. Its CIELAB and CIEDE2000 are the formulas of colorimetry.h written in JavaScript
// (tests/explore_test.cc checks them against the C++ ones, tests/js against references).
//
// The page's HTML, CSS and scripts are the files in app/explore/ (colour.js: formulas and
// interpolation; input.js: compositions and the address; app.js: the page), embedded at
// build time (cmake/EmbedText.cmake); page.html names where the others and the data go
// as @KEY@. Text from the user's files is data: escaped into the HTML (EscapeXml), into
// the JSON block (EscapeJsonForScript), and put in the page as text nodes only.
//
// Binary tables travel as base64 in a JSON block: little-endian float32 for colour,
// spectra and sigma, int16 normals (x, y; z = sqrt(1 - x^2 - y^2)) and uint8 coverage for
// the tiles, uint16 environment maps scaled by their largest value.
#ifndef ALLOYCOLOR_APP_EXPLORE_PAGE_H_
#define ALLOYCOLOR_APP_EXPLORE_PAGE_H_

#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"
#include "alloycolor/render/composition_table.h"
#include "alloycolor/render/renderer.h"

namespace alloycolor::app {

// A spectrum drawn beside the prediction: a measured training sample, or the model at a
// training composition when the model file keeps no spectra.
struct ExploreSample {
  double x_atomic;
  std::string label;
  bool measured;
  std::vector<double> lambda_nm, n, k, r_normal;
};

struct ExplorePageInputs {
  const AlloyModel* model = nullptr;
  std::string source;  // "auag.json", "data Au-Ag, smooth fit"
  int observer_deg = 2;
  const render::CompositionTable* table = nullptr;
  std::vector<std::string> finish_names;  // one per table roughness
  std::vector<ExploreSample> samples;
  std::string samples_note;
  render::NormalMap sphere, ring;
  // Studio light, one per roughness: render::LatLongRadiance on width x height.
  struct EnvironmentMap {
    int width, height;
    std::vector<float> texels;
  };
  std::vector<EnvironmentMap> environment_maps;
  std::string generator;
};

std::string ExplorePageHtml(const ExplorePageInputs& inputs);

}  // namespace alloycolor::app

#endif  // ALLOYCOLOR_APP_EXPLORE_PAGE_H_
