// The USB watcher: the difference of two enumerations is reported as left/arrived messages,
// the polling fallback really enumerates through libusb, and start/stop never hangs. No test
// depends on a device being plugged in or on hotplug events existing (CI has neither).
#include "rig/usb_watcher.h"

#include <gtest/gtest.h>

#include <thread>

namespace brdfrig::rig {
namespace {

UsbDevice Device(int address, uint16_t product) {
  UsbDevice d;
  d.bus = 1;
  d.address = address;
  d.vendor = 0x04a9;
  d.product = product;
  d.still_image = true;
  return d;
}

TEST(UsbWatcherTest, DiffReportsLeftThenArrivedAndAReplugAsBoth) {
  const UsbDevice camera = Device(4, 0x3294);
  UsbDevice replugged = camera;
  replugged.address = 7;  // a replugged camera gets a new address
  const auto events = DiffUsbDevices({camera, Device(5, 0x1)}, {Device(5, 0x1), replugged});
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, UsbEvent::Kind::kLeft);
  EXPECT_EQ(events[0].device, camera);
  EXPECT_EQ(events[1].kind, UsbEvent::Kind::kArrived);
  EXPECT_EQ(events[1].device.ToString(), "usb:001,007 04a9:3294");
  EXPECT_TRUE(DiffUsbDevices({camera}, {camera}).empty());
}

TEST(UsbWatcherTest, QueueDeliversInOrderAndTimesOutWhenEmpty) {
  UsbEventQueue queue;
  EXPECT_FALSE(queue.Pop(std::chrono::milliseconds(1)).has_value());
  std::thread producer([&] {
    queue.Push({UsbEvent::Kind::kLeft, Device(4, 1)});
    queue.Push({UsbEvent::Kind::kArrived, Device(8, 1)});
  });
  const auto first = queue.Pop(std::chrono::seconds(5));
  const auto second = queue.Pop(std::chrono::seconds(5));
  producer.join();
  ASSERT_TRUE(first && second);
  EXPECT_EQ(first->kind, UsbEvent::Kind::kLeft);
  EXPECT_EQ(second->device.address, 8);
}

TEST(UsbWatcherTest, PollingFallbackEnumeratesRepeatedlyAndStopsPromptly) {
  auto queue = std::make_shared<UsbEventQueue>();
  UsbWatcherOptions options;
  options.force_polling = true;
  options.rescan_interval = std::chrono::milliseconds(10);
  const auto start = std::chrono::steady_clock::now();
  {
    UsbWatcher watcher(options, queue);
    if (!watcher.error().empty()) GTEST_SKIP() << watcher.error();
    EXPECT_FALSE(watcher.using_hotplug());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (watcher.enumerations() < 4 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    EXPECT_GE(watcher.enumerations(), 4);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
}

TEST(UsbWatcherTest, HotplugModeWhereAvailableStartsAndStopsPromptly) {
  auto queue = std::make_shared<UsbEventQueue>();
  const auto start = std::chrono::steady_clock::now();
  {
    UsbWatcher watcher({}, queue);
    if (!watcher.error().empty()) GTEST_SKIP() << watcher.error();
    EXPECT_GE(watcher.enumerations(), 1);  // the baseline
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
}

}  // namespace
}  // namespace brdfrig::rig
