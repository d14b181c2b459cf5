#include "simcamera/ptp_responder.h"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "common/error.h"
#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_data.h"

namespace brdfrig::simcamera {
namespace {

PtpReply Code(std::uint16_t code) { return PtpReply{code, {}, std::nullopt, {}}; }
PtpReply Data(std::vector<std::uint8_t> data) { return PtpReply{rc::kOk, {}, std::move(data), {}}; }

// The enumerated values of a property and the current one (the value nearest `initial`).
EnumProperty MakeProperty(std::uint16_t code, std::uint16_t datatype,
                          std::vector<std::uint32_t> values, std::uint32_t initial) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (values.empty()) throw Error("the simulated camera needs at least one value per setting");
  EnumProperty p;
  p.code = code;
  p.datatype = datatype;
  p.values = values;
  p.current =
      *std::min_element(values.begin(), values.end(), [&](std::uint32_t a, std::uint32_t b) {
        return std::llabs(static_cast<long long>(a) - initial) <
               std::llabs(static_cast<long long>(b) - initial);
      });
  p.factory = p.current;
  return p;
}

std::uint32_t TenthsOfMs(double seconds) {
  return static_cast<std::uint32_t>(std::llround(seconds * 10000));
}

std::string CaptureDate() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y%m%dT%H%M%S", &utc);
  return text;
}

}  // namespace

PtpResponder::PtpResponder(CameraOffer offer, ShotFunction shoot)
    : offer_(std::move(offer)), shoot_(std::move(shoot)) {
  std::vector<std::uint32_t> times;
  for (double s : offer_.shutter_speeds_s) {
    // PTP counts exposure time in 0.1 ms: faster speeds cannot be expressed.
    if (TenthsOfMs(s) >= 1) times.push_back(TenthsOfMs(s));
  }
  std::vector<std::uint32_t> isos(offer_.isos.begin(), offer_.isos.end());
  std::vector<std::uint32_t> apertures;
  for (double f : offer_.f_numbers)
    apertures.push_back(static_cast<std::uint32_t>(std::llround(f * 100)));
  properties_.push_back(MakeProperty(prop::kExposureTime, datatype::kUint32, times,
                                     TenthsOfMs(offer_.initial.exposure_s)));
  properties_.push_back(MakeProperty(prop::kExposureIndex, datatype::kUint16, isos,
                                     static_cast<std::uint32_t>(std::lround(offer_.initial.iso))));
  properties_.push_back(
      MakeProperty(prop::kFNumber, datatype::kUint16, apertures,
                   static_cast<std::uint32_t>(std::lround(offer_.initial.f_number * 100))));
}

ExposureSettings PtpResponder::exposure() const {
  ExposureSettings e;
  for (const EnumProperty& p : properties_) {
    if (p.code == prop::kExposureTime) e.exposure_s = p.current / 10000.0;
    if (p.code == prop::kExposureIndex) e.iso = p.current;
    if (p.code == prop::kFNumber) e.f_number = p.current / 100.0;
  }
  return e;
}

EnumProperty* PtpResponder::FindProperty(std::uint16_t code) {
  for (EnumProperty& p : properties_) {
    if (p.code == code) return &p;
  }
  return nullptr;
}

PtpReply PtpResponder::Handle(const OperationRequest& request,
                              const std::vector<std::uint8_t>& data) {
  const auto param = [&](std::size_t i) {
    return i < request.params.size() ? request.params[i] : 0u;
  };
  if (request.code == op::kGetDeviceInfo) return GetDeviceInfo();
  if (request.code == op::kOpenSession) {
    if (session_open_) return Code(rc::kSessionAlreadyOpen);
    session_open_ = true;
    return Code(rc::kOk);
  }
  if (!session_open_) return Code(rc::kSessionNotOpen);
  switch (request.code) {
    case op::kCloseSession:
      session_open_ = false;
      return Code(rc::kOk);
    case op::kGetStorageIds: {
      PtpWriter w;
      w.U32Array({kStorageId});
      return Data(w.Take());
    }
    case op::kGetStorageInfo: {
      if (param(0) != kStorageId) return Code(rc::kInvalidStorageId);
      StorageDescription s;
      s.capacity_bytes = store_.capacity_bytes();
      s.free_bytes =
          s.capacity_bytes - std::min<std::uint64_t>(s.capacity_bytes, store_.bytes_used());
      const int capacity = store_.capacity_files();
      s.free_images = capacity < 0 ? 9999u
                                   : static_cast<std::uint32_t>(std::max<long>(
                                         0, capacity - static_cast<long>(store_.files())));
      s.description = "SD card";
      s.label = "BRDFRIG";
      return Data(StorageInfoDataset(s));
    }
    case op::kGetObjectHandles:
      return GetObjectHandles(request);
    case op::kGetObjectInfo:
      return GetObjectInfo(param(0));
    case op::kGetObject:
      return GetObject(param(0));
    case op::kDeleteObject:
      return DeleteObject(param(0));
    case op::kInitiateCapture:
      return InitiateCapture();
    case op::kGetDevicePropDesc: {
      EnumProperty* p = FindProperty(static_cast<std::uint16_t>(param(0)));
      if (p == nullptr) return Code(rc::kDevicePropNotSupported);
      return Data(DevicePropDescDataset(*p));
    }
    case op::kGetDevicePropValue: {
      EnumProperty* p = FindProperty(static_cast<std::uint16_t>(param(0)));
      if (p == nullptr) return Code(rc::kDevicePropNotSupported);
      return Data(DevicePropValue(*p));
    }
    case op::kSetDevicePropValue:
      return SetProperty(static_cast<std::uint16_t>(param(0)), data);
    default:
      return Code(rc::kOperationNotSupported);
  }
}

