// Text written into XML, HTML and SVG documents (reports, charts, material files).
#ifndef ALLOYCOLOR_CORE_MARKUP_H_
#define ALLOYCOLOR_CORE_MARKUP_H_

#include <string>

namespace alloycolor {

// The five XML special characters as entities (&amp; &lt; &gt; &quot; &#39;), so the text
// can stand in element content and in quoted attributes of XML and HTML alike.
std::string EscapeXml(const std::string& text);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_MARKUP_H_
