// Needs the lab's real rig (label `hardware`, excluded from CI). Point it at the rig file:
//   BRDFRIG_HARDWARE_RIG=/path/rig.yaml ctest --preset release -L hardware
// It runs `rig check`, then moves every axis by +1 degree and back, and switches the light.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "rig/hardware_backends.h"
#include "rig/rig_file.h"
#include "rig/rig_tools.h"

// libgphoto2's state kept until exit: see gphoto2_camera_test.cc.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libgphoto2.so\nleak:libgphoto2_port.so\nleak:libltdl.so\n";
}
extern "C" const char* __asan_default_options() { return "fast_unwind_on_malloc=0"; }

namespace brdfrig::rig {
namespace {

TEST(RigHardwareTest, CheckPassesAndEveryAxisMovesOneDegreeAndBack) {
  const char* file = std::getenv("BRDFRIG_HARDWARE_RIG");
  ASSERT_NE(file, nullptr) << "set BRDFRIG_HARDWARE_RIG to the lab's rig.yaml";
  RegisterHardwareBackends();
  const RigCheckReport report = CheckRig(file);
  std::printf("%s\n", report.ToString().c_str());
  ASSERT_TRUE(report.ok());

  Rig rig = OpenRig(file);
  for (auto& [name, axis] : rig.axes) {
    const double start = axis->Status().position;
    const double one_degree = M_PI / 180;
    const MoveReport there = axis->MoveTo(start + one_degree);
    EXPECT_NEAR(there.position, start + one_degree, 0.05 * one_degree) << name;
    const MoveReport back = axis->MoveTo(start);
    EXPECT_NEAR(back.position, start, 0.05 * one_degree) << name;
  }
  if (rig.light) {
    rig.light->SetOn(true);
    rig.light->SetOn(false);
  }
}

}  // namespace
}  // namespace brdfrig::rig