PtpReply PtpResponder::GetDeviceInfo() const {
  DeviceDescription d;
  d.manufacturer = offer_.manufacturer;
  d.model = offer_.model;
  d.version = offer_.version;
  d.serial = offer_.serial;
  d.operations = {op::kGetDeviceInfo,     op::kOpenSession,       op::kCloseSession,
                  op::kGetStorageIds,     op::kGetStorageInfo,    op::kGetObjectHandles,
                  op::kGetObjectInfo,     op::kGetObject,         op::kDeleteObject,
                  op::kInitiateCapture,   op::kGetDevicePropDesc, op::kGetDevicePropValue,
                  op::kSetDevicePropValue};
  d.events = {event::kObjectAdded, event::kObjectRemoved, event::kDevicePropChanged,
              event::kStoreFull, event::kCaptureComplete};
  for (const EnumProperty& p : properties_) d.properties.push_back(p.code);
  d.formats = {format::kExifJpeg, format::kDng};
  return Data(DeviceInfoDataset(d));
}

PtpReply PtpResponder::GetObjectHandles(const OperationRequest& request) const {
  const std::uint32_t storage = request.params.empty() ? 0xFFFFFFFFu : request.params[0];
  if (storage != 0xFFFFFFFFu && storage != kStorageId) return Code(rc::kInvalidStorageId);
  const std::uint16_t wanted =
      request.params.size() > 1 ? static_cast<std::uint16_t>(request.params[1]) : 0;
  const std::uint32_t parent = request.params.size() > 2 ? request.params[2] : 0;
  // Every file lies in the card's root: "root only" (0xFFFFFFFF) and "all" (0) list them all,
  // and no object is a folder that could hold others.
  PtpWriter w;
  if (parent != 0 && parent != 0xFFFFFFFFu) {
    w.U32Array({});
  } else {
    w.U32Array(store_.Handles(wanted));
  }
  return Data(w.Take());
}

PtpReply PtpResponder::GetObjectInfo(std::uint32_t handle) const {
  const StoredObject* object = store_.Find(handle);
  if (object == nullptr) return Code(rc::kInvalidObjectHandle);
  ObjectDescription d;
  d.storage = kStorageId;
  d.format = object->format;
  d.size = static_cast<std::uint32_t>(object->bytes.size());
  d.width = object->width;
  d.height = object->height;
  d.bit_depth = object->bit_depth;
  d.file_name = object->file_name;
  d.capture_date = object->capture_date;
  return Data(ObjectInfoDataset(d));
}

PtpReply PtpResponder::GetObject(std::uint32_t handle) const {
  const StoredObject* object = store_.Find(handle);
  if (object == nullptr) return Code(rc::kInvalidObjectHandle);
  return Data(object->bytes);
}

PtpReply PtpResponder::DeleteObject(std::uint32_t handle) {
  if (handle == 0xFFFFFFFFu) {
    for (std::uint32_t h : store_.Handles()) store_.Remove(h);
    return Code(rc::kOk);
  }
  return Code(store_.Remove(handle) ? rc::kOk : rc::kInvalidObjectHandle);
}

PtpReply PtpResponder::SetProperty(std::uint16_t code, const std::vector<std::uint8_t>& data) {
  EnumProperty* p = FindProperty(code);
  if (p == nullptr) return Code(rc::kDevicePropNotSupported);
  PtpReader r(data);
  std::uint32_t value = 0;
  try {
    value = p->datatype == datatype::kUint16 ? r.U16() : r.U32();
  } catch (const Error&) {
    return Code(rc::kInvalidDevicePropValue);
  }
  if (std::find(p->values.begin(), p->values.end(), value) == p->values.end()) {
    return Code(rc::kInvalidDevicePropValue);
  }
  p->current = value;
  return Code(rc::kOk);
}

PtpReply PtpResponder::InitiateCapture() {
  if (!store_.Fits(static_cast<std::size_t>(offer_.files_per_shot), last_shot_bytes_)) {
    // A body with a full card refuses the shot and says why on the event channel too. The
    // card's bytes are the camera's memory: it holds at most its capacity plus one shot.
    PtpReply reply = Code(rc::kStoreFull);
    reply.after = [] { return std::vector<PtpEvent>{{event::kStoreFull, {kStorageId}}}; };
    return reply;
  }
  PtpReply reply = Code(rc::kOk);
  reply.after = [this] { return Shoot(); };
  return reply;
}

std::vector<PtpEvent> PtpResponder::Shoot() {
  const std::vector<CapturedFile> files = shoot_(exposure());
  ++captures_;
  const std::string stem = store_.NextStem();
  const std::string date = CaptureDate();
  std::vector<std::uint32_t> handles;
  last_shot_bytes_ = 0;
  for (const CapturedFile& f : files) {
    last_shot_bytes_ += f.bytes.size();
    StoredObject object;
    object.file_name = stem + f.extension;
    object.format = f.format;
    object.bytes = f.bytes;
    object.width = f.width;
    object.height = f.height;
    object.bit_depth = f.bit_depth;
    object.capture_date = date;
    handles.push_back(store_.Add(std::move(object)));
  }
  // libgphoto2's generic capture returns the last ObjectAdded it sees before CaptureComplete
  // and drops earlier ones; files announced after CaptureComplete reach the client as
  // FILE_ADDED events (what tethering code drains for RAW+JPEG). So the first file comes
  // before CaptureComplete and the others after it.
  std::vector<PtpEvent> events;
  if (!handles.empty()) events.push_back({event::kObjectAdded, {handles.front()}});
  events.push_back({event::kCaptureComplete, {}});
  for (std::size_t i = 1; i < handles.size(); ++i) {
    events.push_back({event::kObjectAdded, {handles[i]}});
  }
  return events;
}

}  // namespace brdfrig::simcamera
