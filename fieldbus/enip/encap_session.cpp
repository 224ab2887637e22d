#include "fieldbus/enip/encap_session.hpp"

#include "fieldbus/enip/cpf.hpp"

namespace stepmod::enip {

namespace {
// ListServices' one service: "Communications", CIP encapsulation over TCP (bit 5) and class
// 0/1 I/O over UDP (bit 8).
constexpr std::uint16_t kServiceFlags = (1u << 5) | (1u << 8);
constexpr char kServiceName[16] = "Communications";

std::size_t finish(Writer& w) noexcept {
  w.patch_u16(2, static_cast<std::uint16_t>(w.size() - kEncapHeaderBytes));
  return w.ok() ? w.size() : 0;
}

std::size_t list_services(const EncapHeader& h, std::span<std::uint8_t> out) noexcept {
  Writer w(out);
  put_reply_header(w, h, 0, 0, EncapStatus::kSuccess);
  w.u16(1);
  CpfItemWriter item(w, cpf_item::kListServices);
  w.u16(kEncapProtocolVersion);
  w.u16(kServiceFlags);
  for (const char c : kServiceName) w.u8(static_cast<std::uint8_t>(c));
  item.end();
  return finish(w);
}

std::size_t list_interfaces(const EncapHeader& h, std::span<std::uint8_t> out) noexcept {
  Writer w(out);
  put_reply_header(w, h, 2, 0, EncapStatus::kSuccess);
  w.u16(0);  // no interfaces beyond the one this is
  return w.ok() ? w.size() : 0;
}

// SendRRData: a null address item and an unconnected data item holding a message router
// request; the reply is the same two items around the router's reply.
std::size_t send_rr_data(const EncapFrame& f, EncapContext& ctx,
                         std::span<std::uint8_t> out) noexcept {
  SendData sd;
  const bool ok = parse_send_data(f.data, sd) == CpfParse::kOk && sd.interface_handle == 0 &&
                  sd.cpf.count == 2 && sd.cpf.items[0].type == cpf_item::kNullAddress &&
                  sd.cpf.items[0].data.empty() &&
                  sd.cpf.items[1].type == cpf_item::kUnconnectedData;
  if (!ok) return encode_status_reply(out, f.header, EncapStatus::kIncorrectData);
  Writer w(out);
  put_reply_header(w, f.header, 0, f.header.session, EncapStatus::kSuccess);
  w.u32(0);  // interface handle: CIP
  w.u16(0);  // timeout: unused in a reply
  w.u16(2);
  put_item(w, cpf_item::kNullAddress, {});
  CpfItemWriter data(w, cpf_item::kUnconnectedData);
  route_message(sd.cpf.items[1].data, ctx.router, w);
  data.end();
  return finish(w);
}

SessionStep reply(std::size_t consumed, std::size_t size) noexcept {
  return {consumed, size > 0 ? SessionAction::kReply : SessionAction::kNone, size};
}
}  // namespace

namespace {
// A whole, well-formed TCP frame.
SessionStep tcp_frame(const EncapFrame& f, std::uint32_t connection, EncapContext& ctx,
                      std::span<std::uint8_t> out) noexcept {
  const EncapHeader& h = f.header;
  switch (h.command) {
    case encap_cmd::kNop:
      return {f.size, SessionAction::kNone, 0};
    case encap_cmd::kListIdentity:
      return reply(f.size, encode_list_identity_reply(out, h, ctx.identity, ctx.address));
    case encap_cmd::kListServices:
      return reply(f.size, list_services(h, out));
    case encap_cmd::kListInterfaces:
      return reply(f.size, list_interfaces(h, out));
    case encap_cmd::kRegisterSession:
      return reply(f.size, handle_register_session(out, f, ctx.sessions, connection).reply_size);
    case encap_cmd::kUnRegisterSession: {
      const UnregisterResult u = handle_unregister_session(out, f, ctx.sessions, connection);
      if (u.close) return {f.size, SessionAction::kClose, 0};
      return reply(f.size, u.reply_size);
    }
    default:
      break;
  }
  const bool session_command =
      h.command == encap_cmd::kSendRRData || h.command == encap_cmd::kSendUnitData;
  if (!session_command) {
    return reply(f.size, encode_status_reply(out, h, EncapStatus::kInvalidCommand));
  }
  if (!ctx.sessions.valid(h.session, connection)) {
    return reply(f.size, encode_status_reply(out, h, EncapStatus::kInvalidSession));
  }
  // SendUnitData carries class 3 connected messages: no such connection is ever open here, so
  // there is no one to answer.
  if (h.command == encap_cmd::kSendUnitData) return {f.size, SessionAction::kNone, 0};
  return reply(f.size, send_rr_data(f, ctx, out));
}
}  // namespace

SessionStep handle_tcp(std::span<const std::uint8_t> in, std::uint32_t connection,
                       EncapContext& ctx, std::span<std::uint8_t> out) noexcept {
  EncapFrame f;
  switch (parse_encap(in, f)) {
    case EncapParse::kIncomplete:
      return {};
    case EncapParse::kTooLong:
      return {0, SessionAction::kClose, 0};
    case EncapParse::kDiscard:
      return {f.size, SessionAction::kNone, 0};
    case EncapParse::kFrame:
      break;
  }
  return tcp_frame(f, connection, ctx, out);
}

std::size_t handle_udp(std::span<const std::uint8_t> datagram, EncapContext& ctx,
                       std::span<std::uint8_t> out) noexcept {
  EncapFrame f;
  // One datagram is one frame: a short, long or trailing one is dropped, never answered.
  if (parse_encap(datagram, f) != EncapParse::kFrame || f.size != datagram.size()) return 0;
  switch (f.header.command) {
    case encap_cmd::kListIdentity:
      return encode_list_identity_reply(out, f.header, ctx.identity, ctx.address);
    case encap_cmd::kListServices:
      return list_services(f.header, out);
    case encap_cmd::kListInterfaces:
      return list_interfaces(f.header, out);
    default:
      return 0;  // the others are TCP only; an unknown command over UDP is not answered
  }
}

}  // namespace stepmod::enip
