// The 3602's error bits and reasons agree on every scan of random command sequences, its
// interpolated moves included (tests/module/reasons_fuzz.hpp). The probe of issue 29 found 79
// scans in 3 minutes where they did not: a refused path set Command Error after the axis had
// recorded its reasons for the scan.
#include "tests/module/reasons_fuzz.hpp"
#include "tests/module/rig_3602.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::testing::fuzz {
namespace {

namespace m = words::m3602;
namespace il = m::cmd_lsw;
namespace iw = m::interp_word;

constexpr std::uint16_t kLimits =
    m::cfg_msw::kCaptureEnabled | m::cfg_msw::kExternalEnabled | m::cfg_msw::kHomeEnabled |
    (m::cfg_msw::kFunctionLimit << m::cfg_msw::kCwFunctionShift) |
    (m::cfg_msw::kFunctionLimit << m::cfg_msw::kCcwFunctionShift) | m::cfg_msw::kStepDirOutput;
constexpr std::uint16_t kEStopCw =
    static_cast<std::uint16_t>((kLimits & ~m::cfg_msw::kCwFunction) |
                               (m::cfg_msw::kFunctionEStop << m::cfg_msw::kCwFunctionShift));

void put_split(ImageWords& out, unsigned i, std::int32_t v) {
  const auto p = words::encode_3602(v);
  out.w[i] = p.msw;
  out.w[i + 1] = p.lsw;
}

class Driver3602 final : public Driver {
 public:
  void configure(ImageWords& out, unsigned u, Rng& r) override {
    clear(out, u);
    const auto msw = r.pick<std::uint16_t>({kLimits, kLimits, kLimits, kEStopCw,
                                            kLimits | m::cfg_msw::kDisableAxis,
                                            static_cast<std::uint16_t>(r.bits())});
    out.w[8 * u + m::out_word::kMsw] = static_cast<std::int16_t>(msw | m::cfg_msw::kConfigMode);
    out.w[8 * u + m::out_word::kLsw] = r.percent(90) ? 0x1F : static_cast<std::int16_t>(r.bits());
    put_split(out, 8 * u + m::out_word::kStartingSpeedMsw,
              r.pick<std::int32_t>({1'000, 1'000, 50, 0}));
    out.w[8 * u + m::out_word::kHomingTimeout] = r.pick<std::int16_t>({0, 0, 1, 400});
  }
  void command(ImageWords& out, unsigned u, Rng& r) override {
    std::uint16_t msw = r.pick<std::uint16_t>(
        {m::cmd_msw::kAbsoluteMove, m::cmd_msw::kRelativeMove, m::cmd_msw::kRelativeMove,
         m::cmd_msw::kHold, m::cmd_msw::kResume, m::cmd_msw::kImmediateStop,
         m::cmd_msw::kFindHomeCw, m::cmd_msw::kFindHomeCcw, m::cmd_msw::kJogCw, m::cmd_msw::kJogCcw,
         m::cmd_msw::kPresetPosition, m::cmd_msw::kRunBlendCw, m::cmd_msw::kRunBlendCcw, 1u << 10,
         0});
    if (r.percent(5)) msw |= m::cmd_msw::kHold;  // several command bits at once
    const auto lsw = r.pick<std::uint16_t>({0, 0, 0, 0, il::kSCurve, il::kProgramMinRegistration,
                                            il::kProgramBlend, il::kGpo, il::kLinear,
                                            static_cast<std::uint16_t>(r.bits())});
    const unsigned b = 8 * u;
    out.w[b + m::out_word::kMsw] = static_cast<std::int16_t>(msw);
    out.w[b + m::out_word::kLsw] = static_cast<std::int16_t>(lsw);
    put_split(out, b + m::out_word::kTargetMsw, target(r));
    put_split(out, b + m::out_word::kSpeedMsw, speed(r));
    out.w[b + m::out_word::kAccel] = rate(r);
    out.w[b + m::out_word::kDecel] = rate(r);
  }
  void tweak(ImageWords& out, unsigned u, Rng& r) override {
    const unsigned b = 8 * u;
    switch (r.below(4)) {
      case 0:
        put_split(out, b + m::out_word::kTargetMsw, target(r));
        break;
      case 1:
        put_split(out, b + m::out_word::kSpeedMsw, speed(r));
        break;
      case 2:
        out.w[b + m::out_word::kAccel] = rate(r);
        break;
      default:
        out.w[b + m::out_word::kDecel] = rate(r);
        break;
    }
  }
  void release(ImageWords& out, unsigned u) override {
    out.w[8 * u + m::out_word::kMsw] = 0;
    // Axis 1's interpolation bits are a command too.
    if (u == 0) out.w[m::out_word::kLsw] &= ~static_cast<std::int32_t>(il::kInterpolation);
  }
  void clear(ImageWords& out, unsigned u) override {
    for (unsigned i = 0; i < 8; ++i) out.w[8 * u + i] = 0;
  }
  void reset_errors(ImageWords& out, unsigned u) override {
    clear(out, u);
    out.w[8 * u + m::out_word::kMsw] = static_cast<std::int16_t>(m::cmd_msw::kResetErrors);
  }
  bool clears_latches(const ImageWords& out, unsigned u) const override {
    return (out.w[8 * u + m::out_word::kMsw] &
            (m::cmd_msw::kResetErrors | m::cmd_msw::kPresetPosition)) != 0;
  }
  // An interpolated move: the block in all sixteen words, as the manual asks (the data, then the
  // bits >= 10 ms later) or not (all at once, an MSW bit with it), then released.
  void extra(VirtualMachine& vm, ReasonChecker& ck, Rng& r) override {
    ImageWords& out = vm.plc_out();
    const auto method = r.pick<std::uint16_t>(
        {il::kLinear, il::kLinear, il::kViaPoint, il::kCwCircular, il::kCcwCircular,
         il::kRadiusMethod | il::kCwCircular, il::kRadiusMethod | il::kCcwCircular,
         il::kLinear | il::kViaPoint, il::kRadiusMethod});
    std::uint16_t lsw = method | (r.percent(25) ? il::kAbsoluteCoordinates : 0);
    lsw |= r.pick<std::uint16_t>({0, 0, 0, il::kSCurve});
    clear(out, 0);
    clear(out, 1);
    put_split(out, iw::kSpeedMsw, speed(r));
    out.w[iw::kAccel] = rate(r);
    out.w[iw::kDecel] = rate(r);
    put_split(out, iw::kEndXMsw, point(r));
    put_split(out, iw::kEndYMsw, point(r));
    put_split(out, iw::kPointXMsw, point(r));
    if (method & il::kRadiusMethod) {
      if (r.percent(80)) put_split(out, iw::kPointYMsw, 0);
    } else {
      put_split(out, iw::kPointYMsw, point(r));
    }
    if (r.percent(70)) ck.scans(10 + r.below(3));  // the data first, the bits later
    out.w[iw::kLsw] = static_cast<std::int16_t>(lsw);
    if (r.percent(5)) out.w[iw::kMsw] = static_cast<std::int16_t>(m::cmd_msw::kRelativeMove);
    if (r.percent(5)) out.w[iw::kAxis2Msw] = 1;  // a reserved word
    ck.scans(1 + r.below(4));
    release(out, 0);
  }

