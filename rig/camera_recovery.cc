#include "rig/camera_recovery.h"

#include <thread>

namespace brdfrig::rig {

CameraRecoveryReport RecoverCamera(Camera& camera, UsbEventQueue* events,
                                   const CameraRecoveryOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto deadline = start + options.timeout;
  CameraRecoveryReport report;
  while (true) {
    ++report.attempts;
    try {
      camera.Reopen();
      report.waited_s = std::chrono::duration<double>(Clock::now() - start).count();
      return report;
    } catch (const CameraError& e) {
      const bool worth_waiting = e.recoverable() || e.kind() == CameraError::Kind::kNotFound;
      if (!worth_waiting || Clock::now() >= deadline) throw;
    }
    // Wait for a camera to arrive (or the retry interval, or the deadline), whichever is first.
    const auto wake = std::min(deadline, Clock::now() + options.retry_interval);
    while (Clock::now() < wake) {
      if (events == nullptr) {
        std::this_thread::sleep_until(wake);
        break;
      }
      // Rounded up: a truncated wait of 0 ms would spin through the last millisecond.
      const auto event =
          events->Pop(std::chrono::ceil<std::chrono::milliseconds>(wake - Clock::now()));
      if (!event) break;
      ++report.usb_events;
      if (event->kind == UsbEvent::Kind::kArrived) break;  // try now
    }
  }
}

}  // namespace brdfrig::rig
