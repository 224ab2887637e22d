// stepmod hardware layer for the OpenPLC v3 runtime: the PLC program drives a stepmod module
// (an emulated AMCI 3601/3602/3202) through %IW/%QW, word for word as the module's manual lays
// out its backplane words. Install: see openplc/README.md.
//
// Addresses (the same registers as stepmod's Modbus map, docs/interface.md section 6):
//   %IW0  .. %IW31   the module's input words (3601/3602: one %IW per word; 3202: two per 32-bit
//                    word, high half first)
//   %IW32 .. %IW47   module type, word size (bytes), output words, input words, scan counter
//                    bits 15..0 and 31..16, health flags (docs/interface.md 3.3) low and high,
//                    late-edge faults low and high (Modbus 1000..1009); %IW42 link (below);
//                    %IW43..%IW46 the error reasons' item codes, axis 1 high/low, axis 2
//                    high/low (docs/interface.md 3.4, Modbus 1016..1019); %IW47 reserved (0)
//   %QW0  .. %QW31   the module's output words (same layout as the inputs)
//
// The module is /dev/shm/stepmod.<name>; <name> comes from the environment variable STEPMOD_NAME
// (default "stepmod"), set where the OpenPLC runtime is started.
//
// How OpenPLC v3 (webserver/core/main.cpp) calls this file: glueVars() binds the program's
// located variables; initializeHardware(); one updateBuffersIn() and updateBuffersOut(); then
// mapUnusedIO() points every %IW/%QW the program does NOT declare at OpenPLC's own Modbus
// registers (so no pointer is NULL any more, and Modbus clients of OpenPLC write those %QW).
// Each scan: updateBuffersIn(); lock bufferLock; Modbus master in, the program, Modbus master
// out; unlock; updateBuffersOut(). At stop: disableOutputs() (every %QW pointer set to 0),
// updateBuffersOut(), finalizeHardware().
//
// So: the %QW words the program declares are recorded in initializeHardware() (before
// mapUnusedIO()), and only they are forwarded to the module; the others are written as 0, never
// from OpenPLC's Modbus registers. updateBuffersIn() takes one consistent seqlock snapshot of the
// input image. %IW42 (link) is 1 only while a stepmodd is scanning the image: it has published
// it at least once and the layer saw its scan counter advance within the last kLinkLossNs
// (CLOCK_MONOTONIC here). An image that exists but is not yet published (a daemon starting),
// whose counter is frozen (a daemon stopped with SIGSTOP, or killed: its image stays until a new
// daemon replaces it) or gone is link 0, and every %IW 0. A snapshot that fails (the module
// publishing on every try) keeps the last good words; it too drops the link only after
// kLinkLossNs of failed tries with no good one between. updateBuffersOut() writes the output
// image as one seqlock write and increments the PLC heartbeat (docs/interface.md 3.2): with
// [module] plc_timeout_ms set, a stopped or dead runtime stops the axes as a PLC leaving Run
// mode does (the stop's disableOutputs() only writes zeros, which stops nothing). The image is
// looked for (and its identity checked) on every scan: one stat() of /dev/shm. Only libc and the
// plain-C header stepmod_image.h (copied next to this file) are needed.
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
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
const unsigned kLinkOffset = 10;    // %IW42
const unsigned kReasonOffset = 11;  // %IW43..%IW46: the reasons' item codes, as Modbus 1016..1019
// How long the link lasts without a sign of a live module (its scan counter advancing, a good
// snapshot): far longer than a module's scan (1 ms by default) and its publication
// (microseconds), shorter than any sensible reaction of a program.
const int64_t kLinkLossNs = 100000000;

