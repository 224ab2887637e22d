#include "fieldbus/enip/cpf.hpp"

namespace stepmod::enip {

CpfParse parse_cpf(std::span<const std::uint8_t> buf, Cpf& cpf) noexcept {
  Reader r(buf);
  const std::size_t count = r.u16();
  if (!r.ok()) return CpfParse::kTruncated;
  if (count == 0 || count > kCpfMaxItems) return CpfParse::kTooManyItems;
  for (std::size_t i = 0; i < count; ++i) {
    CpfItem item;
    item.type = r.u16();
    const std::size_t length = r.u16();
    item.data = r.bytes(length);
    if (!r.ok()) return CpfParse::kTruncated;
    cpf.items[i] = item;
  }
  if (r.remaining() != 0) return CpfParse::kTrailingBytes;
  cpf.count = count;
  return CpfParse::kOk;
}

CpfParse parse_send_data(std::span<const std::uint8_t> buf, SendData& out) noexcept {
  Reader r(buf);
  out.interface_handle = r.u32();
  out.timeout = r.u16();
  if (!r.ok()) return CpfParse::kTruncated;
  return parse_cpf(r.rest(), out.cpf);
}

CpfItemWriter::CpfItemWriter(Writer& w, std::uint16_t type) noexcept : w_(w) {
  w_.u16(type);
  length_at_ = w_.size();
  w_.u16(0);
}

void CpfItemWriter::end() noexcept {
  const std::size_t length = w_.size() - (length_at_ + 2);
  if (length > 0xFFFFu) {
    w_.patch_u16(w_.size() + 1, 0);  // cannot patch: marks the writer failed
    return;
  }
  w_.patch_u16(length_at_, static_cast<std::uint16_t>(length));
}

void put_item(Writer& w, std::uint16_t type, std::span<const std::uint8_t> data) noexcept {
  CpfItemWriter item(w, type);
  w.bytes(data);
  item.end();
}

}  // namespace stepmod::enip
