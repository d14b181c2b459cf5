// A tethered camera. Small and synchronous: every call blocks until done or throws
// CameraError. One thread owns one Camera (libgphoto2 is not safe across threads).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "common/error.h"

namespace brdfrig::rig {

struct CameraInfo {
  std::string model;
  std::string port;  // e.g. "usb:001,004", "disk:/path", "sim"
  std::string serial;
  std::string firmware;
  std::vector<double> shutter_speeds;  // offered exposure times in seconds (may be empty)
};

// One file the camera produced for a shot (RAW+JPEG gives two).
struct Frame {
  std::string file_name;           // camera's name, e.g. "IMG_0042.JPG"; extension tells format
  std::vector<std::byte> bytes;    // the file's content
  double exposure_s = 0;           // exposure actually used
  double iso = 0;                  // 0 when unknown
  double exposure_duration_s = 0;  // time the shot took (device clock; virtual for the sim)
  double download_duration_s = 0;  // time the download took
};

class CameraError : public Error {
 public:
  enum class Kind {
    kNotFound,
    kClaimed,
    kBusy,
    kTimeout,
    kGone,
    kStorageFull,
    kUnsupported,
    kIo,
    kBadSettings,
    kOther
  };
  CameraError(Kind kind, int code, const std::string& message)
      : Error(message), kind_(kind), code_(code) {}
  Kind kind() const { return kind_; }
  int code() const { return code_; }  // libgphoto2 code, 0 when not from libgphoto2
  // Whether re-trying (after re-opening, for kGone) may succeed.
  bool recoverable() const {
    return kind_ == Kind::kBusy || kind_ == Kind::kTimeout || kind_ == Kind::kGone ||
           kind_ == Kind::kIo;
  }

 private:
  Kind kind_;
  int code_;
};

class Camera {
 public:
  virtual ~Camera() = default;
  virtual CameraInfo Info() const = 0;
  // Picks the nearest offered shutter speed; returns the exposure actually used (seconds).
  virtual double SetExposure(double seconds) = 0;
  // Takes one shot and returns every file it produced (events drained).
  virtual std::vector<Frame> Capture() = 0;
  // Re-detects and re-opens after the camera went away (kGone). Throws if still absent.
  virtual void Reopen() = 0;
};

}  // namespace brdfrig::rig
