// The byte check in front of toml++ (experiment/src/toml_bytes.hpp): non-ASCII outside strings and
// comments, which toml++ 3.3.0 cannot parse (marzer/tomlplusplus issue #295), and invalid UTF-8
// (RFC 3629) are refused with file:line; non-ASCII text in comments and strings still reads.
#include <gtest/gtest.h>

#include <string>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/scenario.hpp"

namespace fogradar::experiment {
namespace {

// The InvalidParameter message parse_scenario throws for `text`, or "" if it reads.
std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "f.toml");
  } catch (const InvalidParameter& e) {
    return e.what();
  }
  return "";
}

TEST(TomlBytes, NonAsciiOutsideStringsAndCommentsIsRefusedWithItsLine) {
  const std::string bare_key = error_of("[radar]\nk\xC3\xA9y = 1\n");
  EXPECT_EQ(bare_key.rfind("f.toml:2: non-ASCII byte", 0), 0u) << bare_key;
  EXPECT_NE(bare_key.find("issue #295"), std::string::npos) << bare_key;
  EXPECT_EQ(error_of("[radar]\nchirps_per_frame = 1\xC2\xB2\n").rfind("f.toml:2: non-ASCII", 0),
            0u);
  EXPECT_EQ(error_of("[rad\xC3\xA4r]\n").rfind("f.toml:1: non-ASCII", 0), 0u);
}

TEST(TomlBytes, NonAsciiInCommentsAndStringsReadsAsBefore) {
  EXPECT_EQ(error_of("# Gr\xC3\xBC\xC3\x9F"
                     "e \xF0\x9F\x8C\xAB\n[radar] # \xC3\xA9\nchirps_per_frame = 16\n"),
            "");
  // A string value reaches the scenario reader, which names the key and the allowed values.
  const std::string value = error_of("[radar]\nsweep_direction = \"\xC3\xBC\"\n");
  EXPECT_EQ(value.rfind("f.toml:2: radar.sweep_direction", 0), 0u) << value;
  EXPECT_EQ(error_of("[radar]\nsweep_direction = '\xC3\xBC'\n").find("non-ASCII"),
            std::string::npos);
}

TEST(TomlBytes, StringsEndWhereTomlEndsThem) {
  // After a multi-line string closed by five quotes, and after an escaped quote, text is bare
  // again.
  EXPECT_EQ(error_of("[radar.target]\nmodel = \"\"\"e\n\"\"\"\"\"\nk\xC3\xA9 = 1\n")
                .rfind("f.toml:4: non-ASCII", 0),
            0u);
  EXPECT_EQ(
      error_of("[radar.target]\nmodel = \"a\\\"b\" k\xC3\xA9\n").rfind("f.toml:2: non-ASCII", 0),
      0u);
  EXPECT_EQ(
      error_of("[radar.target]\nmodel = '''a\n''''' k\xC3\xA9\n").rfind("f.toml:3: non-ASCII", 0),
      0u);
}

TEST(TomlBytes, InvalidUtf8IsRefusedAnywhere) {
  // RFC 3629 sec. 4: no lone continuation byte, no overlong form, no surrogate, nothing past
  // U+10FFFF.
  for (const char* bad :
       {"\x80", "\xC0\xAF", "\xE0\x80\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xFF", "\xC3"}) {
    const std::string message = error_of(std::string("# ") + bad + "\n");
    EXPECT_EQ(message.rfind("f.toml:1: invalid UTF-8", 0), 0u) << message;
  }
}

}  // namespace
}  // namespace fogradar::experiment
