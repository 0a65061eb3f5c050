// Tests for sensor/base/input_error: the printed form "file:line:col: key 'k': message" with
// the parts that are known, and control bytes of the input shown escaped. Found by probing:
// a lens file with a NUL byte inside a number put the raw byte into the message, so that the
// printed line stopped at it (std::cerr << what()), and a carriage return or an escape
// sequence from a file would be sent to the user's terminal as it is.
#include "sensor/base/input_error.h"

#include <gtest/gtest.h>

#include <string>

namespace camsim {
namespace {

TEST(InputErrorText, NamesThePartsThatAreKnown) {
  EXPECT_EQ(formatInputError({"a.yaml", 3, 7}, "render.spp", "must be ≥ 1"),
            "a.yaml:3:7: key 'render.spp': must be ≥ 1");
  EXPECT_EQ(formatInputError({"a.yaml", 3, 0}, "", "bad"), "a.yaml:3: bad");
  EXPECT_EQ(formatInputError({"", 0, 0}, "k", "bad"), "<input>: key 'k': bad");
}

TEST(InputErrorText, ControlBytesArePrintedEscaped) {
  const std::string withNul("'1\0' is no number", 17);
  const InputError e({"lens\r.txt", 2, 1}, "radius\x1b", withNul);
  const std::string what = e.what();
  EXPECT_EQ(what, "lens\\x0d.txt:2:1: key 'radius\\x1b': '1\\x00' is no number");
  EXPECT_EQ(std::string(e.what()).size(), std::char_traits<char>::length(e.what()));
  // What the program holds stays as it was given; only the printed text is escaped.
  EXPECT_EQ(e.message(), withNul);
  // Tabs, newlines and UTF-8 are text, not control bytes.
  EXPECT_EQ(formatInputError({"f", 0, 0}, "", "a\tb\nc ≥ µm"), "f: a\tb\nc ≥ µm");
  EXPECT_EQ(formatInputError({"f", 0, 0}, "", "del\x7f"), "f: del\\x7f");
  // C1 controls in UTF-8 (U+009B: CSI), escaped; a lone continuation byte is left alone.
  EXPECT_EQ(formatInputError({"f", 0, 0}, "",
                             "a\xc2\x9b"
                             "31m"),
            "f: a\\xc2\\x9b31m");
  EXPECT_EQ(formatInputError({"f", 0, 0}, "", "\xc2\xa0 \x9b"), "f: \xc2\xa0 \x9b");
}

}  // namespace
}  // namespace camsim
