#include "fieldbus/enip/encap_replies.hpp"

#include "fieldbus/enip/cpf.hpp"

namespace stepmod::enip {

std::uint32_t SessionTable::handle_of(std::uint32_t connection) const noexcept {
  for (const Slot& s : slots_) {
    if (s.handle != 0 && s.connection == connection) return s.handle;
  }
  return 0;
}

bool SessionTable::valid(std::uint32_t handle, std::uint32_t connection) const noexcept {
  return handle != 0 && handle_of(connection) == handle;
}

std::uint32_t SessionTable::add(std::uint32_t connection) noexcept {
  for (Slot& s : slots_) {
    if (s.handle != 0) continue;
    s.handle = next_handle_;
    s.connection = connection;
    // Handles are not reused soon: a late request of a closed session finds no session.
    next_handle_ = next_handle_ == 0xFFFFFFFFu ? 1 : next_handle_ + 1;
    return s.handle;
  }
  return 0;
}

void SessionTable::remove(std::uint32_t connection) noexcept {
  for (Slot& s : slots_) {
    if (s.connection == connection) s = Slot{};
  }
}

std::size_t SessionTable::size() const noexcept {
  std::size_t n = 0;
  for (const Slot& s : slots_) n += s.handle != 0 ? 1 : 0;
  return n;
}

std::size_t encode_list_identity_reply(std::span<std::uint8_t> out, const EncapHeader& request,
                                       const IdentityValues& id, SocketAddress address) noexcept {
  Writer w(out);
  put_reply_header(w, request, 0, 0, EncapStatus::kSuccess);  // length patched below
  w.u16(1);                                                   // one item
  CpfItemWriter item(w, cpf_item::kListIdentity);
  w.u16(kEncapProtocolVersion);
  w.be16(2);  // sin_family AF_INET: the socket address is big-endian on the wire
  w.be16(address.port);
  w.be32(address.ip);
  w.zeros(8);
  put_identity_item_tail(w, id);
  item.end();
  w.patch_u16(2, static_cast<std::uint16_t>(w.size() - kEncapHeaderBytes));
  return w.ok() ? w.size() : 0;
}

namespace {
std::size_t register_reply(std::span<std::uint8_t> out, const EncapHeader& request,
                           std::uint32_t session, EncapStatus status) noexcept {
  Writer w(out);
  put_reply_header(w, request, 4, session, status);
  w.u16(kEncapProtocolVersion);  // the version we support, also in a refusal
  w.u16(0);
  return w.ok() ? w.size() : 0;
}
}  // namespace

RegisterResult handle_register_session(std::span<std::uint8_t> out, const EncapFrame& request,
                                       SessionTable& sessions, std::uint32_t connection) noexcept {
  const EncapHeader& h = request.header;
  if (request.data.size() != 4) {
    return {encode_status_reply(out, h, EncapStatus::kInvalidLength), 0};
  }
  Reader r(request.data);
  const std::uint16_t version = r.u16();
  const std::uint16_t options = r.u16();
  if (version != kEncapProtocolVersion || options != 0) {
    return {register_reply(out, h, 0, EncapStatus::kUnsupportedProtocol), 0};
  }
  if (const std::uint32_t existing = sessions.handle_of(connection); existing != 0) {
    return {register_reply(out, h, existing, EncapStatus::kInvalidCommand), 0};
  }
  const std::uint32_t session = sessions.add(connection);
  if (session == 0) return {register_reply(out, h, 0, EncapStatus::kInsufficientMemory), 0};
  return {register_reply(out, h, session, EncapStatus::kSuccess), session};
}

UnregisterResult handle_unregister_session(std::span<std::uint8_t> out, const EncapFrame& request,
                                           SessionTable& sessions,
                                           std::uint32_t connection) noexcept {
  if (sessions.valid(request.header.session, connection)) {
    sessions.remove(connection);
    return {true, 0};
  }
  return {false, encode_status_reply(out, request.header, EncapStatus::kInvalidSession)};
}

}  // namespace stepmod::enip
