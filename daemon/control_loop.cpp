#include "daemon/control_loop.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

#include "daemon/daemon_trace.hpp"
#include "daemon/module_io.hpp"
#include "daemon/module_stack.hpp"
#include "daemon/sim_panel_link.hpp"
#include "daemon/supervision_log.hpp"

namespace stepmod::tools {

namespace {
// How long the shutdown waits for the pulse thread to acknowledge the immediate stops.
constexpr Nanos kStopAckTimeout = 200 * kNsPerMs;
}  // namespace

ControlLoop::ControlLoop(const Parts& parts)
    : parts_(parts),
      supervisor_(parts.config.plc_timeout_ns),
      reasons_(parts.stack.shape().axes),
      units_(parts.stack.shape(), parts.stack.backend()),
      lost_inputs_(parts.stack),
      enables_(parts.stack, parts.config, lost_inputs_, parts.trace),
      health_(parts.stack, parts.config, lost_inputs_, parts.trace),
      pump_(parts.stack, parts.config, parts.trace),
      cpu_notice_(parts.stack, parts.config, parts.output),
      doorbell_(parts.stack.planner(), parts.output) {}

void ControlLoop::run(const std::atomic<bool>& stop, const std::atomic<bool>* halt) {
  next_scan_ = monotonic_now();
  while (!stop.load(std::memory_order_acquire) &&
         (halt == nullptr || !halt->load(std::memory_order_acquire))) {
    const Nanos now = take_events();
    if (now < next_scan_) continue;
    scan(now);
    next_scan_ += parts_.config.scan_ns;
    if (next_scan_ <= now) next_scan_ = now + parts_.config.scan_ns;  // overrun: skip, never burst
  }
  // Within a scan of the stop: the watchdog relay drops while the axes stop.
  pump_.stop(monotonic_now());
}

Nanos ControlLoop::take_events() {
  // Both backends block until an input edge or the scan (the sim on a futex its writes end,
  // gpiod on its event file descriptors): no polling, moving or not.
  const std::size_t n = parts_.stack.backend().wait_events(events_, next_scan_);
  for (std::size_t i = 0; i < n; ++i) {
    const gpio::InputEvent& e = events_[i];
    if (parts_.trace != nullptr) {
      parts_.trace->record_input(
          {e.t, e.axis, static_cast<std::uint8_t>(e.line), static_cast<std::uint8_t>(e.level), 1});
    }
    parts_.stack.personality().on_input(to_module_event(e));
  }
  const Nanos now = monotonic_now();
  lost_inputs_.check(now);
  doorbell_.ring_if_submitted();
  if (parts_.panel != nullptr) parts_.panel->take_forces();
  return now;
}

// One consistent snapshot per scan; a PLC caught mid-write keeps the previous snapshot. The
// supervisor (ipc/plc_supervisor.hpp) decides what the module gets: the live words, or while the
// PLC is lost (heartbeat stale, sequence stuck odd) the frozen last good ones.
const ImageWords& ControlLoop::words_for_module(Nanos now) {
  ipc::ShmImage& image = parts_.image;
  ipc::PlcSupervisor::Sample sample;
  sample.now = now;
  sample.heartbeat = image.heartbeat();
  sample.seq = image.output_seq();
  sample.snapshot_ok = image.read_outputs(sample.words, sample.snapshot_seq);
  sample.lease_until = lease_.scan(image, sample.heartbeat, now, parts_.stack.personality());
  sample.plc_not_in_run =
      parts_.plc_not_in_run != nullptr && parts_.plc_not_in_run->load(std::memory_order_acquire);
  // While a drive enabled a moment ago is not ready, the module keeps scanning the words it
  // had: a command issued meanwhile is a new edge once the drive is ready.
  const ImageWords& live = supervisor_.scan(sample);
  return enables_.holding(now) ? given_ : live;
}

void ControlLoop::scan(Nanos now) {
  module::Personality& personality = parts_.stack.personality();
  ipc::ShmImage& image = parts_.image;
  const ImageWords& out = words_for_module(now);
  log_supervision(supervisor_, now);
  // As a PLC leaving Run mode (docs/interface.md 3.2): every move stops, position invalid. Once
  // per loss; the frozen words keep anything new from starting until the PLC is back.
  if (supervisor_.tripped()) personality.plc_stopped(now);
  // The 3202's blend message (docs/interface.md 3): handed over before the scan that reports it.
  // Not while the PLC is lost: like the frozen words, nothing new is acted on until it is back.
  std::optional<ipc::BlendMessage> message;
  std::int32_t message_result = 0;
  if (!supervisor_.plc_lost()) {
    message = image.pending_message();
    if (message) message_result = personality.on_message(message->data, now);
  }
  personality.scan(out, in_, now);
  if (&out != &given_) given_ = out;
  enables_.scan(supervisor_.plc_lost(), now);
  doorbell_.ring_if_submitted();
  cpu_notice_.scan();
  reasons_.scan(personality, image);
  units_.scan(personality, out, enables_.states(), image);
  // The machine as of this scan, before the status: a reader that sees "stopped" in the status
  // finds the panel showing the motor's last step, not the one of the loop's top.
  if (parts_.panel != nullptr) parts_.panel->publish();
  const ipc::Health health = health_.scan(supervisor_.flags() | lease_.flags());
  pump_.scan(health, now);
  image.publish_inputs(in_, health);
  note_scan_published();
  // Done only once the status that shows the message's effect is published: a PLC that reads
  // the status bits when its message is done (docs/interface.md 3: an error is in the status
  // bits) finds them. Marked done before this publication, a refused message was seen done with
  // Invalid Profile still clear (a loaded machine preempted the control thread in between).
  if (message) image.finish_message(message->seq, message_result);
  watchdog_.scan(now, parts_.output.loops());
}

void ControlLoop::note_scan_published() noexcept {
  const Nanos now = monotonic_now();
  if (last_publish_ != 0) longest_gap_ = std::max(longest_gap_, now - last_publish_);
  last_publish_ = now;
}

void ControlLoop::stop_motion() {
  pump_.stop(monotonic_now());
  parts_.stack.personality().shutdown();
  doorbell_.ring_if_submitted();
  const Nanos deadline = monotonic_now() + kStopAckTimeout;
  for (unsigned a = 0; a < parts_.stack.shape().axes; ++a) {
    while (parts_.stack.motion(a).busy() && monotonic_now() < deadline) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  if (parts_.panel != nullptr) parts_.panel->publish();
}

}  // namespace stepmod::tools
