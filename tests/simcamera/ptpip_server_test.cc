// The PTP/IP server's own handling of initiators, spoken to packet by packet: the init
// handshake, sessions, probes, and a malformed or out-of-order initiator, which must cost
// only its own connection.
#include "simcamera/ptpip_server.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_data.h"
#include "simcamera/ptpip_packet.h"

namespace brdfrig::simcamera {
namespace {

constexpr std::chrono::milliseconds kWait{3000};

class PtpIpServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    CameraServerOptions options;
    options.offer.shutter_speeds_s = {0.01};
    server_ = std::make_unique<PtpIpCameraServer>(options, [](const ExposureSettings&) {
      return std::vector<CapturedFile>{{".JPG", format::kExifJpeg, {1, 2, 3}, 1, 1, 24}};
    });
  }
  void TearDown() override {
    for (int fd : fds_) close(fd);
  }

  int Connect() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    const timeval limit{5, 0};  // a server that never answers fails the test, not hangs it
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(server_->port()));
    inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
    EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    fds_.push_back(fd);
    return fd;
  }

  // The initiator's side of the handshake; returns {command, event} sockets.
  std::pair<int, int> Handshake() {
    const int command = Connect();
    PtpWriter init;
    init.Bytes(std::vector<std::uint8_t>(16, 7)).Ucs2z("test").U32(0x00010000);
    EXPECT_TRUE(WritePacket(command, PacketType::kInitCommandRequest, init.bytes()));
    const std::optional<Packet> ack = ReadPacket(command, kWait);
    EXPECT_TRUE(ack && ack->type == PacketType::kInitCommandAck);
    if (!ack || ack->payload.size() < 4) return {command, -1};
    // The event connection names the connection number of the command connection's ack.
    const std::vector<std::uint8_t> number(ack->payload.begin(), ack->payload.begin() + 4);
    const int event = Connect();
    EXPECT_TRUE(WritePacket(event, PacketType::kInitEventRequest, number));
    const std::optional<Packet> event_ack = ReadPacket(event, kWait);
    EXPECT_TRUE(event_ack && event_ack->type == PacketType::kInitEventAck);
    return {command, event};
  }

  // Sends an operation without data and returns the response code.
  std::uint16_t Operation(int command, std::uint16_t code, std::uint32_t transaction,
                          std::vector<std::uint32_t> params = {}) {
    PtpWriter request;
    request.U32(1).U16(code).U32(transaction);
    for (std::uint32_t p : params) request.U32(p);
    EXPECT_TRUE(WritePacket(command, PacketType::kOperationRequest, request.bytes()));
    for (;;) {
      const std::optional<Packet> packet = ReadPacket(command, kWait);
      if (!packet) return 0;
      if (packet->type == PacketType::kOperationResponse) {
        PtpReader r(packet->payload);
        const std::uint16_t rc = r.U16();
        EXPECT_EQ(r.U32(), transaction);
        return rc;
      }
    }
  }

  std::unique_ptr<PtpIpCameraServer> server_;
  std::vector<int> fds_;
};

TEST_F(PtpIpServerTest, AckCarriesTheCameraGuidAndNameAndOperationsNeedASession) {
  const int command = Connect();
  PtpWriter init;
  init.Bytes(std::vector<std::uint8_t>(16, 7)).Ucs2z("test").U32(0x00010000);
  ASSERT_TRUE(WritePacket(command, PacketType::kInitCommandRequest, init.bytes()));
  const std::optional<Packet> ack = ReadPacket(command, kWait);
  ASSERT_TRUE(ack);
  ASSERT_EQ(ack->type, PacketType::kInitCommandAck);
  ASSERT_GE(ack->payload.size(), 4u + 16 + 2 + 4);
  // connection number, 16-byte GUID, then the name in UCS-2 ("b", "r", ...).
  EXPECT_EQ(ack->payload[20], 'b');
  EXPECT_EQ(ack->payload[22], 'r');

  EXPECT_EQ(Operation(command, op::kGetStorageIds, 1), rc::kSessionNotOpen);
  EXPECT_EQ(Operation(command, op::kOpenSession, 0, {1}), rc::kOk);
  EXPECT_EQ(Operation(command, op::kOpenSession, 1, {1}), rc::kSessionAlreadyOpen);
  EXPECT_EQ(Operation(command, 0x9999, 2), rc::kOperationNotSupported);
  EXPECT_EQ(Operation(command, op::kGetObjectInfo, 3, {42}), rc::kInvalidObjectHandle);
}

