// The capture as a separate process for the kill test: `capture_helper RIG PLAN DIR` runs
// RunCapture with --resume semantics against the simulated rig. Exit 0: session complete;
// 3: the run stopped otherwise; 1: it could not start. The test's SIGKILLs come from
// acquire/test_hooks.h (BRDFRIG_TEST_KILL_AT) or from the parent.
#include <cstdio>
#include <exception>

#include "acquire/capture.h"
#include "sim/devices.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s RIG PLAN SESSION_DIR\n", argv[0]);
    return 1;
  }
  try {
    brdfrig::sim::RegisterSimBackends();
    brdfrig::acquire::CaptureOptions options;
    options.rig_file = argv[1];
    options.plan_file = argv[2];
    options.output_dir = argv[3];
    options.resume = true;
    options.run.retry.initial_backoff_s = 0.001;
    const auto summary = brdfrig::acquire::RunCapture(options);
    std::printf("%s\n", summary.ToString().c_str());
    return summary.run.status == brdfrig::acquire::ExitStatus::kSuccess ? 0 : 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "capture_helper: %s\n", e.what());
    return 1;
  }
}
