#pragma once
// The message router (docs/ethernetip-design.md, "CIP: message router and objects"): a request
// (service, path, data) to the object table's handler, and the reply (service | 0x80, status,
// data). Unconnected_Send to ourselves (route port 1 / link 0, or none) delivers the embedded
// request here and its reply is the reply. What the objects need from the rest of the adapter
// (the image's words, the connection table) comes through RouterContext.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/assembly.hpp"
#include "fieldbus/enip/cip_status.hpp"
#include "fieldbus/enip/epath.hpp"
#include "fieldbus/enip/forward_open.hpp"
#include "fieldbus/enip/identity.hpp"
#include "fieldbus/enip/net_interface.hpp"
#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

namespace cip_service {
inline constexpr std::uint8_t kGetAttributesAll = 0x01;
inline constexpr std::uint8_t kGetAttributeSingle = 0x0E;
inline constexpr std::uint8_t kSetAttributeSingle = 0x10;
}  // namespace cip_service

// The largest reply the router writes (a Get_Attributes_All, a Forward_Open reply).
inline constexpr std::size_t kMaxReplyBytes = 504;

struct MrRequest {
  std::uint8_t service = 0;
  RequestPath path;
  std::span<const std::uint8_t> data;
};

// The general status: success, kNotEnoughData (the path runs past the message) or
// kPathSegmentError (a path that is not class [instance [attribute]]).
std::uint8_t parse_mr_request(std::span<const std::uint8_t> message, MrRequest& out) noexcept;

// The assembly instances' data as the image holds it.
class AssemblyData {
 public:
  virtual ~AssemblyData() = default;
  // Copies instance 100 (input) or 150 (output) into `out` (the layout's size).
  virtual void read(std::uint32_t instance, std::span<std::uint8_t> out) noexcept = 0;
  // Instance 150: one consistent PLC write of the output words (one seqlock write).
  virtual void write_output(std::span<const std::uint8_t> bytes) noexcept = 0;
};

// Who sent the request being routed, and when (CLOCK_MONOTONIC ns): a connection's T→O goes to
// its originator, and its timeout counts from its opening. `local_ip`: the board's address the
// request came in on (its interface is the TCP/IP Interface object's); 0 when not known.
struct RequestOrigin {
  std::uint32_t ip = 0;  // IPv4, host byte order
  std::int64_t now_ns = 0;
  std::uint32_t local_ip = 0;
};

// The connection table, for the Connection Manager's services.
class ConnectionTable {
 public:
  virtual ~ConnectionTable() = default;
  virtual bool owner_open() const noexcept = 0;
  // Opens a validated connection: the ownership rule (check_ownership), then the ids;
  // `ot_id` is ours, T→O is the originator's.
  virtual CipStatus open(const ForwardOpen& fo, const AcceptedOpen& accepted,
                         const RequestOrigin& origin, std::uint32_t& ot_id) noexcept = 0;
  // 0x0107 when no connection has the triad.
  virtual CipStatus close(const ConnectionTriad& triad) noexcept = 0;
};

struct RouterContext {
  const IdentityValues& identity;
  AssemblyLayout layout;
  AdapterLimits limits;
  AssemblyData& assemblies;
  ConnectionTable& connections;
  NetworkPort& network;
  RequestOrigin origin;
};

// Handles `message` (one message router request) and writes its whole reply to `w`.
void route_message(std::span<const std::uint8_t> message, RouterContext& ctx, Writer& w) noexcept;

}  // namespace stepmod::enip
