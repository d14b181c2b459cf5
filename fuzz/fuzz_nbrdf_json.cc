// Neural BRDF files (data/materials/nbrdf/*.json, "nbrdf-mlp" version 1): parsed and
// evaluated once.
#include "brdf/nbrdf.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const brdfrig::brdf::NeuralBrdf brdf =
        brdfrig::brdf::NeuralBrdf::Parse(brdfrig::fuzz::AsString(data, size), "nbrdf.json");
    const brdfrig::brdf::Vec3 l(0.3, 0.1, 0.95), v(-0.2, 0.3, 0.93), n(0, 0, 1);
    brdf.Eval(l.normalized(), v.normalized(), n);
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed file.
  }
  return 0;
}
