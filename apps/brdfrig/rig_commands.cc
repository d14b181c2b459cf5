#include "apps/brdfrig/rig_commands.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/brdfrig/board_options.h"
#include "calibrate/flat_field.h"
#include "calibrate/lens_calibration.h"
#include "calibrate/light_calibration.h"
#include "calibrate/white_reference.h"
#include "common/angles.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "common/utc_time.h"
#include "common/yaml_reader.h"
#include "geometry/light_calibration_file.h"
#include "geometry/white_reference_file.h"
#include "reconstruct/batch.h"
#include "reconstruct/hdr_merge.h"
#include "rig/calibration_status.h"
#include "rig/rig_file.h"
#include "rig/rig_tools.h"
#include "sim/drive_server_tool.h"
#include "sim/scene.h"
#include "simcamera/sim_camera_tool.h"

namespace brdfrig::apps {
namespace {

struct RigArgs {
  std::string rig;
  std::string axis;
  double angle_deg = 0;
  std::string exposure;
  std::string output;
  sim::SimDriveOptions simdrive;
  simcamera::SimCameraOptions simcamera;
  // rig calibrate lens
  std::vector<std::string> photos;
  BoardArgs board;
  calibrate::LensCalibrationOptions lens;
  calibrate::FlatFieldOptions flat;
  calibrate::WhiteReferenceOptions white;
  calibrate::LightCalibrationOptions light;
  std::string scene, flat_file, position, capture;
};

// What the lab believes about the rig, for a calibration that needs the geometry: rig.yaml (its
// calibrations applied) or a scene's `rig:`; nullopt when neither is given.
std::optional<geometry::RigGeometry> BelievedGeometry(const RigArgs& args) {
  if (!args.rig.empty()) return rig::ReadRigDescription(args.rig).geometry;
  if (!args.scene.empty()) {
    return geometry::ParseRigGeometry(LoadYamlFile(args.scene).Required("rig"));
  }
  return std::nullopt;
}

// A light calibration's photos from a capture: at each position its shortest exposure, where
// the mirror's highlight is least clipped.
std::vector<calibrate::LightPhoto> LightPhotos(const reconstruct::CaptureSet& capture) {
  std::vector<calibrate::LightPhoto> photos;
  for (const reconstruct::CapturePosition& position : capture.positions) {
    if (position.frames.empty()) continue;
    const auto shortest =
        std::min_element(position.frames.begin(), position.frames.end(),
                         [](const auto& a, const auto& b) { return a.exposure_s < b.exposure_s; });
    photos.push_back(
        {{shortest->file.filename().string(), reconstruct::ReadPhoto(shortest->file.string())},
         position.axis_readings});
  }
  return photos;
}

// Faults for the simulated drive, to rehearse what an operator sees (docs/rig.md, faults).
void DriveFaultsOptions(CLI::App* cmd, sim::DriveFaults& faults) {
  cmd->add_option("--drop", faults.drop_responses, "Leave the next N requests unanswered");
  cmd->add_option("--corrupt", faults.corrupt_responses, "Corrupt the next N answers");
  cmd->add_option("--exceptions", faults.exception_responses,
                  "Answer the next N requests with --exception-code");
  cmd->add_option("--exception-code", faults.exception_code, "Modbus exception code (default 6)");
  cmd->add_option("--alarm-at", faults.alarm_at_fraction,
                  "Raise an alarm at this fraction (0..1) of the first move");
  cmd->add_option("--alarm-code", faults.alarm_code, "Alarm code (default 0x30 = 48)");
  cmd->add_option("--slow", faults.speed_factor, "Move at this fraction of the commanded speed");
}

// Faults for the simulated camera (docs/rig.md, camera faults).
void CameraFaultsOptions(CLI::App* cmd, simcamera::CameraFaults& faults) {
  cmd->add_option("--busy", faults.busy_responses,
                  "Answer the next N downloads, deletions and settings DeviceBusy");
  cmd->add_option("--slow", faults.response_delay_s,
                  "Delay every response by S seconds (libgphoto2 times out after 2.5 s)");
  cmd->add_option("--drop", faults.drop_downloads,
                  "Break the connection during the next N downloads");
  cmd->add_option("--card-files", faults.card_capacity_files,
                  "The card holds at most N files (a shot is 2: RAW+JPEG); then StoreFull");
  cmd->add_option("--vanish", faults.vanish_s,
                  "At the next capture, disappear from the network for S seconds");
}

}  // namespace

void RegisterRigCommands(CLI::App& app) {
  auto args = std::make_shared<RigArgs>();
  CLI::App* rig = app.add_subcommand("rig", "Check and drive the capture rig by hand");
  rig->require_subcommand(1);

  CLI::App* check = rig->add_subcommand(
      "check", "Find every device of rig.yaml and report model, port, positions and settings");
  check->add_option("--rig", args->rig, "Rig file (rig.yaml)")->required();
  check->callback([args] {
    const rig::RigCheckReport report = rig::CheckRig(args->rig);
    std::printf("%s\n", report.ToString().c_str());
    if (!report.ok()) throw Error("rig check failed: see the FAIL lines above");
  });

  CLI::App* move = rig->add_subcommand("move", "Move one axis to an absolute angle");
  move->add_option("--rig", args->rig, "Rig file (rig.yaml)")->required();
  move->add_option("axis", args->axis, "Axis name as in rig.yaml")->required();
  move->add_option("angle", args->angle_deg, "Target angle in degrees")->required();
  move->callback([args] {
    const rig::MoveReport report = rig::MoveAxis(args->rig, args->axis, args->angle_deg);
    std::printf("%s at %.3f deg after %.2f s\n", args->axis.c_str(), Degrees(report.position),
                report.duration_s);
  });

  CLI::App* shoot = rig->add_subcommand("shoot", "Take one photo with the rig's camera");
  shoot->add_option("--rig", args->rig, "Rig file (rig.yaml)")->required();
  shoot->add_option("--exposure", args->exposure, "Exposure time, e.g. 1/60 or 0.5")->required();
  shoot->add_option("-o,--output", args->output, "Output file (RAW+JPEG: both, by extension)")
      ->required();
  shoot->callback([args] {
    std::printf("%s\n", rig::Shoot(args->rig, args->exposure, args->output).ToString().c_str());
  });

  CLI::App* simdrive = rig->add_subcommand(
      "simdrive", "Serve a simulated Modbus drive (TCP on loopback or RTU on a pty) until Ctrl-C");
  simdrive->add_option("--profile", args->simdrive.profile,
                       "Drive profile: oriental_az_direct, generic, or a .yaml file");
  simdrive->add_option("--tcp", args->simdrive.tcp_port, "Serve TCP on 127.0.0.1:PORT (0: any)");
  simdrive->add_flag("--pty", args->simdrive.pty, "Serve RTU on a new pseudo-terminal");
  simdrive->add_option("--slave", args->simdrive.slave, "Modbus slave id (default 1)");
  DriveFaultsOptions(simdrive, args->simdrive.faults);
  simdrive->callback([args] { sim::RunSimulatedDrive(args->simdrive); });

  CLI::App* simcamera = rig->add_subcommand(
      "simcamera",
      "Serve a simulated PTP/IP network camera (libgphoto2 port ptpip:HOST:PORT) until Ctrl-C");
  simcamera->add_option("--listen", args->simcamera.listen,
                        "HOST:PORT to listen on (default 127.0.0.1:15740; port 0: any)");
  simcamera->add_option("--scene", args->simcamera.scene, "Scene file the camera photographs")
      ->required();
  simcamera->add_option("--rig", args->simcamera.rig,
                        "rig.yaml whose axes (drives) give the pose of each shot");
  simcamera->add_option("--threads", args->simcamera.threads, "Rendering threads (0: all)");
  CameraFaultsOptions(simcamera, args->simcamera.faults);
  simcamera->callback([args] { simcamera::RunSimulatedCamera(args->simcamera); });

  CLI::App* calibrate = rig->add_subcommand("calibrate", "Calibrate the rig from photos");
  calibrate->require_subcommand(1);
  CLI::App* status = calibrate->add_subcommand(
      "status",
      "What rig.yaml's calibrations are, when each was made, with what error, and which are "
      "older than the rig's last change (`changed:`); exit status 3 when any is missing or "
      "stale");
  status->add_option("--rig", args->rig, "Rig file (rig.yaml)")->required();
  status->callback([args] {
    const rig::CalibrationStatus result = rig::ReadCalibrationStatus(args->rig);
    std::printf("%s", result.ToString().c_str());
    if (!result.Current()) throw CLI::RuntimeError(3);
  });
  CLI::App* lens = calibrate->add_subcommand(
      "lens",
      "Intrinsics and distortion from photos of the printed ChArUco board; writes a "
      "calibration file for rig.yaml's `calibration: {lens: FILE}` (never edits rig.yaml)");
  lens->add_option("photos", args->photos, "Photos of the board, or directories of them")
      ->required();
  lens->add_option("-o,--output", args->output, "Calibration file to write (JSON)")->required();
  AddBoardOptions(lens, args->board, true);
  lens->add_option("--camera-model", args->lens.camera_model, "Camera model, recorded");
  lens->add_option("--camera-serial", args->lens.camera_serial, "Camera serial, recorded");
  lens->add_option("--min-corners", args->lens.min_corners,
                   "Board corners every photo must show (default 12)");
  lens->add_option("--min-photos", args->lens.min_photos, "Photos needed (default 4)");
  lens->add_option("--max-edge-width", args->lens.max_edge_width_px,
                   "Widest edge (px) of a photo in focus (default 4)");
  lens->add_option("--min-coverage", args->lens.min_coverage,
                   "Share of the frame the corners must cover, 0..1 (default 0.5)");
  lens->callback([args] {
    calibrate::LensCalibrationOptions options = args->lens;
    options.board = BoardSpecFrom(args->board);
    std::vector<std::filesystem::path> paths(args->photos.begin(), args->photos.end());
    const calibrate::LensCalibrationResult result =
        calibrate::CalibrateLens(calibrate::LoadCalibrationPhotos(paths), options);
    geometry::WriteLensCalibration(args->output, result.calibration);
    std::printf("%swrote %s\n", result.ToString().c_str(), args->output.c_str());
  });

  CLI::App* flat = calibrate->add_subcommand(
      "flat",
      "The camera's gain across the frame (vignetting) from linear photos of a uniformly "
      "radiant card filling the frame; writes the map (EXR, mean 1) and FILE.json");
  flat->add_option("photos", args->photos, "Photos of the card, or directories of them")
      ->required();
  flat->add_option("-o,--output", args->output, "Gain map to write (.exr)")->required();
  flat->add_option("--degree", args->flat.degree, "Degree of the fitted surface (default 6)");
  flat->add_option("--max-fit-rms", args->flat.max_fit_rms,
                   "Largest departure of the photos from a smooth field (default 0.02)");
  flat->callback([args] {
    std::vector<std::filesystem::path> paths(args->photos.begin(), args->photos.end());
    const std::vector<calibrate::CalibrationPhoto> photos = calibrate::LoadCalibrationPhotos(paths);
    const calibrate::FlatFieldResult result = calibrate::CalibrateFlatField(photos, args->flat);
    calibrate::WriteFlatField(args->output, result, photos);
    std::printf("%s\nwrote %s and %s.json\n", result.ToString().c_str(), args->output.c_str(),
                args->output.c_str());
  });

  CLI::App* white = calibrate->add_subcommand(
      "white",
      "The paper's albedo against a reference tile of known reflectance in the cut-out, from "
      "linear photos; writes a JSON file (never edits rig.yaml)");
  white->add_option("photos", args->photos, "Photos, or directories of them")->required();
  white->add_option("-o,--output", args->output, "File to write (JSON)")->required();
  white
      ->add_option("--reference-albedo", args->white.reference_albedo,
                   "The tile's certified reflectance")
      ->required();
  auto* white_rig = white->add_option("--rig", args->rig, "rig.yaml: the geometry");
  white->add_option("--scene", args->scene, "scene.yaml: the geometry")->excludes(white_rig);
  white->add_option("--flat", args->flat_file, "Gain map from `rig calibrate flat` (.exr)");
  white->add_option("--position", args->position,
                    "Where the arms stood: axis=degrees[,axis=degrees...] (default: at rest)");
  white->callback([args] {
    const std::optional<geometry::RigGeometry> believed = BelievedGeometry(*args);
    if (!believed) throw Error("rig calibrate white: give --rig rig.yaml or --scene scene.yaml");
    const geometry::RigGeometry& geometry = *believed;
    calibrate::WhiteReferenceOptions options = args->white;
    if (!args->position.empty()) options.positions = sim::ParsePositionsDegrees(args->position);
    if (!args->flat_file.empty()) {
      cv::Mat channels[3];
      cv::split(ReadRadianceExr(args->flat_file), channels);
      options.flat_field = channels[0];
    }
    std::vector<std::filesystem::path> paths(args->photos.begin(), args->photos.end());
    const std::vector<calibrate::CalibrationPhoto> photos = calibrate::LoadCalibrationPhotos(paths);
    const calibrate::WhiteReferenceResult result =
        calibrate::CalibrateWhiteReference(photos, geometry, options);
    geometry::WhiteReference reference;
    reference.created = NowUtcIso8601();
    reference.software = std::string("brdfrig ") + BRDFRIG_VERSION;
    reference.paper_albedo = result.paper_albedo;
    reference.reference_albedo = options.reference_albedo;
    reference.tile_spread = result.tile_spread;
    reference.per_photo = result.per_photo;
    reference.flat_field = args->flat_file;
    for (const auto& p : photos) reference.photos.push_back(p.name);
    geometry::WriteWhiteReference(args->output, reference);
    std::printf("%s\nwrote %s\n", result.ToString().c_str(), args->output.c_str());
  });

  CLI::App* light = calibrate->add_subcommand(
      "light",
      "The light's position at rest from a capture of a mirror tile (polished black glass) in "
      "the cut-out, at positions whose mirror points spread over it; writes a JSON file for "
      "rig.yaml's `calibration: {light: FILE}` (never edits rig.yaml)");
  light->add_option("capture", args->capture, "The capture: a session, or `brdfrig simulate`'s")
      ->required();
  light->add_option("-o,--output", args->output, "File to write (JSON)")->required();
  auto* light_rig =
      light->add_option("--rig", args->rig, "rig.yaml: the geometry (default: the capture's)");
  light->add_option("--scene", args->scene, "scene.yaml: the geometry")->excludes(light_rig);
  light->add_option("--max-miss", args->light.max_miss_m,
                    "Largest distance (m) of the light from a photo's ray (default 0.002)");
  light->callback([args] {
    const reconstruct::CaptureSet capture = reconstruct::LoadCapture(args->capture);
    const geometry::RigGeometry geometry = BelievedGeometry(*args).value_or(capture.nominal);
    const std::vector<calibrate::LightPhoto> photos = LightPhotos(capture);
    const calibrate::LightCalibrationResult result =
        calibrate::CalibrateLight(photos, geometry, args->light);
    geometry::LightCalibration c;
    c.created = NowUtcIso8601();
    c.software = std::string("brdfrig ") + BRDFRIG_VERSION;
    c.light_position = result.light_position;
    c.nominal_offset_m = result.nominal_offset_m;
    c.rms_miss_m = result.rms_miss_m;
    c.dilution = result.dilution;
    for (std::size_t i = 0; i < photos.size(); ++i) {
      geometry::LightCalibrationPhoto p;
      p.photo = result.photos[i].name;
      for (const auto& [axis, angle] : photos[i].positions) p.positions_deg[axis] = Degrees(angle);
      p.highlight_x = result.photos[i].highlight_x;
      p.highlight_y = result.photos[i].highlight_y;
      p.miss_m = result.photos[i].miss_m;
      c.photos.push_back(p);
    }
    geometry::WriteLightCalibration(args->output, c);
    std::printf("%swrote %s\n", result.ToString().c_str(), args->output.c_str());
  });
}

}  // namespace brdfrig::apps
