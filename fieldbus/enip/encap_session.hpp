#pragma once
// One TCP connection's encapsulation requests, or one UDP datagram's, to their replies
// (docs/ethernetip-design.md, "Encapsulation": the status table). No sockets: the adapter gives
// received bytes and sends what is written to `out`.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/encap_replies.hpp"
#include "fieldbus/enip/message_router.hpp"

namespace stepmod::enip {

struct EncapContext {
  SessionTable& sessions;
  const IdentityValues& identity;
  SocketAddress address;  // ListIdentity's: where clients reach our TCP port
  RouterContext& router;
};

enum class SessionAction {
  kNone,   // nothing to send (an incomplete frame, a NOP, a discarded frame)
  kReply,  // send `reply_size` bytes of `out`
  kClose,  // close the connection (UnRegisterSession, or a frame whose end cannot be trusted)
};

struct SessionStep {
  std::size_t consumed = 0;  // bytes of the input used; 0 with kNone: wait for more
  SessionAction action = SessionAction::kNone;
  std::size_t reply_size = 0;
};

// The first frame at the front of a TCP connection's received bytes. `connection`: the
// server's id of the TCP connection (never 0).
SessionStep handle_tcp(std::span<const std::uint8_t> in, std::uint32_t connection,
                       EncapContext& ctx, std::span<std::uint8_t> out) noexcept;

// One UDP datagram: ListIdentity, ListServices and ListInterfaces are answered; the size of the
// reply, 0 for none.
std::size_t handle_udp(std::span<const std::uint8_t> datagram, EncapContext& ctx,
                       std::span<std::uint8_t> out) noexcept;

}  // namespace stepmod::enip
