#include "fieldbus/enip/net_interface_linux.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <ifaddrs.h>
#include <linux/ethtool.h>
#include <linux/if_link.h>
#include <linux/if_packet.h>
#include <linux/sockios.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <charconv>
#include <cstring>

#include "fieldbus/enip/adapter_sockets.hpp"

namespace stepmod::enip {

namespace {

// Up to the buffer's size of the file at `path` (a /proc, /sys or /etc file); "" when absent.
template <std::size_t N>
std::string_view read_small_file(const char* path, std::array<char, N>& buf) noexcept {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  std::size_t size = 0;
  for (;;) {
    const ssize_t n = ::read(fd, buf.data() + size, buf.size() - size);
    if (n <= 0) break;
    size += static_cast<std::size_t>(n);
    if (size == buf.size()) break;
  }
  ::close(fd);
  return {buf.data(), size};
}

// The next line of `text` from `pos` (without its newline); advances `pos`.
std::string_view next_line(std::string_view text, std::size_t& pos) noexcept {
  const std::size_t end = text.find('\n', pos);
  const std::size_t stop = end == std::string_view::npos ? text.size() : end;
  const std::string_view line = text.substr(pos, stop - pos);
  pos = stop == text.size() ? stop : stop + 1;
  return line;
}

// The `index`th whitespace-separated field of `line`; "" past the last.
std::string_view field(std::string_view line, int index) noexcept {
  std::size_t pos = 0;
  for (int i = 0;; ++i) {
    pos = line.find_first_not_of(" \t\r", pos);
    if (pos == std::string_view::npos) return {};
    const std::size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
    if (i == index) return line.substr(pos, end - pos);
    pos = end;
  }
}

bool parse_hex(std::string_view s, std::uint32_t& out) noexcept {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out, 16);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// Linux's counters of the link (getifaddrs' one snapshot of them) in the Ethernet Link object's
// order; what Linux does not count apart is 0 (docs/ethernetip-design.md, "TCP/IP Interface
// (0xF5) and Ethernet Link").
void from_link_stats(const rtnl_link_stats& st, LinkCounters& out) noexcept {
  out.interface = {st.rx_bytes,
                   st.rx_packets - st.multicast,
                   st.multicast,
                   st.rx_dropped,
                   st.rx_errors,
                   st.rx_nohandler,
                   st.tx_bytes,
                   st.tx_packets,
                   0,
                   st.tx_dropped,
                   st.tx_errors};
  out.media = {st.rx_frame_errors,
               st.rx_crc_errors,
               0,
               0,
               st.tx_heartbeat_errors,
               0,
               st.tx_window_errors,
               st.tx_aborted_errors,
               st.tx_fifo_errors,
               st.tx_carrier_errors,
               st.rx_length_errors,
               st.rx_fifo_errors};
}

// The IPv4 entry of the interface that has `local_ip`; else the one whose network holds it (the
// loopback answers for all of 127.0.0.0/8 with only 127.0.0.1 configured).
const ifaddrs* entry_of(const ifaddrs* all, std::uint32_t local_ip) noexcept {
  const ifaddrs* in_network = nullptr;
  for (const ifaddrs* a = all; a != nullptr; a = a->ifa_next) {
    const std::uint32_t ip = ipv4_of(a->ifa_addr);
    if (ip == 0) continue;
    if (ip == local_ip) return a;
    const std::uint32_t mask = ipv4_of(a->ifa_netmask);
    if (in_network == nullptr && mask != 0 && (ip & mask) == (local_ip & mask)) in_network = a;
  }
  return in_network;
}

// The address, mask, flags and name of the interface with `local_ip`, then its MAC.
bool from_ifaddrs(std::uint32_t local_ip, NetInterface& out) noexcept {
  ifaddrs* all = nullptr;
  if (local_ip == 0 || ::getifaddrs(&all) != 0) return false;
  const ifaddrs* e = entry_of(all, local_ip);
  if (e != nullptr) {
    out.ip = local_ip;
    out.mask = ipv4_of(e->ifa_netmask);
    // An address with a label ("eth0:1") is named by it: the link is the name before ':'.
    const std::string_view name = e->ifa_name;
    out.label.assign(name.substr(0, name.find(':')));
    out.admin_up = (e->ifa_flags & IFF_UP) != 0;
    out.link_up = (e->ifa_flags & IFF_RUNNING) != 0;
    if ((e->ifa_flags & IFF_LOOPBACK) != 0) out.medium = Medium::kInternal;
  }
  for (const ifaddrs* a = all; a != nullptr && e != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_PACKET) continue;
    if (out.label.view() != a->ifa_name) continue;
    const auto* ll = reinterpret_cast<const sockaddr_ll*>(a->ifa_addr);
    if (ll->sll_halen == out.mac.size()) std::memcpy(out.mac.data(), ll->sll_addr, out.mac.size());
    if (a->ifa_data != nullptr) {
      from_link_stats(*static_cast<const rtnl_link_stats*>(a->ifa_data), out.counters);
    }
  }
  ::freeifaddrs(all);
  return e != nullptr;
}

// Speed, duplex, auto-negotiation and port from the ethtool ioctl; a link without them (the
// loopback) keeps "unknown".
void from_ethtool(NetInterface& out) noexcept {
  const int s = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (s < 0) return;
  ethtool_cmd cmd{};
  cmd.cmd = ETHTOOL_GSET;
  ifreq ifr{};
  std::memcpy(ifr.ifr_name, out.label.chars.data(), out.label.length);
  ifr.ifr_data = reinterpret_cast<char*>(&cmd);
  const bool ok = ::ioctl(s, SIOCETHTOOL, &ifr) == 0;
  ::close(s);
  if (!ok) return;
  const std::uint32_t speed = ethtool_cmd_speed(&cmd);
  out.speed_mbps = speed == static_cast<std::uint32_t>(SPEED_UNKNOWN) ? 0 : speed;
  if (cmd.duplex == DUPLEX_FULL) out.duplex = Duplex::kFull;
  if (cmd.duplex == DUPLEX_HALF) out.duplex = Duplex::kHalf;
  out.negotiation = cmd.autoneg == AUTONEG_ENABLE ? Negotiation::kAuto : Negotiation::kForced;
  out.can_negotiate = (cmd.supported & SUPPORTED_Autoneg) != 0;
  if (cmd.port == PORT_TP) out.medium = Medium::kTwistedPair;
  if (cmd.port == PORT_FIBRE) out.medium = Medium::kOptical;
}

}  // namespace

