#pragma once
// The open class 1 connections (docs/ethernetip-design.md, "Class 1 I/O"): one exclusive owner
// and input-only / listen-only connections for HMIs, in fixed slots (no allocation). It accepts
// or drops each O→T packet, says when each T→O is due, closes the silent ones, and keeps what the
// deadman needs: whether the owner PLC has left Run. Time is passed in (CLOCK_MONOTONIC ns), so
// every rule is tested without waiting.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "fieldbus/enip/io_packet.hpp"
#include "fieldbus/enip/message_router.hpp"
#include "fieldbus/enip/xorshift32.hpp"

namespace stepmod::enip {

inline constexpr std::size_t kMaxIoConnections = 4;  // the owner and three HMIs

struct IoConnection {
  bool open = false;
  ConnectionKind kind = ConnectionKind::kExclusiveOwner;
  ConnectionTriad triad;
  std::uint32_t ot_id = 0;
  std::uint32_t to_id = 0;
  std::uint32_t originator_ip = 0;
  IoShape ot_shape;
  std::int64_t to_rpi_ns = 0;
  std::int64_t timeout_ns = 0;
  std::int64_t last_ot_ns = 0;  // the last accepted O→T (or the opening)
  std::int64_t next_to_ns = 0;  // when the next T→O is due
  bool ot_seen = false;
  std::uint32_t ot_encap_sequence = 0;
  std::uint16_t ot_cip_sequence = 0;
  bool run = false;
  std::uint32_t to_encap_sequence = 0;
};

// What an O→T packet did.
enum class OtOutcome {
  kDropped,   // unknown id, wrong sender, old sequence, malformed: nothing changes
  kRunWrite,  // Run with new data: write `data` as one PLC write (and a heartbeat)
  // Run with the CIP sequence count repeated (the same data, written already): the PLC is alive
  // and in Run, so a heartbeat (docs/interface.md 9: every accepted Run packet is one), no write.
  kRunRepeat,
  kRefresh,  // accepted from an input-only / listen-only connection: the timeout restarts
  kIdle,     // the owner's Idle: the PLC left Run
};

struct OtResult {
  OtOutcome outcome = OtOutcome::kDropped;
  std::span<const std::uint8_t> data;
};

class IoConnections : public ConnectionTable {
 public:
  // `seed`: the start of the O→T ids (the adapter gives a random one, tests a fixed one).
  explicit IoConnections(std::uint32_t seed) noexcept : ids_(seed) {}

  bool owner_open() const noexcept override;
  CipStatus open(const ForwardOpen& fo, const AcceptedOpen& accepted, const RequestOrigin& origin,
                 std::uint32_t& ot_id) noexcept override;
  CipStatus close(const ConnectionTriad& triad) noexcept override;

  OtResult on_o_to_t(std::uint32_t from_ip, std::span<const std::uint8_t> datagram,
                     std::int64_t now_ns) noexcept;
  // Closes the connections silent for their timeout (and listen-only ones left without a
  // connection to listen to); true when the owner was among them.
  bool expire(std::int64_t now_ns) noexcept;

  // The earliest time something is due (a T→O or a timeout); INT64_MAX when nothing is open.
  std::int64_t next_due_ns() const noexcept;
  // The connections whose T→O is due at `now_ns`, each once: advance() after sending.
  std::span<IoConnection> slots() noexcept { return slots_; }
  static bool to_due(const IoConnection& c, std::int64_t now_ns) noexcept {
    return c.open && c.next_to_ns <= now_ns;
  }
  static void advance(IoConnection& c, std::int64_t now_ns) noexcept;

  // The deadman: an owner has been open and is now Idle, timed out or closed, until the next
  // Run packet of an owner.
  bool plc_left_run() const noexcept { return left_run_; }
  // Identity attribute 5.
  std::uint16_t identity_status() const noexcept;

 private:
  IoConnection* find_ot(std::uint32_t ot_id) noexcept;
  bool triad_open(const ConnectionTriad& triad) const noexcept;
  std::uint32_t new_id() noexcept;
  void close_slot(IoConnection& c) noexcept;
  void close_orphaned_listeners() noexcept;

  std::array<IoConnection, kMaxIoConnections> slots_{};
  Xorshift32 ids_;
  bool left_run_ = false;
};

}  // namespace stepmod::enip
