// Camera recovery: re-open at once, on a USB "arrived" message, or at the retry interval,
// until a deadline; problems a person must fix are not waited for. The camera here is a
// stand-in whose Reopen() fails a given number of times: a real camera cannot be unplugged in
// CI (the hardware test covers that).
#include "rig/camera_recovery.h"

#include <gtest/gtest.h>

#include <thread>

namespace brdfrig::rig {
namespace {

class FlakyCamera : public Camera {
 public:
  FlakyCamera(int failures, CameraError::Kind kind) : failures_(failures), kind_(kind) {}
  CameraInfo Info() const override { return {}; }
  double SetExposure(double seconds) override { return seconds; }
  std::vector<Frame> Capture() override { return {}; }
  void Reopen() override {
    ++reopens;
    if (failures_-- > 0) throw CameraError(kind_, -52, "not there");
  }
  int reopens = 0;

 private:
  int failures_;
  CameraError::Kind kind_;
};

using std::chrono::milliseconds;

TEST(CameraRecoveryTest, ReopensAtOnceWhenTheCameraIsBack) {
  FlakyCamera camera(0, CameraError::Kind::kGone);
  const CameraRecoveryReport report = RecoverCamera(camera, nullptr);
  EXPECT_EQ(report.attempts, 1);
}

TEST(CameraRecoveryTest, AnArrivedMessageTriggersTheNextAttemptBeforeTheInterval) {
  FlakyCamera camera(1, CameraError::Kind::kGone);
  UsbEventQueue events;
  CameraRecoveryOptions options;
  options.retry_interval = milliseconds(30000);  // only the message can wake it in time
  options.timeout = milliseconds(60000);
  std::thread plug([&] {
    std::this_thread::sleep_for(milliseconds(20));
    events.Push({UsbEvent::Kind::kLeft, {}});
    events.Push({UsbEvent::Kind::kArrived, {}});
  });
  const auto start = std::chrono::steady_clock::now();
  const CameraRecoveryReport report = RecoverCamera(camera, &events, options);
  plug.join();
  EXPECT_EQ(report.attempts, 2);
  EXPECT_EQ(report.usb_events, 2);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(CameraRecoveryTest, WithoutEventsItRetriesAtTheIntervalUntilTheDeadline) {
  FlakyCamera camera(1000, CameraError::Kind::kNotFound);
  CameraRecoveryOptions options;
  options.retry_interval = milliseconds(10);
  options.timeout = milliseconds(100);
  EXPECT_THROW(RecoverCamera(camera, nullptr, options), CameraError);
  EXPECT_GE(camera.reopens, 5);
  EXPECT_LE(camera.reopens, 12);
}

TEST(CameraRecoveryTest, AClaimedCameraIsNotWaitedFor) {
  FlakyCamera camera(1, CameraError::Kind::kClaimed);
  try {
    RecoverCamera(camera, nullptr);
    FAIL();
  } catch (const CameraError& e) {
    EXPECT_EQ(e.kind(), CameraError::Kind::kClaimed);
  }
  EXPECT_EQ(camera.reopens, 1);
}

}  // namespace
}  // namespace brdfrig::rig
