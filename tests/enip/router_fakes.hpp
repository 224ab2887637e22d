#pragma once
// The image, the connection table and the board's interface as the message router sees them, for
// its tests: the assemblies count writes, the connections keep one owner; and the router with
// them.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

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

// The board's interface as the objects' tests know it: 10.0.0.5/24 on eth0, one gateway and
// name server, 100 Mbit/s full duplex auto-negotiated; only for the board's own address.
class FakeNetwork : public NetworkPort {
 public:
  static constexpr std::uint32_t kBoardIp = 0x0A000005u;
  bool describe(std::uint32_t local_ip, NetInterface& out) noexcept override {
    ++asked;
    if (local_ip != kBoardIp) return false;
    out = NetInterface{};
    out.ip = kBoardIp;
    out.mask = 0xFFFFFF00u;
    out.gateway = 0x0A000001u;
    out.name_server = 0x0A000001u;
    out.domain.assign("plant.local");
    out.host_name.assign("stepmod-pi");
    out.label.assign("eth0");
    out.mac = {0xD8, 0x3A, 0xDD, 0x01, 0x02, 0x03};
    out.speed_mbps = 100;
    out.link_up = true;
    out.admin_up = true;
    out.duplex = Duplex::kFull;
    out.negotiation = Negotiation::kAuto;
    out.can_negotiate = true;
    out.medium = Medium::kTwistedPair;
    out.counters.interface[0] = 0x11223344u;
    out.counters.media[1] = 7;
    return true;
  }
  int asked = 0;
};

// The message router with the fakes above: a request in, its whole reply out, as it came in on
// the fake board's address (or `local_ip`).
class RouterFixture : public ::testing::Test {
 protected:
  std::vector<std::uint8_t> ask(const std::vector<std::uint8_t>& message,
                                std::uint32_t local_ip = FakeNetwork::kBoardIp) {
    std::array<std::uint8_t, 600> out{};
    Writer w(out);
    RouterContext ctx{identity,
                      assembly_layout(2, 8, 8),
                      AdapterLimits{},
                      assemblies,
                      connections,
                      network,
                      RequestOrigin{0x0A000002u, 0, local_ip}};
    route_message(message, ctx, w);
    EXPECT_TRUE(w.ok());
    return {w.written().begin(), w.written().end()};
  }
  IdentityValues identity = identity_for(3601, 0x01020304u);
  FakeAssemblies assemblies;
  FakeConnections connections;
  FakeNetwork network;
};

}  // namespace stepmod::enip::test
