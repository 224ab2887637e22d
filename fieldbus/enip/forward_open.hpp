#pragma once
// The Connection Manager's Forward_Open, Large_Forward_Open and Forward_Close requests: parsing,
// validation against the assembly instances and the configured RPI range, the ownership rule,
// and the reply data (docs/ethernetip-design.md, "Connection Manager", in the order given there).
// No connection state here: the caller's connection table says what is open (OpenConnections).
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/assembly.hpp"
#include "fieldbus/enip/cip_status.hpp"
#include "fieldbus/enip/identity.hpp"
#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

inline constexpr std::uint32_t kConnectionManagerClass = 0x06;
namespace cm_service {
inline constexpr std::uint8_t kForwardClose = 0x4E;
inline constexpr std::uint8_t kUnconnectedSend = 0x52;
inline constexpr std::uint8_t kForwardOpen = 0x54;
inline constexpr std::uint8_t kLargeForwardOpen = 0x5B;
}  // namespace cm_service

namespace conn_type {
inline constexpr std::uint8_t kNull = 0;
inline constexpr std::uint8_t kMulticast = 1;
inline constexpr std::uint8_t kPointToPoint = 2;
}  // namespace conn_type

// A network connection parameters word (16-bit in Forward_Open, 32-bit in the large one).
struct NetParams {
  bool redundant_owner = false;
  std::uint8_t type = 0;  // conn_type
  std::uint8_t priority = 0;
  bool variable = false;
  std::uint16_t size = 0;  // bytes, with the sequence count (and the run/idle header)
};
NetParams decode_net_params(std::uint32_t raw, bool large) noexcept;

// Identifies a connection to both ends: the originator's serial of it, vendor and serial.
struct ConnectionTriad {
  std::uint16_t connection_serial = 0;
  std::uint16_t originator_vendor = 0;
  std::uint32_t originator_serial = 0;
  friend bool operator==(const ConnectionTriad&, const ConnectionTriad&) = default;
};

struct ForwardOpen {
  bool large = false;
  std::uint8_t priority_tick = 0;
  std::uint8_t timeout_ticks = 0;
  std::uint32_t ot_id = 0;  // the originator's proposal; we choose the O→T id we consume
  std::uint32_t to_id = 0;  // the originator's: it consumes T→O point-to-point
  ConnectionTriad triad;
  std::uint8_t timeout_multiplier = 0;
  std::uint32_t ot_rpi_us = 0;
  NetParams ot;
  std::uint32_t to_rpi_us = 0;
  NetParams to;
  std::uint8_t transport = 0;  // bit 7 direction, bits 4-6 trigger, bits 0-3 class
  std::span<const std::uint8_t> path;
};

struct ForwardClose {
  std::uint8_t priority_tick = 0;
  std::uint8_t timeout_ticks = 0;
  ConnectionTriad triad;
  std::span<const std::uint8_t> path;
};

// `data`: the request data after the message router's service and path. The general status:
// success, kNotEnoughData or kTooMuchData (bytes after the connection path).
std::uint8_t parse_forward_open(std::span<const std::uint8_t> data, bool large,
                                ForwardOpen& out) noexcept;
std::uint8_t parse_forward_close(std::span<const std::uint8_t> data, ForwardClose& out) noexcept;

struct AdapterLimits {
  std::uint32_t rpi_min_us = 1000;
  std::uint32_t rpi_max_us = 100000;
};

enum class ConnectionKind { kExclusiveOwner, kInputOnly, kListenOnly };

struct AcceptedOpen {
  ConnectionKind kind = ConnectionKind::kExclusiveOwner;
  std::uint64_t timeout_us = 0;  // O→T RPI × 4 × 2^multiplier: silence this long closes it
};

// Everything about a Forward_Open that does not depend on what is open already.
CipStatus validate_forward_open(const ForwardOpen& fo, const AssemblyLayout& layout,
                                const IdentityValues& id, const AdapterLimits& limits,
                                AcceptedOpen& out) noexcept;

// What the connection table holds when a Forward_Open arrives.
struct OpenConnections {
  bool triad_open = false;  // a connection with the request's triad is open
  bool owner = false;       // an exclusive owner connection is open
  bool input_only = false;  // an input-only connection is open
  unsigned free_slots = 0;
};
CipStatus check_ownership(ConnectionKind kind, const OpenConnections& open) noexcept;

// Reply data after the reply status (put_reply_status).
void put_forward_open_success(Writer& w, const ForwardOpen& fo, std::uint32_t ot_id,
                              std::uint32_t to_id) noexcept;
// The data of a refused Forward_Open or Forward_Close (the triad, remaining path size 0,
// reserved) and of an accepted Forward_Close (the triad, application reply size 0, reserved):
// the same bytes.
void put_triad_reply(Writer& w, const ConnectionTriad& triad) noexcept;

}  // namespace stepmod::enip
