// stepmod hardware layer for the OpenPLC v3 runtime: the PLC program drives a stepmod module
// (an emulated AMCI 3601/3602/3202) through %IW/%QW, word for word as the module's manual lays
// out its backplane words. Install: see openplc/README.md.
//
// Addresses (the same registers as stepmod's Modbus map, docs/interface.md section 6):
//   %IW0  .. %IW31   the module's input words (3601/3602: one %IW per word; 3202: two per 32-bit
//                    word, high half first)
//   %IW32 .. %IW47   module type, word size (bytes), output words, input words, scan counter
//                    bits 15..0 and 31..16, health flags (docs/interface.md 3.3) low and high,
//                    late-edge faults low and high, %IW42 link (1 while a running stepmodd's
//                    image is mapped, else 0 and every %IW is 0), %IW43..%IW47 reserved (0)
//   %QW0  .. %QW31   the module's output words (same layout as the inputs)
//
// The module is /dev/shm/stepmod.<name>; <name> comes from the environment variable STEPMOD_NAME
// (default "stepmod"), set where the OpenPLC runtime is started.
//
// Each OpenPLC scan: updateBuffersIn() takes one consistent seqlock snapshot of the input image;
// updateBuffersOut() writes the whole output image as one seqlock write and increments the PLC
// heartbeat (docs/interface.md 3.2), so with [module] plc_timeout_ms a stopped runtime stops the axes.
// Only libc and the plain-C header stepmod_image.h (copied next to this file) are needed.
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "ladder.h"
#include "stepmod_image.h"

