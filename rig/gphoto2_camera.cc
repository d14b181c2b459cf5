#include "rig/gphoto2_camera.h"

#include <fcntl.h>
#include <gphoto2/gphoto2.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "rig/gphoto2_errors.h"
#include "rig/shutter_speed.h"

namespace brdfrig::rig {
namespace {

// Widget names for one setting, in the order tried (Canon EOS, Nikon, Sony, ...).
const std::vector<std::string> kShutterSpeed = {"shutterspeed", "shutterspeed2"};
const std::vector<std::string> kAperture = {"aperture", "f-number"};
const std::vector<std::string> kImageFormat = {"imageformat", "imagequality"};
const std::vector<std::string> kIso = {"iso", "isospeed"};
const std::vector<std::string> kCaptureTarget = {"capturetarget"};

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

GPContextFeedback CancelFunc(GPContext*, void* data) {
  return static_cast<const Gphoto2Camera*>(data)->ShouldCancel() ? GP_CONTEXT_FEEDBACK_CANCEL
                                                                 : GP_CONTEXT_FEEDBACK_OK;
}

// libgphoto2 objects freed at scope exit.
struct ListPtr {
  CameraList* list = nullptr;
  ListPtr() { gp_list_new(&list); }
  ~ListPtr() { gp_list_free(list); }
};
struct FilePtr {
  CameraFile* file = nullptr;
  ~FilePtr() {
    if (file != nullptr) gp_file_free(file);
  }
};
struct WidgetPtr {
  CameraWidget* root = nullptr;
  ~WidgetPtr() {
    if (root != nullptr) gp_widget_free(root);
  }
};

std::string Seconds(std::chrono::milliseconds duration) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", duration.count() / 1000.0);
  return text;
}

std::string DiskPath(const std::string& port) {
  return port.rfind("disk:", 0) == 0 ? port.substr(5) : std::string();
}

bool IsNetworkPort(const std::string& port) { return port.rfind("ptpip:", 0) == 0; }

// Results with which libgphoto2's PTP/IP transport reports a broken or silent link (a closed
// socket reads as a generic error, a silent one as a timeout after 2.5 s). The session on the
// camera cannot continue on that connection: it must be opened again.
bool IsLinkFailure(int result) {
  return result == GP_ERROR || result == GP_ERROR_TIMEOUT || result == GP_ERROR_IO ||
         result == GP_ERROR_IO_READ || result == GP_ERROR_IO_WRITE || result == GP_ERROR_IO_INIT;
}

}  // namespace

Gphoto2Options ReadGphoto2Options(const YamlNode& settings) {
  Gphoto2Options o;
  o.model = settings.Get("model", "");
  o.port = settings.Get("port", "");
  o.image_format = settings.Get("image_format", "");
  o.iso = settings.Get("iso", "");
  o.aperture = settings.Get("aperture", "");
  if (const auto target = settings.Optional("capture_target")) {
    o.capture_target = target->AsString();
    if (o.capture_target != "card" && o.capture_target != "ram") {
      target->Fail("expected card or ram, got '" + o.capture_target + "'");
    }
  }
  o.delete_after_download = settings.Get("delete_after_download", false);
  if (const auto t = settings.Optional("timeout_s")) {
    o.operation_timeout =
        std::chrono::milliseconds(std::llround(1000 * t->Positive(t->AsDouble())));
  }
  if (const auto t = settings.Optional("event_drain_s")) {
    o.event_drain =
        std::chrono::milliseconds(std::llround(1000 * t->InRange(t->AsDouble(), 0, 60)));
  }
  return o;
}

std::vector<DetectedCamera> DetectGphoto2Cameras() {
  GPContext* context = gp_context_new();
  ListPtr list;
  const int count = gp_camera_autodetect(list.list, context);
  std::vector<DetectedCamera> out;
  for (int i = 0; i < count; ++i) {
    const char* name = nullptr;
    const char* value = nullptr;
    gp_list_get_name(list.list, i, &name);
    gp_list_get_value(list.list, i, &value);
    out.push_back({name ? name : "", value ? value : ""});
  }
  gp_context_unref(context);
  return out;
}

Gphoto2Camera::Gphoto2Camera(Gphoto2Options options) : options_(std::move(options)) { Open(); }

Gphoto2Camera::~Gphoto2Camera() { Close(); }

bool Gphoto2Camera::ShouldCancel() const { return std::chrono::steady_clock::now() > deadline_; }

