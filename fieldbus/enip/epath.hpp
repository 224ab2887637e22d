#pragma once
// Padded EPATHs (CIP's paths to objects): the request path of a message router request, and a
// Forward_Open's connection path (docs/ethernetip-design.md, "Connection Manager"). Segments
// are read one at a time as views into the packet; nothing is copied or allocated.
//
//   logical  001 TTT FF: T class 0, instance 1, connection point 3, attribute 4, special 5
//            (electronic key); F 8-bit value, 16-bit (pad byte first), 32-bit (pad byte first)
//   port     000 E PPPP: port P (15: a u16 follows), link address 1 byte or E: a size byte
//            and that many bytes; the segment is padded to an even length
//   network  010 xxxxx: one byte of value (production inhibit time and its kin): skipped
//   data     1000 0000: simple data segment, a size in words and the words
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

struct ElectronicKey {
  std::uint16_t vendor = 0;
  std::uint16_t device_type = 0;
  std::uint16_t product_code = 0;
  std::uint8_t major_byte = 0;  // bit 7: compatibility; bits 0-6: the major revision
  std::uint8_t minor = 0;

  bool compatibility() const noexcept { return (major_byte & 0x80u) != 0; }
  std::uint8_t major() const noexcept { return major_byte & 0x7Fu; }
};

enum class SegmentKind {
  kClass,
  kInstance,
  kConnectionPoint,
  kAttribute,
  kElectronicKey,
  kPort,     // value = port number, data = link address
  kNetwork,  // value = the segment byte (skipped by the users here)
  kData,     // data = the simple data segment's words
};

struct Segment {
  SegmentKind kind = SegmentKind::kClass;
  std::uint32_t value = 0;
  ElectronicKey key;
  std::span<const std::uint8_t> data;
};

// Reads the segments of one path, in order.
class EpathReader {
 public:
  explicit EpathReader(std::span<const std::uint8_t> path) noexcept : r_(path) {}
  // The next segment; false at the end of the path, or on a segment that is malformed or of a
  // kind not served here (then failed()).
  bool next(Segment& s) noexcept;
  bool failed() const noexcept { return failed_; }

 private:
  bool logical(std::uint8_t type_byte, Segment& s) noexcept;
  bool port(std::uint8_t type_byte, Segment& s) noexcept;
  bool fail() noexcept {
    failed_ = true;
    return false;
  }
  Reader r_;
  bool failed_ = false;
};

// A message router request path: class, then optionally instance and attribute.
struct RequestPath {
  std::uint32_t class_id = 0;
  std::uint32_t instance = 0;
  std::uint32_t attribute = 0;
  bool has_instance = false;
  bool has_attribute = false;
};
// False for anything else (a port, a key, a repeated or out-of-order segment).
bool parse_request_path(std::span<const std::uint8_t> path, RequestPath& out) noexcept;

// What a Forward_Open's connection path names: [key] class [config instance] points... [data].
struct ConnectionPath {
  bool has_key = false;
  ElectronicKey key;
  bool has_class = false;
  std::uint32_t class_id = 0;
  bool has_config = false;
  std::uint32_t config_instance = 0;
  std::uint32_t points[2] = {0, 0};  // the O→T (consumed) point, then the T→O (produced) one
  unsigned point_count = 0;
  bool has_data = false;
  std::span<const std::uint8_t> data;
};
// False for a malformed path, or segments in an order the Forward_Open does not allow.
bool parse_connection_path(std::span<const std::uint8_t> path, ConnectionPath& out) noexcept;

}  // namespace stepmod::enip
