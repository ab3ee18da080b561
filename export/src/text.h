// Text helpers shared by the export files (internal).
#ifndef ALLOYCOLOR_EXPORT_SRC_TEXT_H_
#define ALLOYCOLOR_EXPORT_SRC_TEXT_H_

#include <cstdio>
#include <cstdlib>
#include <string>

namespace alloycolor::exports::text {

// Mitsuba 3 reads spectrum files line by line into 1,024 bytes (Properties::Spectrum):
// a longer comment line would be cut and its rest read as numbers.
inline constexpr std::size_t kMaxCommentBytes = 240;

// The shortest of 15-17 significant digits that reads back as the same double.
inline std::string Number(double value) {
  char buf[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
    if (std::strtod(buf, nullptr) == value) break;
  }
  return buf;
}

inline std::string ShortNumber(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

// At most kMaxCommentBytes bytes, cut at a character boundary, with no line breaks.
inline std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  if (text.size() > kMaxCommentBytes) {
    std::size_t cut = kMaxCommentBytes - 3;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
    text = text.substr(0, cut) + "...";
  }
  return text;
}

// XML comments may not contain "--".
inline std::string XmlComment(std::string text) {
  text = OneLine(text);
  std::string out;
  for (char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return "<!-- " + out + " -->\n";
}

}  // namespace alloycolor::exports::text

#endif  // ALLOYCOLOR_EXPORT_SRC_TEXT_H_
