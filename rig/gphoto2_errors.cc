#include "rig/gphoto2_errors.h"

#include <gphoto2/gphoto2-result.h>

namespace brdfrig::rig {

CameraError::Kind Gphoto2ErrorKind(int result) {
  using Kind = CameraError::Kind;
  switch (result) {
    case GP_ERROR_MODEL_NOT_FOUND:
    case GP_ERROR_UNKNOWN_PORT:
      return Kind::kNotFound;
    case GP_ERROR_IO_USB_CLAIM:
    case GP_ERROR_IO_LOCK:
      return Kind::kClaimed;
    case GP_ERROR_CAMERA_BUSY:
      return Kind::kBusy;
    case GP_ERROR_TIMEOUT:
    case GP_ERROR_CANCEL:
      return Kind::kTimeout;
    case GP_ERROR_IO_USB_FIND:
      return Kind::kGone;
    case GP_ERROR_NO_SPACE:
      return Kind::kStorageFull;
    case GP_ERROR_NOT_SUPPORTED:
      return Kind::kUnsupported;
    case GP_ERROR_IO:
    case GP_ERROR_IO_INIT:
    case GP_ERROR_IO_READ:
    case GP_ERROR_IO_WRITE:
    case GP_ERROR_IO_UPDATE:
    case GP_ERROR_IO_USB_CLEAR_HALT:
    case GP_ERROR_CORRUPTED_DATA:
      return Kind::kIo;
    case GP_ERROR_BAD_PARAMETERS:
      return Kind::kBadSettings;
    default:
      return Kind::kOther;
  }
}

CameraError Gphoto2Error(int result, const std::string& what) {
  using Kind = CameraError::Kind;
  const Kind kind = Gphoto2ErrorKind(result);
  std::string advice;
  switch (kind) {
    case Kind::kNotFound:
      advice =
          "no such camera: is it connected by USB, switched on and in PC/PTP mode? "
          "`gphoto2 --auto-detect` lists what libgphoto2 sees";
      break;
    case Kind::kClaimed:
      advice =
          "the camera's USB interface is held by another process. On desktop Linux this "
          "is usually gvfs (gvfs-gphoto2-volume-monitor / gvfsd-gphoto2, which mount "
          "cameras automatically): unmount the camera in the file manager or stop them "
          "(`pkill gvfsd-gphoto2; systemctl --user stop gvfs-gphoto2-volume-monitor`), "
          "and close other tethering tools";
      break;
    case Kind::kBusy:
      advice =
          "the camera is busy (still writing, autofocusing or showing a menu); retried "
          "with back-off and still busy";
      break;
    case Kind::kTimeout:
      advice =
          "no answer in time; check the cable and that the camera has not gone to sleep "
          "(disable auto power-off)";
      break;
    case Kind::kGone:
      advice =
          "the camera disappeared from USB (cable, power, auto power-off); it is "
          "re-detected and re-opened when it comes back";
      break;
    case Kind::kStorageFull:
      advice =
          "the memory card is full: free space, or capture to the camera's RAM "
          "(capturetarget) with delete_after_download";
      break;
    case Kind::kUnsupported:
      advice = "this camera or its libgphoto2 driver does not support the operation";
      break;
    case Kind::kIo:
      advice = "USB I/O error; check the cable and avoid unpowered hubs";
      break;
    case Kind::kBadSettings:
      advice = "the camera rejected the setting (is the mode dial on M?)";
      break;
    case Kind::kOther:
      advice = "see the libgphoto2 message";
      break;
  }
  return CameraError(kind, result,
                     what + " failed: " + gp_result_as_string(result) + " (libgphoto2 " +
                         std::to_string(result) + "): " + advice);
}

}  // namespace brdfrig::rig