 private:
  static std::int32_t target(Rng& r) {
    return r.pick<std::int32_t>({0, 0, 300, -300, 3'000, -3'000, 20'000, 150'000, 1'100'000'000});
  }
  static std::int32_t speed(Rng& r) {
    return r.pick<std::int32_t>({0, 500, 1'000, 5'000, 20'000, 100'000, 2'000'000});
  }
  static std::int16_t rate(Rng& r) { return r.pick<std::int16_t>({0, 1, 10, 50, 500, 5'000}); }
  static std::int32_t point(Rng& r) {
    return r.pick<std::int32_t>({0, 0, 500, -500, 2'000, -2'000, 1'000, 1'100'000'000});
  }
};

TEST(ReasonsFuzz3602, ErrorBitsAndReasonsAgreeOnEveryScan) {
  const std::uint32_t s = seed(3602);
  VirtualMachine vm(default_3602());  // the 3602 rig's machine
  ReasonChecker ck(vm);
  Driver3602 d;
  Rng r(s);
  run(vm, d, r, ck, 20'000);
  expect_agreement("3602", s, ck.tally());
  EXPECT_GE(ck.tally().rises, 100u);  // the sequences do reach the error paths
  EXPECT_GE(ck.tally().codes.size(), 12u);
}

}  // namespace
}  // namespace stepmod::testing::fuzz
