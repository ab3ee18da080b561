// The validation report as documents: JSON and a self-contained HTML page with inline SVG
// plots and colour swatches. These only format what ComputeValidation computed
// (validate/validation.h): the program (`alloycolor validate`) and the Python module
// (`alloycolor.validate`) write the same documents from the same report.
#ifndef ALLOYCOLOR_VALIDATE_REPORT_H_
#define ALLOYCOLOR_VALIDATE_REPORT_H_

#include <nlohmann/json.hpp>
#include <string>

#include "alloycolor/validate/validation.h"

namespace alloycolor::validate {

// {"format": "alloycolor-validation", "version": 1, "data": ..., "methods": [...],
//  "holdouts": [{"x": ..., "results": {METHOD: {"delta_e00": {"0": ...}, ...}}}], ...}
nlohmann::json ValidationJson(const ValidationReport& report);

// A self-contained HTML page (inline CSS and SVG; no scripts, no external files).
std::string ValidationHtml(const ValidationReport& report);

}  // namespace alloycolor::validate

#endif  // ALLOYCOLOR_VALIDATE_REPORT_H_
