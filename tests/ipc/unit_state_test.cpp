// The image's unit-state blocks (docs/interface.md 3.6): what each axis holds beyond its words
// (the configuration taken, its input lines, its drive enable), written by the daemon with the
// input publication and read by a console under the input seqlock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <cstring>
#include <string>

#include "ipc/client.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::ipc {
namespace {

constexpr ModuleShape k3602{ModuleType::k3602, 2, 2, 16, 16};

TEST(UnitStateBlock, AtOffset592PlusFortyEightPerAxisUnderTheInputSeqlock) {
  // docs/interface.md 3.6: the blocks at 592 and 640, their fields at 0, 4, 8, 16.
  const std::size_t offsets[][2] = {{offsetof(stepmod_image_t, units), 592},
                                    {offsetof(stepmod_image_t, units[1]), 640},
                                    {offsetof(stepmod_unit_state_t, inputs), 4},
                                    {offsetof(stepmod_unit_state_t, drive_enable), 8},
                                    {offsetof(stepmod_unit_state_t, config_words), 16},
                                    {sizeof(stepmod_unit_state_t), 48}};
  for (const auto& o : offsets) EXPECT_EQ(o[0], o[1]);

  ShmImage image("t-unit-" + std::to_string(::getpid()), k3602);
  Client client(image.name());
  ASSERT_TRUE(client.read_unit_state(1).has_value());
  EXPECT_EQ(client.read_unit_state(1)->config_seq, 0u);
  EXPECT_FALSE(client.read_unit_state(2).has_value());  // a 3602 has two axes

  stepmod_unit_state_t s{};
  s.config_seq = 2;
  s.inputs = 0x04u | (0x37u << STEPMOD_UNIT_WIRED_SHIFT) | (0x34u << STEPMOD_UNIT_USED_SHIFT) |
             (0x04u << STEPMOD_UNIT_ACTIVE_SHIFT);
  s.drive_enable = STEPMOD_UNIT_ENABLE_WIRED | STEPMOD_UNIT_ENABLE_ASSERTED;
  s.config_words[0] = -31668;  // 16#844C: bit 15, the mode, sign-extended
  s.config_words[3] = 321;
  image.set_unit_state(1, s);
  EXPECT_EQ(client.read_unit_state(1)->config_seq, 0u);  // only with the next publication
  image.publish_inputs(ImageWords{});
  const auto r = client.read_unit_state(1);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->config_seq, 2u);
  EXPECT_EQ(r->inputs, s.inputs);
  EXPECT_EQ(r->drive_enable, 3u);
  EXPECT_EQ(r->config_words[0], -31668);
  EXPECT_EQ(r->config_words[3], 321);
  std::int32_t word = 0;
  std::memcpy(&word, reinterpret_cast<const unsigned char*>(&image.raw()) + 640 + 16 + 12, 4);
  EXPECT_EQ(word, 321);
  EXPECT_EQ(client.read_unit_state(0)->config_seq, 0u);  // axis 1 untouched
}

}  // namespace
}  // namespace stepmod::ipc
