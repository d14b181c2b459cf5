// The simulated camera under bad clients (issue 25, finding 9): newcomers that are silent,
// drip bytes, send garbage or an init request without a GUID, a data phase longer than it
// announced, a peer that stops reading, a client that never deletes its shots. Each must cost
// only its own connection, within bounded memory and time, while a well-behaved initiator
// keeps being served. The limits are set small so that the tests are fast.
#include <gtest/gtest.h>
#include <poll.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>

#include "simcamera/ptpip_server.h"
#include "tests/simcamera/ptpip_test_client.h"

namespace brdfrig::simcamera {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
using testing::ClosedByServer;
using testing::ConnectTo;
using testing::Initiator;
using testing::Operation;

// A shot of two files of `file_bytes` each.
ShotFunction Shots(std::size_t file_bytes) {
  return [file_bytes](const ExposureSettings&) {
    return std::vector<CapturedFile>{
        {".JPG", format::kExifJpeg, std::vector<std::uint8_t>(file_bytes, 1), 1, 1, 24},
        {".DNG", format::kDng, std::vector<std::uint8_t>(file_bytes, 2), 1, 1, 16}};
  };
}

CameraServerOptions SmallLimits() {
  CameraServerOptions options;
  options.offer.shutter_speeds_s = {0.01};
  options.limits.init_timeout = 300ms;
  options.limits.packet_timeout = 300ms;
  options.limits.send_timeout = 300ms;
  return options;
}

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Waits until `done` holds, at most `limit`.
template <typename F>
bool Eventually(F done, Clock::duration limit = 2s) {
  const Clock::time_point end = Clock::now() + limit;
  while (!done()) {
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(10ms);
  }
  return true;
}

// An init command request of `payload` bytes: 4 is no GUID at all.
void SendGuidlessInit(int fd) { WritePacket(fd, PacketType::kInitCommandRequest, {0, 0, 0, 0}); }

TEST(BadClientsTest, GuidlessInitFromANewcomerCostsOnlyItsConnectionAndNoDescriptor) {
  PtpIpCameraServer server(SmallLimits(), Shots(16));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  const int before = testing::OpenDescriptors();
  for (int i = 0; i < 50; ++i) {
    const int fd = ConnectTo(server.port());
    ASSERT_GE(fd, 0);
    SendGuidlessInit(fd);
    ASSERT_TRUE(ClosedByServer(fd)) << "newcomer " << i << " was kept";
    close(fd);
  }
  // Before the fix the first such newcomer closed the served initiator.
  EXPECT_EQ(Operation(served.command, op::kGetStorageIds, 1), rc::kOk);
  EXPECT_EQ(server.counters().connections, 1);
  // ...and kept the newcomer's descriptor open for ever (one per newcomer).
  EXPECT_TRUE(Eventually([&] { return testing::OpenDescriptors() <= before; }))
      << testing::OpenDescriptors() - before << " descriptors leaked";
}

TEST(BadClientsTest, DataPhaseLongerThanAnnouncedIsRefusedAtTheFirstPacketPastIt) {
  PtpIpCameraServer server(SmallLimits(), Shots(16));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  PtpWriter request;
  request.U32(kDataPhaseToCamera).U16(op::kSetDevicePropValue).U32(1).U32(prop::kExposureIndex);
  ASSERT_TRUE(WritePacket(served.command, PacketType::kOperationRequest, request.bytes()));
  PtpWriter start;
  start.U32(1).U64(4);  // announces 4 bytes...
  ASSERT_TRUE(WritePacket(served.command, PacketType::kStartData, start.bytes()));
  std::vector<std::uint8_t> piece(4 + (64 << 10), 0);  // ...sends 64 KiB data packets
  piece[0] = 1;                                        // of transaction 1 (little-endian)
  std::size_t sent = 0;
  while (sent < (64u << 20) && WritePacket(served.command, PacketType::kData, piece)) {
    sent += piece.size();
  }
  // Before the fix the camera buffered every byte (400 MiB → 466 MB resident) until the end
  // data; now the connection ends long before 64 MiB.
  EXPECT_LT(sent, 8u << 20) << "the camera kept reading a data phase past its total";
  EXPECT_GE(server.counters().refused, 1);
  Initiator next(server.port());
  EXPECT_EQ(Operation(next.command, op::kOpenSession, 0, {1}), rc::kOk);
}

TEST(BadClientsTest, IdleNewcomerDelaysNeitherTheServedInitiatorNorANewOne) {
  CameraServerOptions options = SmallLimits();
  options.limits = ConnectionLimits{};  // the defaults: an idle newcomer may wait 5 s
  PtpIpCameraServer server(options, Shots(16));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  const int idle = ConnectTo(server.port());
  ASSERT_GE(idle, 0);
  const Clock::time_point start = Clock::now();
  for (std::uint32_t t = 1; t <= 20; ++t) {
    ASSERT_EQ(Operation(served.command, op::kGetStorageIds, t), rc::kOk);
  }
  // Before the fix the camera waited 5 s for the idle newcomer's first packet, and every
  // operation of the initiator with it (libgphoto2 gives up after 2.5 s).
  EXPECT_LT(Seconds(Clock::now() - start), 2.0);
  // The `gphoto2 --summary` case: a new initiator right after an idle connection.
  const Clock::time_point again = Clock::now();
  Initiator next(server.port());
  EXPECT_EQ(Operation(next.command, op::kOpenSession, 0, {1}), rc::kOk);
  EXPECT_LT(Seconds(Clock::now() - again), 2.0);
  close(idle);
}

TEST(BadClientsTest, DrippingNewcomerDoesNotDelayTheInitiatorAndIsClosedAtItsDeadline) {
  PtpIpCameraServer server(SmallLimits(), Shots(16));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  const int drip = ConnectTo(server.port());
  ASSERT_GE(drip, 0);
  const std::vector<std::uint8_t> init =
      EncodePacket(PacketType::kInitCommandRequest, testing::InitCommandPayload());
  std::atomic<bool> closed{false};
  std::thread dripper([&] {
    // One byte every 50 ms: the whole request would take over a second.
    for (std::uint8_t byte : init) {
      if (send(drip, &byte, 1, MSG_NOSIGNAL) != 1) break;
      pollfd p{drip, POLLIN, 0};
      if (poll(&p, 1, 50) > 0) break;  // closed by the camera
    }
    closed = ClosedByServer(drip);
  });
  double worst = 0;
  for (std::uint32_t t = 1; t <= 20; ++t) {
    const Clock::time_point start = Clock::now();
    ASSERT_EQ(Operation(served.command, op::kGetStorageIds, t), rc::kOk);
    worst = std::max(worst, Seconds(Clock::now() - start));
    std::this_thread::sleep_for(20ms);
  }
  dripper.join();
  close(drip);
  // (Before the fix the camera read the newcomer byte by byte, about 2 s, before anyone else.)
  EXPECT_LT(worst, 0.5) << "an operation waited for the dripping newcomer";
  EXPECT_TRUE(closed) << "the dripping newcomer was not closed at its init deadline";
  EXPECT_EQ(server.counters().connections, 1);
}

TEST(BadClientsTest, PeerThatStopsReadingIsClosedAfterTheSendTimeoutAndNeverBlocksTheCamera) {
  // Files larger than the loopback socket buffers of both sides together.
  PtpIpCameraServer server(SmallLimits(), Shots(16 << 20));
  Initiator stalled(server.port(), 4096);
  ASSERT_EQ(Operation(stalled.command, op::kOpenSession, 0, {1}), rc::kOk);
  ASSERT_EQ(Operation(stalled.command, op::kInitiateCapture, 1, {0, 0}), rc::kOk);
  ASSERT_TRUE(Eventually([&] { return server.files_on_card() == 2; }));
  PtpWriter request;
  request.U32(1).U16(op::kGetObject).U32(2).U32(1);
  ASSERT_TRUE(WritePacket(stalled.command, PacketType::kOperationRequest, request.bytes()));
  // It reads nothing: while the camera's send is stuck, another client is still answered...
  const int other = ConnectTo(server.port());
  ASSERT_GE(other, 0);
  ASSERT_TRUE(WritePacket(other, PacketType::kProbeRequest, {}));
  const std::optional<Packet> refused = ReadPacket(other, testing::kWait);
  ASSERT_TRUE(refused) << "the camera was blocked by a peer that stopped reading";
  EXPECT_EQ(refused->type, PacketType::kInitFail);
  close(other);
  // ...and the stalled peer is closed once the send timeout passed.
  EXPECT_TRUE(Eventually([&] { return server.counters().refused >= 1; }));
  EXPECT_TRUE(ClosedByServer(stalled.command));
  const Clock::time_point start = Clock::now();
  Initiator next(server.port());
  EXPECT_EQ(Operation(next.command, op::kOpenSession, 0, {1}), rc::kOk);
  EXPECT_LT(Seconds(Clock::now() - start), 1.0);
}

TEST(BadClientsTest, CardBytesBoundTheShotsKeptInMemory) {
  CameraServerOptions options = SmallLimits();
  options.card_bytes = 3'500'000;  // three shots of 2 × 0.5 MB fit, a fourth does not
  PtpIpCameraServer server(options, Shots(500'000));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  for (std::uint32_t t = 1; t <= 3; ++t) {
    ASSERT_EQ(Operation(served.command, op::kInitiateCapture, t, {0, 0}), rc::kOk);
    ASSERT_TRUE(Eventually([&] { return server.files_on_card() == 2 * t; }));
  }
  // Before the fix every shot stayed in memory for as long as the camera ran.
  EXPECT_EQ(Operation(served.command, op::kInitiateCapture, 4, {0, 0}), rc::kStoreFull);
  EXPECT_EQ(server.files_on_card(), 6u);
  std::vector<std::uint8_t> info;
  ASSERT_EQ(Operation(served.command, op::kGetStorageInfo, 5, {kStorageId}, nullptr, &info),
            rc::kOk);
  PtpReader r(info, 6);  // storage type, file system, access (3 × UINT16)
  EXPECT_EQ(r.U64(), 3'500'000u) << "the card reports the capacity it enforces";
  // Deleting makes room again, as on a real card.
  ASSERT_EQ(Operation(served.command, op::kDeleteObject, 6, {0xFFFFFFFFu}), rc::kOk);
  EXPECT_EQ(Operation(served.command, op::kInitiateCapture, 7, {0, 0}), rc::kOk);
}

// The "must show": dozens of idle, dripping, half-sending, garbage, GUID-less,
// event-stealing, probing and resetting clients reconnecting all the time, while one initiator
// captures, downloads and deletes. It is served throughout, never replaced, and once the bad
// clients stop the camera holds no descriptor of theirs.
TEST(BadClientsTest, ManyIdleSlowAndMisbehavingClientsWhileAnInitiatorIsServed) {
  PtpIpCameraServer server(SmallLimits(), Shots(200'000));
  Initiator served(server.port());
  ASSERT_EQ(Operation(served.command, op::kOpenSession, 0, {1}), rc::kOk);
  const int baseline = testing::OpenDescriptors();

  std::atomic<bool> stop{false};
  std::atomic<int> bad_connections{0};
  const std::vector<std::uint8_t> init =
      EncodePacket(PacketType::kInitCommandRequest, testing::InitCommandPayload());
  using Misbehave = std::function<void(int fd)>;
  const std::vector<Misbehave> kinds = {
      [](int) {},    // idle
      [&](int fd) {  // drips the init request a byte every 30 ms
        for (std::uint8_t byte : init) {
          if (stop || send(fd, &byte, 1, MSG_NOSIGNAL) != 1) return;
          pollfd p{fd, POLLIN, 0};
          if (poll(&p, 1, 30) > 0) return;
        }
      },
      [&](int fd) {  // half a packet, then silence
        send(fd, init.data(), init.size() / 2, MSG_NOSIGNAL);
      },
      [](int fd) {  // a length no camera accepts
        const std::uint8_t huge[8] = {0xF0, 0xFF, 0xFF, 0x0F, 6, 0, 0, 0};
        send(fd, huge, sizeof huge, MSG_NOSIGNAL);
      },
      [](int fd) { SendGuidlessInit(fd); },
      [](int fd) {  // tries to take the initiator's event connection
        WritePacket(fd, PacketType::kInitEventRequest, {1, 0, 0, 0});
      },
      [](int fd) {  // operations without a handshake, never reading
        PtpWriter request;
        request.U32(1).U16(op::kGetDeviceInfo).U32(1);
        for (int i = 0; i < 100; ++i) {
          WritePacket(fd, PacketType::kOperationRequest, request.bytes());
        }
      },
  };
  std::vector<std::thread> clients;
  for (int copy = 0; copy < 6; ++copy) {
    for (std::size_t kind = 0; kind < kinds.size(); ++kind) {
      clients.emplace_back([&, kind] {
        while (!stop) {
          const int fd = ConnectTo(server.port());
          if (fd < 0) continue;
          ++bad_connections;
          kinds[kind](fd);
          ClosedByServer(fd);  // until the camera closes it (at most its deadlines)
          close(fd);
          std::this_thread::sleep_for(2ms);  // (the test machine has 2 cores)
        }
      });
    }
    clients.emplace_back([&] {  // connects and resets at once
      while (!stop) {
        const int fd = ConnectTo(server.port());
        if (fd < 0) continue;
        const linger reset{1, 0};
        setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
        close(fd);
        std::this_thread::sleep_for(5ms);
      }
    });
  }

  double worst = 0;
  int shots = 0;
  std::uint32_t transaction = 1;
  const auto timed = [&](std::uint16_t code, std::vector<std::uint32_t> params,
                         std::vector<std::uint8_t>* received = nullptr) {
    const Clock::time_point start = Clock::now();
    const std::uint16_t rc =
        Operation(served.command, code, transaction++, params, nullptr, received);
    worst = std::max(worst, Seconds(Clock::now() - start));
    return rc;
  };
  const Clock::time_point end = Clock::now() + 2s;
  while (Clock::now() < end) {
    ASSERT_EQ(timed(op::kInitiateCapture, {0, 0}), rc::kOk) << "shot " << shots;
    std::vector<std::uint32_t> added;
    for (int i = 0; i < 3; ++i) {  // ObjectAdded, CaptureComplete, ObjectAdded
      const std::optional<Packet> e = ReadPacket(served.event, testing::kWait);
      ASSERT_TRUE(e && e->type == PacketType::kEvent) << "shot " << shots << " event " << i;
      PtpReader r(e->payload);
      const std::uint16_t code = r.U16();
      r.U32();  // the transaction
      if (code == event::kObjectAdded) added.push_back(r.U32());
    }
    ASSERT_EQ(added.size(), 2u);
    for (std::uint32_t handle : added) {
      std::vector<std::uint8_t> file;
      ASSERT_EQ(timed(op::kGetObject, {handle}, &file), rc::kOk);
      EXPECT_EQ(file.size(), 200'000u);
      ASSERT_EQ(timed(op::kDeleteObject, {handle}), rc::kOk);
    }
    ++shots;
  }
  stop = true;
  for (std::thread& t : clients) t.join();

  EXPECT_GE(shots, 5);
  // Well under libgphoto2's 2.5 s, also under the sanitizers on 2 cores.
  EXPECT_LT(worst, 1.0) << "an operation of the served initiator waited for bad clients";
  EXPECT_EQ(server.counters().connections, 1) << "a bad client replaced the initiator";
  EXPECT_GT(bad_connections.load(), 100);
  EXPECT_TRUE(Eventually([&] { return testing::OpenDescriptors() <= baseline; }))
      << testing::OpenDescriptors() - baseline << " descriptors still open";
  EXPECT_EQ(timed(op::kGetStorageIds, {}), rc::kOk);
}

}  // namespace
}  // namespace brdfrig::simcamera
