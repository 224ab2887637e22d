// The parsers on mutated packets (docs/ethernetip-design.md, "Fuzz plan", its deterministic
// part): valid packets with bytes flipped, overwritten, inserted and cut, a fixed seed. Nothing
// may crash or read outside the packet (ASan/UBSan run this), and every view a parser returns
// lies inside the packet it was given.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "fieldbus/enip/cpf.hpp"
#include "fieldbus/enip/encap.hpp"
#include "fieldbus/enip/encap_replies.hpp"
#include "fieldbus/enip/encap_session.hpp"
#include "fieldbus/enip/epath.hpp"
#include "fieldbus/enip/forward_open.hpp"
#include "fieldbus/enip/io_packet.hpp"
#include "fieldbus/enip/message_router.hpp"
#include "tests/enip/enip_bytes.hpp"
#include "tests/enip/mutation_corpus.hpp"
#include "tests/enip/router_fakes.hpp"

namespace stepmod::enip {
namespace {

using test::cat;
using test::hex;
using Bytes = std::vector<std::uint8_t>;

bool inside(std::span<const std::uint8_t> part, std::span<const std::uint8_t> whole) {
  if (part.empty()) return true;
  return part.data() >= whole.data() && part.data() + part.size() <= whole.data() + whole.size();
}

// A TCP stream's worth of frames, as the server will take them.
void take_frames(std::span<const std::uint8_t> stream) {
  SessionTable sessions;
  std::array<std::uint8_t, kEncapMaxFrame> out{};
  while (!stream.empty()) {
    EncapFrame f;
    const EncapParse p = parse_encap(stream, f);
    if (p != EncapParse::kFrame && p != EncapParse::kDiscard) return;
    ASSERT_TRUE(inside(f.data, stream));
    ASSERT_LE(f.size, stream.size());
    if (p == EncapParse::kFrame && f.header.command == encap_cmd::kRegisterSession) {
      (void)handle_register_session(out, f, sessions, 1);
    }
    SendData s;
    if (parse_send_data(f.data, s) == CpfParse::kOk) {
      for (std::size_t i = 0; i < s.cpf.count; ++i) {
        ASSERT_TRUE(inside(s.cpf.items[i].data, f.data));
      }
    }
    stream = stream.subspan(f.size);
  }
}

void take_cip(std::span<const std::uint8_t> b) {
  RequestPath rp;
  (void)parse_request_path(b, rp);
  ConnectionPath cp;
  if (parse_connection_path(b, cp)) {
    ASSERT_TRUE(inside(cp.data, b));
  }
  for (const bool large : {false, true}) {
    ForwardOpen fo;
    if (parse_forward_open(b, large, fo) != cip_general::kSuccess) continue;
    ASSERT_TRUE(inside(fo.path, b));
    AcceptedOpen a;
    const CipStatus s = validate_forward_open(fo, assembly_layout(2, 8, 8), identity_for(3601, 1),
                                              AdapterLimits{}, a);
    ASSERT_LE(s.word_count, s.words.size());
  }
  ForwardClose fc;
  if (parse_forward_close(b, fc) == cip_general::kSuccess) {
    ASSERT_TRUE(inside(fc.path, b));
  }
  IoPacket io;
  if (parse_o_to_t(b, IoShape{true, 16}, io) != IoParse::kMalformed) {
    ASSERT_TRUE(inside(io.data, b));
  }
}

// The router on a mutated message, with an owner open: whatever the bytes, the reply is written
// whole and the output words are not.
void route_with_owner(std::span<const std::uint8_t> b) {
  test::FakeAssemblies assemblies;
  test::FakeConnections connections;
  connections.owner = true;
  const IdentityValues id = identity_for(3601, 1);
  test::FakeNetwork network;
  RouterContext ctx{id,      assembly_layout(2, 8, 8), AdapterLimits{}, assemblies, connections,
                    network, RequestOrigin{}};
  std::array<std::uint8_t, kEncapMaxFrame> out{};
  Writer w(out);
  route_message(b, ctx, w);
  ASSERT_TRUE(w.ok());
  ASSERT_GE(w.size(), 4u);
  ASSERT_EQ(assemblies.writes, 0);
}

// The session layer on a mutated stream and datagram, an owner open: replies fit, frames are
// consumed forward, the output words are not written.
void session_with_owner(std::span<const std::uint8_t> b) {
  test::FakeAssemblies assemblies;
  test::FakeConnections connections;
  connections.owner = true;
  SessionTable sessions;
  const IdentityValues id = identity_for(3202, 1);
  test::FakeNetwork network;
  RouterContext router{id,
                       assembly_layout(4, 16, 16),
                       AdapterLimits{},
                       assemblies,
                       connections,
                       network,
                       RequestOrigin{}};
  EncapContext ctx{sessions, id, SocketAddress{}, router};
  std::array<std::uint8_t, kEncapMaxFrame> out{};
  std::span<const std::uint8_t> stream = b;
  for (;;) {
    const SessionStep s = handle_tcp(stream, 1, ctx, out);
    ASSERT_LE(s.reply_size, out.size());
    if (s.consumed == 0 || s.action == SessionAction::kClose) break;
    ASSERT_LE(s.consumed, stream.size());
    stream = stream.subspan(s.consumed);
  }
  ASSERT_LE(handle_udp(b, ctx, out), out.size());
  ASSERT_EQ(assemblies.writes, 0);
}

TEST(EnipMutation, ParsersSurviveMutatedPackets) {
  std::mt19937 rng(20261128);
  for (const Bytes& seed : test::mutation_seeds()) {
    for (int i = 0; i < 3000; ++i) {
      const Bytes b = test::mutate(seed, rng);
      take_frames(b);
      take_cip(b);
      route_with_owner(b);
      session_with_owner(b);
      if (HasFatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace stepmod::enip
