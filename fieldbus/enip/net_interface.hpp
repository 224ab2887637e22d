#pragma once
// What the TCP/IP Interface object (class 0xF5) and the Ethernet Link object (class 0xF6) report:
// the board's network interface that carries the adapter's address, as the board's OS has it
// (net_interface_linux.cpp reads it; the encodings are tcpip_objects.cpp). The OS configures the
// interface: the objects only show it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace stepmod::enip {

// A string of at most N characters, kept without allocation.
template <std::size_t N>
struct FixedText {
  std::array<char, N> chars{};
  std::size_t length = 0;

  void assign(std::string_view s) noexcept {
    length = s.size() < N ? s.size() : N;
    for (std::size_t i = 0; i < length; ++i) chars[i] = s[i];
  }
  std::string_view view() const noexcept { return {chars.data(), length}; }
};

enum class Duplex : std::uint8_t { kUnknown, kHalf, kFull };
enum class Negotiation : std::uint8_t { kUnknown, kAuto, kForced };
// The Ethernet Link object's Interface Type (attribute 7).
enum class Medium : std::uint8_t { kUnknown = 0, kInternal = 1, kTwistedPair = 2, kOptical = 3 };

// The link's counters as the Ethernet Link object orders them (attributes 4 and 5); CIP UDINTs,
// so they wrap at 2^32.
struct LinkCounters {
  // In octets, in unicast, in non-unicast, in discards, in errors, in unknown protocols, out
  // octets, out unicast, out non-unicast, out discards, out errors.
  std::array<std::uint32_t, 11> interface {};
  // Alignment, FCS, single collisions, multiple collisions, SQE test, deferred transmissions,
  // late collisions, excessive collisions, MAC transmit, carrier sense, frame too long, MAC
  // receive errors.
  std::array<std::uint32_t, 12> media{};
};

// CIP's limits: a host name of 64 characters, a domain name of 48 (TCP/IP object attributes 5
// and 6); an interface label is a SHORT_STRING of Linux's interface name (at most 15).
struct NetInterface {
  std::uint32_t ip = 0;  // IPv4 addresses in host byte order; 0: none
  std::uint32_t mask = 0;
  std::uint32_t gateway = 0;
  std::uint32_t name_server = 0;
  std::uint32_t name_server_2 = 0;
  FixedText<48> domain;
  FixedText<64> host_name;
  FixedText<15> label;  // the interface's name ("eth0")
  std::array<std::uint8_t, 6> mac{};
  std::uint32_t speed_mbps = 0;  // 0: unknown
  bool link_up = false;          // carrier (IFF_RUNNING)
  bool admin_up = false;         // IFF_UP
  Duplex duplex = Duplex::kUnknown;
  Negotiation negotiation = Negotiation::kUnknown;
  bool can_negotiate = false;  // the link supports auto-negotiation
  Medium medium = Medium::kUnknown;
  LinkCounters counters;
};

// Where the objects get the interface from: the interface that has `local_ip` (host byte order),
// the address the request came in on; false when no interface has it.
class NetworkPort {
 public:
  virtual ~NetworkPort() = default;
  virtual bool describe(std::uint32_t local_ip, NetInterface& out) noexcept = 0;
};

}  // namespace stepmod::enip
