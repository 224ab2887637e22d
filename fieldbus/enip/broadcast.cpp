#include "fieldbus/enip/broadcast.hpp"

#include <algorithm>
#include <limits>

#include "fieldbus/enip/encap.hpp"

namespace stepmod::enip {

namespace {
constexpr bool is_loopback(std::uint32_t ip) noexcept {
  return (ip >> 24) == 127u;
}
}  // namespace

BroadcastScope BroadcastScope::for_listen(std::uint32_t listen_ip,
                                          std::span<const InterfaceAddress> interfaces) noexcept {
  BroadcastScope s;
  if (is_loopback(listen_ip)) return s;
  for (const InterfaceAddress& i : interfaces) {
    if (is_loopback(i.address) || (listen_ip != 0 && i.address != listen_ip)) continue;
    if (s.count_ == 0) s.add(kLimitedBroadcast);
    if (i.broadcast != 0) s.add(i.broadcast);
    if (listen_ip != 0) s.ifindex_ = i.ifindex;
  }
  return s;
}

void BroadcastScope::add(std::uint32_t broadcast) noexcept {
  const auto end = broadcasts_.begin() + static_cast<std::ptrdiff_t>(count_);
  if (count_ < broadcasts_.size() && std::find(broadcasts_.begin(), end, broadcast) == end) {
    broadcasts_[count_++] = broadcast;
  }
}

bool BroadcastScope::accepts(unsigned ifindex, std::uint32_t destination) const noexcept {
  if (ifindex_ != 0 && ifindex != ifindex_) return false;
  const auto end = broadcasts_.begin() + static_cast<std::ptrdiff_t>(count_);
  return std::find(broadcasts_.begin(), end, destination) != end;
}

std::optional<Nanos> list_identity_max_delay(std::span<const std::uint8_t> datagram) noexcept {
  EncapFrame f;
  if (parse_encap(datagram, f) != EncapParse::kFrame ||
      f.header.command != encap_cmd::kListIdentity) {
    return std::nullopt;
  }
  const unsigned ms = f.header.context[0] | (f.header.context[1] << 8);
  if (ms == 0) return 2000 * kNsPerMs;
  return static_cast<Nanos>(std::max(ms, 500u)) * kNsPerMs;
}

bool DelayedReplies::add(Nanos due, const sockaddr_in& to,
                         std::span<const std::uint8_t> reply) noexcept {
  if (reply.size() > kMaxReply) return false;
  const auto same_sender = [&to](const Pending& p) {
    return p.used && p.to.sin_addr.s_addr == to.sin_addr.s_addr && p.to.sin_port == to.sin_port;
  };
  if (std::any_of(slots_.begin(), slots_.end(), same_sender)) return false;
  for (Pending& p : slots_) {
    if (p.used) continue;
    p.used = true;
    p.due = due;
    p.to = to;
    p.size = reply.size();
    std::copy(reply.begin(), reply.end(), p.bytes.begin());
    return true;
  }
  return false;
}

Nanos DelayedReplies::next_due() const noexcept {
  Nanos next = std::numeric_limits<Nanos>::max();
  for (const Pending& p : slots_) {
    if (p.used) next = std::min(next, p.due);
  }
  return next;
}

}  // namespace stepmod::enip
