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
#include "fieldbus/enip/epath.hpp"
#include "fieldbus/enip/forward_open.hpp"
#include "fieldbus/enip/io_packet.hpp"
#include "fieldbus/enip/encap_session.hpp"
#include "fieldbus/enip/message_router.hpp"
#include "tests/enip/enip_bytes.hpp"
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

Bytes mutate(Bytes b, std::mt19937& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = b.empty() ? 0 : rng() % b.size();
    switch (rng() % 5) {
      case 0: if (!b.empty()) b[at] ^= static_cast<std::uint8_t>(1u << (rng() % 8)); break;
      case 1: if (!b.empty()) b[at] = static_cast<std::uint8_t>(rng()); break;
      case 2: b.insert(b.begin() + static_cast<long>(at), static_cast<std::uint8_t>(rng())); break;
      case 3: b.resize(at); break;
      default: if (!b.empty()) b[at] = (rng() % 2) != 0 ? 0xFF : 0x00; break;
    }
  }
  return b;
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

const Bytes kForwardOpen = hex(
    "03 7d 00000000 78563412 3412 3333 37130000 03 000000 10270000 1648 10270000 1248 01"
    "09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");

std::vector<Bytes> seeds() {
  const Bytes reg = hex("6500 0400 00000000 00000000 0000000000000000 00000000 0100 0000");
  const Bytes rr_head = hex("6f00 4c00 01000000 00000000 0000000000000000 00000000"
                            "00000000 0a00 0200 0000 0000 b200 3c00 54 02 20 06 24 01");
  return {reg,
          cat(reg, cat(rr_head, kForwardOpen)),
          cat(reg, hex("6f00 2400 01000000 00000000 0000000000000000 00000000"
                       "00000000 0a00 0200 0000 0000 b200 1400"
                       "52 02 20 06 24 01 07 f9 0600 01 02 20 01 24 01 01 00 01 00")),
          hex("6300 0000 00000000 00000000 0000000000000000 00000000"),
          kForwardOpen,
          hex("03 7d 3412 3333 37130000 03 00 01 00 20 02 24 01"),
          hex("0200 0280 0800 d0c0b0a0 05000000 b100 1600 0200 01000000"
              "0100 0200 0300 0400 0500 0600 0700 0800"),
          hex("34 04 ffff 2b00 110e 81 01 20 04 24 97 2c 96 2c 64 80 01 aa bb 12 02 31 32"),
          cat(hex("52 02 20 06 24 01 07 f9 18 00 10 03 20 04 24 96 30 03"),
              hex("0000 0000 0000 0000 0000 0000 0000 0000 01 00 01 00"))};
}

// The router on a mutated message, with an owner open: whatever the bytes, the reply is written
// whole and the output words are not.
void route_with_owner(std::span<const std::uint8_t> b) {
  test::FakeAssemblies assemblies;
  test::FakeConnections connections;
  connections.owner = true;
  const IdentityValues id = identity_for(3601, 1);
  RouterContext ctx{id, assembly_layout(2, 8, 8), AdapterLimits{}, assemblies, connections,
                    RequestOrigin{}};
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
  RouterContext router{id, assembly_layout(4, 16, 16), AdapterLimits{}, assemblies, connections,
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
  for (const Bytes& seed : seeds()) {
    for (int i = 0; i < 3000; ++i) {
      const Bytes b = mutate(seed, rng);
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
