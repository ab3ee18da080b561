// Strict JSON reading for manifests and model files. JSON (RFC 8259) leaves duplicate
// object keys undefined and nlohmann-json keeps the last one silently; a file that says
// two things about one field is refused instead: RejectDuplicateKeys is a parser callback
// (nlohmann::json::parse(text, callback)) that tracks the keys of every open object and
// throws Error "SOURCE: duplicate key 'k' in one object" on the second.
// WholeNumber reads an integer field exactly (2^32 + 1 is not 1; 2.5 is not 2).
#ifndef ALLOYCOLOR_CORE_JSON_H_
#define ALLOYCOLOR_CORE_JSON_H_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace alloycolor {

nlohmann::json::parser_callback_t RejectDuplicateKeys(const std::string& source);

// True, with *value set, when `value_json` is an integer (or a float with no fraction)
// within [lo, hi].
bool WholeNumber(const nlohmann::json& value_json, std::int64_t lo, std::int64_t hi,
                 std::int64_t* value);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_JSON_H_
