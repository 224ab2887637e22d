// Benchmark 15 (issue 34): the EtherNet/IP adapter of a real stepmodd, driven by a minimal class
// 1 scanner written here on plain sockets (RegisterSession, a Forward_Open as st-ethernet-ip
// sends it at RPI 2 ms, then one O→T per T→O as that scanner does):
//   O→T to image   the time from sending an O→T packet with new words to the image's output
//                  sequence moving (the adapter's receive, one seqlock write)
//   image to T→O   the time from the module publishing new input words (a move: the position
//                  changes every scan) to the T→O packet that carries them (at most one RPI:
//                  production is periodic)
//   CPU            the adapter thread's and the whole daemon's CPU while the connection runs
//                  at RPI 2 ms with the axis idle
// Usage: enip_bench --stepmodd PATH [--seconds 5] [--samples 1000]
// Output: human-readable lines and one "RESULT bench=enip ..." line for scripts/bench.
#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "bench/proc_cpu.hpp"
#include "core/clock.hpp"
#include "ipc/client.hpp"
#include "module_types/m3601/plc_words_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"

namespace {

using namespace stepmod;
using Bytes = std::vector<std::uint8_t>;
namespace m = words::m3601;

constexpr const char* kTarget = "127.0.77.1";
constexpr const char* kLocal = "127.0.77.2";
constexpr std::uint32_t kRpiUs = 2000;

Bytes hex(const char* text) {
  Bytes b;
  for (const char* p = text; *p != '\0';) {
    if (*p == ' ') {
      ++p;
      continue;
    }
    b.push_back(static_cast<std::uint8_t>(std::stoul(std::string(p, 2), nullptr, 16)));
    p += 2;
  }
  return b;
}

sockaddr_in addr(const char* ip, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  ::inet_pton(AF_INET, ip, &a.sin_addr);
  return a;
}

std::uint32_t u32(const Bytes& b, std::size_t at) {
  return b.size() < at + 4 ? 0
                           : b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
                                 (static_cast<std::uint32_t>(b[at + 3]) << 24);
}

Bytes request(int fd, const Bytes& frame) {
  ::send(fd, frame.data(), frame.size(), MSG_NOSIGNAL);
  Bytes r(1024);
  pollfd p{fd, POLLIN, 0};
  const ssize_t n = ::poll(&p, 1, 3000) > 0 ? ::recv(fd, r.data(), r.size(), 0) : -1;
  r.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return r;
}

// The class 1 scanner: the connection opened over TCP, then O→T answered to each T→O.
class Scanner {
 public:
  bool open() {
    tcp_ = ::socket(AF_INET, SOCK_STREAM, 0);
    const sockaddr_in local = addr(kLocal, 0);
    const sockaddr_in target = addr(kTarget, 44818);
    if (::bind(tcp_, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0 ||
        ::connect(tcp_, reinterpret_cast<const sockaddr*>(&target), sizeof target) != 0) {
      return false;
    }
    const Bytes reg = request(tcp_, hex("6500 0400 00000000 00000000 0000000000000000 00000000"
                                        "0100 0000"));
    Bytes fo =
        hex("6f00 4c00 00000000 00000000 0000000000000000 00000000 00000000 0a00 0200 0000 0000"
            "b200 3c00 54 02 20 06 24 01"
            "03 7d 00000000 78563412 3412 3333 37130000 03 000000 d0070000 1648 d0070000 1248 01"
            "09 34 04 0000 0000 0000 00 00 20 04 24 97 2c 96 2c 64");
    std::memcpy(fo.data() + 4, reg.data() + 4, 4);  // our session handle
    const Bytes r = request(tcp_, fo);
    if (r.size() < 52 || r[42] != 0) return false;  // general status of the Forward_Open
    ot_id_ = u32(r, 44);
    udp_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const sockaddr_in io = addr(kLocal, 2222);
    return ::bind(udp_, reinterpret_cast<const sockaddr*>(&io), sizeof io) == 0;
  }
  // Waits up to `timeout_ms` for a T→O; its input words (16 bytes), empty when none came.
  Bytes receive(int timeout_ms) {
    pollfd p{udp_, POLLIN, 0};
    Bytes b(128);
    if (::poll(&p, 1, timeout_ms) <= 0) return {};
    const ssize_t n = ::recv(udp_, b.data(), b.size(), 0);
    if (n < 36) return {};
    return Bytes(b.begin() + 20, b.begin() + 36);
  }
  // One O→T with `words` (Run); the CIP count moves when the words do.
  void send(const ImageWords& words) {
    if (words != last_) ++count_;
    last_ = words;
    Bytes b = hex("0200 0280 0800 00000000 00000000 b100 1600 0000 01000000");
    ++seq_;
    std::memcpy(b.data() + 6, &ot_id_, 4);
    std::memcpy(b.data() + 10, &seq_, 4);
    std::memcpy(b.data() + 18, &count_, 2);
    for (unsigned i = 0; i < 8; ++i) {
      b.push_back(static_cast<std::uint8_t>(words.w[i]));
      b.push_back(static_cast<std::uint8_t>(words.w[i] >> 8));
    }
    const sockaddr_in to = addr(kTarget, 2222);
    ::sendto(udp_, b.data(), b.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  // As st-ethernet-ip: an O→T after each T→O, for `ms`.
  void run_for(const ImageWords& words, int ms) {
    const Nanos end = monotonic_now() + Nanos{ms} * kNsPerMs;
    while (monotonic_now() < end) {
      if (!receive(50).empty()) send(words);
    }
  }
  ~Scanner() {
    if (tcp_ >= 0) ::close(tcp_);
    if (udp_ >= 0) ::close(udp_);
  }

 private:
  int tcp_ = -1;
  int udp_ = -1;
  std::uint32_t ot_id_ = 0;
  std::uint32_t seq_ = 0;
  std::uint16_t count_ = 0;
  ImageWords last_{};
};

struct Stats {
  double p50 = 0, p99 = 0, max = 0;
  std::size_t n = 0;
};
Stats stats_us(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[static_cast<std::size_t>(q * (v.size() - 1))]; };
  return {at(0.5), at(0.99), v.back(), v.size()};
}

// O→T sent with new words (the decel word, harmless without a command bit) to the image's
// output sequence moving.
Stats ot_to_image(Scanner& s, ipc::Client& image, int samples) {
  std::vector<double> us;
  ImageWords w{};
  for (int i = 0; i < samples; ++i) {
    if (s.receive(100).empty()) continue;
    const std::uint32_t seq = __atomic_load_n(&image.raw().output_seq, __ATOMIC_ACQUIRE);
    w.w[m::out_word::kDecel] = static_cast<std::int16_t>(1 + i % 1000);
    const Nanos t0 = monotonic_now();
    s.send(w);
    while (__atomic_load_n(&image.raw().output_seq, __ATOMIC_ACQUIRE) == seq) {
      if (monotonic_now() - t0 > 100 * kNsPerMs) break;
    }
    us.push_back(static_cast<double>(monotonic_now() - t0) / 1000.0);
  }
  return stats_us(us);
}

// Configures the axis and starts a long move through O→T alone; the words then held.
ImageWords start_move(Scanner& s) {
  const std::uint16_t cfg =
      m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed | m::cfg_msw::kStepDirOutput;
  s.run_for(plc::m3601::configuration_words(cfg, 0x3F, 1000), 100);
  s.run_for(ImageWords{}, 100);
  s.run_for(plc::m3601::command_words(m::cmd_msw::kPresetPosition, 0, 0, 0, 0, 0), 50);
  s.run_for(ImageWords{}, 50);
  const ImageWords move =
      plc::m3601::command_words(m::cmd_msw::kRelativeMove, 0, 10'000'000, 2'000, 100, 100);
  s.run_for(move, 50);
  ImageWords held = move;
  held.w[m::out_word::kMsw] = 0;
  s.run_for(held, 200);
  return held;
}

// The module's new input words (seen by spinning on the image) to the T→O that carries them.
Stats image_to_t_to_o(Scanner& s, ipc::Client& image, const ImageWords& held, int seconds) {
  std::map<std::string, Nanos> seen;  // input bytes -> when the image first showed them
  std::vector<double> us;
  const Nanos end = monotonic_now() + Nanos{seconds} * kNsPerSec;
  std::uint64_t scans = 0;
  while (monotonic_now() < end) {
    if (image.scan_counter() != scans) {
      scans = image.scan_counter();
      ImageWords in;
      if (image.read_inputs(in)) {
        std::string b;
        for (unsigned i = 0; i < 8; ++i) {
          b.push_back(static_cast<char>(in.w[i]));
          b.push_back(static_cast<char>(in.w[i] >> 8));
        }
        seen.emplace(b, monotonic_now());
      }
    }
    const Bytes to = s.receive(0);
    if (to.empty()) continue;
    const Nanos now = monotonic_now();
    if (const auto it = seen.find(std::string(to.begin(), to.end())); it != seen.end()) {
      us.push_back(static_cast<double>(now - it->second) / 1000.0);
      seen.erase(it);
    }
    s.send(held);
  }
  return stats_us(us);
}

double cpu_pct(pid_t pid, const std::string& thread, Scanner& s, int seconds) {
  const auto a = bench::thread_cpu(pid);
  const Nanos t0 = monotonic_now();
  s.run_for(ImageWords{}, seconds * 1000);
  const auto b = bench::thread_cpu(pid);
  double ns = 0;
  for (const auto& [k, v] : b) {
    if (thread.empty() || k.rfind(thread + "/", 0) == 0) ns += v - (a.count(k) ? a.at(k) : 0.0);
  }
  return 100.0 * ns / static_cast<double>(monotonic_now() - t0);
}

}  // namespace

int main(int argc, char** argv) {
  std::string exe;
  int seconds = 5;
  int samples = 1000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--stepmodd") exe = argv[i + 1];
    if (k == "--seconds") seconds = std::stoi(argv[i + 1]);
    if (k == "--samples") samples = std::stoi(argv[i + 1]);
  }
  const std::string sim = "cw_limit_at = 1000000000\nccw_limit_at = -1000000000\n";
  const std::string config = testing::sim_3601_config("", sim) +
                             "\n[ethernetip]\nenabled = true\nlisten = \"" + kTarget + ":44818\"\n";
  testing::DaemonProcess daemon(config, testing::DaemonOptions{false, "", "", exe});
  if (!daemon.wait_ready()) {
    std::fprintf(stderr, "stepmodd did not start:\n%s\n", daemon.log().c_str());
    return 1;
  }
  ipc::Client image(daemon.name());
  Scanner s;
  if (!s.open()) {
    std::fprintf(stderr, "the Forward_Open failed:\n%s\n", daemon.log().c_str());
    return 1;
  }
  s.run_for(ImageWords{}, 200);
  const double cpu_enip = cpu_pct(daemon.pid(), "stepmod-enip", s, seconds);
  const double cpu_all = cpu_pct(daemon.pid(), "", s, seconds);
  const Stats ot = ot_to_image(s, image, samples);
  const ImageWords held = start_move(s);
  const Stats to = image_to_t_to_o(s, image, held, seconds);
  std::printf("O→T to image:  p50 %.1f / p99 %.1f / max %.1f us (%zu samples)\n", ot.p50, ot.p99,
              ot.max, ot.n);
  std::printf("image to T→O:  p50 %.1f / p99 %.1f / max %.1f us (%zu samples, RPI %u us)\n", to.p50,
              to.p99, to.max, to.n, kRpiUs);
  std::printf("CPU at RPI 2 ms, axis idle: adapter thread %.2f %%, whole daemon %.2f %%\n",
              cpu_enip, cpu_all);
  std::printf(
      "RESULT bench=enip ot_p50_us=%.1f ot_p99_us=%.1f ot_max_us=%.1f to_p50_us=%.1f "
      "to_p99_us=%.1f to_max_us=%.1f cpu_enip_pct=%.3f cpu_daemon_pct=%.3f\n",
      ot.p50, ot.p99, ot.max, to.p50, to.p99, to.max, cpu_enip, cpu_all);
  return 0;
}
