// Reading fields out of a parsed JSON document (material.json, nbrdf files), every error naming
// the file and the JSON path of what is wrong, e.g. "m.json: slices[2].green.h: missing".
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "common/error.h"

namespace brdfrig::brdf {

class JsonReader {
 public:
  using json = nlohmann::json;

  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw FileError(source_, (path.empty() ? "" : path + ": ") + message);
  }

  const json& Field(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) Fail(path, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) Fail(Join(path, key), "missing");
    return *it;
  }

  // A finite number at `path`.
  double Number(const json& value, const std::string& path) const {
    if (!value.is_number()) Fail(path, "expected a number, got " + value.dump());
    const double x = value.get<double>();
    if (!std::isfinite(x)) Fail(path, "must be finite");
    return x;
  }

  double Number(const json& object, const std::string& path, const char* key) const {
    return Number(Field(object, path, key), Join(path, key));
  }

  std::string String(const json& object, const std::string& path, const char* key) const {
    const json& value = Field(object, path, key);
    if (!value.is_string()) Fail(Join(path, key), "expected a string, got " + value.dump());
    return value.get<std::string>();
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string source_;
};

}  // namespace brdfrig::brdf
