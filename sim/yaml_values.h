// Small typed readers for scene values that common/yaml_reader.h does not cover.
#pragma once

#include "brdf/brdf.h"
#include "common/yaml_reader.h"

namespace brdfrig::sim {

// A colour: one number (grey) or [r, g, b]; each component in [lo, hi].
brdf::Rgb ReadRgb(const YamlNode& node, double lo, double hi);

// Two numbers [a, b].
std::pair<double, double> ReadPair(const YamlNode& node);

}  // namespace brdfrig::sim
