// material.json, the reconstruction's result, as `render`, `evaluate` and `compare` read it:
// parsed, turned into its BRDF (which validates it) and evaluated once.
#include "brdf/material_file.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const brdfrig::brdf::Material material =
        brdfrig::brdf::ParseMaterial(brdfrig::fuzz::AsString(data, size), "material.json");
    const auto model = material.Model();
    const brdfrig::brdf::Vec3 l(0.3, 0.1, 0.95), v(-0.2, 0.3, 0.93), n(0, 0, 1);
    model->Eval(l.normalized(), v.normalized(), n);
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed material.
  }
  return 0;
}
