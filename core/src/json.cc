#include "alloycolor/core/json.h"

#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "alloycolor/core/text.h"

namespace alloycolor {

nlohmann::json::parser_callback_t RejectDuplicateKeys(const std::string& source) {
  auto open = std::make_shared<std::vector<std::set<std::string>>>();
  return
      [open, source](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        if (event == Event::object_start) {
          open->emplace_back();
        } else if (event == Event::object_end) {
          if (!open->empty()) open->pop_back();
        } else if (event == Event::key && !open->empty()) {
          const std::string key = parsed.is_string() ? parsed.get<std::string>() : parsed.dump();
          if (!open->back().insert(key).second) {
            Fail(source + ": duplicate key " + Quote(key) +
                 " in one object (a JSON file must give each field once)");
          }
        }
        return true;
      };
}

std::string JsonText(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool WholeNumber(const nlohmann::json& value_json, std::int64_t lo, std::int64_t hi,
                 std::int64_t* value) {
  if (value_json.is_number_unsigned()) {
    const std::uint64_t v = value_json.get<std::uint64_t>();
    if (hi < 0 || v > static_cast<std::uint64_t>(hi)) return false;
    if (lo > 0 && v < static_cast<std::uint64_t>(lo)) return false;
    *value = static_cast<std::int64_t>(v);
    return true;
  }
  if (value_json.is_number_integer()) {
    const std::int64_t v = value_json.get<std::int64_t>();
    if (v < lo || v > hi) return false;
    *value = v;
    return true;
  }
  if (value_json.is_number_float()) {
    const double v = value_json.get<double>();
    if (!std::isfinite(v) || v != std::floor(v) || v < static_cast<double>(lo) ||
        v > static_cast<double>(hi)) {
      return false;
    }
    *value = static_cast<std::int64_t>(v);
    return true;
  }
  return false;
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace alloycolor
