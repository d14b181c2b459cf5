// libgphoto2 results as CameraError: a kind the caller can act on (retry, re-open, tell the
// operator) and a message that says what to do, with the libgphoto2 code kept for the log.
#pragma once

#include <string>

#include "rig/camera.h"

namespace brdfrig::rig {

CameraError::Kind Gphoto2ErrorKind(int result);

// `what` is the operation, e.g. "capture on Nikon DSC D750 (usb:001,004)".
CameraError Gphoto2Error(int result, const std::string& what);

}  // namespace brdfrig::rig
