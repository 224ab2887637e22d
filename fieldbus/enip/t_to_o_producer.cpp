#include "fieldbus/enip/t_to_o_producer.hpp"

#include <algorithm>

#include "fieldbus/enip/io_packet.hpp"

namespace stepmod::enip {

std::size_t TtoProducer::produce(std::size_t slot, IoConnection& c,
                                 std::span<const std::uint8_t> input, std::int64_t now_ns,
                                 std::span<std::uint8_t> out) noexcept {
  if (slot >= last_.size() || input.size() > kMaxAssemblyBytes) {
    IoConnections::advance(c, now_ns);
    return 0;
  }
  Last& last = last_[slot];
  const bool fresh = last.ot_id != c.ot_id;  // a connection new in this slot
  const bool changed = fresh || last.size != input.size() ||
                       !std::equal(input.begin(), input.end(), last.data.begin());
  if (fresh) {
    last = Last{};
    last.ot_id = c.ot_id;
  }
  if (changed) {
    ++last.cip_sequence;
    last.size = input.size();
    std::copy(input.begin(), input.end(), last.data.begin());
  }
  // advance() counts the packet: the one written now carries the count after it.
  const std::size_t n =
      encode_t_to_o(out, c.to_id, c.to_encap_sequence + 1, last.cip_sequence, input);
  IoConnections::advance(c, now_ns);
  return n;
}

}  // namespace stepmod::enip