struct Link {
  char object[96];  // "/stepmod.<name>"
  char path[104];   // "/dev/shm/stepmod.<name>"
  stepmod_image_t* img;
  ino_t ino;  // identity of the mapped object: a restarted daemon makes a new one
  dev_t dev;
  // The mapped image's shape as checked when it was mapped (never re-read: the bounds of every
  // copy from and to the image).
  unsigned word_bytes;
  unsigned input_words;
  unsigned output_words;
  int logged_missing;
  // Is a module scanning the image? Its scan counter as last read, and when (CLOCK_MONOTONIC,
  // this process's clock) the layer last saw it change. A count seen once proves nothing: a
  // stopped or killed daemon's image keeps its last one.
  uint64_t scans;
  int seen_advance;
  int64_t advanced_ns;
  int scanning;  // as decided by the last scan (the log says when it changes)
  // The last good snapshot of a published image (valid while has_good).
  int has_good;
  // Since when every try has failed (valid while failing). Counted from the first failed try,
  // not from the last good one: a runtime whose own scan thread was held up (a loaded machine)
  // and then finds the module mid-publication once has not lost the link.
  int failing;
  int64_t failing_since_ns;
  int32_t in[STEPMOD_MAX_WORDS];
  uint16_t header[kHeaderRegs];
  unsigned regs;
  // The %QW the program declares (bound by glueVars() before initializeHardware()).
  unsigned char qw_declared[kRegs];
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
  g_link.has_good = 0;
  g_link.failing = 0;
  g_link.seen_advance = 0;
  g_link.scanning = 0;
}

// Maps the image if it exists and is a valid layout-1 stepmod image; 1 on success.
int map_image() {
  const int fd = shm_open(g_link.object, O_RDWR, 0);
  if (fd < 0) return 0;
  struct stat st = {};
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
  g_link.word_bytes = im->word_bytes;
  g_link.input_words = im->input_words;
  g_link.output_words = im->output_words;
  g_link.scans = stepmod_scan_counter(im);
  return 1;
}

