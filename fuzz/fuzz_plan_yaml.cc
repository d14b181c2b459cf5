// plan.yaml as `brdfrig plan check`, `capture` and the daemon read it (the daemon's clients
// send the text). Bad input must end in brdfrig::Error naming file:line:column.
#include "acquire/plan.h"
#include "common/error.h"
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    brdfrig::acquire::LoadPlanString(brdfrig::fuzz::AsString(data, size), "plan.yaml");
  } catch (const brdfrig::Error&) {
    // The documented rejection of a malformed plan.
  }
  return 0;
}
