// Reports USB devices (cameras by default) arriving and leaving, as messages in a queue that
// the camera's owner thread reads between operations: on "arrived" after a kGone error it
// re-autodetects (Camera::Reopen). libusb hotplug callbacks are used where the platform has
// them; elsewhere (containers without udev, some kernels) the watcher re-enumerates every
// `rescan_interval` and reports the difference. Callbacks never touch the camera: libgphoto2
// is not thread-safe, so the camera thread stays the only one that does.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

struct libusb_context;

namespace brdfrig::rig {

struct UsbDevice {
  int bus = 0;
  int address = 0;
  uint16_t vendor = 0;
  uint16_t product = 0;
  bool still_image = false;  // has an interface of class 6 (PTP/still image): a camera
  bool operator==(const UsbDevice&) const = default;
  std::string ToString() const;  // "usb:001,004 04a9:3294"; the port matches libgphoto2's
};

struct UsbEvent {
  enum class Kind { kArrived, kLeft };
  Kind kind = Kind::kArrived;
  UsbDevice device;
};

// Events that turn enumeration `before` into `after` (left first, then arrived, each in order).
std::vector<UsbEvent> DiffUsbDevices(const std::vector<UsbDevice>& before,
                                     const std::vector<UsbDevice>& after);

// A thread-safe message queue from the watcher to its consumer.
class UsbEventQueue {
 public:
  void Push(UsbEvent event);
  // Waits up to `timeout` for the next event.
  std::optional<UsbEvent> Pop(std::chrono::milliseconds timeout);

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<UsbEvent> events_;
};

struct UsbWatcherOptions {
  std::chrono::milliseconds rescan_interval{2000};  // polling fallback period
  bool force_polling = false;  // ignore hotplug support (tests, misbehaving platforms)
  bool cameras_only = true;    // report only devices with a still-image interface
};

class UsbWatcher {
 public:
  // Starts watching at once; the devices present at start are the baseline (not reported).
  UsbWatcher(UsbWatcherOptions options, std::shared_ptr<UsbEventQueue> queue);
  ~UsbWatcher();
  UsbWatcher(const UsbWatcher&) = delete;
  UsbWatcher& operator=(const UsbWatcher&) = delete;

  bool using_hotplug() const { return using_hotplug_; }
  int enumerations() const { return enumerations_; }  // full scans done so far
  // Empty while libusb works; otherwise why the watcher could not watch (it then does nothing).
  std::string error() const;
  std::vector<UsbDevice> devices() const;  // current known set

  // Called from libusb's hotplug callback (libusb's event thread = our thread).
  void OnHotplug(const UsbDevice& device, bool arrived);

 private:
  void Run();
  std::vector<UsbDevice> Enumerate();
  void Report(const std::vector<UsbEvent>& events);

  UsbWatcherOptions options_;
  std::shared_ptr<UsbEventQueue> queue_;
  libusb_context* context_ = nullptr;
  std::atomic<bool> using_hotplug_{false};
  std::atomic<int> enumerations_{0};
  mutable std::mutex mutex_;
  std::vector<UsbDevice> devices_;
  std::string error_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace brdfrig::rig
