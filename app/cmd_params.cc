// alloycolor params: a fitted model's physical parameters against composition, with
// one-sigma uncertainties from the fit's covariance.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "alloycolor/core/composition.h"
#include "alloycolor/core/error.h"
#include "alloycolor/model/optics.h"
#include "alloycolor/model/physical_model.h"
#include "alloycolor/model/smooth_model.h"
#include "alloycolor/core/units.h"
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

struct Quantity {
  double value;
  double sigma;  // 0 without covariance
};

nlohmann::json ToJson(const Quantity& q) { return {{"value", q.value}, {"sigma", q.sigma}}; }

std::string Text(const Quantity& q, bool with_sigma) {
  char buf[64];
  if (with_sigma) {
    std::snprintf(buf, sizeof buf, "%.5g±%.2g", q.value, q.sigma);
  } else {
    std::snprintf(buf, sizeof buf, "%.5g", q.value);
  }
  return buf;
}

// m*/m_e from (hbar wp)^2 = kPlasmaEv2M3 N_e / (m*/m_e).
double EffectiveMass(double n_e_m3, double wp_ev) {
  return kPlasmaEv2M3 * n_e_m3 / (wp_ev * wp_ev);
}

std::string ElementsLine(const AlloySystem& system) {
  std::ostringstream line;
  line << "# N_e(x) = (x Z_a + (1-x) Z_b) N_A / (x M_a/rho_a + (1-x) M_b/rho_b) (ideal mixing); ";
  for (const Element* e : {&system.a, &system.b}) {
    line << e->symbol << ": Z = " << e->valence << ", rho = " << e->density_g_cm3
         << " g/cm3, M = " << e->atomic_mass << " g/mol" << (e == &system.a ? "; " : "\n");
  }
  return line.str();
}

void PrintTable(const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) width[c] = header[c].size();
  for (const auto& row : rows) {
    for (size_t c = 0; c < row.size(); ++c) {
      // "±" is two bytes and one column.
      const size_t len = row[c].size() - (row[c].find("±") != std::string::npos ? 1 : 0);
      width[c] = std::max(width[c], len);
    }
  }
  auto print = [&](const std::vector<std::string>& cells) {
    std::string line;
    for (size_t c = 0; c < cells.size(); ++c) {
      const size_t len = cells[c].size() - (cells[c].find("±") != std::string::npos ? 1 : 0);
      line += cells[c] + std::string(width[c] - len + (c + 1 < cells.size() ? 2 : 0), ' ');
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::cout << line << "\n";
  };
  print(header);
  for (const auto& row : rows) print(row);
}

