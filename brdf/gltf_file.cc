#include "brdf/gltf_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

using nlohmann::json;

// glTF's enumerations (specification 5.x).
constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;

struct Mesh {
  // 3 floats each per vertex. No TEXCOORD_0: the material has no textures, and the validator
  // reports unused attributes.
  std::vector<float> positions, normals;
  std::vector<std::uint16_t> indices;
};

void AddVertex(Mesh* mesh, const Vec3& p, const Vec3& n) {
  for (int i = 0; i < 3; ++i) {
    mesh->positions.push_back(static_cast<float>(p[i]));
    mesh->normals.push_back(static_cast<float>(n[i]));
  }
}

// A UV sphere of `radius` about the origin (glTF is +Y up). The pole rows keep one vertex per
// segment and only one triangle of each pole quad is drawn, so no triangle is degenerate.
Mesh UvSphere(double radius, int segments, int rings) {
  Mesh mesh;
  for (int r = 0; r <= rings; ++r) {
    const double theta = M_PI * r / rings;  // from +Y
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                   -std::sin(theta) * std::sin(phi));
      AddVertex(&mesh, radius * n, n.normalized());
    }
  }
  const int row = segments + 1;
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const auto a = static_cast<std::uint16_t>(r * row + s), b = static_cast<std::uint16_t>(a + 1),
                 c = static_cast<std::uint16_t>(a + row), d = static_cast<std::uint16_t>(c + 1);
      // Counter-clockwise seen from outside (glTF's front face).
      if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, c, b});
      if (r != rings - 1) mesh.indices.insert(mesh.indices.end(), {b, c, d});
    }
  }
  return mesh;
}

// The sample tile: a w × h rectangle in the XZ plane, facing +Y, centred on the origin.
Mesh Tile(double width, double height) {
  Mesh mesh;
  const Vec3 up = Vec3::UnitY();
  const double x = width / 2, z = height / 2;
  AddVertex(&mesh, Vec3(-x, 0, z), up);
  AddVertex(&mesh, Vec3(x, 0, z), up);
  AddVertex(&mesh, Vec3(x, 0, -z), up);
  AddVertex(&mesh, Vec3(-x, 0, -z), up);
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

class BufferBuilder {
 public:
  // Appends one tightly packed view (4-byte aligned, as every accessor type here needs) and its
  // accessor; returns the accessor's index.
  template <typename T>
  int Add(json* doc, const std::vector<T>& values, int components, const char* type,
          int component_type, int target, bool bounds) {
    if constexpr (std::is_floating_point_v<T>) {
      for (const T x : values) {
        if (!std::isfinite(x)) throw Error("the preview meshes hold infinite or NaN values");
      }
    }
    while (bytes_.size() % 4 != 0) bytes_.push_back('\0');
    const std::size_t offset = bytes_.size();
    bytes_.resize(offset + values.size() * sizeof(T));
    std::memcpy(bytes_.data() + offset, values.data(), values.size() * sizeof(T));
    const int view = static_cast<int>((*doc)["bufferViews"].size());
    (*doc)["bufferViews"].push_back({{"buffer", 0},
                                     {"byteOffset", offset},
                                     {"byteLength", values.size() * sizeof(T)},
                                     {"target", target}});
    json accessor = {{"bufferView", view},
                     {"componentType", component_type},
                     {"count", values.size() / components},
                     {"type", type}};
    if (bounds) {
      json lo = json::array(), hi = json::array();
      for (int c = 0; c < components; ++c) {
        T a = std::numeric_limits<T>::max(), b = std::numeric_limits<T>::lowest();
        for (std::size_t i = c; i < values.size(); i += components) {
          a = std::min(a, values[i]);
          b = std::max(b, values[i]);
        }
        lo.push_back(a);
        hi.push_back(b);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    (*doc)["accessors"].push_back(accessor);
    return static_cast<int>((*doc)["accessors"].size()) - 1;
  }

  std::string Finish() {
    while (bytes_.size() % 4 != 0) bytes_.push_back('\0');
    return bytes_;
  }

 private:
  std::string bytes_;
};

json AddMesh(json* doc, BufferBuilder* buffer, const Mesh& mesh, const std::string& name) {
  const int position =
      buffer->Add(doc, mesh.positions, 3, "VEC3", kFloat, kArrayBuffer, /*bounds=*/true);
  const int normal = buffer->Add(doc, mesh.normals, 3, "VEC3", kFloat, kArrayBuffer, false);
  const int indices =
      buffer->Add(doc, mesh.indices, 1, "SCALAR", kUnsignedShort, kElementArrayBuffer, false);
  return {{"name", name},
          {"primitives",
           {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}}},
             {"indices", indices},
             {"material", 0},
             {"mode", kTriangles}}}}};
}

// Every number in the document is finite (nlohmann::json would write NaN as null).
bool AllFinite(const json& value) {
  if (value.is_number_float()) return std::isfinite(value.get<double>());
  if (value.is_array() || value.is_object()) {
    for (const json& child : value) {
      if (!AllFinite(child)) return false;
    }
  }
  return true;
}

std::string PaddedTo4(std::string text, char pad) {
  while (text.size() % 4 != 0) text.push_back(pad);
  return text;
}

void AppendU32(std::string* out, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) out->push_back(static_cast<char>((x >> (8 * i)) & 0xff));
}

}  // namespace

