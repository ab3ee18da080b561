// The "blend" model: a weighted mean of other methods' models of the same samples,
//   eps(x, lambda) = sum_i w_i eps_i(x, lambda),   w_i > 0, sum w_i = 1,
// what `auto` delivers when its candidates' leave-one-out folds leave more than one of
// them worth a share (fit/methods.h, BuildAuto: w_i proportional to 1 / the mean squared
// fold error). A mean of eps is a convex combination: eps2 > 0 of every member holds for
// the blend, and at a composition where every member passes through its sample, so does
// the blend. The members are whole models of the registry's methods, kept in the file
// (parameters.members: weight and the member's own model document); the blend's own
// uncertainty comes from its folds, as every fitted model's does.
#ifndef ALLOYCOLOR_MODEL_BLEND_MODEL_H_
#define ALLOYCOLOR_MODEL_BLEND_MODEL_H_

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "alloycolor/model/alloy_model.h"

namespace alloycolor {

inline constexpr const char* kBlendMethod = "blend";

class BlendModel : public AlloyModel {
 public:
  struct Member {
    double weight;
    std::unique_ptr<AlloyModel> model;
  };
  // Members of one alloy system, two at least, with positive weights (normalised here to
  // sum to 1); the range is the members' common one. Throws Error otherwise.
  BlendModel(const Dataset& dataset, std::vector<Member> members);
  BlendModel(const nlohmann::json& doc, const std::string& source);

  std::string method() const override { return kBlendMethod; }
  std::vector<std::complex<double>> Permittivity(
      double x_atomic, const std::vector<double>& lambda_nm) const override;
  // Each member bound to the grid, their values weighted.
  std::unique_ptr<BoundModel> Bind(const std::vector<double>& lambda_nm) const override;

  const std::vector<Member>& members() const { return members_; }

 protected:
  nlohmann::json ParametersJson() const override;

 private:
  void Validate(const std::string& where);
  std::vector<Member> members_;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_MODEL_BLEND_MODEL_H_