std::string Gphoto2Camera::Where() const {
  return info_.model.empty() ? std::string("camera") : info_.model + " (" + info_.port + ")";
}

void Gphoto2Camera::RequireOpen(const std::string& what) const {
  if (camera_ == nullptr) {
    throw CameraError(CameraError::Kind::kGone, 0,
                      what +
                          ": the camera is not open (a re-open failed); call Reopen() when it "
                          "is back");
  }
}

CameraWidget* Gphoto2Camera::ReadConfig() {
  RequireOpen("reading the camera's settings");
  CameraWidget* root = nullptr;
  deadline_ = std::chrono::steady_clock::now() + options_.operation_timeout;
  const int result = gp_camera_get_config(camera_, &root, context_);
  deadline_ = std::chrono::steady_clock::time_point::max();
  if (result < GP_OK) {
    if (root != nullptr) gp_widget_free(root);
    return nullptr;
  }
  return root;
}

template <typename Call>
int Gphoto2Camera::Run(const std::string& what, Call call) {
  RequireOpen(what);
  auto backoff = options_.busy_backoff;
  for (int attempt = 1;; ++attempt) {
    deadline_ = std::chrono::steady_clock::now() + options_.operation_timeout;
    const int result = call();
    const bool timed_out = ShouldCancel();
    deadline_ = std::chrono::steady_clock::time_point::max();
    if (result >= GP_OK) return result;
    if (result == GP_ERROR_CAMERA_BUSY && attempt < options_.busy_attempts) {
      std::this_thread::sleep_for(backoff);
      backoff *= 2;
      continue;
    }
    if (IsNetworkPort(info_.port) && (timed_out || IsLinkFailure(result))) {
      // The PTP/IP session is out of step or gone: close it so that nothing reads a late
      // answer as the reply to a new request, and let the owner reopen (a fresh session).
      const std::string where = Where();
      Close();
      throw CameraError(CameraError::Kind::kGone, result,
                        what + " on " + where + " lost the network connection (libgphoto2 " +
                            std::to_string(result) + ": " + gp_result_as_string(result) +
                            "); check that the camera is on and reachable; Reopen() "
                            "reconnects");
    }
    if (timed_out || result == GP_ERROR_CANCEL) {
      throw CameraError(CameraError::Kind::kTimeout, result,
                        what + " on " + Where() + " took longer than " +
                            Seconds(options_.operation_timeout) +
                            " s and was cancelled: check the cable and the camera's power "
                            "saving, then re-open");
    }
    throw Gphoto2Error(result, what + " on " + Where());
  }
}

