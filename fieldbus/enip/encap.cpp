#include "fieldbus/enip/encap.hpp"

namespace stepmod::enip {

namespace {
EncapHeader read_header(Reader& r) noexcept {
  EncapHeader h;
  h.command = r.u16();
  h.length = r.u16();
  h.session = r.u32();
  h.status = r.u32();
  const auto ctx = r.bytes(h.context.size());
  for (std::size_t i = 0; i < ctx.size(); ++i) h.context[i] = ctx[i];
  h.options = r.u32();
  return h;
}
}  // namespace

EncapParse parse_encap(std::span<const std::uint8_t> buf, EncapFrame& frame) noexcept {
  // The length is judged as soon as it is there: a peer announcing an oversized frame is not
  // waited for.
  if (buf.size() >= 4) {
    const std::size_t length = static_cast<std::size_t>(buf[2] | (buf[3] << 8));
    if (length > kEncapMaxData) return EncapParse::kTooLong;
  }
  if (buf.size() < kEncapHeaderBytes) return EncapParse::kIncomplete;
  Reader r(buf);
  frame.header = read_header(r);
  const std::size_t size = kEncapHeaderBytes + frame.header.length;
  if (buf.size() < size) return EncapParse::kIncomplete;
  frame.data = buf.subspan(kEncapHeaderBytes, frame.header.length);
  frame.size = size;
  // A request carries neither options (the spec: "the receiver shall discard the packet") nor a
  // status (only replies do).
  if (frame.header.options != 0 || frame.header.status != 0) return EncapParse::kDiscard;
  return EncapParse::kFrame;
}

bool is_known_command(std::uint16_t command) noexcept {
  switch (command) {
    case encap_cmd::kNop:
    case encap_cmd::kListServices:
    case encap_cmd::kListIdentity:
    case encap_cmd::kListInterfaces:
    case encap_cmd::kRegisterSession:
    case encap_cmd::kUnRegisterSession:
    case encap_cmd::kSendRRData:
    case encap_cmd::kSendUnitData:
      return true;
    default:
      return false;
  }
}

bool allowed_on_udp(std::uint16_t command) noexcept {
  return command == encap_cmd::kListIdentity || command == encap_cmd::kListServices ||
         command == encap_cmd::kListInterfaces;
}

void put_reply_header(Writer& w, const EncapHeader& request, std::uint16_t data_length,
                      std::uint32_t session, EncapStatus status) noexcept {
  w.u16(request.command);
  w.u16(data_length);
  w.u32(session);
  w.u32(static_cast<std::uint32_t>(status));
  w.bytes(request.context);
  w.u32(0);
}

std::size_t encode_status_reply(std::span<std::uint8_t> out, const EncapHeader& request,
                                EncapStatus status) noexcept {
  Writer w(out);
  put_reply_header(w, request, 0, request.session, status);
  return w.ok() ? w.size() : 0;
}

}  // namespace stepmod::enip
