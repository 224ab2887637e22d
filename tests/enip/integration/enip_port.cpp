#include "tests/enip/integration/enip_port.hpp"

#include <algorithm>
#include <cstdio>
#include <thread>
#include <vector>

namespace stepmod::testing {

namespace {
using Clock = std::chrono::steady_clock;
constexpr auto kReachTimeout = std::chrono::seconds(3);
}  // namespace

EnipPort::EnipPort(PartnerProcess& scanner, ipc::Client& image)
    : scanner_(scanner),
      image_(image),
      word_bytes_(image.raw().word_bytes),
      out_words_(image.raw().output_words),
      in_words_(image.raw().input_words) {}

std::string EnipPort::hex_of(const ImageWords& w) const {
  std::string hex;
  char b[3];
  for (unsigned i = 0; i < out_words_; ++i) {
    const auto v = static_cast<std::uint32_t>(w.w[i]);
    for (unsigned k = 0; k < word_bytes_; ++k) {  // little-endian, as CIP carries it
      std::snprintf(b, sizeof b, "%02x", (v >> (8 * k)) & 0xFFu);
      hex += b;
    }
  }
  return hex;
}

// The words go out in the scanner's next O→T; returns once the image holds them.
void EnipPort::write_outputs(const ImageWords& out) {
  out_ = out;
  scanner_.ask("set " + hex_of(out));
  const auto end = Clock::now() + kReachTimeout;
  ImageWords now;
  ImageWords want{};
  for (unsigned i = 0; i < out_words_; ++i) {
    want.w[i] = word_bytes_ == 2 ? static_cast<std::int16_t>(out.w[i]) : out.w[i];
  }
  while (!(image_.read_outputs(now) && now == want)) {
    if (Clock::now() > end) {
      ++lost_writes_;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void EnipPort::update_outputs(const std::function<void(ImageWords&)>& edit) {
  ImageWords w = out_;
  edit(w);
  write_outputs(w);
}

// The scanner's T→O data: the words as the adapter sent them.
bool EnipPort::read_inputs(ImageWords& in) const {
  const auto reply = scanner_.ask("get");
  if (!reply) return false;
  const std::string hex = json_field(*reply, "in");
  if (hex.size() != 2u * word_bytes_ * in_words_) return false;
  in = ImageWords{};
  for (unsigned i = 0; i < in_words_; ++i) {
    std::uint32_t v = 0;
    for (unsigned k = 0; k < word_bytes_; ++k) {
      v |= static_cast<std::uint32_t>(
               std::stoul(hex.substr(2 * (i * word_bytes_ + k), 2), nullptr, 16))
           << (8 * k);
    }
    in.w[i] = word_bytes_ == 2 ? static_cast<std::int16_t>(v) : static_cast<std::int32_t>(v);
  }
  return true;
}

// Until the scanner holds input words that the image showed after now: the T→O read next was
// produced after everything before (a count of T→O packets would not do: on a loaded machine
// node may still have older ones queued).
bool EnipPort::wait_fresh_inputs() {
  std::vector<ImageWords> since;  // the image's input words from now on
  const auto end = Clock::now() + kReachTimeout;
  for (;;) {
    ImageWords now;
    if (image_.read_inputs(now) && (since.empty() || !(since.back() == now))) {
      since.push_back(now);
    }
    ImageWords to;
    if (read_inputs(to) && std::find(since.begin(), since.end(), to) != since.end()) return true;
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

bool EnipPort::wait_scans(unsigned n) {
  return image_.wait_scans(n, std::chrono::milliseconds(3000)) && wait_fresh_inputs();
}

void EnipPort::pass(std::chrono::nanoseconds d) {
  std::this_thread::sleep_for(d);  // the scanner keeps sending O→T: the PLC's heartbeat
}

bool EnipPort::wait_inputs(const std::function<bool(const ImageWords&)>& done,
                           std::chrono::nanoseconds limit) {
  const auto deadline = Clock::now() + limit;
  for (;;) {
    ImageWords in;
    if (read_inputs(in) && done(in)) return true;
    if (Clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace stepmod::testing
