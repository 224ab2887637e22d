#pragma once
// Blend moves of one axis (3601 Ch.4 "Blend Move", Ch.5): the block-by-block programming cycle that
// builds and checks a profile from decoded blocks, the stored profile, and the running blend's Hold
// and end rules. It owns the profile and the cycle's state.
#include <cstdint>
#include <span>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

class Blend {
 public:
  explicit Blend(AxisState& ax) noexcept : ax_(ax) {}

  // Every command-mode scan of a configured axis: the programming handshake (`prev`: the
  // previous scan's command image, for the transmit edge).
  void programming_scan(const AxisCommand& c, const AxisCommand& prev);
  // A whole profile at once (the 3202's blend message, 3202 Ch.5): the block cycle's checks on
  // the first block and the declared segments; stored only if every check passes. While a blend
  // runs: CE and the blend is brought down with its final deceleration (3202-CE-19). Returns
  // whether it was stored.
  bool program(const BlendFirstBlock& first, std::span<const BlendSegmentBlock> segments);
  // Run Blend + / -.
  void run(planner::Direction dir);
  // Hold while a blend runs (3601-CE-23): CE now, cleared by itself when the blend ends.
  void hold();
  // The blend motion has ended (its outcome is the table's).
  void motion_ended();
  // A configuration erases the stored profile and any programming cycle (3601-CE-20).
  void erase();

  // Running for the whole blend (its deceleration included); the acknowledge (3601-LSW-01).
  bool running() const noexcept { return ax_.activity() == Activity::kBlend; }
  bool acknowledge() const noexcept { return ack_; }

 private:
  // One programming block, read on a transmit rising edge; false if it holds an error.
  bool first_block(const BlendFirstBlock& b);
  bool segment_block(const BlendSegmentBlock& b);
  void read_block(const AxisCommand& c);  // one block of the programming cycle
  void end_cycle();                       // the program flag cleared: store or not
  void bring_down();                      // CE-22: programming while the blend runs

  AxisState& ax_;
  planner::BlendSpec profile_{};  // stored profile (dir and vs are set by Run Blend)
  bool stored_ = false;           // a complete, valid profile is stored
  planner::BlendSpec pending_{};  // the profile of the programming cycle under way
  bool cycle_ = false;            // program flag held: a cycle is under way
  bool spoiled_ = false;          // this cycle had an error or was refused: store nothing
  unsigned blocks_ = 0;           // blocks read in this cycle (first block included)
  bool reason_noted_ = false;     // a block check recorded its own reason (error_items.hpp)
  std::int64_t total_ = 0;        // sum of the segment lengths read so far
  bool ack_ = false;              // the acknowledge
  bool hold_error_ = false;       // CE was set by a Hold during the running blend
};

}  // namespace stepmod::module::axis
