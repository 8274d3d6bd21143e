// Text from students, made safe for each format: valid UTF-8, no control character a terminal would act on, no
// spreadsheet formula, no Markdown or XML structure.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "simlab/common/text.h"
#include "simlab/writers/roster.h"

namespace text_test {

using namespace simlab::engine;
using namespace std::string_literals;

namespace {

const std::string kFffd = "\xEF\xBF\xBD";  // U+FFFD

std::string fffd(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += kFffd;
    return s;
}

}  // namespace

TEST_CASE("valid UTF-8 comes back unchanged", "[text]") {
    // ASCII with controls; 2, 3 and 4-byte sequences; the edges: U+10FFFF, U+D7FF and U+E000 around the surrogates.
    const std::string valid = "plain ASCII ~!@#$%^&*()\t\n\r\x01\x7f, \xC3\xA9t\xC3\xA9 \xE2\x9C\x93 "s +
                              "\xF0\x9F\x8D\x8E \xF4\x8F\xBF\xBF \xED\x9F\xBF \xEE\x80\x80";
    CHECK(validUtf8(valid) == valid);
    CHECK(isValidUtf8(valid));
    CHECK(validUtf8("nul\0inside"s) == "nul\0inside"s);
    CHECK(validUtf8("") == "");
    CHECK(isValidUtf8(""));
}

TEST_CASE("invalid UTF-8 becomes one U+FFFD per maximal subpart", "[text]") {
    CHECK(validUtf8("a\xFF" "b") == "a" + kFffd + "b");                 // never a UTF-8 byte
    CHECK(validUtf8("\x80\xBF") == fffd(2));                            // continuation bytes alone
    CHECK(validUtf8("\xC0\x80") == fffd(2));                            // an overlong NUL
    CHECK(validUtf8("\xE0\x80\xAF") == fffd(3));                        // an overlong '/'
    CHECK(validUtf8("\xED\xA0\x80") == fffd(3));                        // a surrogate, U+D800
    CHECK(validUtf8("\xF4\x90\x80\x80") == fffd(4));                    // U+110000, past U+10FFFF
    CHECK(validUtf8("\xF5\x80\x80\x80") == fffd(4));
    CHECK(validUtf8("end\xE2\x9C") == "end" + kFffd);                   // a 3-byte sequence cut short at the end
    CHECK(validUtf8("\xE2\x9C" "A") == kFffd + "A");                    // ... and before an ASCII byte
    CHECK(validUtf8("\xF0\x9F\x8D") == kFffd);                          // a 4-byte one cut short
    CHECK(validUtf8("\xE2\x9C\xE2\x9C\x93") == kFffd + "\xE2\x9C\x93"); // the next sequence is still read
    for (const std::string bad : {"\xFF", "\xC0\x80", "\xED\xA0\x80", "\xF4\x90\x80\x80", "a\xE2\x9C"}) {
        CHECK_FALSE(isValidUtf8(bad));
        CHECK(isValidUtf8(validUtf8(bad)));
    }
}

TEST_CASE("control characters reach a terminal only as escapes a person can read", "[text]") {
    CHECK(printable("\x1b]0;pwned\x07") == "\\x1b]0;pwned\\x07");      // a window title
    CHECK(printable("\x1b[2J") == "\\x1b[2J");                          // clear the screen
    CHECK(printable("\xC2\x9B" "31m") == "\\u009b31m");                 // an 8-bit CSI, U+009B
    CHECK(printable("\xC2\x80\xC2\x9F") == "\\u0080\\u009f");
    CHECK(printable("abc\xE2\x80\xAE" "cba") == "abc\\u202ecba");       // right-to-left override
    CHECK(printable("\xE2\x80\x8E\xE2\x80\x8F\xE2\x80\xAA\xE2\x81\xA6\xE2\x81\xA9\xD8\x9C") ==
          "\\u200e\\u200f\\u202a\\u2066\\u2069\\u061c");
    CHECK(printable("line\xE2\x80\xA8sep") == "line\\u2028sep");
    CHECK(printable("nul\0del\x7f"s) == "nul\\x00del\\x7f");
    CHECK(printable("bad \xFF byte, cut \xE2\x9C") == "bad " + kFffd + " byte, cut " + kFffd);
    CHECK(printable("a \\ stays, \\x1b too") == "a \\ stays, \\x1b too");
    CHECK(printable("caf\xC3\xA9 \xE2\x9C\x93") == "caf\xC3\xA9 \xE2\x9C\x93");
    CHECK(printable(printable("\x1b[2J\xFF\n")) == printable("\x1b[2J\xFF\n"));
}

TEST_CASE("one line, or many with keepNewlines", "[text]") {
    CHECK(printable("two\nlines\tand a tab\r") == "two\\nlines\\tand a tab\\r");
    CHECK(printable("two\nlines\tand a tab", true) == "two\nlines\tand a tab");
    CHECK(printable("dos\r\nline\r\n", true) == "dos\nline\n");
    CHECK(printable("over\rwrite\r", true) == "over\\rwrite\\r");
    CHECK(printable("still\x1b[2J\x0b\x0c", true) == "still\\x1b[2J\\x0b\\x0c");
}

TEST_CASE("CSV cells never start a formula and are quoted when they need it", "[text]") {
    CHECK(csvCell("plain") == "plain");
    CHECK(csvCell("3.5") == "3.5");
    CHECK(csvCell("") == "");
    CHECK(csvCell("a b") == "a b");
    CHECK(csvCell("a,b") == "\"a,b\"");
    CHECK(csvCell("a;b") == "\"a;b\"");
    CHECK(csvCell("say \"hi\"") == "\"say \"\"hi\"\"\"");
    CHECK(csvCell("=HYPERLINK(\"http://x\",\"y\")") == "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
    CHECK(csvCell("+1") == "\"'+1\"");
    CHECK(csvCell("-2+3") == "\"'-2+3\"");
    CHECK(csvCell("@SUM(A1)") == "\"'@SUM(A1)\"");
    CHECK(csvCell("\tx") == "\"'\\tx\"");
    CHECK(csvCell("\rx") == "\"'\\rx\"");
    CHECK(csvCell("  =1") == "\"'  =1\"");
    CHECK(csvCell(" \t1") == "\"' \\t1\"");
    CHECK(csvCell("a=1") == "a=1");
    CHECK(csvCell("a\nb") == "a\\nb");
    CHECK(csvCell("a\x1b[2Jb\xFF") == "a\\x1b[2Jb" + kFffd);
    CHECK(csvCell("\x1b=1") == "\\x1b=1");  // starts with a backslash once shown
}

TEST_CASE("a CSV cell simlab wrote reads back as the text it was made from, shown", "[text]") {
    // What csvCellValue undoes is the apostrophe csvCell put there; a cell led by a tab or a return is neutralized
    // as its escape (found by fuzz-manual: a comment "'<tab>..." kept an apostrophe more at each regrade).
    for (const std::string text : {"plain", "=1", "+1", "-2+3", "@SUM(A1)", "  =1", "\tx", "\rx", " \t1", "a,b"}) {
        const std::vector<std::vector<std::string>> rows = readCsv(csvCell(text) + "\n");
        REQUIRE(rows.size() == 1);
        const std::string value = csvCellValue(rows[0][0]);
        CHECK(value == printable(text));
        CHECK(csvCellValue(readCsv(csvCell(value) + "\n")[0][0]) == value);  // and so again
    }
}

TEST_CASE("Markdown text renders as itself and cannot change the document's structure", "[text]") {
    CHECK(markdownText("plain words, 3.5") == "plain words, 3.5");
    CHECK(markdownText("a | b") == "a \\| b");
    CHECK(markdownText("<script>alert(1)</script>") == "&lt;script>alert(1)&lt;/script>");
    CHECK(markdownText("<!-- x --> <?php <https://x>") == "&lt;!-- x --> &lt;?php &lt;https://x>");
    // What a student wrote reads as written: an arrow, a comparison (CommonMark starts no tag there).
    CHECK(markdownText("state->getTime() < 4 > 3") == "state->getTime() < 4 > 3");
    CHECK(markdownText("> quoted") == "\\> quoted");
    CHECK(markdownText("`x` & *y* _z_ [l](u)") == "\\`x\\` & \\*y\\* \\_z\\_ \\[l\\](u)");
    CHECK(markdownText("ok && done") == "ok && done");              // read as text too: no entity where none can start
    CHECK(markdownText("&copy; &#60;") == "&amp;copy; &amp;#60;");  // what would be a character reference is not
    CHECK(markdownText("a\\|b") == "a\\\\\\|b");  // the student's backslash cannot escape the cell's end
    CHECK(markdownText("one\ntwo") == "one\\\\ntwo");
    CHECK(markdownText("\x1b[2J") == "\\\\x1b\\[2J");
    CHECK(markdownText("# title") == "\\# title");
    CHECK(markdownText("- item") == "\\- item");
    CHECK(markdownText("~~~") == "\\~~~");
    CHECK(markdownText("12. item") == "12\\. item");
    CHECK(markdownText("12") == "12");
    CHECK(markdownText("    code") == "&#32;   code");
    CHECK(markdownText("&lt;") == "&amp;lt;");
}

TEST_CASE("XML text is well-formed in content and in attributes", "[text]") {
    CHECK(xmlText("plain \xC3\xA9") == "plain \xC3\xA9");
    CHECK(xmlText("<a b='c'> & \"d\"") == "&lt;a b=&apos;c&apos;&gt; &amp; &quot;d&quot;");
    CHECK(xmlText("]]>") == "]]&gt;");
    CHECK(xmlText("tab\tnewline\nreturn\r") == "tab&#9;newline&#10;return&#13;");
    CHECK(xmlText("nul\0 bell\x07 esc\x1b"s) == "nul" + kFffd + " bell" + kFffd + " esc" + kFffd);
    CHECK(xmlText("bad \xFF \xED\xA0\x80") == "bad " + kFffd + " " + fffd(3));
    CHECK(xmlText("\xEF\xBF\xBE\xEF\xBF\xBF") == fffd(2));         // U+FFFE, U+FFFF
    CHECK(xmlText("\x7f\xC2\x9B\xE2\x80\xAE") == "\x7f\xC2\x9B\xE2\x80\xAE");  // allowed in XML 1.0, kept
}

}  // namespace text_test
