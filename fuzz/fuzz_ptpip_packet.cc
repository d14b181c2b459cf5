// The simulated PTP/IP camera's packet and operation parser: the bytes a client sends on a
// command connection, fed to the packet assembler in the pieces the server reads
// (simcamera/packet_stream.h), then handled as the server's command connection handles them:
// the init command request, operation requests, probes, data phases to the camera, and every
// operation answered by the camera's responder (sessions, settings, the card, captures with a
// small shot) with its reply encoded as the server would send it. A malformed stream is a
// brdfrig::Error (the server closes that connection); anything else is a finding, and so is a
// packet or a data phase beyond the camera's limit.
#include <algorithm>
#include <cstdlib>
#include <optional>

#include "common/error.h"
#include "simcamera/packet_stream.h"
#include "simcamera/ptp_codes.h"
#include "simcamera/ptp_responder.h"

namespace {

using namespace brdfrig::simcamera;

std::vector<CapturedFile> Shot(const ExposureSettings&) {
  return {{".JPG", format::kExifJpeg, {0xFF, 0xD8, 0xFF, 0xD9}, 1, 1, 24},
          {".DNG", format::kDng, {'I', 'I', 42, 0}, 1, 1, 16}};
}

void Answer(PtpResponder& responder, const OperationRequest& request,
            const std::vector<std::uint8_t>& data) {
  PtpReply reply = responder.Handle(request, data);
  if (reply.data) EncodeDataPhase(request.transaction, *reply.data);
  EncodePacket(PacketType::kOperationResponse,
               ResponsePayload(reply.code, request.transaction, reply.params));
  if (reply.after) {
    for (const PtpEvent& e : reply.after()) {
      EncodePacket(PacketType::kEvent, EventPayload(e.code, request.transaction, e.params));
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  CameraOffer offer;
  offer.shutter_speeds_s = {1.0 / 100, 1.0 / 10};
  PtpResponder responder(offer, Shot);
  responder.store().set_capacity_bytes(64);  // a few shots: the card-full path is reached
  PacketAssembler in;
  std::optional<OperationRequest> request;
  std::optional<IncomingDataPhase> phase;
  std::size_t at = 0;
  try {
    while (at < size) {
      const std::size_t n = std::min(in.wanted(), size - at);
      in.Append(data + at, n);
      at += n;
      const std::optional<Packet> packet = in.Take();
      if (!packet) continue;
      if (packet->payload.size() + kPacketHeaderBytes > kMaxIncomingPacket) std::abort();
      if (phase) {
        if (!phase->Add(*packet)) continue;
        const std::vector<std::uint8_t> bytes = phase->Take();
        if (bytes.size() > kMaxIncomingPacket) std::abort();
        Answer(responder, *request, bytes);
        phase.reset();
        continue;
      }
      switch (packet->type) {
        case PacketType::kInitCommandRequest:
          ParseInitCommandRequest(*packet);
          responder.ResetSession();
          break;
        case PacketType::kProbeRequest:
          break;
        case PacketType::kOperationRequest:
          request = ParseOperationRequest(*packet);
          if (request->data_phase == kDataPhaseToCamera) {
            phase.emplace(request->transaction);
          } else {
            Answer(responder, *request, {});
          }
          break;
        default:
          throw brdfrig::Error("unexpected packet type on the command connection");
      }
    }
  } catch (const brdfrig::Error&) {
    // The documented rejection: the server closes this connection.
  }
  return 0;
}
