#include "sim/simulate.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.h"
#include "common/format.h"
#include "sim/devices.h"
#include "sim/image_io.h"
#include "sim/scene.h"

namespace brdfrig::sim {
namespace {

constexpr int kMaxAttempts = 8;

// Runs `action`, recovering from the transient faults a scene can schedule, as the acquisition
// engine would (a smaller version of it: bounded retries, no back-off).
template <typename Action>
auto WithRecovery(Action action, SimCamera& camera, std::map<std::string, SimAxis>& axes,
                  int* recovered) {
  for (int attempt = 1;; ++attempt) {
    try {
      return action();
    } catch (const rig::CameraError& e) {
      if (!e.recoverable() || attempt >= kMaxAttempts) throw;
      ++*recovered;
      if (e.kind() == rig::CameraError::Kind::kGone) {
        for (int i = 0; i < kMaxAttempts; ++i) {
          try {
            camera.Reopen();
            break;
          } catch (const rig::CameraError& reopen) {
            if (i + 1 == kMaxAttempts) throw;
          }
        }
      }
    } catch (const rig::AxisError& e) {
      if (e.kind() != rig::AxisError::Kind::kAlarm || attempt >= kMaxAttempts) throw;
      ++*recovered;
      for (auto& [name, axis] : axes) axis.ResetAlarm();
    }
  }
}

// A scene holding a printed board: one photo of the board per pose, the arms where
// --positions puts them (at rest by default), at the board's exposure.
SimulateSummary SimulateBoard(const SimulateOptions& options, std::shared_ptr<SimWorld> world,
                              SimulateSummary summary, nlohmann::json log) {
  const Scene& scene = world->scene();
  SimCamera camera(world, {}, options.threads);
  std::map<std::string, SimAxis> axes;
  for (const geometry::RotationAxis& axis : scene.rig.axes)
    axes.emplace(axis.name, SimAxis(world, axis.name));
  nlohmann::json readings = nlohmann::json::object();
  if (!options.positions.empty()) {
    for (const auto& [name, angle] : options.positions.front()) {
      if (!axes.count(name)) throw Error("positions: the scene has no axis named '" + name + "'");
      readings[name] =
          WithRecovery([&, name = name, angle = angle] { return axes.at(name).MoveTo(angle); },
                       camera, axes, &summary.recovered_faults)
              .position;
    }
  }
  const double exposure =
      options.exposures.empty() ? scene.board->exposure_s : options.exposures.front();
  const int poses = static_cast<int>(scene.board->world_from_page.size());
  for (int p = 0; p < poses; ++p) {
    world->SetBoardPose(p);
    const std::vector<rig::Frame> frames = WithRecovery(
        [&] {
          camera.SetExposure(exposure);
          return camera.Capture();
        },
        camera, axes, &summary.recovered_faults);
    const rig::Frame& frame = frames.front();
    const std::string stem = Printf("board_%02d", p);
    WriteFileAtomically(summary.photos_dir / (stem + scene.sensor.Extension()), frame.bytes);
    log["frames"].push_back({{"file", stem + scene.sensor.Extension()},
                             {"board_pose", p},
                             {"axis_readings_rad", readings},
                             {"exposure_s", frame.exposure_s},
                             {"exposure_duration_s", frame.exposure_duration_s},
                             {"download_duration_s", frame.download_duration_s}});
    ++summary.frames;
    if (options.write_truth) {
      nlohmann::json g = world->simulator().GeometryAt(world->TruePositions(), true, p).ToJson();
      g["exposure_s"] = frame.exposure_s;
      g["gain"] = scene.sensor.gain;
      WriteFileAtomically(summary.truth_dir / (stem + ".json"), g.dump(2) + "\n");
    }
  }
  summary.positions = 1;
  summary.virtual_time_s = world->virtual_time_s();
  log["virtual_time_s"] = summary.virtual_time_s;
  WriteFileAtomically(summary.photos_dir / "capture.json", log.dump(2) + "\n");
  return summary;
}

}  // namespace

void SimulateOptions::Validate() const {
  if (scene.empty()) throw OptionsError("scene: a scene file is required");
  if (output_dir.empty()) throw OptionsError("output_dir: an output directory is required");
  for (double t : exposures) {
    if (!(t > 0)) throw OptionsError("exposures: every exposure must be > 0 seconds");
  }
  if (threads < 0) throw OptionsError("threads: must be >= 0");
}

std::string SimulateSummary::ToString() const {
  std::ostringstream out;
  out << "simulated " << frames << " photos at " << positions << " positions in " << wall_time_s
      << " s (the rig would take " << virtual_time_s << " s";
  if (recovered_faults > 0) out << ", " << recovered_faults << " faults recovered";
  out << "); photos in " << photos_dir.string() << ", truth in " << truth_dir.string();
  for (const std::string& w : warnings) out << "\nwarning: " << w;
  return out.str();
}

SimulateSummary Simulate(const SimulateOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  auto world = std::make_shared<SimWorld>(options.loaded_scene ? *options.loaded_scene
                                                               : LoadScene(options.scene));
  const Scene& scene = world->scene();
  if (scene.board) {
    SimulateSummary summary;
    summary.photos_dir = options.output_dir / "photos";
    summary.truth_dir = options.output_dir / "truth";
    std::filesystem::create_directories(summary.photos_dir);
    if (options.write_truth) std::filesystem::create_directories(summary.truth_dir);
    const nlohmann::json log = {
        {"scene", std::filesystem::absolute(options.scene).lexically_normal().string()},
        {"frames", nlohmann::json::array()}};
    summary = SimulateBoard(options, world, summary, log);
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
  }
  const auto positions = options.positions.empty() ? scene.capture.positions : options.positions;
  const auto exposures = options.exposures.empty() ? scene.capture.exposures : options.exposures;
  if (positions.empty()) {
    throw Error(options.scene.string() + ": no positions (give --positions or capture.positions)");
  }
  if (exposures.empty()) {
    throw Error(options.scene.string() + ": no exposures (give --exposures or capture.exposures)");
  }
  SimulateSummary summary;
  summary.photos_dir = options.output_dir / "photos";
  summary.truth_dir = options.output_dir / "truth";
  std::filesystem::create_directories(summary.photos_dir);
  if (options.write_truth) std::filesystem::create_directories(summary.truth_dir);

  SimCamera camera(world, {}, options.threads);
  std::map<std::string, SimAxis> axes;
  for (const geometry::RotationAxis& axis : scene.rig.axes)
    axes.emplace(axis.name, SimAxis(world, axis.name));
  // Absolute: a reader resolves a relative scene against the capture, never its own directory.
  nlohmann::json log = {
      {"scene", std::filesystem::absolute(options.scene).lexically_normal().string()},
      {"frames", nlohmann::json::array()}};

  for (std::size_t p = 0; p < positions.size(); ++p) {
    // The scene's roles apply to the scene's own positions, not to --positions.
    const bool validation = options.positions.empty() && p < scene.capture.validation.size() &&
                            scene.capture.validation[p];
    for (const auto& [name, angle] : positions[p]) {
      if (!axes.count(name)) throw Error("positions: the scene has no axis named '" + name + "'");
      WithRecovery([&, name = name, angle = angle] { return axes.at(name).MoveTo(angle); }, camera,
                   axes, &summary.recovered_faults);
    }
    // Every axis's reading, as the run engine records them: an axis a position does not name
    // stays where the previous one left it, and the reconstruction must know where that is.
    nlohmann::json readings = nlohmann::json::object();
    for (auto& [name, axis] : axes) readings[name] = axis.Status().position;
    for (std::size_t e = 0; e < exposures.size(); ++e) {
      const std::vector<rig::Frame> frames = WithRecovery(
          [&] {
            camera.SetExposure(exposures[e]);
            return camera.Capture();
          },
          camera, axes, &summary.recovered_faults);
      const rig::Frame& frame = frames.front();
      if (std::abs(std::log2(frame.exposure_s / exposures[e])) > 1.0 / 3 && p == 0) {
        summary.warnings.push_back(
            "asked for a " + Printf("%g", exposures[e]) +
            " s exposure, the simulated camera took " + Printf("%g", frame.exposure_s) +
            " s (its shutter speeds and range, " + options.scene.string() + " sensor:)");
      }
      const std::string file =
          Printf("p%02d_e%d", static_cast<int>(p), static_cast<int>(e)) + scene.sensor.Extension();
      WriteFileAtomically(summary.photos_dir / file, frame.bytes);
      log["frames"].push_back({{"file", file},
                               {"position_index", p},
                               {"validation", validation},
                               {"axis_readings_rad", readings},
                               {"exposure_s", frame.exposure_s},
                               {"exposure_duration_s", frame.exposure_duration_s},
                               {"download_duration_s", frame.download_duration_s}});
      ++summary.frames;
    }
    if (options.write_truth) {
      // The truth of what was photographed: where the arms really were.
      const geometry::AxisPositions truth = world->TruePositions();
      const std::string stem = Printf("p%02d", static_cast<int>(p));
      RenderOptions render;
      render.threads = options.threads;
      WriteRadianceExr(summary.truth_dir / (stem + ".exr"),
                       world->simulator().RenderRadiance(truth, render));
      nlohmann::json g = world->simulator().GeometryAt(truth).ToJson();
      g["exposures_s"] = exposures;
      g["gain"] = scene.sensor.gain;
      WriteFileAtomically(summary.truth_dir / (stem + ".json"), g.dump(2) + "\n");
    }
  }
  summary.positions = static_cast<int>(positions.size());
  summary.virtual_time_s = world->virtual_time_s();
  log["virtual_time_s"] = summary.virtual_time_s;
  WriteFileAtomically(summary.photos_dir / "capture.json", log.dump(2) + "\n");
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace brdfrig::sim