void Gphoto2Camera::Open() {
  context_ = gp_context_new();
  gp_context_set_cancel_func(context_, CancelFunc, this);

  std::string model = options_.model;
  std::string port = options_.port;
  if (IsNetworkPort(port)) {
    // Network cameras are not auto-detected: libgphoto2's generic PTP/IP driver serves them.
    if (model.empty()) model = "PTP/IP Camera";
    // libgphoto2 writes to its PTP/IP sockets with write(): a camera that closed the
    // connection would raise SIGPIPE and end the process instead of returning an error.
    signal(SIGPIPE, SIG_IGN);
  }
  if (model.empty() || (port.empty() && DiskPath(options_.port).empty())) {
    const std::vector<DetectedCamera> found = DetectGphoto2Cameras();
    const auto match = std::find_if(found.begin(), found.end(), [&](const DetectedCamera& c) {
      return (model.empty() || c.model == model) && (port.empty() || c.port == port);
    });
    if (match == found.end()) {
      std::string seen;
      for (const auto& c : found) seen += (seen.empty() ? "" : ", ") + c.model + " at " + c.port;
      Close();
      throw CameraError(
          CameraError::Kind::kNotFound, GP_ERROR_MODEL_NOT_FOUND,
          "no camera " + (model.empty() ? std::string("found") : "'" + model + "' found") +
              (port.empty() ? "" : " at " + port) +
              " (libgphoto2 sees: " + (seen.empty() ? "nothing" : seen) +
              "). Is it connected by USB, switched on and in PC/PTP mode? If it is listed by "
              "`lsusb` but not here, gvfs-gphoto2-volume-monitor / gvfsd-gphoto2 may hold it");
    }
    model = match->model;
    port = match->port;
  }

  CameraAbilitiesList* abilities_list = nullptr;
  gp_abilities_list_new(&abilities_list);
  gp_abilities_list_load(abilities_list, context_);
  const int model_index = gp_abilities_list_lookup_model(abilities_list, model.c_str());
  CameraAbilities abilities{};
  if (model_index >= 0) gp_abilities_list_get_abilities(abilities_list, model_index, &abilities);
  gp_abilities_list_free(abilities_list);
  if (model_index < 0) {
    Close();
    throw CameraError(CameraError::Kind::kNotFound, model_index,
                      "libgphoto2 has no driver for camera model '" + model +
                          "' (names as `gphoto2 --list-cameras` prints them)");
  }

  GPPortInfoList* ports = nullptr;
  gp_port_info_list_new(&ports);
  gp_port_info_list_load(ports);
  const int port_index = gp_port_info_list_lookup_path(ports, port.c_str());
  GPPortInfo port_info = nullptr;
  if (port_index >= 0) gp_port_info_list_get_info(ports, port_index, &port_info);

  gp_camera_new(&camera_);
  gp_camera_set_abilities(camera_, abilities);
  if (port_index >= 0) gp_camera_set_port_info(camera_, port_info);
  gp_port_info_list_free(ports);  // the camera keeps its own copy of the port info
  if (port_index < 0) {
    Close();
    throw CameraError(
        CameraError::Kind::kNotFound, port_index,
        "unknown camera port '" + port + "' (expected e.g. usb:001,004 or disk:/dir)");
  }
  info_.model = model;
  info_.port = port;
  // Anything failing after init (settings the body refuses, most often) must release the
  // camera: a constructor that throws runs no destructor, and the USB claim would stay.
  try {
    Run("opening the camera", [&] { return gp_camera_init(camera_, context_); });
    if (const auto serial = GetConfig({"serialnumber", "eosserialnumber"})) info_.serial = *serial;
    if (const auto firmware = GetConfig({"deviceversion", "firmwareversion"})) {
      info_.firmware = *firmware;
    }
    info_.shutter_speeds.clear();
    for (const std::string& label : Choices(kShutterSpeed)) {
      if (const auto s = ParseShutterSpeed(label)) info_.shutter_speeds.push_back(*s);
    }
    std::sort(info_.shutter_speeds.begin(), info_.shutter_speeds.end());
    ApplySettings();
  } catch (...) {
    Close();
    throw;
  }
}

void Gphoto2Camera::Close() {
  if (camera_ != nullptr) {
    // libgphoto2 2.5.30's PTP/IP disconnect also closes descriptor 0 (a Fuji-only socket
    // field it never initializes), which by then may be any file or socket of this process:
    // keep a copy and put it back.
    const int saved_fd0 = IsNetworkPort(info_.port) ? fcntl(0, F_DUPFD_CLOEXEC, 3) : -1;
    gp_camera_exit(camera_, context_);
    if (saved_fd0 >= 0) {
      dup2(saved_fd0, 0);
      close(saved_fd0);
    }
    gp_camera_unref(camera_);
    camera_ = nullptr;
  }
  if (context_ != nullptr) {
    gp_context_unref(context_);
    context_ = nullptr;
  }
}

void Gphoto2Camera::Reopen() {
  Close();
  // After a replug the USB address changes: find the same model again wherever it now is.
  if (options_.port.rfind("usb:", 0) == 0) options_.port.clear();
  if (options_.model.empty()) options_.model = info_.model;
  Open();
  if (exposure_s_ > 0) SetExposure(exposure_s_);
}

void Gphoto2Camera::ApplySettings() {
  if (!options_.image_format.empty()) SetConfig(kImageFormat, options_.image_format);
  if (!options_.iso.empty()) SetConfig(kIso, options_.iso);
  if (!options_.aperture.empty()) SetConfig(kAperture, options_.aperture);
  if (!options_.capture_target.empty()) {
    // Canon and Nikon offer "Internal RAM" and "Memory card"; match on the key word.
    const std::string wanted = options_.capture_target == "card" ? "card" : "ram";
    std::string choice;
    for (const std::string& c : Choices(kCaptureTarget)) {
      if (Lower(c).find(wanted) != std::string::npos) choice = c;
    }
    if (choice.empty()) {
      throw CameraError(CameraError::Kind::kBadSettings, 0,
                        Where() + ": capture_target '" + options_.capture_target +
                            "' is not offered by this camera (no capturetarget widget or no "
                            "matching choice); remove the setting");
    }
    SetConfig(kCaptureTarget, choice);
  }
}