TEST_F(PtpIpServerTest, ProbeOnTheEventChannelIsAnswered) {
  const auto [command, event] = Handshake();
  ASSERT_TRUE(WritePacket(event, PacketType::kProbeRequest, {}));
  const std::optional<Packet> probe = ReadPacket(event, kWait);
  ASSERT_TRUE(probe);
  EXPECT_EQ(probe->type, PacketType::kProbeResponse);
}

TEST_F(PtpIpServerTest, CaptureIsAnsweredThenAnnouncedOnTheEventChannel) {
  const auto [command, event] = Handshake();
  ASSERT_EQ(Operation(command, op::kOpenSession, 0, {1}), rc::kOk);
  ASSERT_EQ(Operation(command, op::kInitiateCapture, 5, {0, 0}), rc::kOk);
  std::vector<std::uint16_t> codes;
  for (int i = 0; i < 2; ++i) {
    const std::optional<Packet> e = ReadPacket(event, kWait);
    ASSERT_TRUE(e && e->type == PacketType::kEvent);
    PtpReader r(e->payload);
    codes.push_back(r.U16());
    EXPECT_EQ(r.U32(), 5u);  // the capture's transaction
  }
  EXPECT_EQ(codes, (std::vector<std::uint16_t>{event::kObjectAdded, event::kCaptureComplete}));
  EXPECT_EQ(server_->files_on_card(), 1u);
}

TEST_F(PtpIpServerTest, EventChannelBeforeACommandChannelIsRefused) {
  const int event = Connect();
  ASSERT_TRUE(WritePacket(event, PacketType::kInitEventRequest, {1, 0, 0, 0}));
  const std::optional<Packet> reply = ReadPacket(event, kWait);
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->type, PacketType::kInitFail);
}

TEST_F(PtpIpServerTest, MalformedPacketCostsOnlyItsConnection) {
  const std::uint8_t huge_length[8] = {0xF0, 0xFF, 0xFF, 0x0F, 6, 0, 0, 0};
  char byte;
  // A newcomer that sends garbage is refused; the initiator already served goes on.
  const auto served = Handshake();
  ASSERT_EQ(Operation(served.first, op::kOpenSession, 0, {1}), rc::kOk);
  const int newcomer = Connect();
  ASSERT_EQ(send(newcomer, huge_length, sizeof huge_length, MSG_NOSIGNAL), 8);
  EXPECT_LE(recv(newcomer, &byte, 1, 0), 0) << "the server kept a desynchronized connection";
  EXPECT_EQ(Operation(served.first, op::kGetStorageIds, 1), rc::kOk);
  // Garbage on the served command connection ends that connection; a new initiator is served.
  ASSERT_EQ(send(served.first, huge_length, sizeof huge_length, MSG_NOSIGNAL), 8);
  EXPECT_LE(recv(served.first, &byte, 1, 0), 0);
  const auto next = Handshake();
  EXPECT_EQ(Operation(next.first, op::kOpenSession, 0, {1}), rc::kOk);
}

TEST_F(PtpIpServerTest, EventRequestNamingAnotherConnectionIsRefused) {
  const auto [command, event] = Handshake();
  const int thief = Connect();
  ASSERT_TRUE(WritePacket(thief, PacketType::kInitEventRequest, {99, 0, 0, 0}));
  const std::optional<Packet> reply = ReadPacket(thief, kWait);
  ASSERT_TRUE(reply);
  EXPECT_EQ(reply->type, PacketType::kInitFail);
  ASSERT_TRUE(WritePacket(event, PacketType::kProbeRequest, {}));
  const std::optional<Packet> probe = ReadPacket(event, kWait);
  ASSERT_TRUE(probe) << "the initiator lost its event connection";
  EXPECT_EQ(probe->type, PacketType::kProbeResponse);
}

TEST_F(PtpIpServerTest, ANewInitiatorReplacesTheOldOneAndStartsWithoutASession) {
  const auto first = Handshake();
  ASSERT_EQ(Operation(first.first, op::kOpenSession, 0, {1}), rc::kOk);
  const auto second = Handshake();
  EXPECT_EQ(Operation(second.first, op::kGetStorageIds, 1), rc::kSessionNotOpen);
  char byte;
  EXPECT_LE(recv(first.first, &byte, 1, 0), 0) << "the old command connection stayed open";
  EXPECT_EQ(server_->counters().connections, 2);
}

}  // namespace
}  // namespace brdfrig::simcamera
