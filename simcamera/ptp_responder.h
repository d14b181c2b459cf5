// The camera side of a PTP session: answers each operation request from the camera's state
// (settings, memory card) without knowing about sockets. A capture is answered at once and
// rendered afterwards, as a body does: the response comes first, the files are announced by
// events when they exist.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "simcamera/object_store.h"
#include "simcamera/ptp_datasets.h"
#include "simcamera/ptpip_packet.h"

namespace brdfrig::simcamera {

struct ExposureSettings {
  double exposure_s = 0.01;
  double iso = 100;
  double f_number = 8;
};

// One file of a shot, as the renderer delivers it.
struct CapturedFile {
  std::string extension;  // ".JPG", ".DNG"
  std::uint16_t format = 0;
  std::vector<std::uint8_t> bytes;
  std::uint32_t width = 0, height = 0, bit_depth = 0;
};
using ShotFunction = std::function<std::vector<CapturedFile>(const ExposureSettings&)>;

// What the camera offers; the first value of each list that matches `initial` is current.
struct CameraOffer {
  std::string manufacturer = "brdfrig";
  std::string model = "brdfrig PTP/IP simulated camera";
  std::string version = "1.0";
  std::string serial = "SIMPTPIP0001";
  std::vector<double> shutter_speeds_s;  // rounded to PTP's 0.1 ms units
  std::vector<int> isos = {100, 200, 400, 800, 1600};
  std::vector<double> f_numbers = {2.8, 4, 5.6, 8, 11, 16};
  ExposureSettings initial;
  int files_per_shot = 2;  // RAW + JPEG
};

struct PtpEvent {
  std::uint16_t code = 0;
  std::vector<std::uint32_t> params;
};

struct PtpReply {
  std::uint16_t code = 0;
  std::vector<std::uint32_t> params;
  std::optional<std::vector<std::uint8_t>> data;  // data phase from the camera
  // Work done after the response is sent (rendering a capture); returns the events to send.
  std::function<std::vector<PtpEvent>()> after;
};

inline constexpr std::uint32_t kStorageId = 0x00010001;

class PtpResponder {
 public:
  PtpResponder(CameraOffer offer, ShotFunction shoot);

  // A new connection starts without a session; the card and the settings stay.
  void ResetSession() { session_open_ = false; }
  PtpReply Handle(const OperationRequest& request, const std::vector<std::uint8_t>& data);

  ExposureSettings exposure() const;
  ObjectStore& store() { return store_; }
  const ObjectStore& store() const { return store_; }
  int captures() const { return captures_; }
  const CameraOffer& offer() const { return offer_; }

 private:
  PtpReply GetDeviceInfo() const;
  PtpReply GetObjectHandles(const OperationRequest& request) const;
  PtpReply GetObjectInfo(std::uint32_t handle) const;
  PtpReply GetObject(std::uint32_t handle) const;
  PtpReply DeleteObject(std::uint32_t handle);
  PtpReply InitiateCapture();
  PtpReply SetProperty(std::uint16_t code, const std::vector<std::uint8_t>& data);
  EnumProperty* FindProperty(std::uint16_t code);
  std::vector<PtpEvent> Shoot();

  CameraOffer offer_;
  ShotFunction shoot_;
  ObjectStore store_;
  std::vector<EnumProperty> properties_;
  bool session_open_ = false;
  int captures_ = 0;
  // The size of the last shot's files: what the next shot is expected to need on the card.
  std::uint64_t last_shot_bytes_ = 0;
};

}  // namespace brdfrig::simcamera
