// Session time versus the sum of unavoidable times (longest axis move per position + settle +
// exposures + downloads) for the default plan on the simulated rig, in the engine's model
// time (device durations as the simulator reports them, host work measured), with recording
// overlapped with the next move or done serially. Usage: bench_acquire_session [scene.yaml]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "acquire/capture.h"
#include "acquire/plan_check.h"
#include "common/angles.h"
#include "sim/devices.h"
#include "sim/scene.h"

namespace {

namespace fs = std::filesystem;
using namespace brdfrig;

std::string PlanFromScene(const sim::Scene& scene) {
  std::ostringstream plan;
  plan << "sample: default-scene\noperator: bench\npositions:\n";
  for (const geometry::AxisPositions& p : scene.capture.positions) {
    plan << "  - {";
    bool first = true;
    for (const auto& [axis, angle] : p) {
      plan << (first ? "" : ", ") << axis << ": " << Degrees(angle);
      first = false;
    }
    plan << "}\n";
  }
  plan << "exposures: [";
  for (std::size_t i = 0; i < scene.capture.exposures.size(); ++i) {
    plan << (i ? ", " : "") << scene.capture.exposures[i];
  }
  plan << "]\nsettle_s: 0.2\n";
  return plan.str();
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path scene_file = fs::absolute(
      argc > 1 ? fs::path(argv[1]) : fs::path(BRDFRIG_SOURCE_DIR) / "sim/scenes/default.yaml");
  const sim::Scene scene = sim::LoadScene(scene_file);
  const fs::path dir = fs::temp_directory_path() / "brdfrig_bench_acquire";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "rig.yaml") << "geometry: " << scene_file.string() << "\n"
                                  << "camera: {backend: sim, scene: " << scene_file.string()
                                  << "}\naxes:\n";
  {
    std::ofstream rig(dir / "rig.yaml", std::ios::app);
    for (const geometry::RotationAxis& axis : scene.rig.axes) {
      rig << "  " << axis.name << ": {backend: sim, scene: " << scene_file.string() << "}\n";
    }
  }
  const std::string plan_text = PlanFromScene(scene);
  std::ofstream(dir / "plan.yaml") << plan_text;
  sim::RegisterSimBackends();

  const acquire::PlanCheckReport estimate = acquire::CheckPlan(
      acquire::LoadPlanFile(dir / "plan.yaml"), rig::ReadRigDescription(dir / "rig.yaml"));
  std::printf("default plan: %zu positions x %zu exposures, %s\n", scene.capture.positions.size(),
              scene.capture.exposures.size(), scene.Summary().c_str());
  std::printf("plan check estimate: %.1f s\n\n", estimate.EstimatedDurationS());

  struct Config {
    const char* name;
    bool overlap;
    bool parallel_moves;
  };
  const Config configs[] = {{"overlapped (writer thread, axes at once)", true, true},
                            {"writer thread, axes one after the other", true, false},
                            {"serial (record, then move; axes in turn)", false, false}};
  std::printf("%-42s %9s %12s %7s %7s %7s %9s %7s %7s\n", "configuration", "session", "unavoidable",
              "ratio", "moves", "expose", "download", "host", "wall");
  int i = 0;
  for (const Config& c : configs) {
    std::string text =
        plan_text + "parallel_moves: " + (c.parallel_moves ? "true" : "false") + "\n";
    const fs::path plan_file = dir / ("plan" + std::to_string(i) + ".yaml");
    std::ofstream(plan_file) << text;
    acquire::CaptureOptions options;
    options.rig_file = dir / "rig.yaml";
    options.plan_file = plan_file;
    options.output_dir = dir / ("session" + std::to_string(i++));
    options.run.overlap = c.overlap;
    const acquire::CaptureSummary summary = acquire::RunCapture(options);
    const acquire::RunTiming& t = summary.run.timing;
    if (summary.run.status != acquire::ExitStatus::kSuccess) {
      std::fprintf(stderr, "run failed: %s\n", summary.ToString().c_str());
      return 1;
    }
    std::printf("%-42s %8.2fs %11.2fs %7.3f %6.2fs %6.2fs %8.2fs %6.2fs %6.1fs\n", c.name,
                t.session_s, t.unavoidable_s, t.Ratio(), t.moves_s, t.exposures_s, t.downloads_s,
                t.host_s, t.wall_s);
  }
  std::printf(
      "\nsession: model time from the first move to the last frame recorded; unavoidable:"
      "\nlongest axis move per position + settle + exposure and shot overhead + download."
      "\nhost: frame checks, durable writes and catalog transactions (real time).\n");
  fs::remove_all(dir);
  return 0;
}
