#include "sim/sample_brdf.h"

#include "brdf/analytic.h"
#include "brdf/material_file.h"
#include "brdf/merl.h"
#include "brdf/nbrdf_library.h"
#include "sim/yaml_values.h"

namespace brdfrig::sim {
namespace {

brdf::MicrofacetParams ReadMicrofacet(const YamlNode& node) {
  brdf::MicrofacetParams p;
  if (auto d = node.Optional("diffuse")) p.diffuse = ReadRgb(*d, 0, 1);
  if (auto f0 = node.Optional("f0")) p.f0 = ReadRgb(*f0, 0, 1);
  const YamlNode alpha = node.Required("alpha");
  p.alpha = alpha.InRange(alpha.AsDouble(), 1e-3, 2);
  return p;
}

// Loads a model file named relative to the scene; its own errors are prefixed with the scene
// line that named it.
template <typename Load>
auto FromFile(const YamlNode& node, const std::filesystem::path& base_dir, Load load) {
  const YamlNode file = node.Required("file");
  const std::filesystem::path path = base_dir / file.AsString();
  try {
    return load(path);
  } catch (const Error& e) {
    file.Fail(e.what());
  }
}

// A measured material: one of the shipped ones by name, or any nbrdf file; exactly one of them.
std::shared_ptr<const brdf::Brdf> ParseNbrdf(const YamlNode& node,
                                             const std::filesystem::path& base_dir) {
  const std::optional<YamlNode> name = node.Optional("name");
  if (name.has_value() == node.Has("file")) {
    node.Fail("an nbrdf sample needs either 'name' (a shipped material) or 'file', not both");
  }
  if (!name) {
    return FromFile(node, base_dir, [](const std::filesystem::path& path) {
      return std::make_shared<brdf::NeuralBrdf>(brdf::NeuralBrdf::Read(path));
    });
  }
  try {
    return std::make_shared<brdf::NeuralBrdf>(brdf::ReadNbrdfMaterial(name->AsString()));
  } catch (const Error& e) {
    name->Fail(e.what());
  }
}

}  // namespace

std::shared_ptr<const brdf::Brdf> ParseSampleBrdf(const YamlNode& node,
                                                  const std::filesystem::path& base_dir) {
  const YamlNode model_node = node.Required("model");
  const std::string model = model_node.AsString();
  std::shared_ptr<const brdf::Brdf> result;
  if (model == "ggx") {
    result = std::make_shared<brdf::Ggx>(ReadMicrofacet(node));
  } else if (model == "cook_torrance") {
    result = std::make_shared<brdf::CookTorrance>(ReadMicrofacet(node));
  } else if (model == "ward") {
    brdf::WardParams p;
    if (auto d = node.Optional("diffuse")) p.diffuse = ReadRgb(*d, 0, 1);
    if (auto s = node.Optional("specular")) p.specular = ReadRgb(*s, 0, 1);
    const YamlNode alpha = node.Required("alpha");
    p.alpha = alpha.InRange(alpha.AsDouble(), 1e-3, 2);
    result = std::make_shared<brdf::Ward>(p);
  } else if (model == "blinn_phong") {
    brdf::BlinnPhongParams p;
    if (auto d = node.Optional("diffuse")) p.diffuse = ReadRgb(*d, 0, 1);
    if (auto s = node.Optional("specular")) p.specular = ReadRgb(*s, 0, 1);
    const YamlNode e = node.Required("exponent");
    p.exponent = e.InRange(e.AsDouble(), 0, 1e6);
    result = std::make_shared<brdf::BlinnPhong>(p);
  } else if (model == "lambert") {
    result = std::make_shared<brdf::Lambert>(ReadRgb(node.Required("albedo"), 0, 1));
  } else if (model == "slices") {
    result = FromFile(node, base_dir, [](const std::filesystem::path& path) {
      return brdf::ReadMaterialFile(path).Model();
    });
  } else if (model == "merl") {
    result = FromFile(node, base_dir, [](const std::filesystem::path& path) {
      return std::make_shared<brdf::MerlTable>(brdf::MerlTable::Read(path));
    });
  } else if (model == "nbrdf") {
    result = ParseNbrdf(node, base_dir);
  } else {
    model_node.Fail("unknown model '" + model +
                    "' (known: ggx, cook_torrance, ward, blinn_phong, lambert, slices, merl, "
                    "nbrdf)");
  }
  node.Finish();
  return result;
}

}  // namespace brdfrig::sim