// Every scan: (re)map the image when it appeared, disappeared or was created anew by a
// restarted stepmodd (the old mapping would otherwise stay valid memory that nobody scans). Once
// a second was too slow: a daemon with plc_timeout_ms = 500 declared the PLC stale before the
// layer had found its image.
void check_link() {
  struct stat st = {};
  const int present = stat(g_link.path, &st) == 0;
  if (g_link.img != nullptr && present && st.st_ino == g_link.ino && st.st_dev == g_link.dev) {
    return;
  }
  if (g_link.img != nullptr) {
    log_line("stepmod: module image %s%s went away\n", g_link.path, "");
    unmap();
  }
  if (present && map_image()) {
    log_line("stepmod: found module image %s%s\n", g_link.path, "");
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

// What one input publication holds for the program (docs/interface.md 3, 3.3, 3.4).
struct Publication {
  int32_t in[STEPMOD_MAX_WORDS];
  uint32_t health;
  uint32_t late;
  uint32_t items[2];
};

// One consistent seqlock snapshot of all of it (the order of stepmod_image.h's readers: acquire
// loads, then the sequence again); 0 if a write overlapped every try.
int read_publication(const stepmod_image_t* im, Publication* p) {
  for (unsigned t = 0; t < 1000u; ++t) {
    if (t > 0 && (t % 32u) == 0u) sched_yield();
    const uint32_t s0 = __atomic_load_n(&im->input_seq, __ATOMIC_ACQUIRE);
    if (s0 & 1u) continue;
    for (unsigned i = 0; i < g_link.input_words; ++i) {
      p->in[i] = stepmod_word_load(&im->input_image, g_link.word_bytes, i);
    }
    p->health = __atomic_load_n(&im->health_flags, __ATOMIC_ACQUIRE);
    p->late = __atomic_load_n(&im->late_faults, __ATOMIC_ACQUIRE);
    for (unsigned a = 0; a < 2u; ++a) {
      p->items[a] = __atomic_load_n(&im->reasons[a].item, __ATOMIC_ACQUIRE);
    }
    if (__atomic_load_n(&im->input_seq, __ATOMIC_RELAXED) == s0) return 1;
  }
  return 0;
}

void keep_publication(const Publication& p, uint64_t scans) {
  const stepmod_image_t* im = g_link.img;
  memcpy(g_link.in, p.in, sizeof p.in);
  g_link.regs = g_link.input_words * g_link.word_bytes / 2u;
  uint16_t* h = g_link.header;
  h[0] = (uint16_t)im->module_type;
  h[1] = (uint16_t)g_link.word_bytes;
  h[2] = (uint16_t)g_link.output_words;
  h[3] = (uint16_t)g_link.input_words;
  h[4] = (uint16_t)(scans & 0xFFFFu);
  h[5] = (uint16_t)((scans >> 16) & 0xFFFFu);
  h[6] = (uint16_t)(p.health & 0xFFFFu);
  h[7] = (uint16_t)(p.health >> 16);
  h[8] = (uint16_t)(p.late & 0xFFFFu);
  h[9] = (uint16_t)(p.late >> 16);
  for (unsigned a = 0; a < 2u; ++a) {
    h[kReasonOffset + 2 * a] = (uint16_t)(p.items[a] >> 16);
    h[kReasonOffset + 2 * a + 1] = (uint16_t)(p.items[a] & 0xFFFFu);
  }
}

// Reads the scan counter and takes a snapshot of the mapped image into g_link; a snapshot that
// fails keeps the last good one.
void take_snapshot(int64_t now) {
  stepmod_image_t* im = g_link.img;
  if (im == nullptr) return;
  // The counter before the words: a count of 1 or more read here (an acquire load of what the
  // daemon increments after each publication) means the snapshot below is of that publication
  // or a later one, never of the zeros the image is created with before its first scan.
  const uint64_t scans = stepmod_scan_counter(im);
  if (scans != g_link.scans) {
    g_link.scans = scans;
    g_link.seen_advance = 1;
    g_link.advanced_ns = now;
  }
  Publication p = {};
  if (!read_publication(im, &p)) {
    if (!g_link.failing) g_link.failing_since_ns = now;
    g_link.failing = 1;
    return;
  }
  g_link.failing = 0;
  if (scans == 0) return;  // nothing published yet
  keep_publication(p, scans);
  g_link.has_good = 1;
}

// The link rule (openplc/README.md): a module that has published and is scanning now, and a
// good snapshot not older than the failed tries allow.
int link_up(int64_t now) {
  const int scanning = g_link.seen_advance && now - g_link.advanced_ns < kLinkLossNs;
  if (scanning != g_link.scanning) {
    log_line(scanning ? "stepmod: module image %s is scanned: link up%s\n"
                      : "stepmod: module image %s not scanned for 100 ms: link down%s\n",
             g_link.path, scanning ? "" : " (stepmodd stopped or dead?)");
    g_link.scanning = scanning;
  }
  return scanning && g_link.has_good &&
         (!g_link.failing || now - g_link.failing_since_ns < kLinkLossNs);
}

}  // namespace

void initializeHardware() {
  memset(&g_link, 0, sizeof g_link);
  // Before mapUnusedIO() binds the rest to OpenPLC's Modbus registers (see the top).
  for (unsigned r = 0; r < kRegs; ++r) g_link.qw_declared[r] = int_output[r] != nullptr;
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
  const int64_t now = stepmod_monotonic_ns();
  take_snapshot(now);
  // Link down: every %IW 0 (the documented link-down values), never words nobody scans.
  const int linked = link_up(now);
  const unsigned regs = linked ? g_link.regs : 0u;
  pthread_mutex_lock(&bufferLock);
  for (unsigned r = 0; r < kRegs; ++r) {
    set_iw(r, r < regs ? reg_of(g_link.in, g_link.word_bytes, r) : 0);
  }
  for (unsigned h = 0; h < kHeaderRegs; ++h) {
    set_iw(kHeaderIw + h, !linked ? 0 : h == kLinkOffset ? 1 : g_link.header[h]);
  }
  pthread_mutex_unlock(&bufferLock);
}

void updateBuffersOut() {
  stepmod_image_t* im = g_link.img;
  if (im == nullptr) return;
  const unsigned word_bytes = g_link.word_bytes;
  const unsigned words = g_link.output_words;
  int32_t out[STEPMOD_MAX_WORDS] = {0};
  pthread_mutex_lock(&bufferLock);
  for (unsigned r = 0; r < words * word_bytes / 2u; ++r) {
    // A %QW the program does not declare is 0: never OpenPLC's Modbus holding register that
    // mapUnusedIO() put behind it (a Modbus client of OpenPLC would otherwise drive the module).
    const uint16_t v = g_link.qw_declared[r] && int_output[r] != nullptr ? *int_output[r] : 0;
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
  stepmod_seq_write(&im->output_seq, &im->output_image, word_bytes, words, out);
  stepmod_heartbeat(im);
}