void RunPhysical(const PhysicalModel& model, const std::vector<double>& xs, bool json) {
  const PhysicalLayout& layout = model.layout();
  const bool with_sigma = model.HasUncertainty();
  nlohmann::json out_rows = nlohmann::json::array();
  std::vector<std::string> header = {"x",        "wp_eV",  "gamma_eV", "tau_fs",
                                     "N_e_m^-3", "m*/m_e", "eps_inf"};
  for (int t = 1; t < layout.num_terms(); ++t) {
    const std::string p = "t" + std::to_string(t) + ":";
    header.push_back(p + "E0_eV");
    header.push_back(p + "E0_nm");
    if (layout.term_kind(t) == TermKind::kRiouxGap) header.push_back(p + "Eg_eV");
    header.push_back(p + "G_eV");
  }
  std::vector<std::vector<std::string>> rows;
  for (double x : xs) {
    const std::vector<PhysicalParameterValue> values = model.ParameterValues(x);
    auto get = [&](int term, const char* name) {
      const int k = layout.Find(term, name);
      return Quantity{values[k].value, values[k].sigma};
    };
    const Quantity wp = get(0, "wp_eV"), gamma = get(0, "gamma_eV"), eps_inf = get(0, "eps_inf");
    const Quantity tau{TauFsFromGammaEv(gamma.value),
                       kHbarEvFs * gamma.sigma / (gamma.value * gamma.value)};
    const double n_e = FreeElectronDensityM3(x, model.system());
    const double m = EffectiveMass(n_e, wp.value);
    const Quantity mass{m, 2.0 * m * wp.sigma / wp.value};
    char xbuf[32];
    std::snprintf(xbuf, sizeof xbuf, "%.4g", x);
    char nbuf[32];
    std::snprintf(nbuf, sizeof nbuf, "%.4e", n_e);
    std::vector<std::string> row = {
        xbuf, Text(wp, with_sigma),   Text(gamma, with_sigma),  Text(tau, with_sigma),
        nbuf, Text(mass, with_sigma), Text(eps_inf, with_sigma)};
    nlohmann::json jrow = {{"x", x},
                           {"x_weight", WeightFromAtomicFraction(x, model.system())},
                           {"wp_eV", ToJson(wp)},
                           {"gamma_eV", ToJson(gamma)},
                           {"tau_fs", ToJson(tau)},
                           {"N_e_m3", n_e},
                           {"m_eff_over_m_e", ToJson(mass)},
                           {"eps_inf", ToJson(eps_inf)}};
    nlohmann::json jterms = nlohmann::json::array();
    for (int t = 1; t < layout.num_terms(); ++t) {
      nlohmann::json jt = {{"kind", TermKindName(layout.term_kind(t))}};
      for (const auto& v : values) {
        if (v.term == t) jt[v.name] = ToJson(Quantity{v.value, v.sigma});
      }
      const Quantity e0 = get(t, "E0_eV");
      const Quantity e0_nm{LambdaNmFromOmegaEv(e0.value),
                           kHcEvNm * e0.sigma / (e0.value * e0.value)};
      jt["E0_nm"] = ToJson(e0_nm);
      jterms.push_back(jt);
      row.push_back(Text(e0, with_sigma));
      row.push_back(Text(e0_nm, with_sigma));
      if (layout.term_kind(t) == TermKind::kRiouxGap)
        row.push_back(Text(get(t, "Eg_eV"), with_sigma));
      row.push_back(Text(get(t, "G_eV"), with_sigma));
    }
    jrow["terms"] = jterms;
    out_rows.push_back(jrow);
    rows.push_back(row);
  }
  if (json) {
    nlohmann::json out = {
        {"system", model.system().Name()},
        {"method", model.method()},
        {"terms", InterbandTermsText(layout.interband())},
        {"degree", layout.degree()},
        {"uncertainty", with_sigma ? "one sigma from the fit's covariance" : "none"},
        {"rows", out_rows}};
    std::cout << out.dump(1) << "\n";
    return;
  }
  std::cout << "# physical model of " << model.system().Name() << ": drude"
            << (layout.interband().empty() ? " only"
                                           : " + " + InterbandTermsText(layout.interband()))
            << ", degree " << layout.degree() << ", fitted " << model.lambda_min_nm() << "-"
            << model.lambda_max_nm() << " nm; x = atomic fraction of " << model.system().a.symbol
            << "\n";
  std::cout << "# tau = hbar / gamma; m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2); "
            << (with_sigma ? "value±sigma (one sigma)" : "no covariance in the model") << "\n";
  std::cout << ElementsLine(model.system());
  for (int t = 1; t < layout.num_terms(); ++t) {
    std::cout << "# t" << t << ": " << TermKindName(layout.term_kind(t))
              << (layout.term_kind(t) == TermKind::kRiouxGap
                      ? " (E0 absorption onset, Eg gap, G width)"
                      : " (E0 centre, G width)")
              << "\n";
  }
  PrintTable(header, rows);
}

// The wavelengths at which a smooth model's tau and m* are shown.
std::vector<double> SmoothWavelengths(const AlloyModel& model) {
  if (model.lambda_min_nm() <= 450 && model.lambda_max_nm() >= 650) return {450, 550, 650};
  const double lo = model.lambda_min_nm(), hi = model.lambda_max_nm();
  std::vector<double> out;
  for (double f : {0.1, 0.5, 0.9}) out.push_back(std::round(lo + (hi - lo) * f));
  return out;
}

