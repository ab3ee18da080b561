// alloycolor predict: n, k of an alloy at one composition on a wavelength grid.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <tuple>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/json.h"
#include "alloycolor/core/spectrum.h"
#include "alloycolor/core/text.h"
#include "alloycolor/model/optics.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct PredictOptions {
  ModelSource source;
  std::string x_text;
  double from_nm = 380, to_nm = 780, step_nm = 5;
  double old_from = 0, old_to = 0, old_step = 0;  // --from, --to, --step: the old names
  std::string format = "csv";
  bool sigma = false;
  bool quiet = false;
};

void Run(const PredictOptions& o, CLI::App* cmd) {
  if (o.format != "csv" && o.format != "json") {
    throw Error("--format: '" + o.format + "' is not csv or json");
  }
  const auto model = o.source.Load(o.quiet);
  if (o.x_text.empty()) throw Error("--x: give one composition, e.g. --x 0.75");
  const std::vector<double> xs = ParseCompositions(o.x_text, model->system(), "--x");
  if (xs.size() != 1) throw Error("--x: predict takes one composition");
  const double x = xs[0];
  CheckComposition(*model, x, o.source.extrapolate);
  double from = o.from_nm, to = o.to_nm, step = o.step_nm;
  bool grid_given = false;
  for (const auto& [name, old, value, given] : {std::tuple{"from", "--from", o.old_from, &from},
                                                {"to", "--to", o.old_to, &to},
                                                {"step", "--step", o.old_step, &step}}) {
    const std::string now = std::string("--lambda-") + name;
    if (cmd->count(old) && cmd->count(now)) {
      throw Error(std::string(old) + " is " + now + "'s old name: give one of them");
    }
    if (cmd->count(old)) {
      *given = value;
      if (!o.quiet)
        Warn(std::string(old) + " is now " + now + " (the old name is accepted until version 0.3)");
    }
    grid_given = grid_given || cmd->count(old) || cmd->count(now);
  }
  if (!grid_given && (model->lambda_min_nm() > from || model->lambda_max_nm() < to)) {
    // The default visible grid is outside the model (infrared data): use its own range.
    from = model->lambda_min_nm();
    to = model->lambda_max_nm();
    step = (to - from) / 100.0;
  }
  if (!(step > 0) || !(to >= from)) {
    throw Error("--lambda-from/--lambda-to/--lambda-step: need from <= to and a positive step");
  }
  if ((to - from) / step > 1e6) {
    throw Error("--lambda-from/--lambda-to/--lambda-step: " + FormatNumber((to - from) / step) +
                " wavelengths; at most 1,000,000 (give a larger --lambda-step)");
  }
  const std::vector<double> grid = UniformGrid(from, to, step);
  const std::vector<std::complex<double>> index = model->Index(x, grid);
  std::vector<double> n_sigma, k_sigma;
  if (o.sigma || o.format == "json") {
    const auto draws = model->CheckedDraws(x, grid);
    if (!draws.empty()) {
      n_sigma.assign(grid.size(), 0.0);
      k_sigma.assign(grid.size(), 0.0);
      for (const auto& eps : draws) {
        for (size_t i = 0; i < grid.size(); ++i) {
          const Complex<double> nk =
              IndexFromPermittivity(Complex<double>{eps[i].real(), eps[i].imag()});
          n_sigma[i] += std::pow(nk.re - index[i].real(), 2);
          k_sigma[i] += std::pow(nk.im - index[i].imag(), 2);
        }
      }
      for (size_t i = 0; i < grid.size(); ++i) {
        n_sigma[i] = std::sqrt(n_sigma[i] / draws.size());
        k_sigma[i] = std::sqrt(k_sigma[i] / draws.size());
      }
    } else if (o.sigma) {
      throw Error("--sigma: the " + model->method() + " model carries no uncertainty");
    }
  }
  // Finite or an error: never a NaN or an infinity in the output.
  for (size_t i = 0; i < grid.size(); ++i) {
    const bool finite =
        std::isfinite(index[i].real()) && std::isfinite(index[i].imag()) &&
        (n_sigma.empty() || (std::isfinite(n_sigma[i]) && std::isfinite(k_sigma[i])));
    if (!finite) {
      throw Error(model->source() + ": x = " + FormatNumber(x) + ", " + FormatNumber(grid[i]) +
                  " nm: the " + model->method() + " model gives no finite n, k" +
                  (n_sigma.empty() ? "" : " or sigma") + " here");
    }
  }
  if (o.format == "json") {
    nlohmann::json out = {{"system", model->system().Name()},
                          {"method", model->method()},
                          {"x", x},
                          {"x_weight", WeightFromAtomicFraction(x, model->system())},
                          {"lambda_nm", grid}};
    std::vector<double> n, k;
    for (const auto& v : index) {
      n.push_back(v.real());
      k.push_back(v.imag());
    }
    out["n"] = n;
    out["k"] = k;
    if (!n_sigma.empty()) {
      out["n_sigma"] = n_sigma;
      out["k_sigma"] = k_sigma;
    }
    PrintOutput(JsonText(out, 1) + "\n");
    return;
  }
  std::ostringstream csv;
  csv.precision(17);
  csv << "lambda_nm,n,k" << (o.sigma ? ",n_sigma,k_sigma" : "") << "\n";
  for (size_t i = 0; i < grid.size(); ++i) {
    csv << grid[i] << "," << index[i].real() << "," << index[i].imag();
    if (o.sigma) csv << "," << n_sigma[i] << "," << k_sigma[i];
    csv << "\n";
  }
  PrintOutput(csv.str());
}

}  // namespace

void RegisterPredict(CLI::App& app) {
  auto o = std::make_shared<PredictOptions>();
  CLI::App* cmd = app.add_subcommand(
      "predict", "Optical constants n, k of the alloy at one composition, as CSV or JSON");
  cmd->footer(
      "Optical constants n, k of the alloy at one composition, on a wavelength grid, as CSV "
      "(lambda_nm,n,k) or JSON (with one-sigma n_sigma, k_sigma for models that carry "
      "uncertainty).");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--x", o->x_text, "Composition: 0.75, 75at%, 75wt% or 18k");
  cmd->add_option("--lambda-from", o->from_nm,
                  "First wavelength, nm (default 380, or the model's range for infrared "
                  "models)");
  cmd->add_option("--lambda-to", o->to_nm, "Last wavelength, nm (default 780)");
  cmd->add_option("--lambda-step", o->step_nm, "Wavelength step, nm")->capture_default_str();
  // The old names, until version 0.3 (--from is a composition in sweep, chart and params).
  cmd->add_option("--from", o->old_from)->group("");
  cmd->add_option("--to", o->old_to)->group("");
  cmd->add_option("--step", o->old_step)->group("");
  cmd->add_option("--format", o->format, "csv or json")->capture_default_str();
  cmd->add_flag("--sigma", o->sigma, "CSV: add n_sigma,k_sigma columns");
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o, cmd]() { Run(*o, cmd); });
}

}  // namespace alloycolor::app
