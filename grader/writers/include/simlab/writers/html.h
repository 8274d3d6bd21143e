// What simlab's HTML pages share: escaping, links, and the frame of a page with its style. Every page is
// self-contained: its style inline, no script, nothing fetched (a Content-Security-Policy says so to the browser).
#pragma once

#include <string>

namespace simlab::engine::writers {

/// Text from anywhere (a student id, a reason) for HTML content or a quoted attribute, on one line: printable
/// (valid UTF-8, controls and bidirectional overrides shown as escapes), then xmlText ('&', '<', '>', '"' and
/// '\'' as entities).
std::string htmlText(const std::string& text);
/// Multi-line text for a <pre> block: the same, with its newlines and tabs kept (as "&#10;" and "&#9;").
std::string htmlBlock(const std::string& text);

/// One segment of a relative URL: every byte but A-Z a-z 0-9 - . _ ~ as %XX. A student id "a b" is "a%20b".
std::string urlSegment(const std::string& bytes);

/// The page up to and including <body>, with `title` (escaped here) in the <title>.
std::string pageStart(const std::string& title);
/// The end of the page.
std::string pageEnd();

/// The class of an outcome's badge: "pass", "fail" (a wrong answer) or "error" (did not run to a verdict).
const char* outcomeClass(const std::string& outcome);

}  // namespace simlab::engine::writers
