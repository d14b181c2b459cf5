// The real Modbus client (ModbusLink + ModbusAxis + ModbusLight) against the simulated drive
// server over loopback TCP and over a pseudo-terminal (RTU), with every injectable fault
// ending in its documented outcome: retried and succeeded, or a clear AxisError after which
// the drive was stopped (or the message says it could not be).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "rig/drive_profile.h"
#include "rig/modbus_axis.h"
#include "rig/modbus_light.h"
#include "rig/modbus_link.h"
#include "sim/modbus_drive_server.h"

namespace brdfrig::rig {
namespace {

using sim::DriveFaults;
using sim::DriveServerOptions;
using sim::ModbusDriveServer;

constexpr double kRadPerDeg = M_PI / 180;

struct Case {
  DriveServerOptions::Transport transport;
  const char* profile;
};

std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.transport == DriveServerOptions::Transport::kTcp ? "Tcp" : "Rtu") +
         "_" + info.param.profile;
}

class ModbusAxisTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    profile_ = LoadDriveProfile(GetParam().profile);
    DriveServerOptions server_options;
    server_options.transport = GetParam().transport;
    server_ = std::make_unique<ModbusDriveServer>(profile_, server_options);

    ModbusLinkOptions link;
    if (GetParam().transport == DriveServerOptions::Transport::kTcp) {
      link.transport = ModbusLinkOptions::Transport::kTcp;
      link.port = server_->port();
    } else {
      link.transport = ModbusLinkOptions::Transport::kRtu;
      link.device = server_->pty_path();
    }
    // Short timeouts keep the fault tests fast; real buses want the 500 ms default.
    link.response_timeout = std::chrono::milliseconds(100);
    link.retry_backoff = std::chrono::milliseconds(5);
    link.attempts = 3;
    link_ = std::make_shared<ModbusLink>(link);

    ModbusAxisOptions options;
    options.steps_per_degree = 100;
    options.speed_deg_s = 200;
    options.acceleration_deg_s2 = 4000;
    options.min_deg = -90;
    options.max_deg = 90;
    options.move_timeout = std::chrono::milliseconds(2000);
    options.poll_interval = std::chrono::milliseconds(5);
    axis_ = std::make_unique<ModbusAxis>("light_arm", link_, profile_, options);
  }

  AxisError ExpectAxisError(double degrees) {
    try {
      axis_->MoveTo(degrees * kRadPerDeg);
    } catch (const AxisError& e) {
      return e;
    }
    ADD_FAILURE() << "move to " << degrees << " deg succeeded";
    return AxisError(AxisError::Kind::kOther, 0, "");
  }

  DriveProfile profile_;
  std::unique_ptr<ModbusDriveServer> server_;
  std::shared_ptr<ModbusLink> link_;
  std::unique_ptr<ModbusAxis> axis_;
};

TEST_P(ModbusAxisTest, MoveReachesTargetAndReadsPositionBack) {
  const MoveReport report = axis_->MoveTo(10 * kRadPerDeg);
  EXPECT_NEAR(report.position, 10 * kRadPerDeg, 0.021 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), 1000);
  EXPECT_GT(report.duration_s, 0.0);
  const AxisStatus status = axis_->Status();
  EXPECT_EQ(status.state, AxisState::kReady);
  EXPECT_NEAR(status.position, 10 * kRadPerDeg, 1e-6);
  EXPECT_GE(server_->counters().moves, 1);  // 2 if a slow answer made the client retry
}

TEST_P(ModbusAxisTest, NegativeMoveThenHomeEndsAtZero) {
  axis_->MoveTo(-5 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), -500);
  axis_->Home();
  EXPECT_EQ(server_->position_steps(), 0);
  EXPECT_EQ(server_->counters().homes, 1);
}

TEST_P(ModbusAxisTest, DroppedResponseIsRetriedAndTheMoveSucceeds) {
  DriveFaults faults;
  faults.drop_responses = 1;
  server_->InjectFaults(faults);
  axis_->MoveTo(3 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), 300);
  EXPECT_EQ(server_->counters().dropped, 1);
  EXPECT_GE(link_->stats().retries, 1);
  EXPECT_GE(link_->stats().reconnects, 1);
}

TEST_P(ModbusAxisTest, CorruptedResponseIsRetriedAndTheMoveSucceeds) {
  DriveFaults faults;
  faults.corrupt_responses = 2;
  server_->InjectFaults(faults);
  axis_->MoveTo(4 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), 400);
  EXPECT_EQ(server_->counters().corrupted, 2);
  EXPECT_GE(link_->stats().retries, 2);
}

TEST_P(ModbusAxisTest, BusyExceptionIsRetriedAndTheMoveSucceeds) {
  DriveFaults faults;
  faults.exception_responses = 1;
  faults.exception_code = 6;  // server busy: ask again later
  server_->InjectFaults(faults);
  axis_->MoveTo(2 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), 200);
  EXPECT_EQ(server_->counters().exceptions, 1);
  EXPECT_GE(link_->stats().retries, 1);
}

