#include "rig/usb_watcher.h"

#include <libusb.h>

#include <algorithm>
#include <cstdio>

namespace brdfrig::rig {
namespace {

UsbDevice Describe(libusb_device* device) {
  UsbDevice out;
  out.bus = libusb_get_bus_number(device);
  out.address = libusb_get_device_address(device);
  libusb_device_descriptor descriptor{};
  if (libusb_get_device_descriptor(device, &descriptor) == 0) {
    out.vendor = descriptor.idVendor;
    out.product = descriptor.idProduct;
    out.still_image = descriptor.bDeviceClass == LIBUSB_CLASS_IMAGE;
  }
  // Cameras declare class 6 on an interface, not on the device: look at the active
  // configuration (read from cached descriptors; the device is not opened).
  libusb_config_descriptor* config = nullptr;
  if (!out.still_image && libusb_get_active_config_descriptor(device, &config) == 0) {
    for (int i = 0; i < config->bNumInterfaces; ++i) {
      const libusb_interface& interface = config->interface[i];
      for (int a = 0; a < interface.num_altsetting; ++a) {
        if (interface.altsetting[a].bInterfaceClass == LIBUSB_CLASS_IMAGE) out.still_image = true;
      }
    }
    libusb_free_config_descriptor(config);
  }
  return out;
}

int LIBUSB_CALL HotplugCallback(libusb_context*, libusb_device* device, libusb_hotplug_event event,
                                void* user_data) {
  static_cast<UsbWatcher*>(user_data)->OnHotplug(Describe(device),
                                                 event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED);
  return 0;  // keep the callback registered
}

}  // namespace

std::string UsbDevice::ToString() const {
  char text[48];
  std::snprintf(text, sizeof(text), "usb:%03d,%03d %04x:%04x", bus, address, vendor, product);
  return text;
}

std::vector<UsbEvent> DiffUsbDevices(const std::vector<UsbDevice>& before,
                                     const std::vector<UsbDevice>& after) {
  std::vector<UsbEvent> events;
  auto contains = [](const std::vector<UsbDevice>& list, const UsbDevice& d) {
    return std::find(list.begin(), list.end(), d) != list.end();
  };
  for (const UsbDevice& d : before) {
    if (!contains(after, d)) events.push_back({UsbEvent::Kind::kLeft, d});
  }
  for (const UsbDevice& d : after) {
    if (!contains(before, d)) events.push_back({UsbEvent::Kind::kArrived, d});
  }
  return events;
}

void UsbEventQueue::Push(UsbEvent event) {
  {
    std::lock_guard lock(mutex_);
    events_.push_back(std::move(event));
  }
  ready_.notify_one();
}

std::optional<UsbEvent> UsbEventQueue::Pop(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (!ready_.wait_for(lock, timeout, [&] { return !events_.empty(); })) return std::nullopt;
  UsbEvent event = std::move(events_.front());
  events_.pop_front();
  return event;
}

UsbWatcher::UsbWatcher(UsbWatcherOptions options, std::shared_ptr<UsbEventQueue> queue)
    : options_(options), queue_(std::move(queue)) {
  const int result = libusb_init(&context_);
  if (result != 0) {
    context_ = nullptr;
    error_ = std::string("libusb cannot start (") + libusb_error_name(result) +
             "): cameras arriving or leaving are not reported; is /dev/bus/usb available?";
    return;
  }
  devices_ = Enumerate();
  thread_ = std::thread([this] { Run(); });
}

UsbWatcher::~UsbWatcher() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (context_ != nullptr) libusb_exit(context_);
}

std::string UsbWatcher::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

std::vector<UsbDevice> UsbWatcher::devices() const {
  std::lock_guard lock(mutex_);
  return devices_;
}

std::vector<UsbDevice> UsbWatcher::Enumerate() {
  std::vector<UsbDevice> out;
  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(context_, &list);
  for (ssize_t i = 0; i < count; ++i) {
    const UsbDevice device = Describe(list[i]);
    if (!options_.cameras_only || device.still_image) out.push_back(device);
  }
  if (list != nullptr) libusb_free_device_list(list, 1);
  ++enumerations_;
  return out;
}

void UsbWatcher::Report(const std::vector<UsbEvent>& events) {
  for (const UsbEvent& e : events) queue_->Push(e);
}

void UsbWatcher::OnHotplug(const UsbDevice& device, bool arrived) {
  std::lock_guard lock(mutex_);
  // A device that has left can no longer be asked for its interfaces, so "left" is matched by
  // bus and address against what we reported as arrived, and that record is what we send.
  const auto it = std::find_if(devices_.begin(), devices_.end(), [&](const UsbDevice& d) {
    return d.bus == device.bus && d.address == device.address;
  });
  if (arrived) {
    if (options_.cameras_only && !device.still_image) return;
    if (it != devices_.end()) return;
    devices_.push_back(device);
    queue_->Push({UsbEvent::Kind::kArrived, device});
  } else if (it != devices_.end()) {
    const UsbDevice gone = *it;
    devices_.erase(it);
    queue_->Push({UsbEvent::Kind::kLeft, gone});
  }
}

void UsbWatcher::Run() {
  libusb_hotplug_callback_handle handle = 0;
  if (!options_.force_polling && libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) &&
      libusb_hotplug_register_callback(
          context_,
          static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                            LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
          // ENUMERATE: a camera plugged in between the first scan and this registration is
          // reported too (devices already known are ignored by OnHotplug).
          LIBUSB_HOTPLUG_ENUMERATE, LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY,
          LIBUSB_HOTPLUG_MATCH_ANY, HotplugCallback, this, &handle) == LIBUSB_SUCCESS) {
    using_hotplug_ = true;
  }
  auto next_scan = std::chrono::steady_clock::now() + options_.rescan_interval;
  while (!stop_) {
    if (using_hotplug_) {
      // Short timeout so that the destructor's stop flag is seen quickly.
      timeval tv{0, 100000};
      libusb_handle_events_timeout_completed(context_, &tv, nullptr);
      continue;
    }
    std::this_thread::sleep_for(std::min(options_.rescan_interval, std::chrono::milliseconds(100)));
    if (std::chrono::steady_clock::now() < next_scan) continue;
    next_scan = std::chrono::steady_clock::now() + options_.rescan_interval;
    std::vector<UsbDevice> now = Enumerate();
    std::lock_guard lock(mutex_);
    Report(DiffUsbDevices(devices_, now));
    devices_ = std::move(now);
  }
  if (using_hotplug_) libusb_hotplug_deregister_callback(context_, handle);
}

}  // namespace brdfrig::rig
