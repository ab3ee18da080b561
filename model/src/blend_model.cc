#include "alloycolor/model/blend_model.h"

#include <algorithm>
#include <cmath>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"

namespace alloycolor {
namespace {

// The members' bound models, their values weighted.
class BlendBoundModel : public BoundModel {
 public:
  BlendBoundModel(std::vector<double> lambda_nm, std::vector<double> weights,
                  std::vector<std::unique_ptr<BoundModel>> members)
      : BoundModel(std::move(lambda_nm)),
        weights_(std::move(weights)),
        members_(std::move(members)) {}
  void Permittivity(double x_atomic, double* eps1, double* eps2) const override {
    const size_t m = lambda_nm().size();
    std::vector<double> e1(m), e2(m);
    std::fill(eps1, eps1 + m, 0.0);
    std::fill(eps2, eps2 + m, 0.0);
    for (size_t i = 0; i < members_.size(); ++i) {
      members_[i]->Permittivity(x_atomic, e1.data(), e2.data());
      for (size_t j = 0; j < m; ++j) {
        eps1[j] += weights_[i] * e1[j];
        eps2[j] += weights_[i] * e2[j];
      }
    }
  }

 private:
  std::vector<double> weights_;
  std::vector<std::unique_ptr<BoundModel>> members_;
};

}  // namespace

BlendModel::BlendModel(const Dataset& dataset, std::vector<Member> members)
    : members_(std::move(members)) {
  double lo = 0, hi = HUGE_VAL;
  for (const Member& m : members_) {
    if (m.model) {
      lo = std::max(lo, m.model->lambda_min_nm());
      hi = std::min(hi, m.model->lambda_max_nm());
    }
  }
  SetCommon(dataset, lo, hi);
  Validate(dataset.manifest_path);
}

BlendModel::BlendModel(const nlohmann::json& doc, const std::string& source) {
  ReadCommon(doc);
  const nlohmann::json& p = doc.at("parameters");
  if (!p.is_object() || !p.contains("members") || !p.at("members").is_array()) {
    throw Error(source + ": parameters.members: expected an array");
  }
  const nlohmann::json& list = p.at("members");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = source + ": parameters.members[" + std::to_string(i) + "]";
    const nlohmann::json& entry = list[i];
    if (!entry.is_object() || !entry.contains("weight") || !entry.at("weight").is_number()) {
      throw Error(where + ".weight: expected a number");
    }
    if (!entry.contains("model") || !entry.at("model").is_object()) {
      throw Error(where + ".model: expected a model document");
    }
    // One level: a blend of blends is refused, so a file cannot nest without bound.
    const nlohmann::json& method = entry.at("model").value("method", nlohmann::json());
    if (method == kBlendMethod) throw Error(where + ".model: a blend cannot be a member");
    members_.push_back(
        {entry.at("weight").get<double>(), ModelFromJson(entry.at("model"), where + ".model")});
  }
  Validate(source);
}

void BlendModel::Validate(const std::string& where) {
  const std::string prefix = where + ": blend: parameters.members";
  if (members_.size() < 2) throw Error(prefix + ": two members at least");
  double sum = 0;
  for (size_t i = 0; i < members_.size(); ++i) {
    const Member& m = members_[i];
    const std::string at = prefix + "[" + std::to_string(i) + "]";
    if (!m.model) throw Error(at + ".model: missing");
    if (!(m.weight > 0 && m.weight <= 1)) {
      throw Error(at + ".weight: " + FormatNumber(m.weight) + " is not in (0, 1]");
    }
    if (std::string(m.model->system().a.symbol) != system().a.symbol ||
        std::string(m.model->system().b.symbol) != system().b.symbol) {
      throw Error(at + ".model: another alloy system than the blend's");
    }
    if (m.model->lambda_min_nm() > lambda_min_nm() || m.model->lambda_max_nm() < lambda_max_nm()) {
      throw Error(at + ".model: does not cover the blend's wavelength range");
    }
    sum += m.weight;
  }
  if (std::abs(sum - 1) > 1e-6) {
    throw Error(prefix + ": the weights sum to " + FormatNumber(sum) + ", not 1");
  }
  for (Member& m : members_) m.weight /= sum;
}

std::vector<std::complex<double>> BlendModel::Permittivity(
    double x_atomic, const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  std::vector<std::complex<double>> eps(lambda_nm.size(), 0.0);
  for (const Member& m : members_) {
    const std::vector<std::complex<double>> e = m.model->Permittivity(x_atomic, lambda_nm);
    for (size_t j = 0; j < eps.size(); ++j) eps[j] += m.weight * e[j];
  }
  return eps;
}

std::unique_ptr<BoundModel> BlendModel::Bind(const std::vector<double>& lambda_nm) const {
  CheckLambda(lambda_nm);
  std::vector<double> weights;
  std::vector<std::unique_ptr<BoundModel>> bound;
  for (const Member& m : members_) {
    weights.push_back(m.weight);
    bound.push_back(m.model->Bind(lambda_nm));
  }
  return std::make_unique<BlendBoundModel>(lambda_nm, std::move(weights), std::move(bound));
}

nlohmann::json BlendModel::ParametersJson() const {
  nlohmann::json list = nlohmann::json::array();
  for (const Member& m : members_) {
    list.push_back({{"weight", m.weight}, {"model", m.model->ToJson()}});
  }
  return {{"members", list}};
}

}  // namespace alloycolor
