#include "fieldbus/enip/tcpip_objects.hpp"

#include <array>
#include <span>
#include <string_view>

namespace stepmod::enip {

namespace {

using Put = void (*)(Writer&, const NetInterface&);

// One attribute: its number, its encoding, and whether Get_Attribute_Single serves it (false:
// only a default inside Get_Attributes_All, an attribute stepmod does not have).
struct AttributeRow {
  std::uint32_t id;
  Put put;
  bool single;
};

// CIP STRING: UINT length, the characters, a pad byte to an even length.
void put_string(Writer& w, std::string_view s) noexcept {
  w.u16(static_cast<std::uint16_t>(s.size()));
  w.bytes(std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()));
  if (s.size() % 2 != 0) w.u8(0);
}

void put_each(Writer& w, std::span<const std::uint32_t> values) noexcept {
  for (const std::uint32_t v : values) w.u32(v);
}

// --- TCP/IP Interface, instance 1 -------------------------------------------------------------

void tcpip_status(Writer& w, const NetInterface& n) noexcept {
  w.u32(n.ip != 0 ? kTcpIpStatusConfigured : 0);
}
// Configuration Capability and Control: none settable over CIP; the configuration is stored
// (the OS's).
void tcpip_zero_dword(Writer& w, const NetInterface&) noexcept {
  w.u32(0);
}
// Physical Link Object: the path to the Ethernet Link object, class 0xF6 instance 1.
void tcpip_physical_link(Writer& w, const NetInterface&) noexcept {
  w.u16(2);  // words
  w.bytes(std::array<std::uint8_t, 4>{0x20, 0xF6, 0x24, 0x01});
}
void tcpip_interface_configuration(Writer& w, const NetInterface& n) noexcept {
  w.u32(n.ip);
  w.u32(n.mask);
  w.u32(n.gateway);
  w.u32(n.name_server);
  w.u32(n.name_server_2);
  put_string(w, n.domain.view());
}
void tcpip_host_name(Writer& w, const NetInterface& n) noexcept {
  put_string(w, n.host_name.view());
}
void tcpip_safety_network_number(Writer& w, const NetInterface&) noexcept {
  w.zeros(6);
}
void tcpip_ttl(Writer& w, const NetInterface&) noexcept {
  w.u8(1);  // CIP's default; stepmod produces no multicast
}
// Multicast Configuration: the default allocation, no addresses (multicast T→O is refused).
void tcpip_multicast(Writer& w, const NetInterface&) noexcept {
  w.u8(0);   // allocation control: the default algorithm
  w.u8(0);   // reserved
  w.u16(0);  // number of addresses
  w.u32(0);  // the first address
}
void tcpip_false(Writer& w, const NetInterface&) noexcept {
  w.u8(0);
}
// Last Conflict Detected: no address conflict detection, so none (activity, MAC, ARP PDU).
void tcpip_last_conflict(Writer& w, const NetInterface&) noexcept {
  w.zeros(35);
}
void tcpip_inactivity_timeout(Writer& w, const NetInterface&) noexcept {
  w.u16(kInactivityTimeoutOff);
}

constexpr std::array<AttributeRow, 13> kTcpIp{{
    {1, tcpip_status, true},
    {2, tcpip_zero_dword, true},
    {3, tcpip_zero_dword, true},
    {4, tcpip_physical_link, true},
    {5, tcpip_interface_configuration, true},
    {6, tcpip_host_name, true},
    {7, tcpip_safety_network_number, false},
    {8, tcpip_ttl, true},
    {9, tcpip_multicast, true},
    {10, tcpip_false, false},  // Select ACD
    {11, tcpip_last_conflict, false},
    {12, tcpip_false, false},  // EtherNet/IP Quick Connect
    {13, tcpip_inactivity_timeout, true},
}};

// --- Ethernet Link, instance 1 ----------------------------------------------------------------

void link_speed(Writer& w, const NetInterface& n) noexcept {
  w.u32(n.speed_mbps);
}
void link_flags_attribute(Writer& w, const NetInterface& n) noexcept {
  w.u32(interface_flags(n));
}
void link_mac(Writer& w, const NetInterface& n) noexcept {
  w.bytes(n.mac);
}
void link_interface_counters(Writer& w, const NetInterface& n) noexcept {
  put_each(w, n.counters.interface);
}
void link_media_counters(Writer& w, const NetInterface& n) noexcept {
  put_each(w, n.counters.media);
}
// Interface Control: bit 0 auto-negotiation on; bit 1 (forced) full duplex; the forced speed.
void link_control(Writer& w, const NetInterface& n) noexcept {
  const bool forced = n.negotiation == Negotiation::kForced;
  std::uint16_t bits = n.negotiation == Negotiation::kAuto ? 1 : 0;
  if (forced && n.duplex == Duplex::kFull) bits |= 2;
  w.u16(bits);
  w.u16(forced ? static_cast<std::uint16_t>(n.speed_mbps) : 0);
}
void link_type(Writer& w, const NetInterface& n) noexcept {
  w.u8(static_cast<std::uint8_t>(n.medium));
}
// Interface State (1 enabled, 2 disabled) and Admin State (1 enable, 2 disable): the same.
void link_enabled(Writer& w, const NetInterface& n) noexcept {
  w.u8(n.admin_up ? 1 : 2);
}
void link_label(Writer& w, const NetInterface& n) noexcept {
  w.short_string(n.label.view());
}
// Interface Capability: bit 1 auto-negotiation; no speed/duplex list (nothing settable).
void link_capability(Writer& w, const NetInterface& n) noexcept {
  w.u32(n.can_negotiate ? 2u : 0u);
  w.u8(0);
}

constexpr std::array<AttributeRow, 11> kEthernetLink{{
    {1, link_speed, true},
    {2, link_flags_attribute, true},
    {3, link_mac, true},
    {4, link_interface_counters, true},
    {5, link_media_counters, true},
    {6, link_control, true},
    {7, link_type, true},
    {8, link_enabled, true},
    {9, link_enabled, true},
    {10, link_label, true},
    {11, link_capability, true},
}};

void put_all(Writer& w, const NetInterface& n, std::span<const AttributeRow> rows) noexcept {
  for (const AttributeRow& row : rows) row.put(w, n);
}

bool put_one(Writer& w, const NetInterface& n, std::span<const AttributeRow> rows,
             std::uint32_t attribute) noexcept {
  for (const AttributeRow& row : rows) {
    if (row.id != attribute) continue;
    if (!row.single) return false;
    row.put(w, n);
    return true;
  }
  return false;
}

}  // namespace

std::uint32_t interface_flags(const NetInterface& n) noexcept {
  std::uint32_t f = n.link_up ? link_flags::kLinkActive : 0;
  if (n.duplex == Duplex::kFull) f |= link_flags::kFullDuplex;
  if (n.negotiation == Negotiation::kAuto) {
    f |= n.link_up ? link_flags::kNegotiated : link_flags::kNegotiationInProgress;
  } else {
    f |= link_flags::kNegotiationNotAttempted;  // forced, or a link without negotiation
  }
  return f;
}

void put_tcpip_all(Writer& w, const NetInterface& n) noexcept {
  put_all(w, n, kTcpIp);
}

bool put_tcpip_attribute(Writer& w, const NetInterface& n, std::uint32_t attribute) noexcept {
  return put_one(w, n, kTcpIp, attribute);
}

void put_ethernet_link_all(Writer& w, const NetInterface& n) noexcept {
  put_all(w, n, kEthernetLink);
}

bool put_ethernet_link_attribute(Writer& w, const NetInterface& n,
                                 std::uint32_t attribute) noexcept {
  return put_one(w, n, kEthernetLink, attribute);
}

}  // namespace stepmod::enip
