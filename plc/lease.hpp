#pragma once
// The commissioning lease (docs/web-console.md, image offsets 576..591): a tool that commands the
// module without a PLC holds it, so that the daemon stops the axes when the tool dies or loses
// its operator. Unlike a PLC's heartbeat, renewal here is explicit: the caller renews only while
// its own deadman says the operator is there (stepmod-web: while the browser's keep-alives
// arrive), so a silent operator lets the lease expire and the daemon stops the axes.
#include <atomic>
#include <chrono>
#include <cstdint>

#include "ipc/client.hpp"

namespace stepmod::plc {

class Lease {
 public:
  static constexpr std::uint32_t kOffHolder = 576;
  static constexpr std::uint32_t kOffSeq = 580;
  static constexpr std::uint32_t kOffExpiry = 584;
  // The contract: at most 500 ms ahead, renewed at least every 100 ms.
  static constexpr std::chrono::milliseconds kAhead{400};
  static constexpr std::chrono::milliseconds kRenewEvery{100};

  // `holder`: the id written into the image (normally the process id). Throws ipc::IpcError
  // when the image is read-only.
  Lease(ipc::Client& client, std::uint32_t holder);
  ~Lease();  // releases if held
  Lease(const Lease&) = delete;
  Lease& operator=(const Lease&) = delete;

  // Takes the lease (compare-and-swap of the holder from 0) if it is free. The caller has
  // checked that no PLC is in control. false: another tool holds it.
  bool take();
  // Moves the expiry kAhead from now. false (and nothing written) when the lease is no longer
  // ours: the daemon freed it after an expiry.
  bool renew();
  // Writes 0 to the holder if it is still ours.
  void release();
  // Ours, as far as the image says.
  bool held() const;
  // Whoever holds it now (0 = free).
  std::uint32_t holder() const;
  std::uint32_t id() const noexcept { return id_; }

  // The same fields of any image, read only (for a display of who holds it).
  static std::uint32_t holder_of(const stepmod_image_t& img);
  static std::uint64_t expiry_of(const stepmod_image_t& img);

 private:
  std::atomic_ref<std::uint32_t> holder_ref() const;
  std::atomic_ref<std::uint32_t> seq_ref() const;
  std::atomic_ref<std::uint64_t> expiry_ref() const;
  void write_expiry();

  unsigned char* base_;
  std::uint32_t id_;
};

}  // namespace stepmod::plc
