#pragma once
// The Modbus register map of docs/interface.md section 6 over a stepmod image: one request PDU in,
// register values or an exception code out. No sockets (ipc/modbus_server does the TCP side), so
// every rule is unit-tested on an image in ordinary memory.
//
//   input registers (function 4)   0 .. N-1     the module's input words
//                                  1000 .. 1019 header, health fields and reason item codes
//                                               (see kHeader* below)
//   holding registers (3, 6, 16)   0 .. M-1     the module's output words
//
// A 16-bit word is one register; a 32-bit word (3202) is two, high half first.
#include <array>
#include <cstdint>
#include <span>

#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

// Modbus exception codes (Modbus Application Protocol v1.1b3, section 7).
enum class ModbusException : std::uint8_t {
  kNone = 0,
  kIllegalFunction = 0x01,
  kIllegalDataAddress = 0x02,
  kIllegalDataValue = 0x03,
  kServerDeviceFailure = 0x04,
  kServerDeviceBusy = 0x06,
  kGatewayTargetFailed = 0x0B,
};

// The request/response limits of the protocol (PDU of at most 253 bytes).
inline constexpr unsigned kModbusMaxRead = 125;   // functions 3 and 4
inline constexpr unsigned kModbusMaxWrite = 123;  // function 16

// Input registers from 1000: the header of docs/interface.md 3, the health fields of 3.3 and the
// item codes of the error reasons (3.4).
inline constexpr std::uint16_t kHeaderBase = 1000;
inline constexpr unsigned kHeaderRegisters = 20;
enum HeaderRegister : std::uint16_t {
  kHeaderModuleType = 0,  // 3601, 3602 or 3202
  kHeaderWordBytes = 1,   // 2 or 4
  kHeaderOutputWords = 2,
  kHeaderInputWords = 3,
  kHeaderScanLow = 4,   // scan counter bits 15..0
  kHeaderScanHigh = 5,  // scan counter bits 31..16
  kHeaderHealthLow = 6,
  kHeaderHealthHigh = 7,
  kHeaderLateLow = 8,
  kHeaderLateHigh = 9,
  // 10 .. 15 reserved: read as 0
  // The error reasons' item codes (docs/interface.md 3.4, docs/error-reasons.md), high half first.
  kHeaderReason1High = 16,
  kHeaderReason1Low = 17,
  kHeaderReason2High = 18,
  kHeaderReason2Low = 19,
};

namespace modbus_fc {
inline constexpr std::uint8_t kReadHolding = 0x03;
inline constexpr std::uint8_t kReadInput = 0x04;
inline constexpr std::uint8_t kWriteSingle = 0x06;
inline constexpr std::uint8_t kWriteMultiple = 0x10;
}  // namespace modbus_fc

struct ModbusResult {
  ModbusException exception = ModbusException::kNone;
  std::uint8_t function = 0;
  std::uint16_t address = 0;
  std::uint16_t count = 0;
  // Reads: the registers read. Writes: the registers written (the reply echoes the request).
  std::array<std::uint16_t, kModbusMaxRead> values{};
  bool wrote = false;  // an accepted write reached the output image (and bumped the heartbeat)
};

class ModbusMap {
 public:
  // `image` must stay valid and have a valid header (word size 2 or 4, at most 16 words).
  // `writes`: [modbus] writes; false refuses functions 6 and 16 with exception 01.
  ModbusMap(stepmod_image_t& image, bool writes);

  unsigned input_registers() const noexcept { return input_regs_; }
  unsigned holding_registers() const noexcept { return holding_regs_; }

  // `pdu`: function code and data, as in the MBAP frame after the unit id.
  ModbusResult handle(std::span<const std::uint8_t> pdu) noexcept;

 private:
  ModbusResult read_inputs(ModbusResult r) const noexcept;
  ModbusResult read_holding(ModbusResult r) const noexcept;
  ModbusResult write(ModbusResult r) noexcept;
  // Register `reg` of a word image holding `word_bytes`-byte words.
  std::uint16_t reg_of(const std::int32_t* words, unsigned reg) const noexcept;

  stepmod_image_t& img_;
  bool writes_;
  unsigned word_bytes_;
  unsigned output_words_;
  unsigned input_words_;
  unsigned input_regs_;
  unsigned holding_regs_;
};

}  // namespace stepmod::ipc
