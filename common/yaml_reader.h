// Strict reading of human-written YAML (rig.yaml, plan.yaml, scene.yaml): every value is
// checked, every error names file:line:column and what was expected, and keys nobody read
// are errors (a typo must not be silently ignored).
#pragma once

#include <yaml-cpp/yaml.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/error.h"

namespace brdfrig {

class YamlNode;

// Loads a YAML file (a regular file of at most kMaxYamlFileBytes); parse errors become
// FileError with the parser's position.
inline constexpr std::size_t kMaxYamlFileBytes = std::size_t{8} << 20;  // 8 MiB
YamlNode LoadYamlFile(const std::string& path);
// Same for text already in memory; `source_name` is used in messages.
YamlNode LoadYamlString(const std::string& text, const std::string& source_name);

// A node plus where it came from. Maps remember which keys were read so that Finish()
// can reject the rest.
class YamlNode {
 public:
  YamlNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path);

  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  bool Has(const std::string& key) const;

  // Child access. Required throws if missing; Optional returns nullopt.
  YamlNode Required(const std::string& key) const;
  std::optional<YamlNode> Optional(const std::string& key) const;

  // Typed scalars. Numbers must be finite. Messages name the expected type.
  double AsDouble() const;
  int AsInt() const;
  bool AsBool() const;
  std::string AsString() const;
  std::vector<double> AsDoubles() const;   // a sequence of numbers
  std::vector<YamlNode> Elements() const;  // sequence items
  std::vector<std::string> Keys() const;   // map keys in file order

  // Shorthands: value of a key, or the default when absent.
  double Get(const std::string& key, double fallback) const;
  int Get(const std::string& key, int fallback) const;
  bool Get(const std::string& key, bool fallback) const;
  std::string Get(const std::string& key, const std::string& fallback) const;
  std::string Get(const std::string& key, const char* fallback) const;

  // Rules on a number read from this node.
  double InRange(double value, double lo, double hi) const;  // lo <= value <= hi
  double Positive(double value) const;                       // value > 0

  // Throws a FileError for the first key of this map that was never read.
  void Finish() const;

  // An error pointing at this node: "file:line:col: <path>: message".
  [[noreturn]] void Fail(const std::string& message) const;

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  int line() const;  // 1-based

 private:
  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;  // e.g. "effects[2].sigma"
  std::shared_ptr<std::set<std::string>> used_keys_;
};

}  // namespace brdfrig
