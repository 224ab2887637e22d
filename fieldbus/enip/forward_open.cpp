#include "fieldbus/enip/forward_open.hpp"

#include "fieldbus/enip/epath.hpp"

namespace stepmod::enip {

namespace {
constexpr std::uint8_t kMaxTimeoutMultiplier = 7;  // 8..255 are reserved
constexpr std::uint16_t kSequenceCountBytes = 2;
constexpr std::uint16_t kRunIdleHeaderBytes = 4;

ConnectionTriad read_triad(Reader& r) noexcept {
  ConnectionTriad t;
  t.connection_serial = r.u16();
  t.originator_vendor = r.u16();
  t.originator_serial = r.u32();
  return t;
}

// The path, `words` 16-bit words long, and nothing after it.
std::uint8_t take_path(Reader& r, std::size_t words, std::span<const std::uint8_t>& path) noexcept {
  path = r.bytes(2 * words);
  if (!r.ok()) return cip_general::kNotEnoughData;
  return r.remaining() == 0 ? cip_general::kSuccess : cip_general::kTooMuchData;
}
}  // namespace

NetParams decode_net_params(std::uint32_t raw, bool large) noexcept {
  NetParams p;
  const unsigned shift = large ? 16 : 0;  // the large word has the small one's flags 16 bits up
  p.redundant_owner = ((raw >> (15 + shift)) & 1u) != 0;
  p.type = static_cast<std::uint8_t>((raw >> (13 + shift)) & 3u);
  p.priority = static_cast<std::uint8_t>((raw >> (10 + shift)) & 3u);
  p.variable = ((raw >> (9 + shift)) & 1u) != 0;
  p.size = static_cast<std::uint16_t>(large ? (raw & 0xFFFFu) : (raw & 0x1FFu));
  return p;
}

std::uint8_t parse_forward_open(std::span<const std::uint8_t> data, bool large,
                                ForwardOpen& out) noexcept {
  Reader r(data);
  out = ForwardOpen{};
  out.large = large;
  out.priority_tick = r.u8();
  out.timeout_ticks = r.u8();
  out.ot_id = r.u32();
  out.to_id = r.u32();
  out.triad = read_triad(r);
  out.timeout_multiplier = r.u8();
  r.skip(3);
  out.ot_rpi_us = r.u32();
  out.ot = decode_net_params(large ? r.u32() : r.u16(), large);
  out.to_rpi_us = r.u32();
  out.to = decode_net_params(large ? r.u32() : r.u16(), large);
  out.transport = r.u8();
  const std::size_t words = r.u8();
  if (!r.ok()) return cip_general::kNotEnoughData;
  return take_path(r, words, out.path);
}

std::uint8_t parse_forward_close(std::span<const std::uint8_t> data, ForwardClose& out) noexcept {
  Reader r(data);
  out = ForwardClose{};
  out.priority_tick = r.u8();
  out.timeout_ticks = r.u8();
  out.triad = read_triad(r);
  const std::size_t words = r.u8();
  r.skip(1);  // reserved
  if (!r.ok()) return cip_general::kNotEnoughData;
  return take_path(r, words, out.path);
}

namespace {
CipStatus check_transport(std::uint8_t transport) noexcept {
  if ((transport & 0x0Fu) != 1)
    return CipStatus::connection(cm_status::kTransportClassNotSupported);
  if ((transport & 0x70u) != 0) return CipStatus::connection(cm_status::kTriggerNotSupported);
  if ((transport & 0x80u) != 0) return CipStatus::connection(cm_status::kDirectionNotSupported);
  return {};
}

CipStatus check_types(const ForwardOpen& fo, ConnectionKind kind) noexcept {
  if (fo.ot.redundant_owner) return CipStatus::connection(cm_status::kRedundantOwnerNotSupported);
  const bool heartbeat = kind != ConnectionKind::kExclusiveOwner;
  const bool ot_ok =
      fo.ot.type == conn_type::kPointToPoint || (heartbeat && fo.ot.type == conn_type::kNull);
  if (!ot_ok) return CipStatus::connection(cm_status::kOtConnectionTypeNotSupported);
  if (fo.to.type != conn_type::kPointToPoint) {
    return CipStatus::connection(cm_status::kToConnectionTypeNotSupported);
  }
  return {};
}

// A zero field of the key matches anything; the compatibility bit accepts an older minor.
CipStatus check_key(const ElectronicKey& key, const IdentityValues& id) noexcept {
  if ((key.vendor != 0 && key.vendor != id.vendor) ||
      (key.product_code != 0 && key.product_code != id.product_code)) {
    return CipStatus::connection(cm_status::kVendorOrProductMismatch);
  }
  if (key.device_type != 0 && key.device_type != id.device_type) {
    return CipStatus::connection(cm_status::kDeviceTypeMismatch);
  }
  const bool major_bad = key.major() != 0 && key.major() != id.major;
  const bool minor_bad =
      key.minor != 0 && (key.compatibility() ? key.minor > id.minor : key.minor != id.minor);
  if (major_bad || minor_bad) return CipStatus::connection(cm_status::kRevisionMismatch);
  return {};
}
}  // namespace

namespace {
// The application path: assembly class, configuration instance 151 (no data), the O→T point
// deciding the kind of connection, T→O point 100.
CipStatus check_app_path(const ConnectionPath& p, ConnectionKind& kind) noexcept {
  if (p.class_id != kAssemblyClass || !p.has_config || p.config_instance != kConfigInstance) {
    return CipStatus::connection(cm_status::kInvalidConfigurationPath);
  }
  if (p.point_count < 1) return CipStatus::connection(cm_status::kInvalidConsumingPath);
  switch (p.points[0]) {
    case kOutputInstance:
      kind = ConnectionKind::kExclusiveOwner;
      break;
    case kInputOnlyHeartbeat:
      kind = ConnectionKind::kInputOnly;
      break;
    case kListenOnlyHeartbeat:
      kind = ConnectionKind::kListenOnly;
      break;
    default:
      return CipStatus::connection(cm_status::kInvalidConsumingPath);
  }
  if (p.point_count < 2 || p.points[1] != kInputInstance) {
    return CipStatus::connection(cm_status::kInvalidProducingPath);
  }
  if (p.has_data && !p.data.empty()) {
    return CipStatus::connection(cm_status::kInvalidConfigurationSize, 0);
  }
  return {};
}

// 0x0112 with, for each direction, whether its RPI is acceptable or the nearest value that is.
CipStatus check_rpi(const ForwardOpen& fo, const AdapterLimits& limits) noexcept {
  std::uint8_t types[2] = {rpi_type::kAcceptable, rpi_type::kAcceptable};
  std::uint32_t values[2] = {fo.ot_rpi_us, fo.to_rpi_us};
  bool refused = false;
  for (int i = 0; i < 2; ++i) {
    if (values[i] < limits.rpi_min_us) {
      types[i] = rpi_type::kMinimum;
      values[i] = limits.rpi_min_us;
      refused = true;
    } else if (values[i] > limits.rpi_max_us) {
      types[i] = rpi_type::kMaximum;
      values[i] = limits.rpi_max_us;
      refused = true;
    }
  }
  if (!refused) return {};
  CipStatus s = CipStatus::connection(cm_status::kRpiNotAcceptable);
  s.words[1] = static_cast<std::uint16_t>(types[0] | (types[1] << 8));
  s.words[2] = static_cast<std::uint16_t>(values[0] & 0xFFFFu);
  s.words[3] = static_cast<std::uint16_t>(values[0] >> 16);
  s.words[4] = static_cast<std::uint16_t>(values[1] & 0xFFFFu);
  s.words[5] = static_cast<std::uint16_t>(values[1] >> 16);
  s.word_count = 6;
  return s;
}

// Connection sizes count the sequence count, and an owner's O→T also the run/idle header. A
// heartbeat (no data) is its sequence count alone; 0 is taken too, as some originators size it.
CipStatus check_sizes(const ForwardOpen& fo, ConnectionKind kind,
                      const AssemblyLayout& layout) noexcept {
  const bool owner = kind == ConnectionKind::kExclusiveOwner;
  const std::uint16_t ot_want =
      owner ? static_cast<std::uint16_t>(layout.output_bytes + kSequenceCountBytes +
                                         kRunIdleHeaderBytes)
            : kSequenceCountBytes;
  const bool ot_ok = fo.ot.size == ot_want || (!owner && fo.ot.size == 0);
  if (!ot_ok) return CipStatus::connection(cm_status::kInvalidOtSize, ot_want);
  const auto to_want = static_cast<std::uint16_t>(layout.input_bytes + kSequenceCountBytes);
  if (fo.to.size != to_want) return CipStatus::connection(cm_status::kInvalidToSize, to_want);
  return {};
}
}  // namespace

CipStatus validate_forward_open(const ForwardOpen& fo, const AssemblyLayout& layout,
                                const IdentityValues& id, const AdapterLimits& limits,
                                AcceptedOpen& out) noexcept {
  ConnectionPath path;
  if (!parse_connection_path(fo.path, path)) {
    return CipStatus::connection(cm_status::kInvalidSegmentInPath);
  }
  if (CipStatus s = check_transport(fo.transport); !s.ok()) return s;
  ConnectionKind kind = ConnectionKind::kExclusiveOwner;
  // The kind (from the O→T point) decides which connection types are allowed, so the path is
  // judged before the types; its refusal still comes after the key's, as listed.
  const CipStatus app = check_app_path(path, kind);
  if (CipStatus s = check_types(fo, kind); !s.ok()) return s;
  if (path.has_key) {
    if (CipStatus s = check_key(path.key, id); !s.ok()) return s;
  }
  if (!app.ok()) return app;
  if (CipStatus s = check_rpi(fo, limits); !s.ok()) return s;
  if (CipStatus s = check_sizes(fo, kind, layout); !s.ok()) return s;
  if (fo.timeout_multiplier > kMaxTimeoutMultiplier) {
    return CipStatus::connection(cm_status::kParameterError);
  }
  out.kind = kind;
  out.timeout_us = static_cast<std::uint64_t>(fo.ot_rpi_us) * (4u << fo.timeout_multiplier);
  return {};
}

CipStatus check_ownership(ConnectionKind kind, const OpenConnections& open) noexcept {
  // A repeated request of an open connection is a duplicate, not a second owner.
  if (open.triad_open) return CipStatus::connection(cm_status::kDuplicateForwardOpen);
  if (kind == ConnectionKind::kExclusiveOwner && open.owner) {
    return CipStatus::connection(cm_status::kOwnershipConflict);
  }
  if (kind == ConnectionKind::kListenOnly && !open.owner && !open.input_only) {
    return CipStatus::connection(cm_status::kNonListenOnlyNotOpened);
  }
  if (open.free_slots == 0) return CipStatus::connection(cm_status::kOutOfConnections);
  return {};
}

namespace {
void put_triad(Writer& w, const ConnectionTriad& triad) noexcept {
  w.u16(triad.connection_serial);
  w.u16(triad.originator_vendor);
  w.u32(triad.originator_serial);
}
}  // namespace

void put_forward_open_success(Writer& w, const ForwardOpen& fo, std::uint32_t ot_id,
                              std::uint32_t to_id) noexcept {
  w.u32(ot_id);
  w.u32(to_id);
  put_triad(w, fo.triad);
  w.u32(fo.ot_rpi_us);  // the actual packet intervals: as requested
  w.u32(fo.to_rpi_us);
  w.u8(0);  // application reply size (words)
  w.u8(0);  // reserved
}

void put_triad_reply(Writer& w, const ConnectionTriad& triad) noexcept {
  put_triad(w, triad);
  w.u8(0);  // a refusal's remaining path size (we route nothing), or Forward_Close's
            // application reply size (words)
  w.u8(0);  // reserved
}

}  // namespace stepmod::enip
