#include "fieldbus/enip/epath.hpp"

namespace stepmod::enip {

namespace {
constexpr std::uint8_t kKeyFormat = 4;  // the only electronic key format CIP defines
constexpr std::uint8_t kSimpleData = 0x80;

bool kind_of_logical(std::uint8_t type, SegmentKind& kind) noexcept {
  switch (type) {
    case 0:
      kind = SegmentKind::kClass;
      return true;
    case 1:
      kind = SegmentKind::kInstance;
      return true;
    case 3:
      kind = SegmentKind::kConnectionPoint;
      return true;
    case 4:
      kind = SegmentKind::kAttribute;
      return true;
    default:
      return false;  // member, service id, extended logical: not served
  }
}
}  // namespace

bool EpathReader::logical(std::uint8_t type_byte, Segment& s) noexcept {
  const std::uint8_t type = (type_byte >> 2) & 0x07u;
  const std::uint8_t format = type_byte & 0x03u;
  if (type == 5) {  // special: the electronic key
    if (format != 0 || r_.u8() != kKeyFormat) return fail();
    s.kind = SegmentKind::kElectronicKey;
    s.key.vendor = r_.u16();
    s.key.device_type = r_.u16();
    s.key.product_code = r_.u16();
    s.key.major_byte = r_.u8();
    s.key.minor = r_.u8();
    return r_.ok() ? true : fail();
  }
  if (!kind_of_logical(type, s.kind)) return fail();
  switch (format) {
    case 0:
      s.value = r_.u8();
      break;
    case 1:
      r_.skip(1);
      s.value = r_.u16();
      break;
    case 2:
      r_.skip(1);
      s.value = r_.u32();
      break;
    default:
      return fail();
  }
  return r_.ok() ? true : fail();
}

bool EpathReader::port(std::uint8_t type_byte, Segment& s) noexcept {
  const std::size_t start = r_.pos() - 1;
  const bool extended_link = (type_byte & 0x10u) != 0;
  const std::size_t link_size = extended_link ? r_.u8() : 1;
  s.kind = SegmentKind::kPort;
  s.value = type_byte & 0x0Fu;
  if (s.value == 15) s.value = r_.u16();
  s.data = r_.bytes(link_size);
  if ((r_.pos() - start) % 2 != 0) r_.skip(1);  // padded to an even length
  return r_.ok() && link_size > 0 ? true : fail();
}

bool EpathReader::next(Segment& s) noexcept {
  if (failed_ || r_.remaining() == 0) return false;
  s = Segment{};
  const std::uint8_t type_byte = r_.u8();
  switch (type_byte >> 5) {
    case 0:
      return port(type_byte, s);
    case 1:
      return logical(type_byte, s);
    case 2:  // network segment: one byte of value
      s.kind = SegmentKind::kNetwork;
      s.value = type_byte;
      r_.skip(1);
      return r_.ok() ? true : fail();
    default:
      break;
  }
  if (type_byte != kSimpleData) return fail();  // symbolic, ANSI extended: not served
  s.kind = SegmentKind::kData;
  const std::size_t words = r_.u8();
  s.data = r_.bytes(2 * words);
  return r_.ok() ? true : fail();
}

bool parse_request_path(std::span<const std::uint8_t> path, RequestPath& out) noexcept {
  out = RequestPath{};
  EpathReader reader(path);
  Segment s;
  if (!reader.next(s) || s.kind != SegmentKind::kClass) return false;
  out.class_id = s.value;
  while (reader.next(s)) {
    if (s.kind == SegmentKind::kInstance && !out.has_instance) {
      out.instance = s.value;
      out.has_instance = true;
    } else if (s.kind == SegmentKind::kAttribute && out.has_instance && !out.has_attribute) {
      out.attribute = s.value;
      out.has_attribute = true;
    } else {
      return false;
    }
  }
  return !reader.failed();
}

namespace {
// A field a connection path gives at most once: taken when `allowed` and not given yet.
template <typename Field, typename Value>
bool take_once(bool& given, Field& field, const Value& value, bool allowed = true) noexcept {
  if (given || !allowed) return false;
  given = true;
  field = value;
  return true;
}

// One segment of a connection path, in the order key, class, config instance, points, data.
bool take_connection_segment(const Segment& s, ConnectionPath& out) noexcept {
  const bool after_points = out.point_count > 0 || out.has_data;
  switch (s.kind) {
    case SegmentKind::kElectronicKey:
      return take_once(out.has_key, out.key, s.key, !out.has_class);
    case SegmentKind::kClass:
      return take_once(out.has_class, out.class_id, s.value);
    case SegmentKind::kInstance:
      return take_once(out.has_config, out.config_instance, s.value,
                       out.has_class && !after_points);
    case SegmentKind::kConnectionPoint:
      if (!out.has_class || out.point_count == 2 || out.has_data) return false;
      out.points[out.point_count++] = s.value;
      return true;
    case SegmentKind::kData:
      return take_once(out.has_data, out.data, s.data);
    case SegmentKind::kNetwork:
      return true;  // production inhibit time and its kin: nothing we act on
    default:
      return false;  // a port (routing) or an attribute: not in a connection path to us
  }
}
}  // namespace

bool parse_connection_path(std::span<const std::uint8_t> path, ConnectionPath& out) noexcept {
  out = ConnectionPath{};
  EpathReader reader(path);
  Segment s;
  while (reader.next(s)) {
    if (!take_connection_segment(s, out)) return false;
  }
  return !reader.failed() && out.has_class;
}

}  // namespace stepmod::enip
