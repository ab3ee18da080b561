// The explorer page: one self-contained HTML file (no network, no external script or font)
// in which a designer drags a composition slider and sees the metal. `alloycolor explore`
// and Python's Model.explore write it through BuildExplorerPage, so the same model and
// options give the same bytes.
//
// The library computes everything (render/composition_table.h: colour against composition
// and angle under each illuminant and roughness, the uncertainty, the spectra;
// render/renderer.h: the sphere's and ring's normals and coverage; the studio
// environment); the page only interpolates those tables and shades each pixel as the
// renderer does: XYZ = E(r) * table(x, mu), mu = n.z, r the mirror direction (E = 1 in
// uniform light), then linear sRGB with the library's matrix, the sRGB transfer curve and
// 8 bits. Its CIELAB and CIEDE2000 are the formulas of colorimetry.h written in JavaScript
// (tests/explore_test.cc checks them against the C++ ones, tests/js against references).
//
// The page's HTML, CSS and scripts are the files in export/explore/ (colour.js: formulas
// and interpolation; input.js: compositions and the address; app.js: the page), embedded
// at build time (cmake/EmbedText.cmake); page.html names where the others and the data go
// as @KEY@. Text from the user's files is data: escaped into the HTML (EscapeXml), into
// the JSON block (EscapeJsonForScript), and put in the page as text nodes only.
//
// Binary tables travel as base64 in a JSON block: little-endian float32 for colour,
// spectra and sigma, int16 normals (x, y; z = sqrt(1 - x^2 - y^2)) and uint8 coverage for
// the tiles, uint16 environment maps scaled by their largest value.
#ifndef ALLOYCOLOR_EXPORT_EXPLORER_PAGE_H_
#define ALLOYCOLOR_EXPORT_EXPLORER_PAGE_H_

#include <string>
#include <vector>

#include "alloycolor/color/colorimetry.h"
#include "alloycolor/core/dataset.h"
#include "alloycolor/core/progress.h"
#include "alloycolor/core/setting.h"
#include "alloycolor/model/alloy_model.h"

namespace alloycolor::exports {

inline constexpr int kExplorerMinSize = 64;
inline constexpr int kExplorerMaxSize = 1024;
inline constexpr double kExplorerMinTolerance = 1e-4;
inline constexpr double kExplorerMaxTolerance = 0.5;

struct ExplorerOptions {
  // The finishes offered for the pictures, as GGX roughness alpha 0-1 (each once; 0, the
  // polished finish, is always offered).
  std::vector<double> roughness = {0.0, 0.2};
  int size = 320;                // width and height of each picture, pixels (64-1024)
  double tolerance_de00 = 0.02;  // largest CIEDE2000 while choosing the table's density
  int threads = 0;               // 0: all the hardware's
  std::string source;            // how the page names the model: "auag.json"
  // Measured spectra drawn beside the prediction (null: the model's own samples where its
  // file keeps them, else the model at its training compositions), and how the page
  // names that data set.
  const Dataset* data = nullptr;
  std::string data_name;
  // Called between the page's steps and within its tables and scans (core/progress.h).
  CancelCheck cancel;
};

// The page and what its tables measured, for the face to report.
struct ExplorerPage {
  std::string html;
  int compositions = 0, angles = 0, illuminants = 0, finishes = 0;
  int check_points = 0;          // where the tables were checked against direct evaluation
  double max_de00 = 0;           // their largest CIEDE2000 there
  int max_srgb8_difference = 0;  // and largest 8-bit sRGB difference
  bool tolerance_met = true;     // false: the tables reached their size limit first
};

// Throws Error naming the option as `spelling` spells it ("size" or "--size"; the
// program's flags are the names with two dashes) for a size, tolerance, roughness or
// thread count out of range.
void CheckExplorerOptions(const ExplorerOptions& options,
                          OptionSpelling spelling = OptionSpelling::kName);

// The page for `model` under each colorimeter (the illuminant selector's choices, one
// observer). Checks the options first (CheckExplorerOptions) and the colorimeters (at
// least one, one observer).
ExplorerPage BuildExplorerPage(const AlloyModel& model,
                               const std::vector<color::Colorimeter>& colorimeters,
                               const ExplorerOptions& options);

}  // namespace alloycolor::exports

#endif  // ALLOYCOLOR_EXPORT_EXPLORER_PAGE_H_
