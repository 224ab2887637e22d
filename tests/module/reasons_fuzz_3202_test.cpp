// The 3202's error bits and reasons agree on every scan of random command sequences
// (tests/module/reasons_fuzz.hpp).
#include "module_types/m3202/plc_words_3202.hpp"
#include "tests/module/reasons_fuzz.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::testing::fuzz {
namespace {

namespace m = words::m3202;

constexpr std::uint32_t kFull =
    m::cfg_bit::kCaptureUsed | m::cfg_bit::kExternalUsed | m::cfg_bit::kHomeUsed |
    m::cfg_bit::kEStopUsed | m::cfg_bit::kCwLimitUsed | m::cfg_bit::kCcwLimitUsed |
    m::cfg_bit::kQuadratureEncoder | m::cfg_bit::kStepDirOutput | m::cfg_bit::kActiveLevels;

class Driver3202 final : public Driver {
 public:
  void configure(ImageWords& out, unsigned u, Rng& r) override {
    const auto bits = r.pick<std::uint32_t>({kFull, kFull, kFull & ~m::cfg_bit::kQuadratureEncoder,
                                             kFull & ~m::cfg_bit::kCwLimitUsed,
                                             kFull | m::cfg_bit::kDisable, r.bits()});
    put(out, u, plc::m3202::configuration_words(bits, r.pick<std::int32_t>({1'000, 1'000, 50, 0})));
  }
  void command(ImageWords& out, unsigned u, Rng& r) override {
    std::uint32_t bits = r.pick<std::uint32_t>(
        {m::cmd_bit::kAbsoluteMove, m::cmd_bit::kRelativeMove, m::cmd_bit::kRelativeMove,
         m::cmd_bit::kHold, m::cmd_bit::kResume, m::cmd_bit::kImmediateStop,
         m::cmd_bit::kFindHomeCw, m::cmd_bit::kFindHomeCcw, m::cmd_bit::kManualCw,
         m::cmd_bit::kManualCcw, m::cmd_bit::kPresetPosition, m::cmd_bit::kPresetEncoder,
         m::cmd_bit::kRunBlendCw, m::cmd_bit::kRunBlendCcw, 1u << 20, 0});
    if (r.percent(5)) bits |= m::cmd_bit::kHold;  // several command bits at once
    bits |= r.pick<std::uint32_t>({0, 0, 0, m::cmd_bit::kSCurve, m::cmd_bit::kEncoderMove});
    put(out, u, plc::m3202::command_words(bits, target(r), speed(r), rate(r), rate(r)));
    if (r.percent(5)) out.w[8 * u + 6] = 1;  // a reserved word
  }
  void tweak(ImageWords& out, unsigned u, Rng& r) override {
    const auto w = plc::m3202::command_words(0, target(r), speed(r), rate(r), rate(r));
    const unsigned i = 1 + r.below(4);
    out.w[8 * u + i] = w[i];
  }
  void release(ImageWords& out, unsigned u) override {
    out.w[8 * u] &= ~static_cast<std::int32_t>(0x3FFFu);
  }
  void clear(ImageWords& out, unsigned u) override { put(out, u, {}); }
  void reset_errors(ImageWords& out, unsigned u) override {
    put(out, u, plc::m3202::command_words(m::cmd_bit::kResetErrors, 0, 0, 0, 0));
  }
  bool clears_latches(const ImageWords& out, unsigned u) const override {
    return (static_cast<std::uint32_t>(out.w[8 * u]) &
            (m::cmd_bit::kResetErrors | m::cmd_bit::kPresetPosition)) != 0;
  }
  // A blend profile message now and then, for a channel or none (3202-IP-11, IP-15).
  void extra(VirtualMachine& vm, ReasonChecker& /*ck*/, Rng& r) override {
    plc::BlendProfile b;
    b.final_decel = r.pick<std::int32_t>({0, 10'000});
    const unsigned n = r.pick<unsigned>({1, 2, 3});
    for (unsigned i = 0; i < n; ++i) {
      b.segments.push_back({.length = r.pick<std::int32_t>({0, 500, 2'000}),
                            .speed = r.pick<std::int32_t>(
                                {500, 5'000, static_cast<std::int32_t>(10'000 + 1'000 * i)}),
                            .accel = 10'000});
    }
    const auto msg = plc::m3202::blend_message(r.pick<std::int32_t>({1, 2, 2, 0}), b);
    vm.stack().personality().on_message(msg, vm.now());
  }

 private:
  static void put(ImageWords& out, unsigned u, const plc::m3202::ChannelWords& w) {
    for (unsigned i = 0; i < 8; ++i) out.w[8 * u + i] = w[i];
  }
  static std::int32_t target(Rng& r) {
    return r.pick<std::int32_t>({0, 0, 300, -300, 3'000, -3'000, 20'000, 150'000});
  }
  static std::int32_t speed(Rng& r) {
    return r.pick<std::int32_t>({0, 500, 1'000, 5'000, 20'000, 100'000, 2'000'000});
  }
  static std::int32_t rate(Rng& r) {
    return r.pick<std::int32_t>({0, 1'000, 10'000, 100'000, 2'000'000'000});
  }
};

TEST(ReasonsFuzz3202, ErrorBitsAndReasonsAgreeOnEveryScan) {
  const std::uint32_t s = seed(3202);
  VirtualMachineOptions o = default_3601();
  o.type = ModuleType::k3202;
  o.axes.push_back(o.axes[0]);
  VirtualMachine vm(o);
  ReasonChecker ck(vm);
  Driver3202 d;
  Rng r(s);
  run(vm, d, r, ck, 20'000);
  expect_agreement("3202", s, ck.tally());
  EXPECT_GE(ck.tally().rises, 100u);  // the sequences do reach the error paths
  EXPECT_GE(ck.tally().codes.size(), 12u);
}

}  // namespace
}  // namespace stepmod::testing::fuzz
