// A model's physical parameters against composition (AlloyModel::Parameters) and their
// table as the model file's parameters.curves and `alloycolor params --format json` write
// it: tau(x) and m*(x), the design's curves, with their one-sigma.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "alloycolor/core/composition.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/optics.h"

namespace alloycolor {

ParameterTable AlloyModel::Parameters(const std::vector<double>& xs) const {
  std::vector<double> lambda = {450, 550, 650};
  if (!(lambda_min_nm_ <= 450 && lambda_max_nm_ >= 650)) {
    lambda.clear();
    for (double f : {0.1, 0.5, 0.9}) {
      lambda.push_back(std::round(lambda_min_nm_ + (lambda_max_nm_ - lambda_min_nm_) * f));
    }
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr int kDraws = 256;
  ParameterTable table;
  table.notes = {
      "tau = hbar / gamma and m*/m_e = e^2 hbar^2 N_e / (eps0 m_e (hbar wp)^2) from "
      "the pointwise Drude inversion of the " +
      method() + " model (eq. 11, 12)" +
      (HasUncertainty()
           ? "; sigma from " + std::to_string(kDraws) + " draws of the model's uncertainty"
           : "")};
  table.columns = {"N_e_m^-3"};
  for (double l : lambda) {
    std::ostringstream tau, mass;
    tau << "tau_fs@" << l << "nm";
    mass << "m*/m_e@" << l << "nm";
    table.columns.push_back(tau.str());
    table.columns.push_back(mass.str());
  }
  for (double x : xs) {
    const double n_e = FreeElectronDensityM3(x, system_);
    const auto draws = CheckedDraws(x, lambda, kDraws);
    std::vector<ParameterTable::Quantity> row = {{n_e, 0.0}};
    for (size_t i = 0; i < lambda.size(); ++i) {
      DrudePoint p;
      if (!DrudeAt(x, lambda[i], &p)) {
        row.push_back({kNaN, kNaN});
        row.push_back({kNaN, kNaN});
        continue;
      }
      const double tau = TauFsFromGammaEv(p.gamma_ev);
      const double mass = EffectiveMassRatio(n_e, p.wp2_ev2);
      double s_tau = 0, s_mass = 0;
      int used = 0;
      for (const auto& d : draws) {
        if (!DrudeInvertible(d[i].real(), d[i].imag())) continue;
        const DrudePoint q = InvertDrude(OmegaEvFromLambdaNm(lambda[i]), d[i].real(), d[i].imag());
        s_tau += std::pow(TauFsFromGammaEv(q.gamma_ev) - tau, 2);
        s_mass += std::pow(EffectiveMassRatio(n_e, q.wp2_ev2) - mass, 2);
        ++used;
      }
      row.push_back({tau, used ? std::sqrt(s_tau / used) : 0.0});
      row.push_back({mass, used ? std::sqrt(s_mass / used) : 0.0});
    }
    table.x_atomic.push_back(x);
    table.rows.push_back(std::move(row));
  }
  return table;
}

namespace {

nlohmann::json QuantityJson(const ParameterTable::Quantity& q) {
  if (!std::isfinite(q.value)) return nullptr;
  return {{"value", q.value},
          {"sigma", std::isfinite(q.sigma) ? nlohmann::json(q.sigma) : nullptr}};
}

}  // namespace

std::string FreeElectronDensityNote(const AlloySystem& system) {
  std::ostringstream line;
  line << "N_e(x) = (x Z_a + (1-x) Z_b) N_A / (x M_a/rho_a + (1-x) M_b/rho_b) (ideal mixing); ";
  for (const Element* e : {&system.a, &system.b}) {
    line << e->symbol << ": Z = " << e->valence
         << (e->valence_conventional ? " (conventional: no free-electron valence in Ashcroft & "
                                       "Mermin Table 1.1; m* scales with it)"
                                     : "")
         << ", rho = " << e->density_g_cm3 << " g/cm3, M = " << e->atomic_mass << " g/mol"
         << (e == &system.a ? "; " : "");
  }
  return line.str();
}

nlohmann::json ParameterCurvesJson(const AlloyModel& model, double from, double to, int steps) {
  std::vector<double> xs;
  for (int i = 0; i < steps; ++i) {
    xs.push_back(steps == 1 ? from : from + (to - from) * i / (steps - 1.0));
  }
  const ParameterTable table = model.Parameters(xs);
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < table.rows.size(); ++i) {
    nlohmann::json row = {
        {"x", table.x_atomic[i]},
        {"x_weight", WeightFromAtomicFraction(table.x_atomic[i], model.system())}};
    for (size_t c = 0; c < table.columns.size(); ++c) {
      row[table.columns[c]] = QuantityJson(table.rows[i][c]);
    }
    rows.push_back(row);
  }
  nlohmann::json notes = table.notes;
  notes.push_back(FreeElectronDensityNote(model.system()));
  return {{"system", model.system().Name()},
          {"method", model.method()},
          {"uncertainty", model.HasUncertainty() ? "one sigma" : model.NoErrorBarReason()},
          {"notes", notes},
          {"rows", rows}};
}

nlohmann::json ParameterCurvesJson(const AlloyModel& model) {
  return ParameterCurvesJson(model, model.x_min(), model.x_max(), 11);
}

}  // namespace alloycolor