std::uint32_t default_gateway(std::string_view proc_net_route, std::string_view ifname) noexcept {
  constexpr std::uint32_t kRtfGateway = 0x2;
  std::size_t pos = 0;
  next_line(proc_net_route, pos);  // the header
  while (pos < proc_net_route.size()) {
    const std::string_view line = next_line(proc_net_route, pos);
    std::uint32_t destination = 1;
    std::uint32_t gateway = 0;
    std::uint32_t flags = 0;
    if (field(line, 0) != ifname || !parse_hex(field(line, 1), destination) ||
        !parse_hex(field(line, 2), gateway) || !parse_hex(field(line, 3), flags)) {
      continue;
    }
    // The kernel prints the network-order words as host integers.
    if (destination == 0 && (flags & kRtfGateway) != 0) return ntohl(gateway);
  }
  return 0;
}

void read_resolv_conf(std::string_view text, NetInterface& out) noexcept {
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::string_view line = next_line(text, pos);
    const std::string_view key = field(line, 0);
    if (key == "nameserver") {
      const std::uint32_t ip = parse_ipv4(field(line, 1));
      if (ip == 0) continue;  // an IPv6 server: the attribute holds IPv4 only
      if (out.name_server == 0) {
        out.name_server = ip;
      } else if (out.name_server_2 == 0) {
        out.name_server_2 = ip;
      }
    } else if (key == "domain" || key == "search") {
      out.domain.assign(field(line, 1));  // the last of them wins, as in the resolver
    }
  }
}

bool LinuxNetworkPort::read(std::uint32_t local_ip, NetInterface& out) const noexcept {
  out = NetInterface{};
  if (!from_ifaddrs(local_ip, out)) return false;
  std::array<char, 8192> buf{};
  out.gateway = default_gateway(read_small_file("/proc/net/route", buf), out.label.view());
  read_resolv_conf(read_small_file(resolv_conf_, buf), out);
  std::array<char, 65> host{};
  if (::gethostname(host.data(), host.size()) == 0) {  // 64 characters and the NUL
    host.back() = '\0';
    out.host_name.assign(host.data());
  }
  from_ethtool(out);
  return true;
}

bool LinuxNetworkPort::describe(std::uint32_t local_ip, NetInterface& out) noexcept {
  const Nanos now = monotonic_now();
  if (local_ip != snapshot_ip_ || now - snapshot_at_ >= kSnapshotLife) {
    snapshot_ok_ = read(local_ip, snapshot_);
    snapshot_ip_ = local_ip;
    snapshot_at_ = now;
  }
  out = snapshot_;
  return snapshot_ok_;
}

}  // namespace stepmod::enip
