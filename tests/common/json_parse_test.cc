#include "common/json_parse.h"

#include <gtest/gtest.h>

#include <string>

#include "common/error.h"

namespace brdfrig {
namespace {

// Issue 25, finding 5: a file nested 200,000 arrays deep parsed, then overflowed the stack when
// the document was copied, printed or compared.
TEST(ParseJsonTest, TooDeepNestingIsAFileErrorNamingTheSource) {
  const std::string deep = std::string(200000, '[') + std::string(200000, ']');
  try {
    (void)ParseJson(deep, "deep.json");
    FAIL() << "a 200,000 deep document was accepted";
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), "deep.json");
    EXPECT_NE(std::string(e.what()).find("nested more than 64 deep"), std::string::npos)
        << e.what();
  }
  const std::string objects = "{\"a\":" + std::string(100, '[') + std::string(100, ']') + "}";
  EXPECT_THROW((void)ParseJson(objects, "objects.json"), FileError);
}

TEST(ParseJsonTest, ParsesUpToTheLimitAndIgnoresBracketsInStrings) {
  const std::string at_limit =
      std::string(kMaxJsonDepth, '[') + "1" + std::string(kMaxJsonDepth, ']');
  EXPECT_EQ(ParseJson(at_limit, "ok.json").dump(), at_limit);
  const std::string text = "{\"s\": \"" + std::string(1000, '[') + "\\\"{\", \"n\": [1, 2]}";
  const nlohmann::json doc = ParseJson(text, "strings.json");
  EXPECT_EQ(doc["s"].get<std::string>().size(), 1002u);
  EXPECT_EQ(doc["n"].size(), 2u);
}

TEST(ParseJsonTest, InvalidJsonIsAFileErrorNamingTheSource) {
  try {
    (void)ParseJson("{\"a\": 1e400}", "big.json");
    FAIL() << "1e400 was accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("big.json: not valid JSON"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)ParseJson("[1, 2", "cut.json"), FileError);
}

}  // namespace
}  // namespace brdfrig
