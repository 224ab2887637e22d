#pragma once
// CIP general statuses and the Connection Manager's extended statuses that the adapter answers
// (docs/ethernetip-design.md lists when each is given), and a refusal as one value.
#include <array>
#include <cstdint>

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

namespace cip_general {
inline constexpr std::uint8_t kSuccess = 0x00;
inline constexpr std::uint8_t kConnectionFailure = 0x01;  // with a Connection Manager status
inline constexpr std::uint8_t kPathSegmentError = 0x04;
inline constexpr std::uint8_t kPathDestinationUnknown = 0x05;
inline constexpr std::uint8_t kServiceNotSupported = 0x08;
inline constexpr std::uint8_t kObjectStateConflict = 0x0C;
inline constexpr std::uint8_t kAttributeNotSettable = 0x0E;
inline constexpr std::uint8_t kReplyDataTooLarge = 0x11;
inline constexpr std::uint8_t kNotEnoughData = 0x13;
inline constexpr std::uint8_t kAttributeNotSupported = 0x14;
inline constexpr std::uint8_t kTooMuchData = 0x15;
}  // namespace cip_general

namespace cm_status {
inline constexpr std::uint16_t kDuplicateForwardOpen = 0x0100;
inline constexpr std::uint16_t kOwnershipConflict = 0x0106;
inline constexpr std::uint16_t kConnectionNotFound = 0x0107;
inline constexpr std::uint16_t kRpiNotAcceptable = 0x0112;
inline constexpr std::uint16_t kOutOfConnections = 0x0113;
inline constexpr std::uint16_t kVendorOrProductMismatch = 0x0114;
inline constexpr std::uint16_t kDeviceTypeMismatch = 0x0115;
inline constexpr std::uint16_t kRevisionMismatch = 0x0116;
inline constexpr std::uint16_t kNonListenOnlyNotOpened = 0x0119;
inline constexpr std::uint16_t kTransportClassNotSupported = 0x011C;
inline constexpr std::uint16_t kTriggerNotSupported = 0x011D;
inline constexpr std::uint16_t kDirectionNotSupported = 0x011E;
inline constexpr std::uint16_t kOtConnectionTypeNotSupported = 0x0123;
inline constexpr std::uint16_t kToConnectionTypeNotSupported = 0x0124;
inline constexpr std::uint16_t kRedundantOwnerNotSupported = 0x0125;
inline constexpr std::uint16_t kInvalidConfigurationSize = 0x0126;
inline constexpr std::uint16_t kInvalidOtSize = 0x0127;
inline constexpr std::uint16_t kInvalidToSize = 0x0128;
inline constexpr std::uint16_t kInvalidConfigurationPath = 0x0129;
inline constexpr std::uint16_t kInvalidConsumingPath = 0x012A;
inline constexpr std::uint16_t kInvalidProducingPath = 0x012B;
inline constexpr std::uint16_t kParameterError = 0x0205;
inline constexpr std::uint16_t kPortNotAvailable = 0x0311;
inline constexpr std::uint16_t kInvalidSegmentInPath = 0x0315;
}  // namespace cm_status

// 0x0112's RPI types (the nearest acceptable value of each direction).
namespace rpi_type {
inline constexpr std::uint8_t kAcceptable = 0;
inline constexpr std::uint8_t kMinimum = 2;
inline constexpr std::uint8_t kMaximum = 3;
}  // namespace rpi_type

// A CIP reply's status: the general status and its additional 16-bit words (for a Connection
// Manager refusal, the first is the extended status). 0x0112 has the most: 6 words.
struct CipStatus {
  std::uint8_t general = cip_general::kSuccess;
  std::array<std::uint16_t, 6> words{};
  std::uint8_t word_count = 0;

  bool ok() const noexcept { return general == cip_general::kSuccess; }
  std::uint16_t extended() const noexcept { return word_count > 0 ? words[0] : 0; }

  static CipStatus general_only(std::uint8_t g) noexcept {
    CipStatus s;
    s.general = g;
    return s;
  }
  // General status 0x01 with `ext`, and `more` (the correct size of 0x0127/0x0128).
  static CipStatus connection(std::uint16_t ext) noexcept {
    CipStatus s;
    s.general = cip_general::kConnectionFailure;
    s.words[0] = ext;
    s.word_count = 1;
    return s;
  }
  static CipStatus connection(std::uint16_t ext, std::uint16_t more) noexcept {
    CipStatus s = connection(ext);
    s.words[1] = more;
    s.word_count = 2;
    return s;
  }
};

// The head of a message router reply: service | 0x80, reserved 0, the general status, the
// number of additional status words and the words.
inline void put_reply_status(Writer& w, std::uint8_t service, const CipStatus& st) noexcept {
  w.u8(static_cast<std::uint8_t>(service | 0x80u));
  w.u8(0);
  w.u8(st.general);
  w.u8(st.word_count);
  for (std::size_t i = 0; i < st.word_count; ++i) w.u16(st.words[i]);
}

}  // namespace stepmod::enip