std::vector<std::string> Gphoto2Camera::Choices(const std::vector<std::string>& names) {
  WidgetPtr config{ReadConfig()};
  if (config.root == nullptr) return {};
  for (const std::string& name : names) {
    CameraWidget* widget = nullptr;
    if (gp_widget_get_child_by_name(config.root, name.c_str(), &widget) < GP_OK) continue;
    std::vector<std::string> out;
    const int n = gp_widget_count_choices(widget);
    for (int i = 0; i < n; ++i) {
      const char* choice = nullptr;
      if (gp_widget_get_choice(widget, i, &choice) >= GP_OK && choice) out.emplace_back(choice);
    }
    return out;
  }
  return {};
}

std::vector<std::pair<std::string, std::string>> Gphoto2Camera::CurrentSettings() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto* names : {&kShutterSpeed, &kIso, &kAperture, &kImageFormat, &kCaptureTarget}) {
    for (const std::string& name : *names) {
      if (const auto value = GetConfig({name})) {
        out.emplace_back(name, *value);
        break;
      }
    }
  }
  return out;
}

std::optional<std::string> Gphoto2Camera::GetConfig(const std::vector<std::string>& names) {
  WidgetPtr config{ReadConfig()};
  if (config.root == nullptr) return std::nullopt;
  for (const std::string& name : names) {
    CameraWidget* widget = nullptr;
    if (gp_widget_get_child_by_name(config.root, name.c_str(), &widget) < GP_OK) continue;
    CameraWidgetType type;
    gp_widget_get_type(widget, &type);
    if (type == GP_WIDGET_TEXT || type == GP_WIDGET_RADIO || type == GP_WIDGET_MENU) {
      const char* value = nullptr;
      if (gp_widget_get_value(widget, &value) >= GP_OK && value) return std::string(value);
    }
    return std::nullopt;
  }
  return std::nullopt;
}

std::pair<std::string, std::string> Gphoto2Camera::SetConfig(const std::vector<std::string>& names,
                                                             const std::string& value) {
  WidgetPtr config;
  Run("reading the configuration",
      [&] { return gp_camera_get_config(camera_, &config.root, context_); });
  for (const std::string& name : names) {
    CameraWidget* widget = nullptr;
    if (gp_widget_get_child_by_name(config.root, name.c_str(), &widget) < GP_OK) continue;
    CameraWidgetType type;
    gp_widget_get_type(widget, &type);
    std::string used = value;
    if (type == GP_WIDGET_RADIO || type == GP_WIDGET_MENU) {
      std::string offered;
      used.clear();
      const int n = gp_widget_count_choices(widget);
      for (int i = 0; i < n; ++i) {
        const char* choice = nullptr;
        if (gp_widget_get_choice(widget, i, &choice) < GP_OK || !choice) continue;
        offered += (offered.empty() ? "" : ", ") + std::string(choice);
        // Exact match first; "f/8" and "8" name the same aperture.
        const std::string c = Lower(choice);
        const std::string v = Lower(value);
        if (c == v || c == "f/" + v || "f/" + c == v) used = choice;
      }
      if (used.empty()) {
        throw CameraError(
            CameraError::Kind::kBadSettings, GP_ERROR_BAD_PARAMETERS,
            Where() + ": " + name + " '" + value + "' is not offered (choices: " + offered + ")");
      }
    }
    int set = GP_ERROR_BAD_PARAMETERS;
    if (type == GP_WIDGET_RADIO || type == GP_WIDGET_MENU || type == GP_WIDGET_TEXT) {
      set = gp_widget_set_value(widget, used.c_str());
    } else if (type == GP_WIDGET_RANGE) {
      // A range widget takes a float (some bodies expose ISO or exposure compensation so).
      char* end = nullptr;
      const float number = std::strtof(used.c_str(), &end);
      if (end != used.c_str()) set = gp_widget_set_value(widget, &number);
    } else if (type == GP_WIDGET_TOGGLE) {
      const int on = Lower(used) == "1" || Lower(used) == "on" || Lower(used) == "true";
      set = gp_widget_set_value(widget, &on);
    }
    if (set < GP_OK) {
      throw CameraError(CameraError::Kind::kBadSettings, set,
                        Where() + ": cannot set " + name + " to '" + value + "'");
    }
    // One widget at a time: libgphoto2 2.5.30's whole-tree set_config goes on to the next
    // widget when the camera refuses a property (DeviceBusy) and can return success, which
    // would record a shot with an exposure the camera never took.
    const std::string what = "setting " + name + " to '" + used + "'";
    try {
      Run(what,
          [&] { return gp_camera_set_single_config(camera_, name.c_str(), widget, context_); });
    } catch (const CameraError& e) {
      // libgphoto2 2.5.30 reports every refused property as "bad parameters", whether the
      // camera was busy or the link stalled (the value itself is one the camera offers). On a
      // network camera the session may be out of step: close it and have the owner reopen.
      if (!IsNetworkPort(info_.port) || e.kind() != CameraError::Kind::kBadSettings) throw;
      const std::string where = Where();
      Close();
      throw CameraError(CameraError::Kind::kGone, e.code(),
                        what + " on " + where +
                            " was refused (camera busy or not answering; libgphoto2 " +
                            std::to_string(e.code()) +
                            "); Reopen() reconnects and the "
                            "setting is made again");
    }
    return {name, used};
  }
  std::string tried;
  for (const auto& n : names) tried += (tried.empty() ? "" : "/") + n;
  throw CameraError(CameraError::Kind::kUnsupported, GP_ERROR_NOT_SUPPORTED,
                    Where() + " has no " + tried +
                        " setting (some cameras only offer it in manual mode: set the mode "
                        "dial to M)");
}