void GltfScene::Validate() const {
  material.Validate();
  if (!(tile_width_m > 0 && tile_width_m <= 100) || !(tile_height_m > 0 && tile_height_m <= 100)) {
    throw Error("GltfScene.tile_width_m/tile_height_m = " + std::to_string(tile_width_m) + "/" +
                std::to_string(tile_height_m) + "; must be in (0, 100] metres");
  }
  // (segments + 1) · (rings + 1) vertices must fit 16-bit indices.
  if (sphere_segments < 3 || sphere_rings < 2 ||
      (sphere_segments + 1) * (sphere_rings + 1) > 65535) {
    throw Error("GltfScene.sphere_segments/sphere_rings = " + std::to_string(sphere_segments) +
                "/" + std::to_string(sphere_rings) +
                "; need >= 3 and >= 2 with at most 65535 vertices");
  }
  if (!extras.is_object()) throw Error("GltfScene.extras: must be a JSON object");
}

GltfDocument BuildGltf(const GltfScene& scene, const std::string& buffer_uri) {
  scene.Validate();
  const GltfParams& p = scene.material;
  json doc = {
      {"asset", {{"version", "2.0"}, {"generator", std::string("brdfrig ") + BRDFRIG_VERSION}}},
      {"extensionsUsed", {"KHR_materials_ior", "KHR_materials_specular"}},
      {"scene", 0},
      {"bufferViews", json::array()},
      {"accessors", json::array()}};
  json material = {{"name", scene.name},
                   {"pbrMetallicRoughness",
                    {{"baseColorFactor", {p.base_color[0], p.base_color[1], p.base_color[2], 1.0}},
                     {"metallicFactor", p.metallic},
                     {"roughnessFactor", p.roughness}}},
                   {"extensions",
                    {{"KHR_materials_ior", {{"ior", p.ior}}},
                     {"KHR_materials_specular",
                      {{"specularFactor", p.specular},
                       {"specularColorFactor",
                        {p.specular_color[0], p.specular_color[1], p.specular_color[2]}}}}}}};
  if (!scene.extras.empty()) material["extras"] = scene.extras;
  doc["materials"] = json::array({material});

  // The sphere's diameter is the tile's shorter side; it stands beside the tile on its plane.
  const double radius = 0.5 * std::min(scene.tile_width_m, scene.tile_height_m);
  BufferBuilder buffer;
  doc["meshes"] = json::array();
  doc["meshes"].push_back(AddMesh(&doc, &buffer,
                                  UvSphere(radius, scene.sphere_segments, scene.sphere_rings),
                                  "preview sphere"));
  doc["meshes"].push_back(
      AddMesh(&doc, &buffer, Tile(scene.tile_width_m, scene.tile_height_m), "sample tile"));
  doc["nodes"] = {{{"name", "preview sphere"},
                   {"mesh", 0},
                   {"translation", {0.5 * scene.tile_width_m + 1.5 * radius, radius, 0.0}}},
                  {{"name", "sample tile"}, {"mesh", 1}}};
  doc["scenes"] = {{{"name", scene.name}, {"nodes", {0, 1}}}};
  GltfDocument out;
  out.buffer = buffer.Finish();
  json gltf_buffer = {{"byteLength", out.buffer.size()}};
  if (!buffer_uri.empty()) gltf_buffer["uri"] = buffer_uri;
  doc["buffers"] = json::array({gltf_buffer});
  out.json = std::move(doc);
  return out;
}

std::string PackGlb(const GltfDocument& document) {
  const std::string json_chunk = PaddedTo4(document.json.dump(), ' ');
  const std::string bin_chunk = PaddedTo4(document.buffer, '\0');
  std::string out;
  const std::size_t total = 12 + 8 + json_chunk.size() + 8 + bin_chunk.size();
  if (total > std::numeric_limits<std::uint32_t>::max()) throw Error("glTF file too large");
  AppendU32(&out, 0x46546C67);  // "glTF"
  AppendU32(&out, 2);
  AppendU32(&out, static_cast<std::uint32_t>(total));
  AppendU32(&out, static_cast<std::uint32_t>(json_chunk.size()));
  AppendU32(&out, 0x4E4F534A);  // "JSON"
  out += json_chunk;
  AppendU32(&out, static_cast<std::uint32_t>(bin_chunk.size()));
  AppendU32(&out, 0x004E4942);  // "BIN\0"
  out += bin_chunk;
  return out;
}

void WriteGltfFile(const std::filesystem::path& output, const GltfScene& scene) {
  const std::string ext = output.extension().string();
  if (ext != ".glb" && ext != ".gltf") {
    throw FileError(output.string(), "a glTF file's name must end in .glb or .gltf");
  }
  const bool binary = ext == ".glb";
  const std::filesystem::path bin = std::filesystem::path(output).replace_extension(".bin");
  GltfDocument document;
  try {
    document = BuildGltf(scene, binary ? "" : bin.filename().string());
  } catch (const FileError&) {
    throw;
  } catch (const Error& e) {
    throw FileError(output.string(), std::string("nothing written: ") + e.what());
  }
  // The writer's own check (the vertex data is checked as it is packed): a NaN in the JSON
  // would be written as null, an infinity not at all.
  if (!AllFinite(document.json)) {
    throw FileError(output.string(), "the glTF would hold infinite or NaN values; nothing written");
  }
  if (binary) {
    WriteFileAtomically(output, PackGlb(document));
    return;
  }
  // The buffer first: a .gltf on disk always finds its .bin complete.
  WriteFileAtomically(bin, document.buffer);
  WriteFileAtomically(output, document.json.dump(2) + "\n");
}

}  // namespace brdfrig::brdf
