// Text helpers shared by the readers (n,k files, manifests, compositions), so that every
// error message is built and every number is read the same way:
//  - Fail throws the library's Error with a one-line message (control characters, which
//    can come from a damaged file or path, become '?');
//  - Quote shows text from the user in a message, cut to a readable length;
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

// 'text', or its first max_chars characters followed by "...".
std::string Quote(std::string_view text, std::size_t max_chars = 40);

// A message made safe for one terminal line: control characters (newlines, escape
// codes) become '?', and text over max_chars is cut, ending in "...".
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
// needs more than one edit per three letters of `word` (at least one allowed).
std::string NearestName(std::string_view word, const std::vector<std::string>& names);

// Splits text at '\n' (a final empty piece after a trailing '\n' is kept).
std::vector<std::string_view> Lines(std::string_view text);

// 1-based line of a byte offset of text (offsets past the end count as the last line).
int LineOfByte(std::string_view text, std::size_t byte);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_TEXT_H_
