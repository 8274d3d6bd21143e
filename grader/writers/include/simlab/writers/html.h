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
/// An outcome's badge: its word after a symbol that says the same without colour (a check mark for passed, a
/// cross for failed, a warning sign for the rest), coloured by outcomeClass.
std::string outcomeBadge(const std::string& outcome);

/// A picture in a page with its text alternative. A plot simlab drew (simlab/plot.h's drawPlot: an SVG whose
/// <metadata id="simlab-plot-data"> holds its points) is shown with its title as the image's alt, its description
/// (the SVG's <desc>) beside it, and a link to its points as tables, in a <details> after the figure; another SVG
/// with a <desc> of its own gets that description; any other picture gets `alt`. `src` is the image's source (a data
/// URI, or a path the page resolves), `svg` the picture's text when it is an SVG (else empty), `id` a name unique in
/// the page, and `link` a file to link in the caption (empty: none).
std::string figureHtml(const std::string& id, const std::string& src, const std::string& svg, const std::string& alt,
                       const std::string& link = "");

}  // namespace simlab::engine::writers
