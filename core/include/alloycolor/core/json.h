// Strict JSON reading for manifests and model files. JSON (RFC 8259) leaves duplicate
// object keys undefined and nlohmann-json keeps the last one silently; a file that says
// two things about one field is refused instead: RejectDuplicateKeys is a parser callback
// (nlohmann::json::parse(text, callback)) that tracks the keys of every open object and
// throws Error "SOURCE: duplicate key 'k' in one object" on the second.
// WholeNumber reads an integer field exactly (2^32 + 1 is not 1; 2.5 is not 2).
// JsonText is the one way JSON is written: a string holding bytes that are not UTF-8 (a
// file name from a Latin-1 folder, byte 0xff) is written with U+FFFD in their place
// instead of failing (nlohmann's default throws "invalid UTF-8 byte", naming nothing).
#ifndef ALLOYCOLOR_CORE_JSON_H_
#define ALLOYCOLOR_CORE_JSON_H_

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace alloycolor {

nlohmann::json::parser_callback_t RejectDuplicateKeys(const std::string& source);

// True, with *value set, when `value_json` is an integer (or a float with no fraction)
// within [lo, hi].
// `value` as JSON text: indent < 0 for one line, else that many spaces per level;
// invalid UTF-8 replaced by U+FFFD.
std::string JsonText(const nlohmann::json& value, int indent = -1);

bool WholeNumber(const nlohmann::json& value_json, std::int64_t lo, std::int64_t hi,
                 std::int64_t* value);

// A number, or null where it is not finite (JSON has no NaN nor infinity).
nlohmann::json NumberOrNull(double value);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_JSON_H_
