// alloycolor params: a model's physical parameters against composition (AlloyModel::
// Parameters), with one-sigma uncertainties, as a table or JSON.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/json.h"
#include "common.h"

namespace alloycolor::app {
namespace {

struct ParamsOptions {
  ModelSource source;
  std::string from_text, to_text;
  int steps = 11;
  std::string format = "text";
  bool quiet = false;
};

std::string Text(const ParameterTable::Quantity& q, bool with_sigma) {
  if (!std::isfinite(q.value)) return "-";
  char buf[64];
  if (with_sigma && std::isfinite(q.sigma)) {
    std::snprintf(buf, sizeof buf, "%.5g±%.2g", q.value, q.sigma);
  } else {
    std::snprintf(buf, sizeof buf, "%.5g", q.value);
  }
  return buf;
}

// Columns padded to their widest cell ("±" is two bytes and one column).
void PrintTable(const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows, std::ostream* out) {
  const auto width_of = [](const std::string& cell) {
    return cell.size() - (cell.find("±") != std::string::npos ? 1 : 0);
  };
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) width[c] = header[c].size();
  for (const auto& row : rows) {
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], width_of(row[c]));
  }
  auto print = [&](const std::vector<std::string>& cells) {
    std::string line;
    for (size_t c = 0; c < cells.size(); ++c) {
      line += cells[c] +
              std::string(width[c] - width_of(cells[c]) + (c + 1 < cells.size() ? 2 : 0), ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    *out << line << "\n";
  };
  print(header);
  for (const auto& row : rows) print(row);
}

void Run(const ParamsOptions& o) {
  if (o.format != "text" && o.format != "json") {
    throw Error("--format: '" + o.format + "' is not text or json");
  }
  if (o.steps < 1 || o.steps > 100000) throw Error("--steps: need 1..100000");
  const auto model = o.source.Load(o.quiet);
  const double from = o.from_text.empty()
                          ? model->x_min()
                          : ParseCompositions(o.from_text, model->system(), "--from").at(0);
  const double to = o.to_text.empty() ? model->x_max()
                                      : ParseCompositions(o.to_text, model->system(), "--to").at(0);
  CheckComposition(*model, from, o.source.extrapolate);
  CheckComposition(*model, to, o.source.extrapolate);
  if (o.format == "json") {
    PrintOutput(JsonText(ParameterCurvesJson(*model, from, to, o.steps), 1) + "\n");
    return;
  }
  std::vector<double> xs;
  for (int i = 0; i < o.steps; ++i) {
    xs.push_back(o.steps == 1 ? from : from + (to - from) * i / (o.steps - 1.0));
  }
  const ParameterTable table = model->Parameters(xs);
  const bool with_sigma = model->HasUncertainty();
  std::ostringstream text;
  text << "# " << model->method() << " model of " << model->system().Name()
       << "; x = atomic fraction of " << model->system().a.symbol << "\n";
  for (const std::string& note : table.notes) text << "# " << note << "\n";
  text << "# " << FreeElectronDensityNote(model->system()) << "\n";
  std::vector<std::string> header = {"x"};
  header.insert(header.end(), table.columns.begin(), table.columns.end());
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < table.rows.size(); ++i) {
    char xbuf[32];
    std::snprintf(xbuf, sizeof xbuf, "%.4g", table.x_atomic[i]);
    std::vector<std::string> row = {xbuf};
    for (const auto& q : table.rows[i]) row.push_back(Text(q, with_sigma));
    rows.push_back(std::move(row));
  }
  PrintTable(header, rows, &text);
  PrintOutput(text.str());
}

}  // namespace

void RegisterParams(CLI::App& app) {
  auto o = std::make_shared<ParamsOptions>();
  o->source.method = "physical";
  CLI::App* cmd = app.add_subcommand(
      "params",
      "A model's physical parameters (plasma energy, damping, tau, m*) against composition");
  cmd->footer(
      "A model's physical parameters against composition, with one-sigma "
      "uncertainties from the fit's covariance. Physical model: plasma energy wp, damping "
      "gamma, scattering time tau = hbar/gamma, free-carrier density N_e, effective mass "
      "m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2), eps_inf, and each interband "
      "term's centre (eV and nm) and width. Every other model: tau and m* from the pointwise "
      "Drude inversion (eq. 11, 12) at 450, 550, 650 nm (three wavelengths across the range "
      "for infrared models). N_e(x) assumes ideal "
      "mixing of molar volumes (Zen's law): N_e = (x Z_a + (1-x) Z_b) N_A / (x M_a/rho_a + "
      "(1-x) M_b/rho_b), with each element's valence Z (free electrons per atom), density "
      "rho and atomic mass M from the element table (printed with the output).");
  o->source.AddOptions(cmd, true);
  cmd->add_option("--from", o->from_text,
                  "First composition (default: the model's lowest training composition)");
  cmd->add_option("--to", o->to_text,
                  "Last composition (default: the model's highest training composition)");
  cmd->add_option("--steps", o->steps, "Number of compositions")->capture_default_str();
  cmd->add_option("--format", o->format, "text or json")->capture_default_str();
  cmd->add_flag("--quiet", o->quiet, "No warnings or progress on stderr");
  cmd->callback([o]() { Run(*o); });
}

}  // namespace alloycolor::app
