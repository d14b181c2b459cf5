#include "brdf/material_file.h"

#include <cmath>
#include <limits>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "brdfrig-slices";
constexpr int kVersion = 1;
constexpr const char* kChannelNames[3] = {"red", "green", "blue"};
constexpr const char* kParamNames[4] = {"A1", "A2", "h", "x0"};

// Reads fields out of a parsed document, naming the JSON path of whatever is wrong.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw FileError(source_, (path.empty() ? "" : path + ": ") + message);
  }

  const json& Field(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) Fail(path, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) Fail(Join(path, key), "missing");
    return *it;
  }

  double Number(const json& object, const std::string& path, const char* key) const {
    const json& value = Field(object, path, key);
    if (!value.is_number()) Fail(Join(path, key), "expected a number, got " + value.dump());
    const double x = value.get<double>();
    if (!std::isfinite(x)) Fail(Join(path, key), "must be finite");
    return x;
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string source_;
};

LobeParams ParseLobe(const Reader& r, const json& slice, const std::string& path, int c) {
  const std::string channel_path = Reader::Join(path, kChannelNames[c]);
  const json& channel = r.Field(slice, path, kChannelNames[c]);
  LobeParams p;
  p.a1 = r.Number(channel, channel_path, "A1");
  p.a2 = r.Number(channel, channel_path, "A2");
  p.h = r.Number(channel, channel_path, "h");
  p.x0 = r.Number(channel, channel_path, "x0");
  return p;
}

SliceDiagnostics ParseDiagnostics(const Reader& r, const json& d, const std::string& path) {
  SliceDiagnostics out;
  out.residual = r.Number(d, path, "residual");
  const json& count = r.Field(d, path, "sample_count");
  if (!count.is_number_integer() || count.get<long long>() < 0) {
    r.Fail(Reader::Join(path, "sample_count"), "expected a non-negative integer");
  }
  out.sample_count = count.get<int>();
  const json& range = r.Field(d, path, "theta_range");
  if (!range.is_array() || range.size() != 2 || !range[0].is_number() || !range[1].is_number()) {
    r.Fail(Reader::Join(path, "theta_range"), "expected [min, max] in radians");
  }
  out.theta_min = range[0].get<double>();
  out.theta_max = range[1].get<double>();
  if (d.contains("stddev")) {
    out.has_stddev = true;
    for (int c = 0; c < 3; ++c) {
      const std::string sp = Reader::Join(path, "stddev");
      const json& list = r.Field(d.at("stddev"), sp, kChannelNames[c]);
      if (!list.is_array() || list.size() != 4) {
        r.Fail(Reader::Join(sp, kChannelNames[c]), "expected 4 values (A1, A2, h, x0)");
      }
      for (int k = 0; k < 4; ++k) {
        out.stddev[c][k] =
            list[k].is_number() ? list[k].get<double>() : std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  if (d.contains("warnings")) {
    for (const json& w : d.at("warnings")) {
      if (!w.is_string()) r.Fail(Reader::Join(path, "warnings"), "expected strings");
      out.warnings.push_back(w.get<std::string>());
    }
  }
  return out;
}

json SerializeDiagnostics(const SliceDiagnostics& d) {
  json out = {{"residual", d.residual},
              {"sample_count", d.sample_count},
              {"theta_range", {d.theta_min, d.theta_max}},
              {"warnings", d.warnings}};
  if (d.has_stddev) {
    json stddev = json::object();
    for (int c = 0; c < 3; ++c) {
      json list = json::array();
      for (double s : d.stddev[c]) list.push_back(std::isfinite(s) ? json(s) : json(nullptr));
      stddev[kChannelNames[c]] = list;
    }
    out["stddev"] = stddev;
  }
  return out;
}

}  // namespace

Material ParseMaterial(const std::string& json_text, const std::string& source_name) {
  const Reader r(source_name);
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    r.Fail("", std::string("not valid JSON (") + e.what() + ")");
  }
  const json& format = r.Field(doc, "", "format");
  if (format != kFormat)
    r.Fail("format", std::string("expected \"") + kFormat + "\", got " + format.dump());
  const json& version = r.Field(doc, "", "version");
  if (version != kVersion) {
    r.Fail("version",
           "this brdfrig reads version " + std::to_string(kVersion) + ", got " + version.dump());
  }
  const json& slices = r.Field(doc, "", "slices");
  if (!slices.is_array() || slices.empty()) r.Fail("slices", "expected a non-empty array");

  Material material;
  for (std::size_t i = 0; i < slices.size(); ++i) {
    const std::string path = "slices[" + std::to_string(i) + "]";
    Slice slice;
    slice.theta_in = r.Number(slices[i], path, "theta_in");
    for (int c = 0; c < 3; ++c) slice.channel[c] = ParseLobe(r, slices[i], path, c);
    material.slices.push_back(slice);
    if (slices[i].contains("diagnostics")) {
      material.diagnostics.push_back(
          ParseDiagnostics(r, slices[i].at("diagnostics"), Reader::Join(path, "diagnostics")));
    }
  }
  if (!material.diagnostics.empty() && material.diagnostics.size() != material.slices.size()) {
    r.Fail("slices", "diagnostics must be given for every slice or for none");
  }
  if (doc.contains("provenance")) material.provenance = doc.at("provenance");
  // The model's own validation names the slice and field (A1 >= A2 >= 0, h > 0, knot order).
  try {
    SliceModel check(material.slices);
  } catch (const FileError&) {
    throw;
  } catch (const Error& e) {
    r.Fail("", e.what());
  }
  return material;
}

Material ReadMaterialFile(const std::filesystem::path& path) {
  return ParseMaterial(ReadFileToString(path), path.string());
}

std::string SerializeMaterial(const Material& material) {
  SliceModel check(material.slices);  // never write a model we could not read back
  if (!material.diagnostics.empty() && material.diagnostics.size() != material.slices.size()) {
    throw Error("material: diagnostics must be given for every slice or for none");
  }
  json slices = json::array();
  for (std::size_t i = 0; i < material.slices.size(); ++i) {
    const Slice& s = material.slices[i];
    json slice = {{"theta_in", s.theta_in}};
    for (int c = 0; c < 3; ++c) {
      const LobeParams& p = s.channel[c];
      slice[kChannelNames[c]] = {{kParamNames[0], p.a1},
                                 {kParamNames[1], p.a2},
                                 {kParamNames[2], p.h},
                                 {kParamNames[3], p.x0}};
    }
    if (!material.diagnostics.empty()) {
      slice["diagnostics"] = SerializeDiagnostics(material.diagnostics[i]);
    }
    slices.push_back(slice);
  }
  const json doc = {{"format", kFormat},
                    {"version", kVersion},
                    {"slices", slices},
                    {"provenance", material.provenance}};
  return doc.dump(2) + "\n";
}

void WriteMaterialFile(const std::filesystem::path& path, const Material& material) {
  WriteFileAtomically(path, SerializeMaterial(material));
}

}  // namespace brdfrig::brdf
