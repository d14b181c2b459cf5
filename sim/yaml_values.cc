#include "sim/yaml_values.h"

#include <string>

namespace brdfrig::sim {

brdf::Rgb ReadRgb(const YamlNode& node, double lo, double hi) {
  brdf::Rgb rgb;
  if (node.IsScalar()) {
    rgb = brdf::Rgb::Constant(node.AsDouble());
  } else {
    const std::vector<double> v = node.AsDoubles();
    if (v.size() != 3) {
      node.Fail("expected a number or [r, g, b], got " + std::to_string(v.size()) + " numbers");
    }
    rgb = {v[0], v[1], v[2]};
  }
  for (int c = 0; c < 3; ++c) node.InRange(rgb[c], lo, hi);
  return rgb;
}

std::pair<double, double> ReadPair(const YamlNode& node) {
  const std::vector<double> v = node.AsDoubles();
  if (v.size() != 2) node.Fail("expected two numbers, got " + std::to_string(v.size()));
  return {v[0], v[1]};
}

}  // namespace brdfrig::sim
