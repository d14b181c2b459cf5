#include "common/yaml_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"

namespace brdfrig {
namespace {

std::string ChildPath(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// yaml-cpp keeps both entries of a repeated key and lookups see the first: a second
// `exposures:` further down a plan would be silently ignored. Strict reading refuses it.
void RejectDuplicateKeys(const YAML::Node& node, const std::string& source, std::set<int>* visited,
                         int depth = 0) {
  // Deeper than any configuration: a hostile file must not exhaust the stack.
  if (depth > 64) {
    const YAML::Mark mark = node.Mark();
    throw FileError(source, mark.line + 1, mark.column + 1, "nested more than 64 levels deep");
  }
  // An alias is the anchored node again (same position): checked once, so that a chain of
  // aliases ("billion laughs") costs nothing here.
  if ((node.IsMap() || node.IsSequence()) && !visited->insert(node.Mark().pos).second) return;
  if (node.IsMap()) {
    std::set<std::string> seen;
    for (const auto& kv : node) {
      if (kv.first.IsScalar() && !seen.insert(kv.first.Scalar()).second) {
        const YAML::Mark mark = kv.first.Mark();
        throw FileError(source, mark.line + 1, mark.column + 1,
                        "duplicate key '" + kv.first.Scalar() + "' (each key may appear once)");
      }
      RejectDuplicateKeys(kv.second, source, visited, depth + 1);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) RejectDuplicateKeys(item, source, visited, depth + 1);
  }
}

}  // namespace

YamlNode LoadYamlFile(const std::string& path) {
  // Human-written configuration: a regular file of at most a few MiB (never a FIFO or device).
  return LoadYamlString(ReadFileToString(path, kMaxYamlFileBytes), path);
}

YamlNode LoadYamlString(const std::string& text, const std::string& source_name) {
  auto file = std::make_shared<const std::string>(source_name);
  try {
    YAML::Node root = YAML::Load(text);
    if (!root.IsMap()) {
      throw FileError(source_name, 1, 1, "expected a mapping of keys at the top level");
    }
    std::set<int> visited;
    RejectDuplicateKeys(root, source_name, &visited);
    return YamlNode(root, file, "");
  } catch (const YAML::Exception& e) {
    throw FileError(source_name, e.mark.line + 1, e.mark.column + 1, e.msg);
  }
}

YamlNode::YamlNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
    : node_(std::move(node)),
      file_(std::move(file)),
      path_(std::move(path)),
      used_keys_(std::make_shared<std::set<std::string>>()) {}

int YamlNode::line() const { return node_.Mark().line + 1; }

void YamlNode::Fail(const std::string& message) const {
  const YAML::Mark mark = node_.Mark();
  const std::string prefix = path_.empty() ? "" : path_ + ": ";
  throw FileError(*file_, mark.line + 1, mark.column + 1, prefix + message);
}

bool YamlNode::Has(const std::string& key) const { return IsMap() && node_[key].IsDefined(); }

std::optional<YamlNode> YamlNode::Optional(const std::string& key) const {
  if (!IsMap()) Fail("expected a mapping with key '" + key + "'");
  used_keys_->insert(key);
  const YAML::Node child = node_[key];
  if (!child.IsDefined()) return std::nullopt;
  // `key:` with nothing after it is a slip (a value deleted, a typo), not "use the default":
  // silently falling back would hide it.
  if (child.IsNull()) {
    // A null value has no position of its own: point at its key.
    for (const auto& kv : node_) {
      if (kv.first.Scalar() != key) continue;
      const YAML::Mark mark = kv.first.Mark();
      throw FileError(*file_, mark.line + 1, mark.column + 1,
                      ChildPath(path_, key) +
                          ": no value given (write one, or remove the key to use the default)");
    }
  }
  return YamlNode(child, file_, ChildPath(path_, key));
}

YamlNode YamlNode::Required(const std::string& key) const {
  std::optional<YamlNode> child = Optional(key);
  if (!child) Fail("missing required key '" + key + "'");
  return *child;
}

double YamlNode::AsDouble() const {
  if (!IsScalar()) Fail("expected a number");
  double value = 0;
  if (!YAML::convert<double>::decode(node_, value)) {
    Fail("expected a number, got '" + node_.Scalar() + "'");
  }
  if (!std::isfinite(value)) Fail("expected a finite number, got '" + node_.Scalar() + "'");
  return value;
}

int YamlNode::AsInt() const {
  if (!IsScalar()) Fail("expected an integer");
  int value = 0;
  if (!YAML::convert<int>::decode(node_, value)) {
    Fail("expected an integer, got '" + node_.Scalar() + "'");
  }
  return value;
}

bool YamlNode::AsBool() const {
  if (!IsScalar()) Fail("expected true or false");
  bool value = false;
  if (!YAML::convert<bool>::decode(node_, value)) {
    Fail("expected true or false, got '" + node_.Scalar() + "'");
  }
  return value;
}

std::string YamlNode::AsString() const {
  if (!IsScalar()) Fail("expected a string");
  return node_.Scalar();
}

std::vector<YamlNode> YamlNode::Elements() const {
  if (!IsSequence()) Fail("expected a list");
  std::vector<YamlNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i) + "]");
  }
  return out;
}

std::vector<double> YamlNode::AsDoubles() const {
  std::vector<double> out;
  for (const YamlNode& item : Elements()) out.push_back(item.AsDouble());
  return out;
}

std::vector<std::string> YamlNode::Keys() const {
  if (!IsMap()) Fail("expected a mapping");
  std::vector<std::string> keys;
  for (const auto& kv : node_) keys.push_back(kv.first.Scalar());
  return keys;
}

double YamlNode::Get(const std::string& key, double fallback) const {
  auto child = Optional(key);
  return child ? child->AsDouble() : fallback;
}
int YamlNode::Get(const std::string& key, int fallback) const {
  auto child = Optional(key);
  return child ? child->AsInt() : fallback;
}
bool YamlNode::Get(const std::string& key, bool fallback) const {
  auto child = Optional(key);
  return child ? child->AsBool() : fallback;
}
std::string YamlNode::Get(const std::string& key, const std::string& fallback) const {
  auto child = Optional(key);
  return child ? child->AsString() : fallback;
}
std::string YamlNode::Get(const std::string& key, const char* fallback) const {
  return Get(key, std::string(fallback));
}

double YamlNode::InRange(double value, double lo, double hi) const {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream msg;
    msg << "must be in [" << lo << ", " << hi << "], got " << value;
    Fail(msg.str());
  }
  return value;
}

double YamlNode::Positive(double value) const {
  if (!(value > 0)) {
    std::ostringstream msg;
    msg << "must be > 0, got " << value;
    Fail(msg.str());
  }
  return value;
}

void YamlNode::Finish() const {
  if (!IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    if (!used_keys_->count(key)) {
      const YAML::Mark mark = kv.first.Mark();
      throw FileError(*file_, mark.line + 1, mark.column + 1,
                      "unknown key '" + ChildPath(path_, key) + "'");
    }
  }
}

}  // namespace brdfrig
