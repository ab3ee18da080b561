#include "alloycolor/core/text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <system_error>

#include "alloycolor/core/error.h"

namespace alloycolor {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// The length of the well-formed UTF-8 sequence at the start of text (RFC 3629: no
// overlong forms, no surrogates, nothing past U+10FFFF), or 0 when there is none.
std::size_t Utf8SequenceLength(std::string_view text) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) lo = 0xA0;
    if (lead == 0xED) hi = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) lo = 0x90;
    if (lead == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (text.size() < length || byte(1) < lo || byte(1) > hi) return 0;
  for (std::size_t i = 2; i < length; ++i) {
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

std::string SafeText(std::string_view text, std::size_t max_chars) {
  std::string line;
  line.reserve(std::min(text.size(), max_chars + 3));
  std::size_t chars = 0;
  while (!text.empty()) {
    if (chars >= max_chars) {
      line += "...";
      break;
    }
    const std::size_t length = Utf8SequenceLength(text);
    const unsigned char u = static_cast<unsigned char>(text.front());
    if (length == 0 || u < 0x20 || u == 0x7f) {
      line += '?';
      text.remove_prefix(1);
    } else {
      line.append(text.substr(0, length));
      text.remove_prefix(length);
    }
    ++chars;
  }
  return line;
}

void Fail(std::string message) { throw Error(SafeText(message, std::string::npos)); }

std::string Quote(std::string_view text, std::size_t max_chars) {
  return "'" + SafeText(text, max_chars) + "'";
}

std::string MessageLine(std::string_view text, std::size_t max_chars) {
  return SafeText(text, max_chars);
}

std::string FormatNumber(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return buffer;
}

bool ParseFiniteDouble(std::string_view token, double* value) {
  const bool plus = !token.empty() && token.front() == '+';
  if (plus) token.remove_prefix(1);
  if (token.empty() || (plus && token.front() == '-')) return false;
  const char* end = token.data() + token.size();
  double parsed = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), end, parsed);
  if (ec != std::errc() || ptr != end || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

std::string_view Trim(std::string_view text) {
  while (!text.empty() && IsBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && IsBlank(text.back())) text.remove_suffix(1);
  return text;
}

std::string Lower(std::string_view text) {
  std::string result(text);
  for (char& c : result) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return result;
}

bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

namespace {

// Optimal string alignment distance: Levenshtein with adjacent swaps counted as one edit.
std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t replace = d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, replace});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::string NearestName(std::string_view word, const std::vector<std::string>& names) {
  constexpr std::size_t kMaxLength = 100;  // longer words are not names misspelt
  if (word.empty() || word.size() > kMaxLength) return "";
  const std::string lower_word = Lower(word);
  const std::size_t allowed = std::max<std::size_t>(1, word.size() / 3);
  std::string nearest;
  std::size_t best = allowed + 1;
  for (const std::string& name : names) {
    if (name.size() > kMaxLength) continue;
    const std::size_t distance = EditDistance(lower_word, Lower(name));
    if (distance < best) {
      best = distance;
      nearest = name;
    }
  }
  if (!nearest.empty()) return nearest;
  // Failing that, a name of three letters or more that begins the word or that the word
  // begins ("output" for "out", "obs" for "observer"): the longest shared start wins.
  std::size_t longest = 0;
  for (const std::string& name : names) {
    const std::string lower_name = Lower(name);
    const std::size_t shared = std::min(lower_name.size(), lower_word.size());
    if (shared < 3 || shared <= longest || name.size() > kMaxLength) continue;
    if (lower_name.compare(0, shared, lower_word, 0, shared) == 0) {
      longest = shared;
      nearest = name;
    }
  }
  return nearest;
}

std::vector<std::string_view> Lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

int LineOfByte(std::string_view text, std::size_t byte) {
  byte = std::min(byte, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + byte, '\n'));
}

std::string IsoDateUtc(long long seconds_since_epoch) {
  const std::time_t t = static_cast<std::time_t>(seconds_since_epoch);
  std::tm utc{};
  if (gmtime_r(&t, &utc) == nullptr) return "";
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string NowUtcIso8601() {
  const char* fixed = std::getenv("SOURCE_DATE_EPOCH");
  double seconds = 0;
  if (fixed != nullptr && ParseFiniteDouble(fixed, &seconds) && seconds >= 0 && seconds < 1e11) {
    return IsoDateUtc(static_cast<long long>(seconds));
  }
  return IsoDateUtc(static_cast<long long>(std::time(nullptr)));
}

}  // namespace alloycolor
