// The simulator panel (docs/interface.md 4): header, publication, forcing.
#include "ipc/sim_panel.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace stepmod::ipc {
namespace {

std::string test_name(const char* tag) {
  return std::string("p-") + tag + "-" + std::to_string(::getpid());
}

TEST(SimPanel, HeaderAndPath) {
  const std::string n = test_name("hdr");
  {
    SimPanelServer s(n, 2);
    struct stat st {};
    ASSERT_EQ(::stat(("/dev/shm/stepmod." + n + ".sim").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0660u);
    SimPanelClient c(n);
    EXPECT_EQ(c.axes(), 2u);
  }
  EXPECT_THROW(SimPanelClient{n}, IpcError) << "removed with the server";
}

TEST(SimPanel, PublishedStateReadByClient) {
  const std::string n = test_name("pub");
  SimPanelServer s(n, 2);
  SimPanelClient c(n);
  s.publish_position(1, -123456789012);
  s.publish_encoder(1, 42);
  s.publish_outputs(1, 0b101);
  const PanelAxis a = c.read(1);
  EXPECT_EQ(a.position, -123456789012);
  EXPECT_EQ(a.encoder, 42);
  EXPECT_EQ(a.outputs, 0b101u);
  EXPECT_EQ(c.read(0).position, 0);
  EXPECT_THROW(c.read(2), IpcError);
}

TEST(SimPanel, ForceAndRelease) {
  const std::string n = test_name("force");
  SimPanelServer s(n, 1);
  SimPanelClient c(n);
  c.force(0, STEPMOD_IN_HOME, true);
  c.force(0, STEPMOD_IN_CW_LIMIT, false);
  EXPECT_EQ(s.force_mask(0), (1u << 2) | (1u << 4));
  EXPECT_EQ(s.force_levels(0) & ((1u << 2) | (1u << 4)), 1u << 2);
  c.force(0, STEPMOD_IN_HOME, false);
  EXPECT_EQ(s.force_levels(0) & (1u << 2), 0u);
  c.release(0, STEPMOD_IN_HOME);
  EXPECT_EQ(s.force_mask(0), 1u << 4);
  c.release_all(0);
  EXPECT_EQ(s.force_mask(0), 0u);
  EXPECT_THROW(c.force(1, 0, true), IpcError);
  EXPECT_THROW(c.force(0, 6, true), IpcError);
}

TEST(SimPanel, SecondServerRefused) {
  const std::string n = test_name("dup");
  SimPanelServer s(n, 1);
  EXPECT_THROW(SimPanelServer(n, 1), IpcError);
}

}  // namespace
}  // namespace stepmod::ipc
