// The toy method (toy_method.h): its model, its reader and builder, and its registration.
#include "toy_method.h"

#include <complex>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "alloycolor/core/grid.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/alloy_model.h"
#include "alloycolor/model/registry.h"

namespace alloycolor::toy {
namespace {

class ConstantModel : public AlloyModel {
 public:
  ConstantModel(const Dataset& dataset, double eps1) : eps1_(eps1) {
    const WavelengthRange range = CommonRange(dataset);
    SetCommon(dataset, range.lo_nm, range.hi_nm);
  }
  ConstantModel(const nlohmann::json& doc, const std::string& source) {
    ReadCommon(doc);
    set_source(source);
    eps1_ = doc.at("parameters").at("eps1").get<double>();
  }
  std::string method() const override { return kMethod; }
  std::vector<std::complex<double>> Permittivity(
      double, const std::vector<double>& lambda_nm) const override {
    CheckLambda(lambda_nm);
    return std::vector<std::complex<double>>(lambda_nm.size(), {eps1_, kEps2});
  }

 protected:
  nlohmann::json ParametersJson() const override { return {{"eps1", eps1_}}; }

 private:
  double eps1_ = 0;
};

std::unique_ptr<AlloyModel> Read(const nlohmann::json& doc, const std::string& source) {
  return std::make_unique<ConstantModel>(doc, source);
}

// The option arrives checked against its declaration, its default filled in.
std::unique_ptr<AlloyModel> Build(const Dataset& dataset, const fit::FitSettings& settings) {
  return std::make_unique<ConstantModel>(dataset, settings.options.Number(kOption));
}

MethodInfo Info() {
  MethodInfo info;
  info.name = kMethod;
  info.summary = "a toy: eps = eps1 + i at every wavelength and composition (tests/toy_method.h)";
  info.read = &Read;
  info.build = &Build;
  info.traits.auto_rank = -1;  // not a candidate of auto
  info.traits.validate_default = false;
  OptionSpec eps1;
  eps1.name = kOption;
  eps1.flag = kFlag;
  eps1.kind = OptionKind::kNumber;
  eps1.range = {-100, -0.01, false};
  eps1.default_value = OptionValue::Number(-10);
  eps1.help = "the toy's eps1, at every wavelength and composition";
  info.options = {eps1};
  return info;
}

// The one registration, before main.
const MethodRegistration kRegistration{Info()};

}  // namespace
}  // namespace alloycolor::toy
