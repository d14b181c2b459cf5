// A tethered camera through libgphoto2. Opens the first camera found, or one by model and/or
// port ("usb:001,004"; "ptpip:HOST:PORT:PORT" for a network camera, served by libgphoto2's
// generic "PTP/IP Camera" driver; "disk:/dir" for the Directory Browse driver). On a network
// camera a lost or silent link, or a refused setting, closes the camera and is kGone: Reopen()
// starts a new PTP session (docs/rig.md). Settings go through config widgets whose names differ
// between makers; each setting tries the known names in order (see docs/rig.md). Every call runs
// under our own watchdog: libgphoto2 polls the context's cancel function during long operations,
// and we answer "cancel" once the deadline has passed. Busy cameras are retried with back-off.
//
// Not thread-safe: one thread owns the camera (libgphoto2 contexts are not shared).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/yaml_reader.h"
#include "rig/camera.h"

typedef struct _Camera Camera;
typedef struct _GPContext GPContext;
typedef struct _CameraWidget CameraWidget;

namespace brdfrig::rig {

struct Gphoto2Options {
  std::string model;  // empty: the first camera found
  std::string port;   // empty: wherever `model` is found; "ptpip:..." needs no model
  // Settings applied on open; empty leaves the camera's value. Values must be among the
  // choices the camera offers (matched case-insensitively); errors list the choices.
  std::string image_format;    // e.g. "RAW + Large Fine JPEG" (imageformat / imagequality)
  std::string iso;             // e.g. "100"
  std::string aperture;        // e.g. "8" (aperture / f-number)
  std::string capture_target;  // "card" or "ram": matched against the offered choices
  bool delete_after_download = false;
  std::chrono::milliseconds operation_timeout{30000};  // watchdog for one camera operation
  std::chrono::milliseconds event_drain{2000};         // waiting for the second file of RAW+JPEG
  int busy_attempts = 5;
  std::chrono::milliseconds busy_backoff{200};  // doubled after each busy answer
};

// Reads a camera's rig.yaml settings: model, port, image_format, iso, aperture,
// capture_target, delete_after_download, timeout_s, event_drain_s.
Gphoto2Options ReadGphoto2Options(const YamlNode& settings);

struct DetectedCamera {
  std::string model;
  std::string port;
};

// Cameras libgphoto2 finds on USB (and other auto-detectable ports) right now.
std::vector<DetectedCamera> DetectGphoto2Cameras();

struct CameraFileRef {
  std::string folder;  // e.g. "/store_00010001/DCIM/100CANON"
  std::string name;    // e.g. "IMG_0042.JPG"
};

class Gphoto2Camera : public Camera {
 public:
  // Opens the camera and applies the settings; throws CameraError.
  explicit Gphoto2Camera(Gphoto2Options options);
  ~Gphoto2Camera() override;
  Gphoto2Camera(const Gphoto2Camera&) = delete;
  Gphoto2Camera& operator=(const Gphoto2Camera&) = delete;

  CameraInfo Info() const override { return info_; }
  double SetExposure(double seconds) override;
  std::vector<Frame> Capture() override;
  void Reopen() override;

  // Files on the camera's storage, folders walked recursively from `folder`.
  std::vector<CameraFileRef> ListFiles(const std::string& folder = "/");
  Frame Download(const CameraFileRef& file);
  // Streams a file to `fd` (not closed) without holding it in memory; returns its size.
  std::size_t DownloadToFd(const CameraFileRef& file, int fd);
  void Delete(const CameraFileRef& file);

  // Sets the first widget of `names` the camera has to `value` (nearest case-insensitive
  // match among its choices); returns the widget name and value used. Throws kUnsupported
  // when the camera has none of the widgets, kBadSettings when the value is not offered.
  std::pair<std::string, std::string> SetConfig(const std::vector<std::string>& names,
                                                const std::string& value);
  // Current value of the first widget of `names` the camera has.
  std::optional<std::string> GetConfig(const std::vector<std::string>& names);
  // Current values of the exposure-related widgets the camera has, as (widget, value):
  // shutterspeed, iso, aperture|f-number, imageformat|imagequality, capturetarget.
  std::vector<std::pair<std::string, std::string>> CurrentSettings();
  // Offered choices of the first widget of `names` (empty when none or not a choice widget).
  std::vector<std::string> Choices(const std::vector<std::string>& names);

  // The watchdog for each following operation (default: Gphoto2Options::operation_timeout).
  void set_operation_timeout(std::chrono::milliseconds timeout) {
    options_.operation_timeout = timeout;
  }

  // Called by the libgphoto2 context while an operation runs (see the .cc).
  bool ShouldCancel() const;

 private:
  void Open();
  void Close();
  void ApplySettings();
  // Throws kGone naming `what` when the camera is not open (a re-open failed).
  void RequireOpen(const std::string& what) const;
  // The whole settings tree, read under the watchdog; nullptr when the camera offers none.
  // The caller frees it.
  CameraWidget* ReadConfig();
  // Runs a libgphoto2 call under the watchdog, retrying busy answers; maps failures.
  template <typename Call>
  int Run(const std::string& what, Call call);
  std::string Where() const;

  Gphoto2Options options_;
  ::Camera* camera_ = nullptr;
  GPContext* context_ = nullptr;
  CameraInfo info_;
  double exposure_s_ = 0;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
};

}  // namespace brdfrig::rig
