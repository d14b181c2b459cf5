#include "common/yaml_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace brdfrig {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(YamlReaderTest, ReadsTypedValuesAndDefaults) {
  YamlNode root = LoadYamlString("a: 1.5\nb: 3\nc: true\nd: hello\ne: [1, 2]\n", "t.yaml");
  EXPECT_DOUBLE_EQ(root.Required("a").AsDouble(), 1.5);
  EXPECT_EQ(root.Get("b", 0), 3);
  EXPECT_TRUE(root.Get("c", false));
  EXPECT_EQ(root.Get("d", "x"), "hello");
  EXPECT_EQ(root.Required("e").AsDoubles(), (std::vector<double>{1, 2}));
  EXPECT_DOUBLE_EQ(root.Get("missing", 7.0), 7.0);
  root.Finish();
}

TEST(YamlReaderTest, UnknownKeyNamesFileLineAndColumn) {
  YamlNode root = LoadYamlString("a: 1\nsensor:\n  bits: 12\n  bitz: 3\n", "scene.yaml");
  root.Get("a", 0);
  YamlNode sensor = root.Required("sensor");
  sensor.Get("bits", 0);
  root.Finish();
  EXPECT_THAT(ErrorOf([&] { sensor.Finish(); }),
              HasSubstr("scene.yaml:4:3: unknown key 'sensor.bitz'"));
}

// Issue 15, finding 6: yaml-cpp keeps the first of two equal keys, so a second `exposures:`
// further down a plan was silently ignored.
TEST(YamlReaderTest, DuplicateKeyIsAnErrorAtTheSecond) {
  EXPECT_THAT(ErrorOf([] { LoadYamlString("a: 1\nb: 2\na: 3\n", "plan.yaml"); }),
              HasSubstr("plan.yaml:3:1: duplicate key 'a'"));
  EXPECT_THAT(ErrorOf([] { LoadYamlString("s:\n  - {x: 1, y: 2, x: 3}\n", "scene.yaml"); }),
              HasSubstr("scene.yaml:2:18: duplicate key 'x'"));
  // Aliases are checked once, however often they are used (no "billion laughs").
  std::string bomb = "a0: &a0 {k: 1}\n";
  for (int i = 1; i < 40; ++i) {
    bomb += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [*a" + std::to_string(i - 1) +
            ", *a" + std::to_string(i - 1) + "]\n";
  }
  EXPECT_NO_THROW(LoadYamlString(bomb, "bomb.yaml"));
}

TEST(YamlReaderTest, WrongTypeSaysWhatWasExpectedAndWhere) {
  YamlNode root = LoadYamlString("list:\n  - 1\n  - two\n", "plan.yaml");
  EXPECT_THAT(ErrorOf([&] { root.Required("list").AsDoubles(); }),
              HasSubstr("plan.yaml:3:5: list[1]: expected a number, got 'two'"));
}

TEST(YamlReaderTest, MissingRequiredKeyIsAnError) {
  YamlNode root = LoadYamlString("a: 1\n", "rig.yaml");
  EXPECT_THAT(ErrorOf([&] { root.Required("camera"); }),
              HasSubstr("missing required key 'camera'"));
}

TEST(YamlReaderTest, KeyWithoutValueIsAnErrorNotTheDefault) {
  YamlNode root = LoadYamlString("host: 10.0.0.2\nport:\n", "rig.yaml");
  EXPECT_THAT(ErrorOf([&] { root.Get("port", 502); }),
              HasSubstr("rig.yaml:2:1: port: no value given"));
}

TEST(YamlReaderTest, RangeChecksReportTheValue) {
  YamlNode root = LoadYamlString("albedo: 1.5\n", "scene.yaml");
  YamlNode albedo = root.Required("albedo");
  EXPECT_THAT(ErrorOf([&] { albedo.InRange(albedo.AsDouble(), 0, 1); }),
              HasSubstr("scene.yaml:1:9: albedo: must be in [0, 1], got 1.5"));
}

TEST(YamlReaderTest, SyntaxErrorCarriesParserPosition) {
  EXPECT_THAT(ErrorOf([] { LoadYamlString("a: [1, 2\nb: 3\n", "bad.yaml"); }),
              HasSubstr("bad.yaml:"));
}

TEST(YamlReaderTest, MissingFileIsAFileError) {
  EXPECT_THAT(ErrorOf([] { LoadYamlFile("/nonexistent/x.yaml"); }),
              HasSubstr("/nonexistent/x.yaml: cannot open file"));
}

}  // namespace
}  // namespace brdfrig