double Gphoto2Camera::SetExposure(double seconds) {
  const std::vector<std::string> labels = Choices(kShutterSpeed);
  const int index = NearestShutterSpeed(labels, seconds);
  if (index < 0) {
    throw CameraError(CameraError::Kind::kUnsupported, GP_ERROR_NOT_SUPPORTED,
                      Where() +
                          " offers no shutter speeds to choose from (no shutterspeed "
                          "widget, or the mode dial is not on M)");
  }
  SetConfig(kShutterSpeed, labels[static_cast<std::size_t>(index)]);
  exposure_s_ = *ParseShutterSpeed(labels[static_cast<std::size_t>(index)]);
  return exposure_s_;
}

std::vector<CameraFileRef> Gphoto2Camera::ListFiles(const std::string& folder) {
  std::vector<CameraFileRef> out;
  ListPtr files;
  Run("listing " + folder,
      [&] { return gp_camera_folder_list_files(camera_, folder.c_str(), files.list, context_); });
  for (int i = 0; i < gp_list_count(files.list); ++i) {
    const char* name = nullptr;
    gp_list_get_name(files.list, i, &name);
    out.push_back({folder, name});
  }
  ListPtr folders;
  Run("listing " + folder, [&] {
    return gp_camera_folder_list_folders(camera_, folder.c_str(), folders.list, context_);
  });
  for (int i = 0; i < gp_list_count(folders.list); ++i) {
    const char* name = nullptr;
    gp_list_get_name(folders.list, i, &name);
    const std::string child = (folder == "/" ? "/" : folder + "/") + name;
    for (auto& f : ListFiles(child)) out.push_back(std::move(f));
  }
  return out;
}