namespace {

const unsigned kRegs = 32;      // %IW0..31 / %QW0..31: 16 words of at most 32 bits
const unsigned kHeaderIw = 32;  // %IW32..47
const unsigned kHeaderRegs = 16;
const unsigned kLinkOffset = 10;        // %IW42
const int64_t kRecheckNs = 1000000000;  // how often the image is looked for again

struct Link {
  char object[96];  // "/stepmod.<name>"
  char path[104];   // "/dev/shm/stepmod.<name>"
  stepmod_image_t* img;
  ino_t ino;  // identity of the mapped object: a restarted daemon makes a new one
  dev_t dev;
  int64_t next_check_ns;
  int logged_missing;
};

Link g_link;

void log_line(const char* fmt, const char* a, const char* b) {
  char msg[512];
  snprintf(msg, sizeof msg, fmt, a, b);
  openplc_log(msg);
}

void unmap() {
  if (g_link.img != nullptr) munmap(g_link.img, STEPMOD_IMAGE_SIZE);
  g_link.img = nullptr;
}

// Maps the image if it exists and is a valid layout-1 stepmod image; 1 on success.
int map_image() {
  const int fd = shm_open(g_link.object, O_RDWR, 0);
  if (fd < 0) return 0;
  struct stat st;
  void* p = MAP_FAILED;
  if (fstat(fd, &st) == 0 && st.st_size >= (off_t)STEPMOD_IMAGE_SIZE) {
    p = mmap(nullptr, STEPMOD_IMAGE_SIZE, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  }
  close(fd);
  if (p == MAP_FAILED) return 0;
  stepmod_image_t* im = static_cast<stepmod_image_t*>(p);
  const int ok = stepmod_magic_is(im->magic, STEPMOD_IMAGE_MAGIC) &&
                 im->version == STEPMOD_LAYOUT_VERSION &&
                 (im->word_bytes == 2u || im->word_bytes == 4u) &&
                 im->output_words <= STEPMOD_MAX_WORDS && im->input_words <= STEPMOD_MAX_WORDS;
  if (!ok) {
    munmap(p, STEPMOD_IMAGE_SIZE);
    return 0;
  }
  g_link.img = im;
  g_link.ino = st.st_ino;
  g_link.dev = st.st_dev;
  return 1;
}

// Once a second: (re)map the image when it appeared, disappeared or was created anew by a
// restarted stepmodd (the old mapping would otherwise stay valid memory that nobody scans).
void check_link() {
  const int64_t now = stepmod_monotonic_ns();
  if (now < g_link.next_check_ns) return;
  g_link.next_check_ns = now + kRecheckNs;
  struct stat st;
  const int present = stat(g_link.path, &st) == 0;
  if (g_link.img != nullptr && present && st.st_ino == g_link.ino && st.st_dev == g_link.dev) {
    return;
  }
  if (g_link.img != nullptr) {
    log_line("stepmod: module image %s%s went away\n", g_link.path, "");
    unmap();
  }
  if (present && map_image()) {
    log_line("stepmod: linked to %s%s\n", g_link.path, "");
    g_link.logged_missing = 0;
  } else if (!g_link.logged_missing) {
    log_line("stepmod: no module image %s (is stepmodd running?)%s\n", g_link.path, "");
    g_link.logged_missing = 1;
  }
}

// Register r of a word image: a 16-bit word, or one half of a 32-bit word (high half first).
uint16_t reg_of(const int32_t* words, unsigned word_bytes, unsigned r) {
  if (word_bytes == 2u) return (uint16_t)words[r];
  const uint32_t w = (uint32_t)words[r / 2];
  return (uint16_t)(r % 2 == 0 ? w >> 16 : w & 0xFFFFu);
}

void set_iw(unsigned i, uint16_t v) {
  if (int_input[i] != nullptr) *int_input[i] = v;  // NULL: the program does not use this %IW
}

}  // namespace

void initializeHardware() {
  memset(&g_link, 0, sizeof g_link);
  const char* name = getenv("STEPMOD_NAME");
  if (name == nullptr || name[0] == '\0') name = "stepmod";
  snprintf(g_link.object, sizeof g_link.object, "/stepmod.%s", name);
  snprintf(g_link.path, sizeof g_link.path, "/dev/shm/stepmod.%s", name);
  check_link();
}

void finalizeHardware() {
  unmap();
}

void updateBuffersIn() {
  check_link();
  int32_t in[STEPMOD_MAX_WORDS] = {0};
  uint16_t header[kHeaderRegs] = {0};
  unsigned regs = 0;
  unsigned word_bytes = 2;
  stepmod_image_t* im = g_link.img;
  if (im != nullptr) {
    uint32_t health = 0;
    uint32_t late = 0;
    word_bytes = im->word_bytes;
    // A snapshot that failed (the module was publishing on every try) keeps the zeros and
    // drops the link bit for this scan; the next scan tries again.
    const int ok = stepmod_read_inputs(im, in) && stepmod_read_health(im, &health, &late);
    const uint64_t scans = stepmod_scan_counter(im);
    regs = ok ? im->input_words * word_bytes / 2u : 0u;
    header[0] = (uint16_t)im->module_type;
    header[1] = (uint16_t)word_bytes;
    header[2] = (uint16_t)im->output_words;
    header[3] = (uint16_t)im->input_words;
    header[4] = (uint16_t)(scans & 0xFFFFu);
    header[5] = (uint16_t)((scans >> 16) & 0xFFFFu);
    header[6] = (uint16_t)(health & 0xFFFFu);
    header[7] = (uint16_t)(health >> 16);
    header[8] = (uint16_t)(late & 0xFFFFu);
    header[9] = (uint16_t)(late >> 16);
    header[kLinkOffset] = (uint16_t)(ok ? 1 : 0);
  }
  pthread_mutex_lock(&bufferLock);
  for (unsigned r = 0; r < kRegs; ++r) set_iw(r, r < regs ? reg_of(in, word_bytes, r) : 0);
  for (unsigned h = 0; h < kHeaderRegs; ++h) set_iw(kHeaderIw + h, header[h]);
  pthread_mutex_unlock(&bufferLock);
}

void updateBuffersOut() {
  stepmod_image_t* im = g_link.img;
  if (im == nullptr) return;
  const unsigned word_bytes = im->word_bytes;
  const unsigned words = im->output_words;
  int32_t out[STEPMOD_MAX_WORDS] = {0};
  pthread_mutex_lock(&bufferLock);
  for (unsigned r = 0; r < words * word_bytes / 2u; ++r) {
    const uint16_t v = int_output[r] != nullptr ? *int_output[r] : 0;
    if (word_bytes == 2u) {
      out[r] = (int16_t)v;
    } else if (r % 2 == 0) {
      out[r / 2] = (int32_t)(((uint32_t)out[r / 2] & 0xFFFFu) | ((uint32_t)v << 16));
    } else {
      out[r / 2] = (int32_t)(((uint32_t)out[r / 2] & 0xFFFF0000u) | v);
    }
  }
  pthread_mutex_unlock(&bufferLock);
  // The whole output image, every scan, as the backplane carries it; then the heartbeat: this
  // PLC is in Run mode.
  stepmod_write_outputs(im, out);
  stepmod_heartbeat(im);
}