void RunSmooth(const SmoothModel& model, const std::vector<double>& xs, bool json) {
  const std::vector<double> lambda = SmoothWavelengths(model);
  const bool with_sigma = model.HasUncertainty();
  std::vector<std::string> header = {"x", "N_e_m^-3"};
  for (double l : lambda) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "tau_fs@%gnm", l);
    header.push_back(buf);
    std::snprintf(buf, sizeof buf, "m*/m_e@%gnm", l);
    header.push_back(buf);
  }
  std::vector<std::vector<std::string>> rows;
  nlohmann::json out_rows = nlohmann::json::array();
  constexpr int kDraws = 256;
  for (double x : xs) {
    const double n_e = FreeElectronDensityM3(x, model.system());
    const auto eps = model.Permittivity(x, lambda);
    const auto draws = model.PermittivityDraws(x, lambda, kDraws, 20261122u);
    char xbuf[32], nbuf[32];
    std::snprintf(xbuf, sizeof xbuf, "%.4g", x);
    std::snprintf(nbuf, sizeof nbuf, "%.4e", n_e);
    std::vector<std::string> row = {xbuf, nbuf};
    nlohmann::json jrow = {
        {"x", x}, {"x_weight", WeightFromAtomicFraction(x, model.system())}, {"N_e_m3", n_e}};
    nlohmann::json jl = nlohmann::json::array();
    for (size_t i = 0; i < lambda.size(); ++i) {
      const double omega = OmegaEvFromLambdaNm(lambda[i]);
      auto tau_mass = [&](std::complex<double> e) {
        const DrudePoint p = InvertDrude(omega, e.real(), e.imag());
        return std::pair<double, double>{TauFsFromGammaEv(p.gamma_ev),
                                         EffectiveMass(n_e, std::sqrt(p.wp2_ev2))};
      };
      const auto [tau, mass] = tau_mass(eps[i]);
      double s_tau = 0, s_mass = 0;
      for (const auto& d : draws) {
        const auto [t, m] = tau_mass(d[i]);
        s_tau += (t - tau) * (t - tau);
        s_mass += (m - mass) * (m - mass);
      }
      if (!draws.empty()) {
        s_tau = std::sqrt(s_tau / draws.size());
        s_mass = std::sqrt(s_mass / draws.size());
      }
      row.push_back(Text({tau, s_tau}, with_sigma));
      row.push_back(Text({mass, s_mass}, with_sigma));
      jl.push_back({{"lambda_nm", lambda[i]},
                    {"tau_fs", ToJson({tau, s_tau})},
                    {"m_eff_over_m_e", ToJson({mass, s_mass})}});
    }
    jrow["at"] = jl;
    out_rows.push_back(jrow);
    rows.push_back(row);
  }
  if (json) {
    nlohmann::json out = {{"system", model.system().Name()},
                          {"method", model.method()},
                          {"uncertainty", with_sigma ? "one sigma from 256 draws of the "
                                                       "fit's covariance"
                                                     : "none"},
                          {"rows", out_rows}};
    std::cout << out.dump(1) << "\n";
    return;
  }
  std::cout << "# smooth model of " << model.system().Name() << ": tau and m* at " << lambda.size()
            << " wavelengths; x = atomic fraction of " << model.system().a.symbol << "\n";
  std::cout << "# tau = hbar / gamma; m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2); "
            << (with_sigma ? "value±sigma (one sigma, from draws of the covariance)"
                           : "no covariance in the model")
            << "\n";
  std::cout << ElementsLine(model.system());
  PrintTable(header, rows);
}

void Run(const ParamsOptions& o) {
  if (o.format != "text" && o.format != "json") {
    throw Error("--format: '" + o.format + "' is not text or json");
  }
  if (o.steps < 1 || o.steps > 100000) throw Error("--steps: need 1..100000");
  const auto model = o.source.Load(o.quiet);
  const auto* physical = dynamic_cast<const PhysicalModel*>(model.get());
  const auto* smooth = dynamic_cast<const SmoothModel*>(model.get());
  if (!physical && !smooth) {
    throw Error("params: a " + model->method() +
                " model has no fitted physical parameters; give a physical or smooth model "
                "(alloycolor fit --method physical)");
  }
  const double from =
      o.from_text.empty() ? model->x_min() : ParseCompositions(o.from_text, model->system()).at(0);
  const double to =
      o.to_text.empty() ? model->x_max() : ParseCompositions(o.to_text, model->system()).at(0);
  CheckComposition(*model, from, o.source.extrapolate);
  CheckComposition(*model, to, o.source.extrapolate);
  std::vector<double> xs;
  for (int i = 0; i < o.steps; ++i) {
    xs.push_back(o.steps == 1 ? from : from + (to - from) * i / (o.steps - 1.0));
  }
  if (physical) {
    RunPhysical(*physical, xs, o.format == "json");
  } else {
    RunSmooth(*smooth, xs, o.format == "json");
  }
}

}  // namespace

void RegisterParams(CLI::App& app) {
  auto o = std::make_shared<ParamsOptions>();
  o->source.method = "physical";
  CLI::App* cmd = app.add_subcommand(
      "params",
      "A fitted model's physical parameters against composition, with one-sigma "
      "uncertainties from the fit's covariance. Physical model: plasma energy wp, damping "
      "gamma, scattering time tau = hbar/gamma, free-carrier density N_e, effective mass "
      "m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2), eps_inf, and each interband "
      "term's centre (eV and nm) and width. Smooth model: tau and m* at 450, 550, 650 nm "
      "(three wavelengths across the range for infrared models). N_e(x) assumes ideal "
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