Frame Gphoto2Camera::Download(const CameraFileRef& file) {
  const auto start = std::chrono::steady_clock::now();
  FilePtr camera_file;
  gp_file_new(&camera_file.file);
  Run("downloading " + file.folder + "/" + file.name, [&] {
    return gp_camera_file_get(camera_, file.folder.c_str(), file.name.c_str(), GP_FILE_TYPE_NORMAL,
                              camera_file.file, context_);
  });
  const char* data = nullptr;
  unsigned long size = 0;
  gp_file_get_data_and_size(camera_file.file, &data, &size);
  Frame frame;
  frame.file_name = file.name;
  frame.bytes.resize(size);
  if (size > 0) std::copy_n(reinterpret_cast<const std::byte*>(data), size, frame.bytes.begin());
  frame.exposure_s = exposure_s_;
  frame.download_duration_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

std::size_t Gphoto2Camera::DownloadToFd(const CameraFileRef& file, int fd) {
  // libgphoto2 owns the descriptor it is given and closes it in gp_file_free (checked with
  // 2.5.30): give it a duplicate so the caller's stays open.
  const off_t begin = lseek(fd, 0, SEEK_CUR);  // a dup shares the file offset
  const int copy = dup(fd);
  if (copy == -1) throw CameraError(CameraError::Kind::kIo, 0, "dup() of the output file failed");
  FilePtr camera_file;
  if (gp_file_new_from_fd(&camera_file.file, copy) < GP_OK) {
    close(copy);
    throw CameraError(CameraError::Kind::kIo, 0, "cannot stream to the output file");
  }
  Run("downloading " + file.folder + "/" + file.name, [&] {
    return gp_camera_file_get(camera_, file.folder.c_str(), file.name.c_str(), GP_FILE_TYPE_NORMAL,
                              camera_file.file, context_);
  });
  gp_file_free(camera_file.file);  // flushes and closes `copy`
  camera_file.file = nullptr;
  const off_t end = lseek(fd, 0, SEEK_CUR);
  return end > begin && begin >= 0 ? static_cast<std::size_t>(end - begin) : 0;
}

void Gphoto2Camera::Delete(const CameraFileRef& file) {
  Run("deleting " + file.folder + "/" + file.name, [&] {
    return gp_camera_file_delete(camera_, file.folder.c_str(), file.name.c_str(), context_);
  });
}

std::vector<Frame> Gphoto2Camera::Capture() {
  const auto start = std::chrono::steady_clock::now();
  CameraFilePath path{};
  try {
    Run("capture", [&] { return gp_camera_capture(camera_, GP_CAPTURE_IMAGE, &path, context_); });
  } catch (const CameraError& e) {
    if (e.code() == GP_ERROR_NO_MEMORY) {
      // libgphoto2's PTP driver reports a StoreFull event during capture this way.
      throw CameraError(CameraError::Kind::kStorageFull, e.code(),
                        Where() +
                            ": the memory card ran full during capture: free space, or "
                            "capture to the camera's RAM (capture_target: ram) with "
                            "delete_after_download");
    }
    if (e.kind() == CameraError::Kind::kUnsupported) {
      throw CameraError(e.kind(), e.code(),
                        Where() +
                            " cannot capture: its libgphoto2 driver has no remote "
                            "capture (check `gphoto2 --abilities`); use a tethering-capable "
                            "camera");
    }
    if (e.kind() == CameraError::Kind::kIo) {
      // An I/O error is how a camera that was unplugged or switched off usually shows up.
      const auto found = DetectGphoto2Cameras();
      const bool present = std::any_of(found.begin(), found.end(), [&](const DetectedCamera& c) {
        return c.model == info_.model;
      });
      if (!present && DiskPath(info_.port).empty()) {
        throw CameraError(CameraError::Kind::kGone, e.code(),
                          Where() + " went away during capture (" + e.what() +
                              "); reconnect or switch it on; Reopen() re-detects it");
      }
    }
    throw;
  }
  const double exposure_duration =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<CameraFileRef> files = {{path.folder, path.name}};
  // Drain events: RAW+JPEG announces the second file as FILE_ADDED after the capture returns,
  // and leaving events queued confuses the next capture on some bodies.
  const auto drain_end = std::chrono::steady_clock::now() + options_.event_drain;
  while (std::chrono::steady_clock::now() < drain_end) {
    CameraEventType type = GP_EVENT_UNKNOWN;
    void* data = nullptr;
    const int timeout_ms =
        static_cast<int>(std::min<long>(200, std::chrono::duration_cast<std::chrono::milliseconds>(
                                                 drain_end - std::chrono::steady_clock::now())
                                                 .count()));
    const int result =
        gp_camera_wait_for_event(camera_, std::max(1, timeout_ms), &type, &data, context_);
    if (result < GP_OK) break;  // drivers without events (or errors): nothing more to drain
    if (type == GP_EVENT_FILE_ADDED && data != nullptr) {
      const auto* added = static_cast<const CameraFilePath*>(data);
      // Some bodies announce the file gp_camera_capture already returned: keep each once.
      const bool known = std::any_of(files.begin(), files.end(), [&](const CameraFileRef& f) {
        return f.folder == added->folder && f.name == added->name;
      });
      if (!known) files.push_back({added->folder, added->name});
    }
    free(data);
    if (type == GP_EVENT_TIMEOUT) break;
  }

  double iso = 0;
  if (const auto label = GetConfig(kIso)) {
    char* end = nullptr;
    const double value = std::strtod(label->c_str(), &end);
    if (end != label->c_str()) iso = value;
  }
  // Every file is in memory before any is deleted from the card: a failed second download
  // (RAW+JPEG) must not cost the first file.
  std::vector<Frame> frames;
  for (const CameraFileRef& file : files) {
    Frame frame = Download(file);
    frame.exposure_duration_s = exposure_duration;
    frame.iso = iso;
    frames.push_back(std::move(frame));
  }
  if (options_.delete_after_download) {
    for (const CameraFileRef& file : files) Delete(file);
  }
  return frames;
}

}  // namespace brdfrig::rig
