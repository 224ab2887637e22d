#include "fieldbus/enip/io_packet.hpp"

#include "fieldbus/enip/cpf.hpp"
#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

namespace {
constexpr std::size_t kSequencedAddressBytes = 8;
}  // namespace

IoParse parse_o_to_t(std::span<const std::uint8_t> datagram, const IoShape& shape,
                     IoPacket& out) noexcept {
  Cpf cpf;
  if (parse_cpf(datagram, cpf) != CpfParse::kOk || cpf.count != 2) return IoParse::kMalformed;
  const CpfItem& address = cpf.items[0];
  const CpfItem& data = cpf.items[1];
  if (address.type != cpf_item::kSequencedAddress ||
      address.data.size() != kSequencedAddressBytes || data.type != cpf_item::kConnectedData) {
    return IoParse::kMalformed;
  }
  Reader a(address.data);
  out.connection_id = a.u32();
  out.encap_sequence = a.u32();
  Reader d(data.data);
  out.cip_sequence = d.u16();
  out.run = shape.run_idle_header ? (d.u32() & 1u) != 0 : false;
  if (!d.ok()) return IoParse::kMalformed;
  out.data = d.rest();
  return out.data.size() == shape.data_bytes ? IoParse::kOk : IoParse::kWrongSize;
}

std::size_t encode_t_to_o(std::span<std::uint8_t> out, std::uint32_t connection_id,
                          std::uint32_t encap_sequence, std::uint16_t cip_sequence,
                          std::span<const std::uint8_t> data) noexcept {
  Writer w(out);
  w.u16(2);
  CpfItemWriter address(w, cpf_item::kSequencedAddress);
  w.u32(connection_id);
  w.u32(encap_sequence);
  address.end();
  CpfItemWriter connected(w, cpf_item::kConnectedData);
  w.u16(cip_sequence);
  w.bytes(data);
  connected.end();
  return w.ok() ? w.size() : 0;
}

}  // namespace stepmod::enip
