// Text written into XML, HTML and SVG documents (reports, charts, material files, the
// explorer page). Text from a user's file enters a document only through these.
#ifndef ALLOYCOLOR_CORE_MARKUP_H_
#define ALLOYCOLOR_CORE_MARKUP_H_

#include <string>

namespace alloycolor {

// The five XML special characters as entities (&amp; &lt; &gt; &quot; &#39;), so the text
// can stand in element content and in quoted attributes of XML and HTML alike.
std::string EscapeXml(const std::string& text);

// JSON text made safe to stand inside an HTML <script> element: <, > and & become
// \u003c, \u003e and \u0026, and U+2028, U+2029 (line ends to JavaScript) \u2028, \u2029,
// so the text can neither close the element nor start a comment or markup (HTML Living
// Standard, "Restrictions for contents of script elements"). These characters occur in
// JSON only inside strings, where the escapes stand for the same characters: a JSON
// parser reads the same value.
std::string EscapeJsonForScript(const std::string& json_text);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_MARKUP_H_
