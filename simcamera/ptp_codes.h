// The PTP (ISO 15740 / PIMA 15740) and PTP/IP (CIPA DC-005) numbers the simulated camera
// speaks: packet types, operations, responses, events, device properties, data types and
// object formats. Only what the simulator implements is listed.
#pragma once

#include <cstdint>

namespace brdfrig::simcamera {

// PTP/IP packet types (DC-005 section 2.3).
enum class PacketType : std::uint32_t {
  kInitCommandRequest = 1,
  kInitCommandAck = 2,
  kInitEventRequest = 3,
  kInitEventAck = 4,
  kInitFail = 5,
  kOperationRequest = 6,
  kOperationResponse = 7,
  kEvent = 8,
  kStartData = 9,
  kData = 10,
  kCancel = 11,
  kEndData = 12,
  kProbeRequest = 13,
  kProbeResponse = 14,
};

// Data phase field of an operation request: 1 = no data or data from the camera, 2 = data to
// the camera.
inline constexpr std::uint32_t kDataPhaseToCamera = 2;

namespace op {
inline constexpr std::uint16_t kGetDeviceInfo = 0x1001;
inline constexpr std::uint16_t kOpenSession = 0x1002;
inline constexpr std::uint16_t kCloseSession = 0x1003;
inline constexpr std::uint16_t kGetStorageIds = 0x1004;
inline constexpr std::uint16_t kGetStorageInfo = 0x1005;
inline constexpr std::uint16_t kGetObjectHandles = 0x1007;
inline constexpr std::uint16_t kGetObjectInfo = 0x1008;
inline constexpr std::uint16_t kGetObject = 0x1009;
inline constexpr std::uint16_t kDeleteObject = 0x100B;
inline constexpr std::uint16_t kInitiateCapture = 0x100E;
inline constexpr std::uint16_t kGetDevicePropDesc = 0x1014;
inline constexpr std::uint16_t kGetDevicePropValue = 0x1015;
inline constexpr std::uint16_t kSetDevicePropValue = 0x1016;
}  // namespace op

namespace rc {
inline constexpr std::uint16_t kOk = 0x2001;
inline constexpr std::uint16_t kGeneralError = 0x2002;
inline constexpr std::uint16_t kSessionNotOpen = 0x2003;
inline constexpr std::uint16_t kOperationNotSupported = 0x2005;
inline constexpr std::uint16_t kInvalidStorageId = 0x2008;
inline constexpr std::uint16_t kInvalidObjectHandle = 0x2009;
inline constexpr std::uint16_t kDevicePropNotSupported = 0x200A;
inline constexpr std::uint16_t kStoreFull = 0x200C;
inline constexpr std::uint16_t kDeviceBusy = 0x2019;
inline constexpr std::uint16_t kInvalidDevicePropValue = 0x201C;
inline constexpr std::uint16_t kSessionAlreadyOpen = 0x201E;
}  // namespace rc

namespace event {
inline constexpr std::uint16_t kObjectAdded = 0x4002;
inline constexpr std::uint16_t kObjectRemoved = 0x4003;
inline constexpr std::uint16_t kDevicePropChanged = 0x4006;
inline constexpr std::uint16_t kStoreFull = 0x400A;
inline constexpr std::uint16_t kCaptureComplete = 0x400D;
}  // namespace event

namespace prop {
inline constexpr std::uint16_t kFNumber = 0x5007;        // UINT16, f-number × 100
inline constexpr std::uint16_t kExposureTime = 0x500D;   // UINT32, units of 0.1 ms
inline constexpr std::uint16_t kExposureIndex = 0x500F;  // UINT16, ISO
}  // namespace prop

namespace datatype {
inline constexpr std::uint16_t kUint16 = 0x0004;
inline constexpr std::uint16_t kUint32 = 0x0006;
}  // namespace datatype

namespace format {
inline constexpr std::uint16_t kExifJpeg = 0x3801;
inline constexpr std::uint16_t kDng = 0x3811;
}  // namespace format

}  // namespace brdfrig::simcamera
