// Text helpers shared by the readers (n,k files, manifests, compositions), so that every
// error message is built and every number is read the same way:
//  - Fail throws the library's Error with a one-line message (control characters, which
//    can come from a damaged file or path, and bytes that are not UTF-8, from a file in
//    another encoding, become '?': a message is always valid UTF-8 on one line);
//  - Quote shows text from the user or a file in a message, made safe the same way and
//    cut to a readable length;
//  - ParseFiniteDouble reads a whole token as a finite number in the C locale
//    ("1.5", "-2e-3", "+4"; not "nan", "inf", "1.5x" or "");
//  - Trim, Lower, Lines split and normalise text; LineOfByte turns a byte offset (as
//    nlohmann-json reports one) into a 1-based line.
#ifndef ALLOYCOLOR_CORE_TEXT_H_
#define ALLOYCOLOR_CORE_TEXT_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace alloycolor {

[[noreturn]] void Fail(std::string message);

// 'text', or its first max_chars characters followed by "...", made safe as SafeText.
std::string Quote(std::string_view text, std::size_t max_chars = 40);

// Text made safe for one terminal line: control characters (newlines, escape codes) and
// every byte that is not part of a well-formed UTF-8 sequence become '?'; text over
// max_chars characters is cut, ending in "...".
std::string SafeText(std::string_view text, std::size_t max_chars);

// A message made safe for one terminal line (SafeText), cut at max_chars characters.
std::string MessageLine(std::string_view text, std::size_t max_chars = 300);

// A number for a message: up to 10 significant digits.
std::string FormatNumber(double value);

bool ParseFiniteDouble(std::string_view token, double* value);

// Removes spaces, tabs, '\r', '\f' and '\v' at both ends.
std::string_view Trim(std::string_view text);

// ASCII letters to lower case; other bytes unchanged.
std::string Lower(std::string_view text);

bool EndsWith(std::string_view text, std::string_view suffix);

// The name of `names` closest to `word` (a misspelt name, an option without its dashes),
// for a "did you mean" in a message: ASCII case ignored, distance counted in edits (a
// letter inserted, deleted, replaced, or two neighbours swapped); "" when the closest
// needs more than one edit per three letters of `word` (at least one allowed) and no name
// of three letters or more begins `word` or is begun by it ("out" for "output").
std::string NearestName(std::string_view word, const std::vector<std::string>& names);

// Splits text at '\n' (a final empty piece after a trailing '\n' is kept).
std::vector<std::string_view> Lines(std::string_view text);

// A time as ISO 8601 in UTC, "2026-12-06T10:00:00Z" (seconds since 1970).
std::string IsoDateUtc(long long seconds_since_epoch);
// Now, or where the environment sets SOURCE_DATE_EPOCH (reproducible files, as build tools
// honour it) that time: the date a fit records in its model's history.
std::string NowUtcIso8601();

// 1-based line of a byte offset of text (offsets past the end count as the last line).
int LineOfByte(std::string_view text, std::size_t byte);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_TEXT_H_
