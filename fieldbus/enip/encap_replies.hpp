#pragma once
// The encapsulation commands answered without CIP: ListIdentity, RegisterSession and
// UnRegisterSession (docs/ethernetip-design.md, "Encapsulation"), and the session table they
// keep. Replies are written into a caller's buffer; a size of 0 means "send nothing".
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/encap.hpp"
#include "fieldbus/enip/identity.hpp"

namespace stepmod::enip {

inline constexpr std::uint16_t kEncapProtocolVersion = 1;
inline constexpr std::size_t kMaxSessions = 8;

// Sessions, each bound to the TCP connection that registered it (`connection`: an id the server
// gives each TCP connection, never 0). A handle is only valid on its own connection, so a peer
// gains nothing by guessing another's.
class SessionTable {
 public:
  std::uint32_t handle_of(std::uint32_t connection) const noexcept;  // 0 = none
  bool valid(std::uint32_t handle, std::uint32_t connection) const noexcept;
  std::uint32_t add(std::uint32_t connection) noexcept;  // the new handle; 0 = table full
  void remove(std::uint32_t connection) noexcept;
  std::size_t size() const noexcept;

 private:
  struct Slot {
    std::uint32_t handle = 0;
    std::uint32_t connection = 0;
  };
  std::array<Slot, kMaxSessions> slots_{};
  std::uint32_t next_handle_ = 1;
};

// The address ListIdentity reports: where a client reaches our TCP port (host byte order).
struct SocketAddress {
  std::uint32_t ip = 0;
  std::uint16_t port = 44818;
};

std::size_t encode_list_identity_reply(std::span<std::uint8_t> out, const EncapHeader& request,
                                       const IdentityValues& id, SocketAddress address) noexcept;

struct RegisterResult {
  std::size_t reply_size = 0;
  std::uint32_t session = 0;  // the handle registered, 0 = refused (the reply says why)
};
RegisterResult handle_register_session(std::span<std::uint8_t> out, const EncapFrame& request,
                                       SessionTable& sessions, std::uint32_t connection) noexcept;

struct UnregisterResult {
  bool close = false;          // the session ended: close the TCP connection, no reply
  std::size_t reply_size = 0;  // otherwise an error reply (not this connection's session)
};
UnregisterResult handle_unregister_session(std::span<std::uint8_t> out, const EncapFrame& request,
                                           SessionTable& sessions,
                                           std::uint32_t connection) noexcept;

}  // namespace stepmod::enip
