#pragma once
// The image and the connection table as the message router sees them, for its tests: the
// assemblies count writes, the connections keep one owner.
#include <array>
#include <cstdint>
#include <span>

#include "fieldbus/enip/message_router.hpp"

namespace stepmod::enip::test {

class FakeAssemblies : public AssemblyData {
 public:
  void read(std::uint32_t instance, std::span<std::uint8_t> out) noexcept override {
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i] = static_cast<std::uint8_t>(instance == kInputInstance ? 0x10 + i : output[i]);
    }
  }
  void write_output(std::span<const std::uint8_t> bytes) noexcept override {
    ++writes;
    for (std::size_t i = 0; i < bytes.size(); ++i) output[i] = bytes[i];
  }
  std::array<std::uint8_t, 64> output{};
  int writes = 0;
};

class FakeConnections : public ConnectionTable {
 public:
  bool owner_open() const noexcept override { return owner; }
  CipStatus open(const ForwardOpen& fo, const AcceptedOpen& accepted, const RequestOrigin&,
                 std::uint32_t& ot_id) noexcept override {
    OpenConnections state;
    state.owner = owner;
    state.free_slots = 4;
    const CipStatus st = check_ownership(accepted.kind, state);
    if (!st.ok()) return st;
    owner = accepted.kind == ConnectionKind::kExclusiveOwner;
    triad = fo.triad;
    ot_id = 0xA0B0C0D0u;
    return {};
  }
  CipStatus close(const ConnectionTriad& t) noexcept override {
    if (!owner || !(t == triad)) return CipStatus::connection(cm_status::kConnectionNotFound);
    owner = false;
    return {};
  }
  bool owner = false;
  ConnectionTriad triad;
};

}  // namespace stepmod::enip::test
