// The Identity object's values and encodings (docs/ethernetip-design.md, "Identity").
#include "fieldbus/enip/identity.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

std::vector<std::uint8_t> bytes_of(const Writer& w) {
  return {w.written().begin(), w.written().end()};
}

TEST(EnipIdentity, ValuesFollowTheModuleType) {
  for (const std::uint32_t type : {3601u, 3602u, 3202u}) {
    const IdentityValues id = identity_for(type, 7);
    EXPECT_EQ(id.product_code, type);
    EXPECT_EQ(id.vendor, kVendorId);
    EXPECT_EQ(id.device_type, kDeviceType);
    EXPECT_EQ(id.serial, 7u);
    EXPECT_EQ(id.product_name(), "stepmod " + std::to_string(type));
  }
}

TEST(EnipIdentity, GetAttributesAllIsAttributesOneToSevenInOrder) {
  const IdentityValues id = identity_for(3601, 0x11223344u);
  std::array<std::uint8_t, 64> buf{};
  Writer w(buf);
  put_identity_all(w, id);
  ASSERT_TRUE(w.ok());
  const auto want =
      hex("ffff 2b00 110e 01 01 3000 44332211 0c"
          "73 74 65 70 6d 6f 64 20 33 36 30 31");  // "stepmod 3601"
  EXPECT_EQ(bytes_of(w), want);
}

TEST(EnipIdentity, SingleAttributes) {
  const IdentityValues id = identity_for(3202, 5);
  std::array<std::uint8_t, 64> buf{};
  Writer w(buf);
  ASSERT_TRUE(put_identity_attribute(w, id, 3));
  EXPECT_EQ(bytes_of(w), hex("820c"));
  Writer w8(buf);
  ASSERT_TRUE(put_identity_attribute(w8, id, 8));
  EXPECT_EQ(bytes_of(w8), hex("03"));
  Writer w9(buf);
  EXPECT_FALSE(put_identity_attribute(w9, id, 9));
  EXPECT_FALSE(put_identity_attribute(w9, id, 0));
  EXPECT_EQ(w9.size(), 0u);
}

TEST(EnipIdentity, SerialIsStableDistinctAndNeverZero) {
  const auto a = identity_serial("0123456789abcdef", "x");
  EXPECT_EQ(a, identity_serial("0123456789abcdef", "x"));
  EXPECT_NE(a, identity_serial("0123456789abcdef", "y"));
  EXPECT_NE(identity_serial("ab", "c"), identity_serial("a", "bc"));
  EXPECT_NE(identity_serial("", ""), 0u);
}

TEST(EnipIdentity, StatusWordSaysOwnershipAndRunState) {
  EXPECT_EQ(identity_status_word(false, 0, false), 0x0030);
  EXPECT_EQ(identity_status_word(true, 1, true), 0x0061);
  EXPECT_EQ(identity_status_word(false, 2, false), 0x0070);
}

}  // namespace
}  // namespace stepmod::enip
