// alloycolor export: n and k of a metal (measured, --nk) or of an alloy at one composition
// as the spectrum files and material definitions pbrt-v4 and Mitsuba 3 read for conductors.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/export/spectral_export.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ExportOptions {
  std::string nk_file;
  ModelSource source;
  std::string x_text;
  std::string format = "spd";
  std::string out;
  bool quiet = false;
};

std::string Format(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

// A Mitsuba object id from a description: letters, digits, '-', '_' and '.'.
std::string Identifier(const std::string& text) {
  std::string id = "alloycolor_";
  for (char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '-' || c == '.';
    id += keep ? c : '_';
  }
  return id;
}

void Run(const ExportOptions& o) {
  if (o.format != "spd") {
    throw Error("--format: unknown format '" + o.format + "' (spd: pbrt-v4 and Mitsuba 3)");
  }
  if (o.out.empty()) throw Error("--out: give a file name prefix");
  CheckOutputFolder(o.out, "--out");
  exports::ConductorSpectra spectra;
  std::string id;
  if (!o.nk_file.empty()) {
    if (!o.source.model_path.empty() || !o.source.data_dir.empty() || !o.x_text.empty()) {
      throw Error("--nk takes no --model, --data or --x");
    }
    std::vector<std::string> warnings;
    const NkSpectrum nk = ReadNkFile(o.nk_file, &warnings);
    if (!o.quiet) {
      for (const auto& w : warnings) Warn(w);
    }
    spectra = exports::MeasuredSpectra(nk, "measured n, k from " + o.nk_file);
    std::string stem = o.nk_file.substr(o.nk_file.find_last_of('/') + 1);
    id = Identifier(stem.substr(0, stem.find_last_of('.')));
  } else {
    if (o.source.model_path.empty() && o.source.data_dir.empty()) {
      throw Error("give --nk FILE, or --model FILE (or --data DIR) with --x");
    }
    if (o.x_text.empty()) throw Error("--x: give the composition, e.g. --x 0.75 or 18k");
    const auto model = o.source.Load(o.quiet);
    const std::vector<double> xs = ParseCompositions(o.x_text, model->system());
    if (xs.size() != 1) throw Error("--x: export takes one composition, not " + o.x_text);
    const double x = xs[0];
    CheckComposition(*model, x, o.source.extrapolate);
    const AlloySystem& system = model->system();
    const std::string material =
        system.Name() + " at x = " + Format("%.6g", x) + " (atomic fraction of " + system.a.symbol +
        "; " + Format("%.4g", 100.0 * WeightFromAtomicFraction(x, system)) + " wt% " +
        system.a.symbol + "), " + model->method() + " model " +
        (o.source.model_path.empty() ? "built from data " + o.source.data_dir
                                     : "from " + o.source.model_path);
    spectra = exports::ModelSpectra(*model, x, material);
    id = Identifier(system.Name() + "_x" + Format("%.6g", x));
  }
  const std::vector<std::string> header = {std::string("written by alloycolor ") +
                                           ALLOYCOLOR_VERSION};
  const std::string eta_file = o.out + ".eta.spd";
  const std::string k_file = o.out + ".k.spd";
  // Everything is formatted before the first file is written.
  const std::string eta_text = exports::SpdText(spectra, true, header);
  const std::string k_text = exports::SpdText(spectra, false, header);
  const std::string pbrt_text = exports::PbrtMaterialText(spectra, eta_file, k_file, header);
  const std::string xml_text = exports::MitsubaBsdfXml(spectra, id, eta_file, k_file, header);
  if (!o.quiet) {
    for (const std::string& note : spectra.notes) Warn(note);
  }
  WriteOutput(eta_file, eta_text, o.quiet);
  WriteOutput(k_file, k_text, o.quiet);
  WriteOutput(o.out + ".pbrt", pbrt_text, o.quiet);
  WriteOutput(o.out + ".xml", xml_text, o.quiet);
}

}  // namespace

void RegisterExport(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Spectra of n and k for renderers: PREFIX.eta.spd and PREFIX.k.spd (wavelength_nm "
      "value per line, 360-830 nm at least, at the model's or file's own wavelengths, "
      "digits enough to read back the exact doubles; end values held where the data stop short of "
      "360 or 830 nm, "
      "as the comment lines say), PREFIX.pbrt (pbrt-v4 conductor material) and PREFIX.xml "
      "(Mitsuba 3 conductor bsdf), from measured n, k (--nk FILE) or an alloy at one "
      "composition --x (--model or --data).");
  cmd->add_option("--nk", o->nk_file,
                  "Optical constants: refractiveindex.info YAML or CSV (lambda_nm,n,k)");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--x", o->x_text,
                  "Composition of the system's first element: 0.75, 75at%, 75wt%, 18k");
  cmd->add_option("--format", o->format, "spd (pbrt-v4 and Mitsuba 3)")->capture_default_str();
  cmd->add_option("--out", o->out,
                  "Output prefix: writes PREFIX.eta.spd, PREFIX.k.spd, "
                  "PREFIX.pbrt, PREFIX.xml")
      ->required();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
