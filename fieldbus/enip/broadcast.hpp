#pragma once
// ListIdentity by broadcast (docs/ethernetip-design.md, "Encapsulation"): what RSLinx's browse
// and other scanners send to find the devices on a network. Which broadcasts an adapter answers,
// and the random delay the encapsulation spec asks of a target before it answers one, so that a
// network of boards does not answer at once. Pure: the sockets are the adapter's.
#include <netinet/in.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/clock.hpp"

namespace stepmod::enip {

// One IPv4 address of the machine (getifaddrs), host byte order.
struct InterfaceAddress {
  unsigned ifindex = 0;
  std::uint32_t address = 0;
  std::uint32_t broadcast = 0;  // 0: the interface has none (loopback, point-to-point)
};

// The broadcasts an adapter listening on one address answers: 255.255.255.255 and the subnet
// broadcast of the interface holding that address, arriving on that interface. Listening on
// 0.0.0.0: those of every interface. Listening on loopback, or on an address no interface holds:
// none (a board listening on 127.0.0.1 never announces itself to the plant network).
class BroadcastScope {
 public:
  static constexpr std::uint32_t kLimitedBroadcast = 0xFFFFFFFFu;
  static constexpr std::size_t kMaxBroadcasts = 8;

  BroadcastScope() = default;
  static BroadcastScope for_listen(std::uint32_t listen_ip,
                                   std::span<const InterfaceAddress> interfaces) noexcept;

  bool enabled() const noexcept { return count_ > 0; }
  // Whether the adapter's own socket cannot receive them (it is bound to one address) and a
  // second one, bound to 0.0.0.0, must.
  bool needs_own_socket() const noexcept { return enabled() && ifindex_ != 0; }
  // A datagram that arrived on interface `ifindex` for IP destination `destination` (IP_PKTINFO).
  bool accepts(unsigned ifindex, std::uint32_t destination) const noexcept;

 private:
  void add(std::uint32_t broadcast) noexcept;
  unsigned ifindex_ = 0;  // 0: any interface
  std::array<std::uint32_t, kMaxBroadcasts> broadcasts_{};
  std::size_t count_ = 0;
};

// The delay a broadcast ListIdentity allows its answer, or nothing when `datagram` is not a
// ListIdentity request (only ListIdentity is answered to a broadcast). The sender context's first
// 16 bits are the maximum in ms: 0 means 2000, less than 500 means 500.
std::optional<Nanos> list_identity_max_delay(std::span<const std::uint8_t> datagram) noexcept;

// Replies waiting for their time. At most kSlots wait, one per sender (address and port): a
// broadcast that finds them all taken, or its sender's answer still waiting, is not answered, so
// a flood of requests neither grows the queue nor the replies, and one sender holds one slot.
class DelayedReplies {
 public:
  static constexpr std::size_t kSlots = 8;
  static constexpr std::size_t kMaxReply = 256;

  // False when every slot is taken, `to` has an answer waiting already, or the reply is larger
  // than kMaxReply.
  bool add(Nanos due, const sockaddr_in& to, std::span<const std::uint8_t> reply) noexcept;
  // The earliest due time, INT64_MAX when none waits.
  Nanos next_due() const noexcept;
  // Hands every reply due at `now` to `send(to, bytes)` and frees its slot.
  template <class Send>
  void send_due(Nanos now, Send&& send) noexcept {
    for (Pending& p : slots_) {
      if (!p.used || p.due > now) continue;
      send(p.to, std::span<const std::uint8_t>(p.bytes.data(), p.size));
      p.used = false;
    }
  }

 private:
  struct Pending {
    bool used = false;
    Nanos due = 0;
    sockaddr_in to{};
    std::size_t size = 0;
    std::array<std::uint8_t, kMaxReply> bytes{};
  };
  std::array<Pending, kSlots> slots_{};
};

}  // namespace stepmod::enip
