// Getting a camera back after it went away (CameraError::kGone and the other recoverable
// kinds): run by the camera's owner thread, which is the only thread that touches the camera.
// It re-opens at once, then again whenever the USB watcher reports a camera arriving, and at a
// fixed interval as well (watchers in containers may never see events), until a deadline.
#pragma once

#include <chrono>

#include "rig/camera.h"
#include "rig/usb_watcher.h"

namespace brdfrig::rig {

struct CameraRecoveryOptions {
  std::chrono::milliseconds timeout{60000};        // give up after this long
  std::chrono::milliseconds retry_interval{2000};  // re-open attempts without any USB event
};

struct CameraRecoveryReport {
  int attempts = 0;    // Reopen() calls, the successful one included
  int usb_events = 0;  // watcher messages consumed while waiting
  double waited_s = 0;
};

// Returns once Reopen() succeeded. Throws the last CameraError when the deadline passes or an
// attempt fails with a kind that waiting cannot fix (kClaimed, kBadSettings, kUnsupported:
// a person has to act). `events` may be null (no watcher).
CameraRecoveryReport RecoverCamera(Camera& camera, UsbEventQueue* events,
                                   const CameraRecoveryOptions& options = {});

}  // namespace brdfrig::rig
