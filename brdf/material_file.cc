#include "brdf/material_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "brdf/json_reader.h"
#include "common/atomic_file.h"
#include "common/base64.h"
#include "common/error.h"
#include "common/json_parse.h"

namespace brdfrig::brdf {
namespace {

using nlohmann::json;

constexpr const char* kMaterialFormat = "brdfrig-material";
constexpr int kMaterialVersion = 2;
constexpr const char* kLegacyFormat = "brdfrig-slices";  // version 1: slices only
constexpr const char* kParamNames[4] = {"A1", "A2", "h", "x0"};

using Reader = JsonReader;

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
  if (!count.is_number_integer() || count.get<long long>() < 0 ||
      count.get<long long>() > std::numeric_limits<int>::max()) {
    r.Fail(Reader::Join(path, "sample_count"), "expected a non-negative integer of at most " +
                                                   std::to_string(std::numeric_limits<int>::max()));
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

Rgb ParseRgb(const Reader& r, const json& object, const std::string& path, const char* key) {
  const json& value = r.Field(object, path, key);
  const std::string field = Reader::Join(path, key);
  if (!value.is_array() || value.size() != 3) r.Fail(field, "expected [red, green, blue]");
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    if (!value[c].is_number() || !std::isfinite(value[c].get<double>())) {
      r.Fail(field, "expected finite numbers, got " + value.dump());
    }
    out[c] = value[c].get<double>();
  }
  return out;
}

std::vector<double> ParseList(const Reader& r, const json& object, const std::string& path,
                              const char* key) {
  std::vector<double> out;
  if (!object.contains(key)) return out;
  const json& list = object.at(key);
  const std::string field = Reader::Join(path, key);
  if (!list.is_array() || list.size() > 256)
    r.Fail(field, "expected a list of at most 256 numbers");
  for (const json& x : list) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) {
      r.Fail(field, "expected finite numbers, got " + x.dump());
    }
    out.push_back(x.get<double>());
  }
  return out;
}

MicrofacetModelParams ParseMicrofacet(const Reader& r, const json& doc, ModelKind kind) {
  const std::string path = "microfacet";
  const json& m = r.Field(doc, "", "microfacet");
  MicrofacetModelParams p;
  p.distribution = kind == ModelKind::kGgx        ? Distribution::kGgx
                   : kind == ModelKind::kBeckmann ? Distribution::kBeckmann
                                                  : Distribution::kTable;
  p.diffuse = ParseRgb(r, m, path, "diffuse");
  p.f0 = ParseRgb(r, m, path, "f0");
  p.alpha = r.Number(m, path, "alpha");
  p.fresnel_knots = ParseList(r, m, path, "fresnel_knots");
  if (p.distribution == Distribution::kTable) {
    p.log_d = ParseList(r, m, path, "log_d");
    p.max_theta_h = r.Number(m, path, "max_theta_h");
    p.shadowing_alpha = r.Number(m, path, "shadowing_alpha");
  }
  try {
    p.Validate();
  } catch (const Error& e) {
    r.Fail(path, e.what());
  }
  return p;
}

json SerializeMicrofacet(const MicrofacetModelParams& p) {
  auto rgb = [](const Rgb& c) { return json::array({c[0], c[1], c[2]}); };
  json m = {{"diffuse", rgb(p.diffuse)},
            {"f0", rgb(p.f0)},
            {"alpha", p.alpha},
            {"fresnel_knots", p.fresnel_knots}};
  if (p.distribution == Distribution::kTable) {
    m["log_d"] = p.log_d;
    m["max_theta_h"] = p.max_theta_h;
    m["shadowing_alpha"] = p.shadowing_alpha;
  }
  return m;
}

// The table as 16-bit codes over its own range: q spans about ln ε .. 10, so a step is about
// 3e-4 in q, 0.03 % in f, far below what a capture resolves; 2 bytes a node keeps a 64 × 32 × 8
// table near 130 KB of base64 (a file to mail).
json SerializeTable(const RusinkiewiczGrid& grid, const TableValues& q) {
  double lo = q[0][0], hi = q[0][0];
  for (const auto& channel : q) {
    for (const double x : channel) lo = std::min(lo, x), hi = std::max(hi, x);
  }
  const double scale = hi > lo ? (hi - lo) / 65535 : 1;
  json t = {{"grid",
             {{"theta_h", grid.theta_h},
              {"theta_d", grid.theta_d},
              {"phi_d", grid.phi_d},
              {"epsilon", grid.epsilon},
              {"cos_floor", grid.cos_floor}}},
            {"encoding", "uint16-base64"},
            {"offset", lo},
            {"scale", scale}};
  for (int c = 0; c < 3; ++c) {
    std::vector<std::uint8_t> bytes(2 * q[c].size());
    for (std::size_t i = 0; i < q[c].size(); ++i) {
      const auto u =
          static_cast<std::uint16_t>(std::lround(std::clamp((q[c][i] - lo) / scale, 0.0, 65535.0)));
      bytes[2 * i] = static_cast<std::uint8_t>(u & 0xff);
      bytes[2 * i + 1] = static_cast<std::uint8_t>(u >> 8);
    }
    t[kChannelNames[c]] = Base64Encode(bytes);
  }
  return t;
}

