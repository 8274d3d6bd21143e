// Text from students, made safe for where it goes. Student ids (folder names), file names, compiler messages and
// test output are bytes that may not be UTF-8 and may hold terminal control sequences (ESC [2J clears a screen,
// ESC ] 0 ; ... BEL retitles a window, 8-bit C1 controls) or bidirectional overrides. Each output format has one
// function here, and the writer of that format calls it on every text it did not write itself.
#pragma once

#include <map>
#include <string>

namespace simlab::engine {

/// `bytes` as valid UTF-8; valid text comes back unchanged. What is not valid (a byte that cannot start a
/// sequence, an overlong form, a surrogate U+D800..U+DFFF, a code point past U+10FFFF, a sequence cut short)
/// becomes U+FFFD, one for each maximal subpart as Unicode recommends (chapter 3, "U+FFFD Substitution of Maximal
/// Subparts"; also WHATWG's decoder and Python's errors="replace"): a stray byte is one U+FFFD, C0 80 is two,
/// ED A0 80 three, F4 90 80 80 four, and a sequence that starts well but stops early (E2 9C then the end, or
/// E2 9C 41) is one U+FFFD for the bytes it had.
std::string validUtf8(const std::string& bytes);
/// True if `bytes` is valid UTF-8 by the same rules.
bool isValidUtf8(const std::string& bytes);

/// For a terminal, a log or plain text: validUtf8, then every control character shown as an escape a person can
/// read (ASCII, so nothing of it acts on a terminal):
///   - tab, newline and carriage return as "\t", "\n", "\r"; other C0 controls (U+0000..U+001F) and DEL as "\x1b";
///   - C1 controls (U+0080..U+009F) as "\u009b";
///   - the bidirectional controls (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069) and the Unicode line
///     and paragraph separators (U+2028, U+2029) as "\u202e".
/// With `keepNewlines` (multi-line text such as a compiler's message) newlines and tabs stay as they are and a
/// carriage return just before a newline is dropped (CR LF becomes LF); any other carriage return is still "\r",
/// as it would let a line overwrite itself. A backslash stays a backslash: this is for display, not a reversible
/// encoding. printable(printable(x)) == printable(x).
std::string printable(const std::string& bytes, bool keepNewlines = false);

/// A CSV cell: printable on one line, then neutralized against formula injection as OWASP advises: if `text`
/// begins, raw or after leading spaces, with '=', '+', '-', '@', a tab or a carriage return, the cell gets a
/// leading single quote. The cell is quoted with double quotes (inner ones doubled) if a quote was added
/// or it holds a comma, a double quote or a semicolon (the separator Excel uses in many locales). So 3.5 and plain
/// stay as they are, -2+3 becomes "'-2+3" (with the double quotes), and a tab then x becomes "'\tx". Numbers
/// simlab writes itself are not passed through here.
std::string csvCell(const std::string& text);

/// `s` without the spaces and tabs at either end (a cell as a person typed it).
std::string trimmed(const std::string& s);

/// A cell of a CSV file simlab wrote, as it was before csvCell neutralized it: without the apostrophe put before a
/// cell a spreadsheet would read as a formula.
std::string csvCellValue(const std::string& cell);

/// Inline Markdown text for a table cell, a heading or a line after a label ("- " + markdownText(x)): printable on
/// one line (a newline shows as "\n": in Markdown it would end the cell or start a block), then escaped so it
/// renders as the same characters and cannot change the document's structure: '\', '`', '|', '*', '_', '[' and
/// ']' get a backslash, a '<' that could start a tag or an autolink (before a letter, '/', '!' or '?') becomes
/// "&lt;", and a '&' that could start a character reference "&amp;"; the rest stays as written, for a reader of the
/// file as text. So "a|b" is "a\|b", "<script>" is "&lt;script>", "p->x" and "i < n" stay, and a student's "\|" is
/// "\\\|". In case the text starts a line, a first character that would begin a block ('#', '+', '-', '=', '~', '>',
/// or digits then '.' or ')') gets a backslash and a first space becomes "&#32;" (no indented code block). For
/// multi-line text, indent printable(text, true) as a code block instead.
std::string markdownText(const std::string& text);

/// Text for XML 1.0 content or a double- or single-quoted attribute (JUnit): validUtf8, '&', '<', '>', '"' and '\''
/// as entities; tab, newline and carriage return as "&#9;", "&#10;", "&#13;" (so an attribute keeps them instead
/// of a reader turning them into spaces); the characters XML 1.0 forbids (other C0 controls, U+FFFE, U+FFFF) as
/// U+FFFD. Everything else, C1 and bidirectional controls included, is kept.
std::string xmlText(const std::string& text);

/// `word` as a POSIX shell reads it back as one word: as it is where that is safe, else in single quotes.
std::string shellWord(const std::string& word);

/// A file simlab writes from a template of its own (a platform's script, grader/*/scripts/): `text` with each
/// @NAME@ of `values` in its place. A @NAME@ alone on its line with an empty value takes its line with it. Throws
/// std::logic_error naming a @NAME@ the template holds and `values` has not, or one of `values` it never holds.
std::string filledTemplate(std::string text, const std::map<std::string, std::string>& values);

}  // namespace simlab::engine
