// The 3601's error bits and reasons agree on every scan of random command sequences
// (tests/module/reasons_fuzz.hpp).
#include "module_types/m3601/plc_words_3601.hpp"
#include "tests/module/reasons_fuzz.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing::fuzz {
namespace {

namespace m = words::m3601;

constexpr std::uint16_t kFullConfig = m::cfg_msw::kCaptureUsed | m::cfg_msw::kExternalUsed |
                                      m::cfg_msw::kHomeUsed | m::cfg_msw::kEStopUsed |
                                      m::cfg_msw::kCwLimitUsed | m::cfg_msw::kCcwLimitUsed |
                                      m::cfg_msw::kQuadratureEncoder | m::cfg_msw::kStepDirOutput;

class Driver3601 final : public Driver {
 public:
  void configure(ImageWords& out, unsigned /*u*/, Rng& r) override {
    const auto msw = r.pick<std::uint16_t>(
        {kFullConfig, kFullConfig, kFullConfig & ~m::cfg_msw::kQuadratureEncoder,
         kFullConfig & ~m::cfg_msw::kCwLimitUsed, static_cast<std::uint16_t>(r.bits())});
    const std::uint16_t lsw = r.percent(90) ? 0x003F : static_cast<std::uint16_t>(r.bits());
    out = plc::m3601::configuration_words(msw, lsw,
                                          r.pick<std::int32_t>({1'000, 1'000, 50, 5'000, 0}));
  }
  void command(ImageWords& out, unsigned /*u*/, Rng& r) override {
    std::uint16_t msw = r.pick<std::uint16_t>(
        {m::cmd_msw::kAbsoluteMove, m::cmd_msw::kRelativeMove, m::cmd_msw::kRelativeMove,
         m::cmd_msw::kHold, m::cmd_msw::kResume, m::cmd_msw::kImmediateStop,
         m::cmd_msw::kFindHomeCw, m::cmd_msw::kFindHomeCcw, m::cmd_msw::kManualCw,
         m::cmd_msw::kManualCcw, m::cmd_msw::kPresetPosition, m::cmd_msw::kPresetEncoder,
         m::cmd_msw::kRunBlendCw, m::cmd_msw::kRunBlendCcw, m::cmd_msw::kReserved14, 0});
    if (r.percent(5)) msw |= m::cmd_msw::kHold;  // several command bits at once
    const auto lsw =
        r.pick<std::uint16_t>({0, 0, 0, 0, m::cmd_lsw::kSCurve, m::cmd_lsw::kEncoderMove,
                               m::cmd_lsw::kEncoderFollower, m::cmd_lsw::kStoreMinRegistration,
                               m::cmd_lsw::kProgramBlend, static_cast<std::uint16_t>(r.bits())});
    out = plc::m3601::command_words(msw, lsw, target(r), speed(r), rate(r), rate(r));
  }
  void tweak(ImageWords& out, unsigned /*u*/, Rng& r) override {
    const ImageWords w = plc::m3601::command_words(0, 0, target(r), speed(r), rate(r), rate(r));
    const unsigned i = 2 + r.below(6);
    out.w[i] = w.w[i];
  }
  void release(ImageWords& out, unsigned /*u*/) override { out.w[m::out_word::kMsw] = 0; }
  void clear(ImageWords& out, unsigned /*u*/) override { out = ImageWords{}; }
  void reset_errors(ImageWords& out, unsigned /*u*/) override {
    out = plc::m3601::command_words(m::cmd_msw::kResetErrors, 0, 0, 0, 0, 0);
  }
  bool clears_latches(const ImageWords& out, unsigned /*u*/) const override {
    return (out.w[m::out_word::kMsw] & (m::cmd_msw::kResetErrors | m::cmd_msw::kPresetPosition)) !=
           0;
  }

 private:
  static std::int32_t target(Rng& r) {
    return r.pick<std::int32_t>({0, 0, 300, -300, 3'000, -3'000, 20'000, 150'000, 9'000'000});
  }
  static std::int32_t speed(Rng& r) {
    return r.pick<std::int32_t>({0, 500, 1'000, 5'000, 20'000, 100'000, 2'000'000});
  }
  static std::int16_t rate(Rng& r) { return r.pick<std::int16_t>({0, 1, 10, 50, 500, 5'000}); }
};

TEST(ReasonsFuzz3601, ErrorBitsAndReasonsAgreeOnEveryScan) {
  const std::uint32_t s = seed(3601);
  VirtualMachine vm(default_3601());
  ReasonChecker ck(vm);
  Driver3601 d;
  Rng r(s);
  run(vm, d, r, ck, 20'000);
  expect_agreement("3601", s, ck.tally());
  EXPECT_GE(ck.tally().rises, 100u);  // the sequences do reach the error paths
  EXPECT_GE(ck.tally().codes.size(), 12u);
}

}  // namespace
}  // namespace stepmod::testing::fuzz
