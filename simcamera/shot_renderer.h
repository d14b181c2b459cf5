// What the simulated network camera photographs: the scene rendered by the simulator for the
// axis positions at the moment of the shot (read from the drives, see drive_positions.h) and
// the exposure set over PTP, delivered as a RAW+JPEG pair like a real body: a linear DNG
// (LibRaw reads it back to the sensor values) and an 8-bit sRGB JPEG.
//
// Exposure: the scene's sensor gain holds at ISO 100 and f/8; other ISO values and apertures
// scale the signal by iso/100 and (8/f)², so every setting changes the photo the way it would.
#pragma once

#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <optional>

#include "geometry/rig_geometry.h"
#include "sim/simulator.h"
#include "simcamera/ptp_responder.h"

namespace brdfrig::simcamera {

using PositionsFunction = std::function<geometry::AxisPositions()>;

class ShotRenderer {
 public:
  // `threads`: rendering threads (0 = all hardware threads).
  ShotRenderer(sim::Scene scene, PositionsFunction positions, int threads = 0);

  // Renders one shot: the JPEG first, then the DNG.
  std::vector<CapturedFile> Shoot(const ExposureSettings& exposure);

  const sim::Scene& scene() const { return simulator_.scene(); }
  int shots() const { return shots_; }
  const geometry::AxisPositions& last_positions() const { return last_positions_; }

 private:
  sim::Simulator simulator_;
  PositionsFunction positions_;
  int threads_;
  int shots_ = 0;
  geometry::AxisPositions last_positions_;
  // The radiance of the last pose, reused across a bracket (only the exposure changes).
  std::optional<geometry::AxisPositions> cached_pose_;
  cv::Mat cached_radiance_;
};

// The signal factor of an exposure relative to ISO 100 at f/8, times the exposure time: what
// Simulator::Expose is given as the exposure.
double EffectiveExposure(const ExposureSettings& exposure);

}  // namespace brdfrig::simcamera
