#pragma once
// The TCP/IP Interface object (class 0xF5) and the Ethernet Link object (class 0xF6), instance 1:
// their attributes' encodings from a NetInterface (docs/ethernetip-design.md, "TCP/IP Interface
// and Ethernet Link"). Get_Attributes_All gives attributes 1 to 13 (0xF5) and 1 to 11 (0xF6) in
// order, the ones stepmod does not have as their defaults (as CIP asks); Get_Attribute_Single
// gives the ones it has. Nothing is settable: the board's OS configures the interface.
#include <cstdint>

#include "fieldbus/enip/net_interface.hpp"
#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

inline constexpr std::uint32_t kTcpIpInterfaceClass = 0xF5;
inline constexpr std::uint32_t kEthernetLinkClass = 0xF6;
// Their instance attributes are 1 to these.
inline constexpr std::uint32_t kTcpIpLastAttribute = 13;
inline constexpr std::uint32_t kEthernetLinkLastAttribute = 11;

// Interface Flags (0xF6 attribute 2): bit 0 link active, bit 1 full duplex, bits 2-4 the
// negotiation status.
namespace link_flags {
inline constexpr std::uint32_t kLinkActive = 1u << 0;
inline constexpr std::uint32_t kFullDuplex = 1u << 1;
inline constexpr std::uint32_t kNegotiationInProgress = 0u << 2;
inline constexpr std::uint32_t kNegotiated = 3u << 2;
inline constexpr std::uint32_t kNegotiationNotAttempted = 4u << 2;
}  // namespace link_flags

// Status (0xF5 attribute 1): the interface configuration is valid (from the OS, "non-volatile
// storage" in CIP's words) when the interface has an address.
inline constexpr std::uint32_t kTcpIpStatusConfigured = 1;
// Encapsulation Inactivity Timeout (0xF5 attribute 13): 0, the adapter closes no session for
// being idle (a ninth connection closes the longest idle one instead).
inline constexpr std::uint16_t kInactivityTimeoutOff = 0;

void put_tcpip_all(Writer& w, const NetInterface& n) noexcept;
// False: the object has no such attribute for Get_Attribute_Single (0x14).
bool put_tcpip_attribute(Writer& w, const NetInterface& n, std::uint32_t attribute) noexcept;

void put_ethernet_link_all(Writer& w, const NetInterface& n) noexcept;
bool put_ethernet_link_attribute(Writer& w, const NetInterface& n,
                                 std::uint32_t attribute) noexcept;

// Interface Flags from the link's state.
std::uint32_t interface_flags(const NetInterface& n) noexcept;

}  // namespace stepmod::enip
