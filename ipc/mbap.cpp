#include "ipc/mbap.hpp"

namespace stepmod::ipc {

namespace {
std::uint16_t be16(std::span<const std::uint8_t> p, std::size_t at) noexcept {
  return static_cast<std::uint16_t>((p[at] << 8) | p[at + 1]);
}
void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v & 0xFFu));
}
// The MBAP header of a response whose PDU has `pdu_bytes` bytes.
void put_header(std::vector<std::uint8_t>& out, const MbapFrame& request, std::size_t pdu_bytes) {
  put16(out, request.transaction);
  put16(out, 0);
  put16(out, static_cast<std::uint16_t>(1 + pdu_bytes));
  out.push_back(request.unit);
}
}  // namespace

MbapStatus parse_mbap(std::span<const std::uint8_t> buf, MbapFrame& frame) noexcept {
  // Each field is judged as soon as it is there: a client is not waited for to send a frame
  // that is already known to be malformed.
  if (buf.size() >= 4 && be16(buf, 2) != 0) return MbapStatus::kBadProtocol;
  if (buf.size() < 6) return MbapStatus::kIncomplete;
  const std::size_t length = be16(buf, 4);
  if (length < 2 || length > kMbapMaxLength) return MbapStatus::kBadLength;
  if (buf.size() >= 8 && buf[7] >= 0x80) return MbapStatus::kBadFunction;
  const std::size_t size = 6 + length;
  if (buf.size() < size) return MbapStatus::kIncomplete;
  frame.transaction = be16(buf, 0);
  frame.unit = buf[6];
  frame.pdu = buf.subspan(kMbapHeaderBytes, length - 1);
  frame.size = size;
  return MbapStatus::kFrame;
}

void append_exception(std::vector<std::uint8_t>& out, const MbapFrame& request,
                      ModbusException code) {
  put_header(out, request, 2);
  out.push_back(static_cast<std::uint8_t>(request.pdu[0] | 0x80u));
  out.push_back(static_cast<std::uint8_t>(code));
}

void append_response(std::vector<std::uint8_t>& out, const MbapFrame& request,
                     const ModbusResult& r) {
  if (r.exception != ModbusException::kNone) {
    append_exception(out, request, r.exception);
    return;
  }
  switch (r.function) {
    case modbus_fc::kReadHolding:
    case modbus_fc::kReadInput:
      put_header(out, request, 2 + 2u * r.count);
      out.push_back(r.function);
      out.push_back(static_cast<std::uint8_t>(2 * r.count));
      for (unsigned i = 0; i < r.count; ++i) put16(out, r.values[i]);
      return;
    case modbus_fc::kWriteSingle:
      put_header(out, request, 5);
      out.push_back(r.function);
      put16(out, r.address);
      put16(out, r.values[0]);
      return;
    default:  // kWriteMultiple: the only other function ModbusMap answers normally
      put_header(out, request, 5);
      out.push_back(r.function);
      put16(out, r.address);
      put16(out, r.count);
      return;
  }
}

}  // namespace stepmod::ipc
