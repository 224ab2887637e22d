// The shared-memory image (docs/interface.md 3): layout, creation rules, client checks, the seqlock
// single-threaded behaviour, heartbeat and scan counter.
#include <fcntl.h>
#include <grp.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "ipc/client.hpp"
#include "ipc/shm_image.hpp"

extern "C" {
int stepmod_c_read_inputs(const stepmod_image_t* im, int32_t* out);
void stepmod_c_write_outputs(stepmod_image_t* im, const int32_t* in);
void stepmod_c_heartbeat(stepmod_image_t* im);
unsigned stepmod_c_offset_of_input_image(void);
unsigned stepmod_c_panel_size(void);
}

namespace stepmod::ipc {
namespace {

constexpr ModuleShape k3601{ModuleType::k3601, 1, 2, 8, 8};
constexpr ModuleShape k3602{ModuleType::k3602, 2, 2, 16, 16};
constexpr ModuleShape k3202{ModuleType::k3202, 2, 4, 16, 16};

// Unique per process and test, so parallel ctest runs never share an object.
std::string test_name(const char* tag) {
  return std::string("t-") + tag + "-" + std::to_string(::getpid());
}

TEST(ImageLayout, OffsetsMatchInterfaceSection3) {
  EXPECT_EQ(sizeof(stepmod_image_t), 4096u);
  EXPECT_EQ(offsetof(stepmod_image_t, version), 8u);
  EXPECT_EQ(offsetof(stepmod_image_t, module_type), 12u);
  EXPECT_EQ(offsetof(stepmod_image_t, word_bytes), 16u);
  EXPECT_EQ(offsetof(stepmod_image_t, output_words), 20u);
  EXPECT_EQ(offsetof(stepmod_image_t, input_words), 24u);
  EXPECT_EQ(offsetof(stepmod_image_t, scan_counter), 32u);
  EXPECT_EQ(offsetof(stepmod_image_t, plc_heartbeat), 40u);
  EXPECT_EQ(offsetof(stepmod_image_t, output_seq), 48u);
  EXPECT_EQ(offsetof(stepmod_image_t, input_seq), 52u);
  EXPECT_EQ(offsetof(stepmod_image_t, output_image), 64u);
  EXPECT_EQ(offsetof(stepmod_image_t, input_image), 128u);
  EXPECT_EQ(offsetof(stepmod_image_t, msg_request_seq), 192u);
  EXPECT_EQ(offsetof(stepmod_image_t, msg_done_seq), 196u);
  EXPECT_EQ(offsetof(stepmod_image_t, msg_result), 200u);
  EXPECT_EQ(offsetof(stepmod_image_t, msg_data), 208u);
  EXPECT_EQ(stepmod_c_offset_of_input_image(), 128u);  // same layout seen from C
}

TEST(ImageLayout, PanelOffsetsMatchInterfaceSection4) {
  EXPECT_EQ(stepmod_c_panel_size(), 4096u);
  for (unsigned i = 0; i < STEPMOD_PANEL_MAX_AXES; ++i) {
    const std::size_t base = offsetof(stepmod_panel_t, axis) + i * sizeof(stepmod_panel_axis_t);
    EXPECT_EQ(base + offsetof(stepmod_panel_axis_t, position), 64u + 64u * i);
    EXPECT_EQ(base + offsetof(stepmod_panel_axis_t, encoder), 72u + 64u * i);
    EXPECT_EQ(base + offsetof(stepmod_panel_axis_t, force_mask), 80u + 64u * i);
    EXPECT_EQ(base + offsetof(stepmod_panel_axis_t, force_levels), 84u + 64u * i);
    EXPECT_EQ(base + offsetof(stepmod_panel_axis_t, outputs), 88u + 64u * i);
  }
}

TEST(ImageName, Charset) {
  EXPECT_TRUE(valid_name("stepmod"));
  EXPECT_TRUE(valid_name("a-b_c-09"));
  EXPECT_FALSE(valid_name(""));
  EXPECT_FALSE(valid_name("Stepmod"));
  EXPECT_FALSE(valid_name("a/b"));
  EXPECT_FALSE(valid_name("a.b"));
  EXPECT_FALSE(valid_name("a b"));
  EXPECT_FALSE(valid_name(std::string(65, 'a')));
  EXPECT_TRUE(valid_name(std::string(64, 'a')));
  EXPECT_THROW(ShmImage("../etc", k3601), IpcError);
  EXPECT_THROW(Client("../etc"), IpcError);
}

TEST(ShmImage, CreatesHeaderModeAndUnlinks) {
  const std::string n = test_name("hdr");
  const std::string path = "/dev/shm/stepmod." + n;
  {
    const mode_t old = ::umask(077);  // the image must still be 0660
    ShmImage img(n, k3202);
    ::umask(old);
    struct stat st {};
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0660u);
    EXPECT_EQ(st.st_size, 4096);
    const stepmod_image_t& r = img.raw();
    EXPECT_EQ(std::memcmp(r.magic, "STEPMOD\0", 8), 0);
    EXPECT_EQ(r.version, 1u);
    EXPECT_EQ(r.module_type, 3202u);
    EXPECT_EQ(r.word_bytes, 4u);
    EXPECT_EQ(r.output_words, 16u);
    EXPECT_EQ(r.input_words, 16u);
    EXPECT_EQ(r.reserved28, 0u);
    EXPECT_EQ(r.scan_counter, 0u);
    EXPECT_EQ(r.owner_pid, static_cast<std::uint64_t>(::getpid()));
  }
  EXPECT_NE(::access(path.c_str(), F_OK), 0) << "unlinked on destruction";
}

TEST(ShmImage, SecondDaemonWithSameNameRefused) {
  const std::string n = test_name("dup");
  ShmImage a(n, k3601);
  try {
    ShmImage b(n, k3601);
    FAIL() << "second image created";
  } catch (const IpcError& e) {
    EXPECT_NE(std::string(e.what()).find("in use by process"), std::string::npos) << e.what();
  }
  Client c(n);  // the first one is intact
  EXPECT_EQ(c.type(), ModuleType::k3601);
}

// Writes a header with `pid` as owner, like a daemon that then died without cleaning up.
void make_leftover(const std::string& n, std::uint64_t pid, const char* magic) {
  const std::string obj = "/stepmod." + n;
  const int fd = ::shm_open(obj.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);
  auto* im = static_cast<stepmod_image_t*>(
      ::mmap(nullptr, 4096, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0));
  std::memcpy(im->magic, magic, 8);
  im->owner_pid = pid;
  ::munmap(im, 4096);
  ::close(fd);
}

pid_t dead_pid() {
  const pid_t p = ::fork();
  if (p == 0) ::_exit(0);
  int st = 0;
  ::waitpid(p, &st, 0);
  return p;  // reaped: no such process any more (pid reuse within the test is not a concern)
}

TEST(ShmImage, StaleImageOfCrashedDaemonReplaced) {
  const std::string n = test_name("stale");
  make_leftover(n, static_cast<std::uint64_t>(dead_pid()), "STEPMOD\0");
  ShmImage img(n, k3601);
  EXPECT_EQ(img.raw().owner_pid, static_cast<std::uint64_t>(::getpid()));
}

// The pid recorded in a crashed daemon's image may belong to another process by now (pids are
// reused): what tells a live owner is its lock on the object, not kill(pid, 0).
TEST(ShmImage, StaleImageWhosePidWasReusedIsReplaced) {
  const std::string n = test_name("reused");
  make_leftover(n, static_cast<std::uint64_t>(::getpid()), "STEPMOD\0");  // a live pid, no lock
  ShmImage img(n, k3601);
  EXPECT_EQ(img.raw().owner_pid, static_cast<std::uint64_t>(::getpid()));
  EXPECT_NE(img.replaced_description().find("stale"), std::string::npos);
}

TEST(ShmImage, ImageIsLockedWhileItsOwnerHoldsIt) {
  const std::string n = test_name("locked");
  const std::string obj = "/stepmod." + n;
  {
    ShmImage img(n, k3601);
    const int fd = ::shm_open(obj.c_str(), O_RDONLY, 0);
    ASSERT_GE(fd, 0);
    EXPECT_NE(::flock(fd, LOCK_SH | LOCK_NB), 0) << "the owner's lock is held";
    EXPECT_EQ(errno, EWOULDBLOCK);
    ::close(fd);
  }
  EXPECT_LT(::shm_open(obj.c_str(), O_RDONLY, 0), 0) << "unlinked with its owner";
}

TEST(ShmImage, UnknownExistingObjectRefusedWithHint) {
  const std::string n = test_name("unknown");
  make_leftover(n, 0, "GARBAGE\0");
  try {
    ShmImage img(n, k3601);
    FAIL();
  } catch (const IpcError& e) {
    EXPECT_NE(std::string(e.what()).find("remove /dev/shm/stepmod." + n), std::string::npos)
        << e.what();
  }
  ::shm_unlink(("/stepmod." + n).c_str());
}

TEST(Client, AbsentImageClearError) {
  try {
    Client c(test_name("absent"));
    FAIL();
  } catch (const IpcError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(Client, BadMagicAndVersionRejected) {
  const std::string n = test_name("magic");
  make_leftover(n, 1, "NOTSTEP\0");
  EXPECT_THROW(Client{n}, IpcError);
  ::shm_unlink(("/stepmod." + n).c_str());

  ShmImage img(n, k3601);
  auto& raw = const_cast<stepmod_image_t&>(img.raw());
  raw.version = 2;
  try {
    Client c(n);
    FAIL();
  } catch (const IpcError& e) {
    EXPECT_NE(std::string(e.what()).find("layout version 2"), std::string::npos) << e.what();
  }
}

TEST(Client, SeesShape) {
  const std::string n = test_name("shape");
  ShmImage img(n, k3602);
  Client c(n);
  EXPECT_EQ(c.type(), ModuleType::k3602);
  EXPECT_EQ(c.shape().axes, 2u);
  EXPECT_EQ(c.shape().word_bytes, 2u);
  EXPECT_EQ(c.shape().output_words, 16u);
  EXPECT_EQ(c.shape().input_words, 16u);
  EXPECT_TRUE(c.writable());
}

TEST(ShmImage, OutputsSignExtendedAndInputsTruncated16Bit) {
  const std::string n = test_name("w16");
  ShmImage img(n, k3601);
  Client c(n);
  ImageWords out;
  out.w = {-1, 0x7FFF, -32768, 0x12345, 5, 6, 7, 8, 99, 99, 99, 99, 99, 99, 99, 99};
  c.write_outputs(out);
  ImageWords got;
  ASSERT_TRUE(img.read_outputs(got));
  EXPECT_EQ(got.w[0], -1);
  EXPECT_EQ(got.w[1], 32767);
  EXPECT_EQ(got.w[2], -32768);
  EXPECT_EQ(got.w[3], 0x2345);  // truncated to 16 bits
  EXPECT_EQ(got.w[7], 8);
  EXPECT_EQ(got.w[8], 0) << "words beyond output_words are not part of the image";

  ImageWords in;
  in.w[0] = 0x1FFFF;  // -> 0xFFFF -> -1
  in.w[1] = 40000;    // -> -25536
  in.w[7] = -2;
  img.publish_inputs(in);
  ImageWords back;
  ASSERT_TRUE(c.read_inputs(back));
  EXPECT_EQ(back.w[0], -1);
  EXPECT_EQ(back.w[1], -25536);
  EXPECT_EQ(back.w[7], -2);
  EXPECT_EQ(c.scan_counter(), 1u);
  EXPECT_EQ(img.scan_counter(), 1u);
}

TEST(ShmImage, Words32BitFull) {
  const std::string n = test_name("w32");
  ShmImage img(n, k3202);
  Client c(n);
  c.write_word(15, INT32_MIN);
  c.write_word(0, INT32_MAX);
  ImageWords got;
  ASSERT_TRUE(img.read_outputs(got));
  EXPECT_EQ(got.w[0], INT32_MAX);
  EXPECT_EQ(got.w[15], INT32_MIN);
  EXPECT_THROW(c.write_word(16, 0), IpcError);
  ImageWords in;
  in.w[15] = -123456789;
  img.publish_inputs(in);
  ImageWords back;
  ASSERT_TRUE(c.read_inputs(back));
  EXPECT_EQ(back.w[15], -123456789);
  EXPECT_EQ(c.raw().input_image.w32[15], -123456789);
}

TEST(ShmImage, WriteWordKeepsOtherWordsAndSeqEven) {
  const std::string n = test_name("ww");
  ShmImage img(n, k3601);
  Client c(n);
  ImageWords out;
  for (unsigned i = 0; i < 8; ++i) out.w[i] = static_cast<int>(i) + 10;
  c.write_outputs(out);
  c.write_word(3, -7);
  ImageWords got;
  ASSERT_TRUE(c.read_outputs(got));
  out.w[3] = -7;
  EXPECT_EQ(got, out);
  EXPECT_EQ(c.raw().output_seq % 2, 0u);
  EXPECT_EQ(c.raw().output_seq, 4u);  // two writes, +2 each
}

TEST(ShmImage, ReadOutputsFailsWhilePlcMidWriteAndKeepsPrevious) {
  const std::string n = test_name("mid");
  ShmImage img(n, k3601);
  Client c(n);
  c.write_word(0, 42);
  ImageWords prev;
  ASSERT_TRUE(img.read_outputs(prev));
  c.update_outputs([&](ImageWords& w) {
    w.w[0] = 43;
    ImageWords during = prev;
    EXPECT_FALSE(img.read_outputs(during)) << "sequence is odd during the write";
    EXPECT_EQ(during, prev) << "untouched on failure";
  });
  ImageWords after;
  ASSERT_TRUE(img.read_outputs(after));
  EXPECT_EQ(after.w[0], 43);
}

TEST(ShmImage, CPlcHeaderFunctionsInteroperate) {
  const std::string n = test_name("cplc");
  ShmImage img(n, k3601);
  Client c(n);
  auto* raw = const_cast<stepmod_image_t*>(&c.raw());
  const int32_t words[16] = {1, -2, 3, -4, 5, -6, 7, -8};
  stepmod_c_write_outputs(raw, words);
  ImageWords got;
  ASSERT_TRUE(img.read_outputs(got));
  EXPECT_EQ(got.w[1], -2);
  EXPECT_EQ(got.w[7], -8);
  ImageWords in;
  in.w[2] = -300;
  img.publish_inputs(in);
  int32_t back[16] = {};
  ASSERT_EQ(stepmod_c_read_inputs(raw, back), 1);
  EXPECT_EQ(back[2], -300);
  stepmod_c_heartbeat(raw);
  EXPECT_EQ(img.heartbeat(), 1u);
}

TEST(ShmImage, HeartbeatAndScanWaits) {
  const std::string n = test_name("hb");
  ShmImage img(n, k3601);
  Client c(n);
  EXPECT_EQ(img.heartbeat(), 0u);
  c.heartbeat();
  c.heartbeat();
  EXPECT_EQ(img.heartbeat(), 2u);
  EXPECT_EQ(c.heartbeat_value(), 2u);
  EXPECT_FALSE(c.wait_scans(1, std::chrono::milliseconds(5))) << "nobody scans";
  img.publish_inputs({});
  img.publish_inputs({});
  EXPECT_TRUE(c.wait_scan_counter(2, std::chrono::milliseconds(5)));
}

TEST(ShmImage, MessageAreaIdleWithoutRequest) {
  const std::string n = test_name("msg");
  ShmImage img(n, k3202);
  EXPECT_FALSE(img.pending_message().has_value());
}

// A user outside the daemon's group (the image is 0660) is told which group to join and how,
// not only "Permission denied" (issue 33).
TEST(ShmImage, AUserOutsideTheGroupIsToldWhichGroupToJoin) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to become another user";
  const std::string n = test_name("perm");
  ShmImage img(n, k3601);
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(fds[0]);
    std::string m = "(opened)";
    if (::setgroups(0, nullptr) != 0 || ::setresgid(65534, 65534, 65534) != 0 ||
        ::setresuid(65534, 65534, 65534) != 0) {
      m = "(cannot drop privileges)";
    } else {
      try {
        Client c(n);
      } catch (const IpcError& e) {
        m = e.what();
      }
    }
    const ssize_t w = ::write(fds[1], m.data(), m.size());
    ::_exit(w == static_cast<ssize_t>(m.size()) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string got;
  char buf[512];
  for (ssize_t r; (r = ::read(fds[0], buf, sizeof buf)) > 0;)
    got.append(buf, static_cast<std::size_t>(r));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_NE(got.find("Permission denied"), std::string::npos) << got;
  EXPECT_NE(got.find("usermod -aG stepmod"), std::string::npos) << got;
}

}  // namespace
}  // namespace stepmod::ipc
