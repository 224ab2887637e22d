#pragma once
// The Identity object (class 0x01, instance 1): its values per module type, as documented in
// docs/ethernetip-design.md ("Identity"), and their encodings for Get_Attributes_All,
// Get_Attribute_Single and ListIdentity's CIP identity item.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

// stepmod has no ODVA vendor id: it claims no registered vendor's.
inline constexpr std::uint16_t kVendorId = 0xFFFF;
// Generic device (keyable): no CIP device profile's objects are implemented.
inline constexpr std::uint16_t kDeviceType = 0x2B;
// Changes when the words or the assembly instances change.
inline constexpr std::uint8_t kRevisionMajor = 1;
inline constexpr std::uint8_t kRevisionMinor = 1;
inline constexpr std::uint8_t kStateOperational = 3;
inline constexpr std::size_t kProductNameMax = 32;  // SHORT_STRING as the Identity object caps it

// Attribute 5, status: bit 0 owned; bits 4-7 the extended device status.
namespace identity_status {
inline constexpr std::uint16_t kOwned = 0x0001;
inline constexpr std::uint16_t kNoIoConnection = 3u << 4;
inline constexpr std::uint16_t kIoInRun = 6u << 4;
inline constexpr std::uint16_t kIoAllIdle = 7u << 4;
}  // namespace identity_status

struct IdentityValues {
  std::uint16_t vendor = kVendorId;
  std::uint16_t device_type = kDeviceType;
  std::uint16_t product_code = 0;  // the module type: 3601, 3602 or 3202
  std::uint8_t major = kRevisionMajor;
  std::uint8_t minor = kRevisionMinor;
  std::uint16_t status = identity_status::kNoIoConnection;
  std::uint32_t serial = 0;
  std::array<char, kProductNameMax> name{};
  std::uint8_t name_length = 0;
  std::uint8_t state = kStateOperational;

  std::string_view product_name() const noexcept { return {name.data(), name_length}; }
};

// The values of a module of `module_type` (3601, 3602 or 3202), with `serial`.
IdentityValues identity_for(std::uint32_t module_type, std::uint32_t serial) noexcept;

// A serial number stable across restarts and distinct per module of a rack: FNV-1a (32-bit) of
// the machine id and the module's name. 0 (which CIP tools show as "none") is never returned.
std::uint32_t identity_serial(std::string_view machine_id, std::string_view module_name) noexcept;

// Attribute 5 from the connections: `owned` an exclusive owner exists; `connections` I/O
// connections open; `any_run` at least one of them in Run.
std::uint16_t identity_status_word(bool owned, unsigned connections, bool any_run) noexcept;

// Get_Attributes_All reply data: attributes 1 to 7 in order (vendor, device type, product code,
// revision, status, serial, product name).
void put_identity_all(Writer& w, const IdentityValues& id) noexcept;

// Get_Attribute_Single reply data for `attribute`; false for an attribute the object does not
// have (the caller answers general status 0x14).
bool put_identity_attribute(Writer& w, const IdentityValues& id, std::uint8_t attribute) noexcept;

// The fields of ListIdentity's CIP identity item that follow its socket address: vendor ...
// product name, state.
void put_identity_item_tail(Writer& w, const IdentityValues& id) noexcept;

}  // namespace stepmod::enip
