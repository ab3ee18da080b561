// The fit's options checked before any work (fit/methods.h CheckFitOptions): each against
// its method's declaration (model/registry.h), then the fit grid's together.
#include <string>

#include "alloycolor/core/error.h"
#include "alloycolor/core/grid.h"
#include "alloycolor/core/text.h"
#include "alloycolor/fit/methods.h"
#include "alloycolor/model/registry.h"

namespace alloycolor::fit {
namespace {

std::string SpelledOption(const char* name, OptionSpelling spelling) {
  const OptionSpec* spec = FindOption(name);
  return spec != nullptr ? Spelled(*spec, spelling) : std::string(name);
}

}  // namespace

void CheckFitGrid(const OptionValues& options, const Dataset& dataset, OptionSpelling spelling) {
  const bool has_from = options.Has("lambda_from_nm"), has_to = options.Has("lambda_to_nm");
  const std::string range_names =
      SpelledOption("lambda_from_nm", spelling) + ", " + SpelledOption("lambda_to_nm", spelling);
  if (has_from != has_to) {
    throw Error(range_names + ": give both, or neither for the method's own range");
  }
  if (has_from && !(options.Number("lambda_from_nm") < options.Number("lambda_to_nm"))) {
    throw Error(range_names + ": from " + FormatNumber(options.Number("lambda_from_nm")) +
                " nm is not below to " + FormatNumber(options.Number("lambda_to_nm")) + " nm");
  }
  if (!options.Has("lambda_step_nm")) return;
  const double step = options.Number("lambda_step_nm");
  double lo = 0, hi = 0;
  if (has_from) {
    lo = options.Number("lambda_from_nm");
    hi = options.Number("lambda_to_nm");
  } else {
    const WavelengthRange common = CommonRange(dataset);
    lo = common.lo_nm;
    hi = common.hi_nm;
  }
  if ((hi - lo) / step > kMaxFitGridNodes) {
    throw Error(SpelledOption("lambda_step_nm", spelling) + ": a step of " + FormatNumber(step) +
                " nm over " + FormatNumber(lo) + "-" + FormatNumber(hi) + " nm makes over " +
                std::to_string(kMaxFitGridNodes) + " grid nodes; give a larger step");
  }
}

OptionValues CheckFitOptions(const std::string& method, const OptionValues& given,
                             const Dataset& dataset, OptionSpelling spelling) {
  OptionValues checked = CheckMethodOptions(method, given, spelling);
  CheckFitGrid(checked, dataset, spelling);
  return checked;
}

}  // namespace alloycolor::fit