TEST_P(ModbusAxisTest, IllegalAddressExceptionIsAClearErrorAndTheDriveIsStopped) {
  DriveFaults faults;
  faults.exception_responses = 1;
  faults.exception_code = 2;  // illegal data address: asking again will not help
  server_->InjectFaults(faults);
  const AxisError e = ExpectAxisError(5);
  EXPECT_EQ(e.kind(), AxisError::Kind::kCommunication);
  EXPECT_NE(std::string(e.what()).find("exception 2"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("the drive was stopped"), std::string::npos) << e.what();
  // Not retried: one exception answer was enough to give up (the stop may be retried under
  // load, so only the exception count is exact).
  EXPECT_EQ(server_->counters().exceptions, 1);
  EXPECT_EQ(std::string(e.what()).find("attempts"), std::string::npos) << e.what();
  EXPECT_GE(server_->counters().stops, 1);
  EXPECT_FALSE(server_->moving());
}

TEST_P(ModbusAxisTest, SilentDriveIsAClearErrorAfterBoundedAttemptsAndNothingMoves) {
  DriveFaults faults;
  faults.drop_responses = 1000;
  server_->InjectFaults(faults);
  const auto start = std::chrono::steady_clock::now();
  const AxisError e = ExpectAxisError(5);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(e.kind(), AxisError::Kind::kCommunication);
  const std::string message = e.what();
  EXPECT_NE(message.find("after 3 attempts"), std::string::npos) << message;
  EXPECT_NE(message.find("stop command FAILED"), std::string::npos) << message;
  EXPECT_EQ(server_->counters().moves, 0);
  EXPECT_LT(seconds, 2.0);  // 3 attempts x 100 ms for the move, the same for the stop
}

TEST_P(ModbusAxisTest, AlarmDuringMoveCarriesItsCodeAndTheDriveIsStopped) {
  DriveFaults faults;
  faults.alarm_at_fraction = 0.5;
  faults.alarm_code = 0x30;
  server_->InjectFaults(faults);
  const AxisError e = ExpectAxisError(20);
  EXPECT_EQ(e.kind(), AxisError::Kind::kAlarm);
  EXPECT_EQ(e.alarm_code(), 0x30);
  EXPECT_NE(std::string(e.what()).find("0x30"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("the drive was stopped"), std::string::npos) << e.what();
  EXPECT_GE(server_->counters().stops, 1);
  EXPECT_NEAR(server_->position_steps(), 1000, 100);
  EXPECT_EQ(axis_->Status().state, AxisState::kAlarm);
  EXPECT_EQ(axis_->Status().alarm_code, 0x30);

  axis_->ResetAlarm();
  EXPECT_EQ(axis_->Status().state, AxisState::kReady);
  axis_->MoveTo(20 * kRadPerDeg);
  EXPECT_EQ(server_->position_steps(), 2000);
}

TEST_P(ModbusAxisTest, SlowMoveTimesOutAndTheDriveIsStopped) {
  DriveFaults faults;
  faults.speed_factor = 0.001;
  server_->InjectFaults(faults);
  ModbusAxisOptions options;
  options.steps_per_degree = 100;
  options.speed_deg_s = 200;
  options.move_timeout = std::chrono::milliseconds(300);
  options.poll_interval = std::chrono::milliseconds(5);
  axis_ = std::make_unique<ModbusAxis>("light_arm", link_, profile_, options);
  const AxisError e = ExpectAxisError(30);
  EXPECT_EQ(e.kind(), AxisError::Kind::kTimeout);
  EXPECT_NE(std::string(e.what()).find("still moving"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("the drive was stopped"), std::string::npos) << e.what();
  EXPECT_GE(server_->counters().stops, 1);
  EXPECT_FALSE(server_->moving());
  EXPECT_LT(std::abs(server_->position_steps()), 3000);
}

TEST_P(ModbusAxisTest, TargetOutsideLimitsIsRejectedBeforeAnyMotion) {
  const AxisError e = ExpectAxisError(120);
  EXPECT_EQ(e.kind(), AxisError::Kind::kLimits);
  EXPECT_EQ(server_->counters().requests, 0);
}

TEST_P(ModbusAxisTest, CoilSwitchedLightFollowsCommands) {
  ModbusLight light(link_, 1, 3);
  light.SetOn(true);
  EXPECT_TRUE(server_->coil(3));
  EXPECT_TRUE(light.IsOn());
  light.SetOn(false);
  EXPECT_FALSE(server_->coil(3));
}

INSTANTIATE_TEST_SUITE_P(
    Transports, ModbusAxisTest,
    ::testing::Values(Case{DriveServerOptions::Transport::kTcp, "oriental_az_direct"},
                      Case{DriveServerOptions::Transport::kPty, "oriental_az_direct"},
                      Case{DriveServerOptions::Transport::kTcp, "generic"},
                      Case{DriveServerOptions::Transport::kPty, "generic"}),
    CaseName);

TEST(ModbusLinkTest, DevicesOnOneEndpointShareOneLinkWhileAnyIsAlive) {
  ModbusLinkOptions bus;
  bus.transport = ModbusLinkOptions::Transport::kRtu;
  bus.device = "/dev/ttyUSB7";
  auto first = SharedModbusLink(bus);
  EXPECT_EQ(SharedModbusLink(bus), first);  // a second slave on the same RS-485 bus
  ModbusLinkOptions other = bus;
  other.device = "/dev/ttyUSB8";
  EXPECT_NE(SharedModbusLink(other), first);
  first.reset();
  EXPECT_EQ(SharedModbusLink(bus).use_count(), 1);  // a fresh link once the last user is gone
}

TEST(ModbusLinkTest, ConnectionRefusedIsAClearError) {
  ModbusLinkOptions options;
  options.port = 1;  // nothing listens on port 1 of loopback
  options.attempts = 2;
  options.response_timeout = std::chrono::milliseconds(50);
  ModbusLink link(options);
  try {
    link.ReadRegisters(1, 0, 2);
    FAIL() << "read from a closed port succeeded";
  } catch (const ModbusError& e) {
    EXPECT_EQ(e.kind(), ModbusError::Kind::kConnect);
    EXPECT_NE(std::string(e.what()).find("tcp://127.0.0.1:1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::rig