void ParseTable(const Reader& r, const json& doc, RusinkiewiczGrid* grid, TableValues* q) {
  const json& t = r.Field(doc, "", "table");
  const json& g = r.Field(t, "table", "grid");
  const auto count = [&](const char* key) {
    const double x = r.Number(g, "table.grid", key);
    if (x != std::floor(x) || x < 2 || x > 512) {
      r.Fail(Reader::Join("table.grid", key), "expected a whole number in [2, 512]");
    }
    return static_cast<int>(x);
  };
  grid->theta_h = count("theta_h");
  grid->theta_d = count("theta_d");
  grid->phi_d = count("phi_d");
  grid->epsilon = r.Number(g, "table.grid", "epsilon");
  grid->cos_floor = r.Number(g, "table.grid", "cos_floor");
  try {
    grid->Validate();
  } catch (const Error& e) {
    r.Fail("table.grid", e.what());
  }
  if (r.String(t, "table", "encoding") != "uint16-base64") {
    r.Fail("table.encoding", "expected \"uint16-base64\"");
  }
  const double offset = r.Number(t, "table", "offset");
  const double scale = r.Number(t, "table", "scale");
  if (!(scale > 0)) r.Fail("table.scale", "must be > 0");
  for (int c = 0; c < 3; ++c) {
    const std::string field = Reader::Join("table", kChannelNames[c]);
    const auto bytes = Base64Decode(r.String(t, "table", kChannelNames[c]));
    if (!bytes) r.Fail(field, "not base64");
    if (bytes->size() != 2 * static_cast<std::size_t>(grid->Cells())) {
      r.Fail(field, "holds " + std::to_string(bytes->size() / 2) + " values, the grid has " +
                        std::to_string(grid->Cells()));
    }
    (*q)[c].resize(grid->Cells());
    for (int i = 0; i < grid->Cells(); ++i) {
      (*q)[c][i] = offset + scale * ((*bytes)[2 * i] | ((*bytes)[2 * i + 1] << 8));
    }
  }
  try {
    RusinkiewiczTable check(*grid, *q);
  } catch (const Error& e) {
    r.Fail("table", e.what());
  }
}

GltfParams ParseGltf(const Reader& r, const json& doc) {
  const std::string path = "gltf";
  const json& g = r.Field(doc, "", "gltf");
  GltfParams p;
  p.base_color = ParseRgb(r, g, path, "base_color");
  p.metallic = r.Number(g, path, "metallic");
  p.roughness = r.Number(g, path, "roughness");
  p.ior = r.Number(g, path, "ior");
  p.specular = r.Number(g, path, "specular");
  p.specular_color = ParseRgb(r, g, path, "specular_color");
  try {
    p.Validate();
  } catch (const Error& e) {
    r.Fail(path, e.what());
  }
  return p;
}

json SerializeGltf(const GltfParams& p) {
  auto rgb = [](const Rgb& c) { return json::array({c[0], c[1], c[2]}); };
  return {{"base_color", rgb(p.base_color)}, {"metallic", p.metallic},
          {"roughness", p.roughness},        {"ior", p.ior},
          {"specular", p.specular},          {"specular_color", rgb(p.specular_color)}};
}

Distribution DistributionOf(ModelKind kind) {
  return kind == ModelKind::kGgx        ? Distribution::kGgx
         : kind == ModelKind::kBeckmann ? Distribution::kBeckmann
                                        : Distribution::kTable;
}

}  // namespace

const char* ModelKindName(ModelKind kind) {
  switch (kind) {
    case ModelKind::kSeed:
      return "seed";
    case ModelKind::kSeedConstrained:
      return "seed_constrained";
    case ModelKind::kMicrofacet:
      return "microfacet";
    case ModelKind::kGgx:
      return "ggx";
    case ModelKind::kBeckmann:
      return "beckmann";
    case ModelKind::kPrior:
      return "prior";
    case ModelKind::kGltf:
      return "gltf";
  }
  return "?";
}

ModelKind ParseModelKind(const std::string& name) {
  std::string known;
  for (ModelKind kind : kAllModelKinds) {
    if (name == ModelKindName(kind)) return kind;
    known += std::string(known.empty() ? "" : ", ") + ModelKindName(kind);
  }
  throw Error("unknown model kind '" + name + "' (known: " + known + ")");
}

