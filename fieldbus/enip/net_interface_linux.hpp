#pragma once
// The board's network interface as Linux has it, for the TCP/IP Interface and Ethernet Link
// objects: the address, mask and flags (getifaddrs), the MAC (its AF_PACKET entry), the default
// gateway (/proc/net/route), the name servers and domain (/etc/resolv.conf), the host name,
// speed, duplex and auto-negotiation (the ethtool ioctl), the counters (getifaddrs' snapshot of
// the link's statistics). Read by the adapter's thread, which also serves the I/O: getifaddrs and
// the ioctl take the kernel's network lock, so a snapshot serves the requests of one second (a
// tool polling the counters costs one read a second) and a DHCP renewal or a pulled cable shows
// within a second.
#include <cstdint>
#include <string_view>

#include "core/clock.hpp"
#include "fieldbus/enip/net_interface.hpp"

namespace stepmod::enip {

// The default route's gateway of interface `ifname` in /proc/net/route's text (host byte order);
// 0 when it has none.
std::uint32_t default_gateway(std::string_view proc_net_route, std::string_view ifname) noexcept;

// The first two IPv4 "nameserver" lines and the "domain" (else the first "search" name) of
// /etc/resolv.conf's text, into `out`.
void read_resolv_conf(std::string_view text, NetInterface& out) noexcept;

class LinuxNetworkPort : public NetworkPort {
 public:
  explicit LinuxNetworkPort(const char* resolv_conf = "/etc/resolv.conf") noexcept
      : resolv_conf_(resolv_conf) {}
  bool describe(std::uint32_t local_ip, NetInterface& out) noexcept override;

 private:
  static constexpr Nanos kSnapshotLife = kNsPerSec;

  bool read(std::uint32_t local_ip, NetInterface& out) const noexcept;

  const char* resolv_conf_;
  NetInterface snapshot_;
  std::uint32_t snapshot_ip_ = 0;
  Nanos snapshot_at_ = -kSnapshotLife;  // none yet: stale at any CLOCK_MONOTONIC time
  bool snapshot_ok_ = false;
};

}  // namespace stepmod::enip
