#include "fieldbus/enip/objects.hpp"

#include <array>

#include "fieldbus/enip/tcpip_objects.hpp"

namespace stepmod::enip {

namespace {
constexpr std::uint32_t kIdentityClass = 0x01;
constexpr std::uint32_t kAssemblyDataAttribute = 3;

CipStatus status(std::uint8_t general) noexcept {
  return CipStatus::general_only(general);
}

// Identity: instance 1 only.
CipStatus identity_get_all(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  if (req.path.instance != 1 || req.path.has_attribute) {
    return status(cip_general::kPathDestinationUnknown);
  }
  if (!req.data.empty()) return status(cip_general::kTooMuchData);
  put_identity_all(data, ctx.identity);
  return {};
}

CipStatus identity_get_single(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  if (req.path.instance != 1) return status(cip_general::kPathDestinationUnknown);
  if (!req.path.has_attribute || req.path.attribute > 0xFF ||
      !put_identity_attribute(data, ctx.identity, static_cast<std::uint8_t>(req.path.attribute))) {
    return status(cip_general::kAttributeNotSupported);
  }
  return {};
}

// Assembly: the data attribute of 100 and 150; the others have no data.
std::size_t assembly_bytes(std::uint32_t instance, const AssemblyLayout& layout,
                           bool& known) noexcept {
  known = true;
  switch (instance) {
    case kInputInstance:
      return layout.input_bytes;
    case kOutputInstance:
      return layout.output_bytes;
    case kConfigInstance:
    case kInputOnlyHeartbeat:
    case kListenOnlyHeartbeat:
      return 0;
    default:
      known = false;
      return 0;
  }
}

CipStatus assembly_get_single(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  bool known = false;
  const std::size_t bytes = assembly_bytes(req.path.instance, ctx.layout, known);
  if (!known) return status(cip_general::kPathDestinationUnknown);
  if (req.path.attribute != kAssemblyDataAttribute) {
    return status(cip_general::kAttributeNotSupported);
  }
  std::array<std::uint8_t, 64> words{};  // the image's largest: 16 DINTs
  if (bytes > words.size()) return status(cip_general::kReplyDataTooLarge);
  if (bytes > 0) ctx.assemblies.read(req.path.instance, std::span(words).first(bytes));
  data.bytes(std::span(words).first(bytes));
  return {};
}

// Explicit writes reach the output words only while no exclusive owner writes them.
CipStatus assembly_set_single(const MrRequest& req, RouterContext& ctx, Writer&) noexcept {
  bool known = false;
  const std::size_t bytes = assembly_bytes(req.path.instance, ctx.layout, known);
  if (!known) return status(cip_general::kPathDestinationUnknown);
  if (req.path.attribute != kAssemblyDataAttribute) {
    return status(cip_general::kAttributeNotSupported);
  }
  if (req.path.instance != kOutputInstance) return status(cip_general::kAttributeNotSettable);
  if (ctx.connections.owner_open()) return status(cip_general::kObjectStateConflict);
  if (req.data.size() < bytes) return status(cip_general::kNotEnoughData);
  if (req.data.size() > bytes) return status(cip_general::kTooMuchData);
  ctx.assemblies.write_output(req.data);
  return {};
}

// Connection Manager, instance 1.
bool cm_instance(const MrRequest& req) noexcept {
  return req.path.has_instance && req.path.instance == 1 && !req.path.has_attribute;
}

CipStatus forward_open(const MrRequest& req, RouterContext& ctx, Writer& data,
                       bool large) noexcept {
  if (!cm_instance(req)) return status(cip_general::kPathDestinationUnknown);
  ForwardOpen fo;
  if (const std::uint8_t g = parse_forward_open(req.data, large, fo); g != cip_general::kSuccess) {
    return status(g);
  }
  AcceptedOpen accepted;
  CipStatus st = validate_forward_open(fo, ctx.layout, ctx.identity, ctx.limits, accepted);
  std::uint32_t ot_id = 0;
  if (st.ok()) st = ctx.connections.open(fo, accepted, ctx.origin, ot_id);
  if (st.ok()) {
    put_forward_open_success(data, fo, ot_id, fo.to_id);
  } else {
    put_triad_reply(data, fo.triad);
  }
  return st;
}

CipStatus cm_forward_open(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return forward_open(req, ctx, data, false);
}

CipStatus cm_large_forward_open(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return forward_open(req, ctx, data, true);
}

// The close's path is checked to be an EPATH; which connection closes is the triad's business.
CipStatus cm_forward_close(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  if (!cm_instance(req)) return status(cip_general::kPathDestinationUnknown);
  ForwardClose fc;
  if (const std::uint8_t g = parse_forward_close(req.data, fc); g != cip_general::kSuccess) {
    return status(g);
  }
  EpathReader path(fc.path);
  Segment s;
  while (path.next(s)) {
  }
  const CipStatus st = path.failed() ? CipStatus::connection(cm_status::kInvalidSegmentInPath)
                                     : ctx.connections.close(fc.triad);
  put_triad_reply(data, fc.triad);
  return st;
}

// TCP/IP Interface and Ethernet Link: instance 1, the interface the request came in on.
using PutAll = void (*)(Writer&, const NetInterface&);
using PutOne = bool (*)(Writer&, const NetInterface&, std::uint32_t);

// The interface the request came in on; false when none has its address any more (0x0C).
bool describe_interface(RouterContext& ctx, NetInterface& n) noexcept {
  return ctx.network.describe(ctx.origin.local_ip, n);
}

CipStatus interface_get_all(const MrRequest& req, RouterContext& ctx, Writer& data,
                            PutAll put) noexcept {
  if (req.path.instance != 1 || req.path.has_attribute) {
    return status(cip_general::kPathDestinationUnknown);
  }
  if (!req.data.empty()) return status(cip_general::kTooMuchData);
  NetInterface n;
  if (!describe_interface(ctx, n)) return status(cip_general::kObjectStateConflict);
  put(data, n);
  return {};
}

CipStatus interface_get_single(const MrRequest& req, RouterContext& ctx, Writer& data,
                               PutOne put) noexcept {
  if (req.path.instance != 1) return status(cip_general::kPathDestinationUnknown);
  if (!req.path.has_attribute) return status(cip_general::kAttributeNotSupported);
  NetInterface n;
  if (!describe_interface(ctx, n)) return status(cip_general::kObjectStateConflict);
  if (!put(data, n, req.path.attribute)) return status(cip_general::kAttributeNotSupported);
  return {};
}

// Nothing is settable: the board's OS configures its interface.
CipStatus interface_set_single(const MrRequest& req, std::uint32_t last_attribute) noexcept {
  if (req.path.instance != 1) return status(cip_general::kPathDestinationUnknown);
  if (!req.path.has_attribute || req.path.attribute == 0 || req.path.attribute > last_attribute) {
    return status(cip_general::kAttributeNotSupported);
  }
  return status(cip_general::kAttributeNotSettable);
}

CipStatus tcpip_get_all(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return interface_get_all(req, ctx, data, put_tcpip_all);
}
CipStatus tcpip_get_single(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return interface_get_single(req, ctx, data, put_tcpip_attribute);
}
CipStatus tcpip_set_single(const MrRequest& req, RouterContext&, Writer&) noexcept {
  return interface_set_single(req, kTcpIpLastAttribute);
}
CipStatus link_get_all(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return interface_get_all(req, ctx, data, put_ethernet_link_all);
}
CipStatus link_get_single(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  return interface_get_single(req, ctx, data, put_ethernet_link_attribute);
}
CipStatus link_set_single(const MrRequest& req, RouterContext&, Writer&) noexcept {
  return interface_set_single(req, kEthernetLinkLastAttribute);
}

// The class attributes (instance 0) of the objects that describe the board, as CIP tools read
// them before the instance's: revision, the highest instance, the number of instances, the
// highest class attribute and the highest instance attribute. A row per class.
struct ClassRow {
  std::uint32_t class_id;
  std::uint16_t revision;
  std::uint16_t last_instance_attribute;
};

constexpr std::array<ClassRow, 3> kClassTable{{
    {kIdentityClass, 1, 8},
    {kTcpIpInterfaceClass, 4, kTcpIpLastAttribute},
    {kEthernetLinkClass, 4, kEthernetLinkLastAttribute},
}};

constexpr std::uint16_t kLastClassAttribute = 7;

const ClassRow* class_row(std::uint32_t class_id) noexcept {
  for (const ClassRow& row : kClassTable) {
    if (row.class_id == class_id) return &row;
  }
  return nullptr;
}

// Get_Attribute_Single of a class attribute: 1, 2, 3, 6 and 7 (4 and 5, the optional attribute
// and service lists, are not kept: 0x14).
CipStatus class_get_single(const MrRequest& req, const ClassRow& row, Writer& data) noexcept {
  if (!req.path.has_attribute) return status(cip_general::kAttributeNotSupported);
  switch (req.path.attribute) {
    case 1:
      data.u16(row.revision);
      return {};
    case 2:  // the highest instance
    case 3:  // how many
      data.u16(1);
      return {};
    case 6:
      data.u16(kLastClassAttribute);
      return {};
    case 7:
      data.u16(row.last_instance_attribute);
      return {};
    default:
      return status(cip_general::kAttributeNotSupported);
  }
}

constexpr std::array<ServiceRow, 13> kServiceTable{{
    {kIdentityClass, cip_service::kGetAttributesAll, identity_get_all},
    {kIdentityClass, cip_service::kGetAttributeSingle, identity_get_single},
    {kAssemblyClass, cip_service::kGetAttributeSingle, assembly_get_single},
    {kAssemblyClass, cip_service::kSetAttributeSingle, assembly_set_single},
    {kConnectionManagerClass, cm_service::kForwardOpen, cm_forward_open},
    {kConnectionManagerClass, cm_service::kLargeForwardOpen, cm_large_forward_open},
    {kConnectionManagerClass, cm_service::kForwardClose, cm_forward_close},
    {kTcpIpInterfaceClass, cip_service::kGetAttributesAll, tcpip_get_all},
    {kTcpIpInterfaceClass, cip_service::kGetAttributeSingle, tcpip_get_single},
    {kTcpIpInterfaceClass, cip_service::kSetAttributeSingle, tcpip_set_single},
    {kEthernetLinkClass, cip_service::kGetAttributesAll, link_get_all},
    {kEthernetLinkClass, cip_service::kGetAttributeSingle, link_get_single},
    {kEthernetLinkClass, cip_service::kSetAttributeSingle, link_set_single},
}};
}  // namespace

std::span<const ServiceRow> service_table() noexcept {
  return kServiceTable;
}

CipStatus dispatch(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept {
  const bool class_instance = req.path.has_instance && req.path.instance == 0;
  if (class_instance && req.service == cip_service::kGetAttributeSingle) {
    if (const ClassRow* row = class_row(req.path.class_id))
      return class_get_single(req, *row, data);
  }
  bool class_known = false;
  for (const ServiceRow& row : kServiceTable) {
    if (row.class_id != req.path.class_id) continue;
    class_known = true;
    if (row.service == req.service) return row.handler(req, ctx, data);
  }
  return status(class_known ? cip_general::kServiceNotSupported
                            : cip_general::kPathDestinationUnknown);
}

}  // namespace stepmod::enip
