#include "sim/devices.h"

#include <cstdio>

#include "common/atomic_file.h"
#include "rig/backend_registry.h"
#include "sim/image_io.h"

namespace brdfrig::sim {
namespace {

std::string FrameStem(int number) {
  char name[32];
  std::snprintf(name, sizeof name, "SIM_%04d", number);
  return name;
}

std::shared_ptr<SimWorld> WorldFrom(const YamlNode& settings, const rig::DeviceContext& context) {
  const YamlNode scene = settings.Required("scene");
  const std::filesystem::path path = std::filesystem::path(context.base_dir) / scene.AsString();
  try {
    return SimWorld::Shared(path);
  } catch (const FileError&) {
    throw;  // already points into the scene file
  } catch (const Error& e) {
    scene.Fail(e.what());
  }
}

}  // namespace

SimCamera::SimCamera(std::shared_ptr<SimWorld> world, std::filesystem::path truth_dir, int threads)
    : world_(std::move(world)), truth_dir_(std::move(truth_dir)), threads_(threads) {}

rig::CameraInfo SimCamera::Info() const {
  rig::CameraInfo info;
  info.model = world_->scene().sensor.model;
  info.port = "sim";
  info.serial = "SIM0001";
  info.firmware = BRDFRIG_VERSION;
  info.shutter_speeds = world_->scene().sensor.shutter_speeds;
  return info;
}

double SimCamera::SetExposure(double seconds) { return world_->SetExposure(seconds); }

std::vector<rig::Frame> SimCamera::Capture() {
  const ShotTicket shot = world_->BeginShot();
  const Simulator& simulator = world_->simulator();
  const std::tuple<geometry::AxisPositions, bool, int> key{shot.true_positions, shot.light_on,
                                                           shot.board_pose};
  const bool new_pose = !cached_key_ || *cached_key_ != key;
  if (new_pose) {
    RenderOptions options;
    options.threads = threads_;
    options.light_on = shot.light_on;
    options.board_pose = shot.board_pose;
    cached_radiance_ = simulator.RenderRadiance(shot.true_positions, options);
    cached_key_ = key;
  }
  const cv::Mat sensor = simulator.Expose(cached_radiance_, shot.exposure_s,
                                          static_cast<std::uint64_t>(shot.number), threads_);
  rig::Frame frame;
  const std::string stem = FrameStem(shot.number);
  frame.file_name = stem + world_->scene().sensor.Extension();
  frame.bytes = simulator.EncodePhoto(sensor);
  frame.exposure_s = shot.exposure_s;
  frame.iso = 100;
  frame.exposure_duration_s = shot.exposure_duration_s;
  frame.download_duration_s = shot.download_duration_s;
  if (!truth_dir_.empty()) {
    std::filesystem::create_directories(truth_dir_);
    if (new_pose) {
      cached_radiance_file_ = stem + "_radiance.exr";
      WriteRadianceExr(truth_dir_ / cached_radiance_file_, cached_radiance_);
    }
    nlohmann::json truth =
        simulator.GeometryAt(shot.true_positions, shot.light_on, shot.board_pose).ToJson();
    truth["photo"] = frame.file_name;
    truth["exposure_s"] = shot.exposure_s;
    truth["gain"] = world_->scene().sensor.gain;
    truth["radiance_file"] = cached_radiance_file_;
    WriteFileAtomically(truth_dir_ / (stem + ".json"), truth.dump(2) + "\n");
  }
  world_->FinishShot(shot);
  return {std::move(frame)};
}

void SimCamera::Reopen() { world_->ReopenCamera(); }

SimAxis::SimAxis(std::shared_ptr<SimWorld> world, std::string axis)
    : world_(std::move(world)), axis_(std::move(axis)) {
  if (!world_->scene().rig.FindAxis(axis_)) {
    throw Error("the scene has no axis named '" + axis_ + "'");
  }
}

void SimAxis::Home() { world_->HomeAxis(axis_); }
rig::MoveReport SimAxis::MoveTo(double angle) { return world_->MoveAxis(axis_, angle); }
rig::AxisStatus SimAxis::Status() { return world_->AxisStatus(axis_); }
void SimAxis::ResetAlarm() { world_->ResetAxisAlarm(axis_); }

void RegisterSimBackends() {
  rig::RegisterCameraBackend("sim",
                             [](const YamlNode& settings, const rig::DeviceContext& context) {
                               auto world = WorldFrom(settings, context);
                               std::filesystem::path truth;
                               if (auto dir = settings.Optional("truth_dir")) {
                                 truth = std::filesystem::path(context.base_dir) / dir->AsString();
                               }
                               const int threads = settings.Get("threads", 0);
                               settings.Finish();
                               return std::make_unique<SimCamera>(world, truth, threads);
                             });
  rig::RegisterAxisBackend("sim", [](const YamlNode& settings, const rig::DeviceContext& context) {
    auto world = WorldFrom(settings, context);
    const std::string axis = settings.Get("axis", context.device_name);
    if (!world->scene().rig.FindAxis(axis)) {
      const YamlNode at = settings.Has("axis") ? settings.Required("axis") : settings;
      at.Fail("the scene has no axis named '" + axis + "'");
    }
    settings.Finish();
    return std::make_unique<SimAxis>(world, axis);
  });
  rig::RegisterLightBackend("sim", [](const YamlNode& settings, const rig::DeviceContext& context) {
    auto world = WorldFrom(settings, context);
    settings.Finish();
    return std::make_unique<SimLight>(world);
  });
}

}  // namespace brdfrig::sim
