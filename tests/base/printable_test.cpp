// printable(): text from files and scripts made safe to print (engine/base/format.hpp).
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"

using hapscene::printable;
using namespace std::string_literals;

TEST_CASE("printable escapes control characters and keeps printable text and UTF-8") {
  CHECK(printable("spring") == "spring");
  CHECK(printable("a\tb") == "a\tb");  // print() separates values with tabs
  CHECK(printable("x\nPASS y\r") == "x\\nPASS y\\r");
  CHECK(printable("\x1b[2K") == "\\x1b[2K");
  CHECK(printable("cut\0here"s) == "cut\\x00here");
  CHECK(printable("\x7f") == "\\x7f");
  CHECK(printable("F = \xc2\xb5N, 20 \xe2\x84\x83, \xf0\x9f\x98\x80") == "F = \xc2\xb5N, 20 \xe2\x84\x83, \xf0\x9f\x98\x80");
  CHECK(printable("\xc2\x9b" "2J") == "\\xc2\\x9b2J");                    // C1 control (CSI)
  CHECK(printable("\xff\xfe") == "\\xff\\xfe");                            // not UTF-8
  CHECK(printable("\xe2\x84") == "\\xe2\\x84");                            // cut short
  CHECK(printable("\xc0\xaf") == "\\xc0\\xaf");                            // overlong
  CHECK(printable("\xed\xa0\x80") == "\\xed\\xa0\\x80");                   // a surrogate
  // Escaping twice changes nothing.
  const std::string once = printable("a\nb\0c\xff"s);
  CHECK(printable(once) == once);
}

TEST_CASE("write_printable never splits an escape and always ends the text") {
  char out[6];
  CHECK(hapscene::write_printable("ab\ncd", out, sizeof out) == 5);
  CHECK(std::string(out) == "ab\\nc");
  CHECK(hapscene::write_printable("abcd\ne", out, sizeof out) == 4);  // "\\n" would not fit
  CHECK(std::string(out) == "abcd");
  CHECK(hapscene::write_printable("\x01\x02", out, sizeof out) == 4);
  CHECK(std::string(out) == "\\x01");
  CHECK(hapscene::write_printable("x", out, 1) == 0);
  CHECK(out[0] == '\0');
}

TEST_CASE("an InputError's message is printable, NUL and all") {
  const hapscene::InputError error("env.json: /effects/0/type: unknown effect type \"a\nPASS\0b\""s);
  CHECK(std::string(error.what()) == "env.json: /effects/0/type: unknown effect type \"a\\nPASS\\x00b\"");
}
