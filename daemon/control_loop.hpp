#pragma once
// A module's control thread's loop (one per module of the rack, real-time below the pulse thread
// on real lines): input events as they come, the PLC image once per scan. Each scan: the PLC
// supervision and the lease decide which words the module gets, the module scans them, and its
// followers run in order (drive enables, the pulse thread's doorbell, the CPU notice, reasons,
// panel, and with the health words the charge pump), before the input image and health words
// are published.
#include <array>
#include <atomic>
#include <optional>

#include "config/config.hpp"
#include "daemon/charge_pump_feed.hpp"
#include "daemon/cpu_notice.hpp"
#include "daemon/drive_enable_feed.hpp"
#include "daemon/health_words.hpp"
#include "daemon/lease_keeper.hpp"
#include "daemon/lost_input_watch.hpp"
#include "daemon/pulse_doorbell.hpp"
#include "daemon/reason_publisher.hpp"
#include "daemon/unit_state_publisher.hpp"
#include "gpio/backend.hpp"
#include "ipc/plc_supervisor.hpp"
#include "ipc/shm_image.hpp"
#include "systemd/watchdog.hpp"

namespace stepmod::tools {

class ModuleTrace;
class SimPanelLink;
class ModuleStack;

class ControlLoop {
 public:
  // What the loop works on; all of it outlives the loop. `trace` and `panel` may be null.
  struct Parts {
    const Config& config;
    ModuleStack& stack;
    rt::StepOutput& output;  // the rack's, shared with the other modules
    ipc::ShmImage& image;
    ModuleTrace* trace;
    SimPanelLink* panel;
    // A fieldbus PLC out of Run (the EtherNet/IP adapter's deadman); null: no such fieldbus.
    const std::atomic<bool>* plc_not_in_run = nullptr;
  };
  explicit ControlLoop(const Parts& parts);

  // Until `stop` or `halt` (null: none; a rack halts its modules when one of them fails): input
  // events as they come, a scan every [module] scan_us.
  void run(const std::atomic<bool>& stop, const std::atomic<bool>* halt = nullptr);
  // After run(): the charge pump stopped (if run() could not), immediate stop of every axis, and
  // a bounded wait until the pulse thread has acknowledged it.
  void stop_motion();
  // After the pulse thread has stopped, as the daemon idles every output.
  void trace_enable_release(Nanos now) noexcept { enables_.trace_release(now); }
  // The longest time between two published scans (a PLC saw nothing new for that long); 0: none.
  Nanos longest_scan_gap() const noexcept { return longest_gap_; }

 private:
  // Blocks until an input edge or the next scan; hands the edges to the module. Returns the time.
  Nanos take_events();
  void scan(Nanos now);
  // The words the module scans: the supervisor's verdict on the PLC's snapshot, or while a drive
  // gets ready, the words it scanned last.
  const ImageWords& words_for_module(Nanos now);
  void note_scan_published() noexcept;

  Parts parts_;
  std::array<gpio::InputEvent, 64> events_{};
  ImageWords in_{};
  ImageWords given_{};  // the output words the module last scanned (held while a drive gets ready)
  Nanos next_scan_ = 0;
  ipc::PlcSupervisor supervisor_;
  LeaseKeeper lease_;         // docs/interface.md 3.5
  ReasonPublisher reasons_;   // docs/interface.md 3.4
  UnitStatePublisher units_;  // docs/interface.md 3.6
  LostInputWatch lost_inputs_;
  DriveEnableFeed enables_;
  HealthWords health_;
  ChargePumpFeed pump_;  // docs/safety.md "Charge pump"
  CpuNotice cpu_notice_;
  PulseDoorbell doorbell_;
  systemd::Watchdog watchdog_;  // WatchdogSec=: petted per scan while the pulse thread loops
  Nanos longest_gap_ = 0;
  Nanos last_publish_ = 0;
};

}  // namespace stepmod::tools
