#pragma once
// The commissioning lease (image offsets 576..591, docs/commissioning.md), the tool's side: the one
// implementation every tool uses. A tool that commands the module without a PLC holds it, so that
// the daemon (ipc/lease_watch.hpp) stops the axes when the tool dies or loses its operator. The
// core is explicit: the caller renews, and renews only while its own deadman says the operator is
// there (stepmod-web: while the browser's keep-alives arrive). ipc::LeaseClient
// (ipc/lease_client.hpp) is this lease renewed by a thread of its own, for a tool whose process
// being alive is the deadman (stepmodctl --wait). The holder must not bump the PLC heartbeat (that
// is a PLC's: health bit 7).
//
// Only the holder writes the expiry (issue 29): a take is the compare-and-swap of the holder
// first, then the expiry, then the sequence (the daemon's mark that the take is complete). A take
// that finds the lease held writes nothing, so no retrying tool can push a dead holder's deadline.
#include <atomic>
#include <chrono>
#include <cstdint>

#include "ipc/client.hpp"
#include "ipc/lease_limits.hpp"

namespace stepmod::ipc {

class Lease {
 public:
  // The contract: the expiry at most 500 ms ahead, renewed at least every 100 ms.
  static constexpr std::chrono::milliseconds kAhead{400};
  static constexpr std::chrono::milliseconds kRenewAtLeastEvery{100};
  static_assert(kAhead.count() * kNsPerMs < kLeaseMaxAheadNs);

  // `holder`: the id written into the image (this process' id when 0). Throws ipc::IpcError
  // when the image is read-only.
  explicit Lease(Client& client, std::uint32_t holder = 0);
  ~Lease();  // releases if held
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;

  // Takes the lease (compare-and-swap of the holder from 0, then the expiry, then the sequence)
  // if it is free; renews it if it is ours already. The caller has checked that no PLC is in
  // control. false: another tool holds it (nothing was written), or the daemon freed this take
  // before it completed (this process was held off the CPU for longer than kLeaseMaxAheadNs).
  bool take();
  // Takes the lease over from `from` (stepmodctl --steal: the operator's explicit choice, which
  // the daemon logs): as take(), but the compare-and-swap is from `from`. false when `from` no
  // longer holds it.
  bool take_over(std::uint32_t from);
  // Moves the expiry kAhead from now. false (and nothing written) when the lease is no longer
  // ours: the daemon freed it after an expiry, or another tool took it over.
  bool renew() noexcept;
  // Writes 0 to the holder if it is still ours (nothing stops: the axes keep what they do).
  void release() noexcept;
  // Ours, as far as the image says.
  bool held() const noexcept;
  // Whoever holds it now (0 = free).
  std::uint32_t holder() const noexcept;
  std::uint32_t id() const noexcept { return id_; }

  // The same fields of any image, read only (for a display of who holds it).
  static std::uint32_t holder_of(const stepmod_image_t& img);
  static std::uint64_t expiry_of(const stepmod_image_t& img);
  // Whether a process `pid` runs (kill(pid, 0); one of another user counts). A holder that does
  // not is dead: the daemon frees its lease at most kLeaseMaxAheadNs after its last renewal. Only
  // meaningful within one PID namespace; false for 0.
  static bool process_running(std::uint32_t pid) noexcept;

 private:
  bool complete_take() noexcept;
  void write_expiry() noexcept;

  // The image is shared memory written by other processes: every access is atomic.
  std::atomic_ref<std::uint32_t> holder_;
  std::atomic_ref<std::uint32_t> seq_;
  std::atomic_ref<std::uint64_t> expiry_;
  std::uint32_t id_;
};

}  // namespace stepmod::ipc