bool IsSliceKind(ModelKind kind) {
  return kind == ModelKind::kSeed || kind == ModelKind::kSeedConstrained;
}

std::shared_ptr<const Brdf> Material::Model() const {
  if (IsSliceKind(kind)) return std::make_shared<SliceModel>(slices);
  if (kind == ModelKind::kPrior) return std::make_shared<RusinkiewiczTable>(table_grid, table);
  if (kind == ModelKind::kGltf) {
    if (!gltf) throw Error("material of kind 'gltf' holds no gltf parameters");
    return std::make_shared<GltfModel>(*gltf);
  }
  if (microfacet.distribution != DistributionOf(kind)) {
    throw Error(std::string("material of kind '") + ModelKindName(kind) +
                "' holds a distribution of kind '" + DistributionName(microfacet.distribution) +
                "'");
  }
  return std::make_shared<MicrofacetModel>(microfacet);
}

SliceModel Material::Slices() const {
  if (!IsSliceKind(kind)) {
    throw Error(std::string("material of kind '") + ModelKindName(kind) + "' has no slices");
  }
  return SliceModel(slices);
}

Material ParseMaterial(const std::string& json_text, const std::string& source_name) {
  const Reader r(source_name);
  const json doc = ParseJson(json_text, source_name);
  const json& format = r.Field(doc, "", "format");
  const json& version = r.Field(doc, "", "version");
  Material material;
  if (format == kLegacyFormat) {
    if (version != 1)
      r.Fail("version", "brdfrig-slices files are version 1, got " + version.dump());
  } else if (format == kMaterialFormat) {
    if (version != kMaterialVersion) {
      r.Fail("version", "this brdfrig reads version " + std::to_string(kMaterialVersion) +
                            ", got " + version.dump());
    }
    const json& kind = r.Field(doc, "", "kind");
    if (!kind.is_string()) r.Fail("kind", "expected a string, got " + kind.dump());
    try {
      material.kind = ParseModelKind(kind.get<std::string>());
    } catch (const Error& e) {
      r.Fail("kind", e.what());
    }
  } else {
    r.Fail("format", std::string("expected \"") + kMaterialFormat + "\" (or the older \"" +
                         kLegacyFormat + "\"), got " + format.dump());
  }
  if (doc.contains("fit")) material.fit = doc.at("fit");
  if (doc.contains("ladder")) material.ladder = doc.at("ladder");
  if (doc.contains("provenance")) material.provenance = doc.at("provenance");
  // Kind gltf's model, or any other kind's glTF version.
  if (material.kind == ModelKind::kGltf || doc.contains("gltf")) material.gltf = ParseGltf(r, doc);
  if (doc.contains("gltf_fit")) {
    material.gltf_fit = doc.at("gltf_fit");
    if (!material.gltf_fit.is_object()) r.Fail("gltf_fit", "expected an object");
  }
  if (material.kind == ModelKind::kGltf) return material;
  if (material.kind == ModelKind::kPrior) {
    ParseTable(r, doc, &material.table_grid, &material.table);
    return material;
  }
  if (!IsSliceKind(material.kind)) {
    material.microfacet = ParseMicrofacet(r, doc, material.kind);
    return material;
  }
  const json& slices = r.Field(doc, "", "slices");
  if (!slices.is_array() || slices.empty()) r.Fail("slices", "expected a non-empty array");

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
  (void)material.Model();  // never write a model we could not read back
  json doc = {{"format", kMaterialFormat},
              {"version", kMaterialVersion},
              {"kind", ModelKindName(material.kind)}};
  if (IsSliceKind(material.kind)) {
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
    doc["slices"] = slices;
  } else if (material.kind == ModelKind::kPrior) {
    doc["table"] = SerializeTable(material.table_grid, material.table);
  } else if (material.kind == ModelKind::kGltf) {
    // Written below, like any kind's glTF version.
  } else {
    doc["microfacet"] = SerializeMicrofacet(material.microfacet);
  }
  if (material.gltf) {
    material.gltf->Validate();
    doc["gltf"] = SerializeGltf(*material.gltf);
  }
  if (!material.gltf_fit.empty()) doc["gltf_fit"] = material.gltf_fit;
  doc["fit"] = material.fit;
  doc["ladder"] = material.ladder;
  doc["provenance"] = material.provenance;
  return doc.dump(2) + "\n";
}

void WriteMaterialFile(const std::filesystem::path& path, const Material& material) {
  WriteFileAtomically(path, SerializeMaterial(material));
}

}  // namespace brdfrig::brdf
