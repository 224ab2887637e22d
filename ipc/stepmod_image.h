/* stepmod shared-memory layouts (docs/interface.md sections 3 and 4), for soft PLCs and tools.
 *
 * Plain C11 / C++ header, only libc/POSIX headers (strict -std=c11 needs _POSIX_C_SOURCE
 * >= 199309L for clock_gettime): a soft PLC written in C can include
 * it as is. Compile with GCC or Clang (the seqlock functions use the __atomic builtins, which work
 * across processes on shared memory because the fields are naturally aligned and lock-free).
 *
 * I/O image: /dev/shm/stepmod.<name>   (shm_open("/stepmod.<name>"), 4096 bytes)
 * Sim panel: /dev/shm/stepmod.<name>.sim
 *
 * Extensions to layout version 1 (in its reserved space, see docs/interface.md section 3):
 *   image offset 56 (u64): process id of the stepmodd that owns the image (0 = unknown). Lets a
 *                          new daemon tell a stale image left by a crashed one from a live one.
 *   panel offset 16 (u64): same for the simulator panel.
 *   image offset 424 (u32): the largest lateness of a late-edge fault so far, in microseconds
 *                           (saturating), beside the fault count of offset 420 (section 3.3).
 *   image offset 448 + 64 * (axis - 1): the error reason of each axis (section 3.4,
 *                           docs/error-reasons.md), under the input seqlock.
 *   image offset 576..591: the commissioning lease (section 3.5, docs/commissioning.md).
 *   image offset 592 + 48 * (axis - 1): what each axis holds beyond its words (section 3.6): the
 *                           configuration words it took, its input lines, its drive enable;
 *                           under the input seqlock.
 */
#ifndef STEPMOD_IMAGE_H
#define STEPMOD_IMAGE_H

#include <sched.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

#ifdef __cplusplus
#define STEPMOD_STATIC_ASSERT(c, m) static_assert(c, m)
extern "C" {
#else
#define STEPMOD_STATIC_ASSERT(c, m) _Static_assert(c, m)
#endif

/* All integers are little-endian (docs/interface.md 3); the structs below are native-endian, so
 * this header only describes the layout on a little-endian host. */
STEPMOD_STATIC_ASSERT(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
                      "the stepmod image is little-endian; this header maps it natively");

/* ---------------------------------------------------------------------------------------------
 * Section 3: the I/O image
 * ------------------------------------------------------------------------------------------- */
#define STEPMOD_IMAGE_SIZE 4096u
#define STEPMOD_IMAGE_MAGIC "STEPMOD" /* 8 bytes with its NUL */
#define STEPMOD_LAYOUT_VERSION 1u
#define STEPMOD_MAX_WORDS 16u
#define STEPMOD_MSG_DINTS 52u

enum stepmod_image_offset {
  STEPMOD_OFF_MAGIC = 0,
  STEPMOD_OFF_VERSION = 8,
  STEPMOD_OFF_MODULE_TYPE = 12,
  STEPMOD_OFF_WORD_BYTES = 16,
  STEPMOD_OFF_OUTPUT_WORDS = 20,
  STEPMOD_OFF_INPUT_WORDS = 24,
  STEPMOD_OFF_RESERVED28 = 28,
  STEPMOD_OFF_SCAN_COUNTER = 32,
  STEPMOD_OFF_PLC_HEARTBEAT = 40,
  STEPMOD_OFF_OUTPUT_SEQ = 48,
  STEPMOD_OFF_INPUT_SEQ = 52,
  STEPMOD_OFF_OWNER_PID = 56, /* extension, see above */
  STEPMOD_OFF_OUTPUT_IMAGE = 64,
  STEPMOD_OFF_INPUT_IMAGE = 128,
  STEPMOD_OFF_MSG_REQUEST_SEQ = 192,
  STEPMOD_OFF_MSG_DONE_SEQ = 196,
  STEPMOD_OFF_MSG_RESULT = 200,
  STEPMOD_OFF_RESERVED204 = 204,
  STEPMOD_OFF_MSG_DATA = 208,
  STEPMOD_OFF_HEALTH_FLAGS = 416,  /* section 3.3, under the input seqlock */
  STEPMOD_OFF_LATE_FAULTS = 420,   /* section 3.3, under the input seqlock */
  STEPMOD_OFF_WORST_LATE_US = 424, /* extension, see above; under the input seqlock */
  STEPMOD_OFF_REASONS = 448,       /* section 3.4: 64 bytes per axis, under the input seqlock */
  STEPMOD_REASON_STRIDE = 64,
  STEPMOD_OFF_LEASE_HOLDER = 576, /* section 3.5 */
  STEPMOD_OFF_LEASE_SEQ = 580,
  STEPMOD_OFF_LEASE_EXPIRY = 584,
  STEPMOD_OFF_UNITS = 592, /* section 3.6: 48 bytes per axis, under the input seqlock */
  STEPMOD_UNIT_STRIDE = 48,
  STEPMOD_OFF_END_OF_FIELDS = 688
};

/* Daemon health flags (offset 416, docs/interface.md 3.3): a bit each, set while the condition
 * lasts. */
#define STEPMOD_HEALTH_LATE_EDGE (1u << 0)      /* a late-edge fault stopped an axis */
#define STEPMOD_HEALTH_PLC_STALE (1u << 1)      /* PLC heartbeat stale: as in Program mode */
#define STEPMOD_HEALTH_SEQ_STUCK (1u << 2)      /* output sequence left odd (PLC died mid-write) */
#define STEPMOD_HEALTH_SEQ_BYPASS (1u << 3)     /* output words changed, sequence did not */
#define STEPMOD_HEALTH_TRACE_LOST (1u << 4)     /* trace records lost (the VCD says so too) */
#define STEPMOD_HEALTH_INPUT_LOST (1u << 5)     /* input events lost: the moving axes were stopped */
#define STEPMOD_HEALTH_LEASE_EXPIRED (1u << 6)  /* a commissioning lease expired: axes stopped */
#define STEPMOD_HEALTH_LEASE_CONFLICT (1u << 7) /* PLC heartbeat changed during a lease */

/* Section 3.4: why an error bit was set (item code: docs/error-reasons.md). */
#define STEPMOD_REASON_TEXT 56u
typedef struct stepmod_reason {
  uint32_t seq;                   /* +1 per new reason of this axis */
  uint32_t item;                  /* checklist item code, 0 = none */
  char text[STEPMOD_REASON_TEXT]; /* "3601-CE-05: Vp 500 is below Vs 1000", NUL-terminated */
} stepmod_reason_t;

/* Section 3.6: what an axis/channel holds beyond its words, for consoles and HMIs. Input bits
 * are in the simulator panel's order (STEPMOD_IN_CAPTURE .. STEPMOD_IN_CCW_LIMIT, bit 0..5). */
#define STEPMOD_UNIT_CONFIG_WORDS 8u
#define STEPMOD_UNIT_LEVELS_SHIFT 0u  /* electrical level of each input line now */
#define STEPMOD_UNIT_WIRED_SHIFT 8u   /* the line is wired (the daemon's configuration has it) */
#define STEPMOD_UNIT_USED_SHIFT 16u   /* the module's configuration uses the input */
#define STEPMOD_UNIT_ACTIVE_SHIFT 24u /* used and at its active level (after the polarity) */
#define STEPMOD_UNIT_ENABLE_WIRED (1u << 0)    /* a drive-enable line is wired */
#define STEPMOD_UNIT_ENABLE_ASSERTED (1u << 1) /* and asserted now */
typedef struct stepmod_unit_state {
  uint32_t config_seq;   /* +1 each time the axis leaves configuration mode; 0 = none yet */
  uint32_t inputs;       /* STEPMOD_UNIT_*_SHIFT fields */
  uint32_t drive_enable; /* STEPMOD_UNIT_ENABLE_* bits */
  uint32_t reserved;
  /* The axis' output words (its 8 of the image, 16- or 32-bit values) of the last scan in
   * configuration mode before config_seq's change: the configuration the axis took, unless its
   * status shows a Configuration Error (then it holds none and these words were refused). */
  int32_t config_words[STEPMOD_UNIT_CONFIG_WORDS];
} stepmod_unit_state_t;

/* 64 bytes of backplane words: 16-bit words (3601/3602) sit at 2*i, 32-bit words (3202) at 4*i. */
typedef union stepmod_words {
  int16_t w16[32];
  int32_t w32[16];
  uint8_t bytes[64];
} stepmod_words_t;

/* Every field is naturally aligned at its contract offset, so the struct needs no packing; the
 * asserts below pin each offset. (Packing would make the __atomic accesses on its members
 * potentially unaligned, which is what we must avoid across processes.) */
typedef struct stepmod_image {
  char magic[8];
  uint32_t version;
  uint32_t module_type;  /* 3601, 3602 or 3202 */
  uint32_t word_bytes;   /* 2 or 4 */
  uint32_t output_words; /* PLC -> module: 8 or 16 */
  uint32_t input_words;  /* module -> PLC: 8 or 16 */
  uint32_t reserved28;
  uint64_t scan_counter;  /* +1 after each completed module I/O scan */
  uint64_t plc_heartbeat; /* written by the PLC (section 3.2) */
  uint32_t output_seq;    /* seqlock of output_image, PLC writes */
  uint32_t input_seq;     /* seqlock of input_image, module writes */
  uint64_t owner_pid;     /* extension: pid of the owning stepmodd */
  stepmod_words_t output_image;
  stepmod_words_t input_image;
  uint32_t msg_request_seq; /* 3202 blend message: PLC increments after writing msg_data */
  uint32_t msg_done_seq;    /* module sets it equal to msg_request_seq when processed */
  int32_t msg_result;       /* 0 accepted, otherwise see the module's status bits */
  uint32_t reserved204;
  int32_t msg_data[STEPMOD_MSG_DINTS];
  uint32_t health_flags;  /* section 3.3: STEPMOD_HEALTH_* bits */
  uint32_t late_faults;   /* section 3.3: late-edge faults since the daemon started */
  uint32_t worst_late_us; /* extension: largest late-edge fault lateness, us */
  uint8_t reserved428[STEPMOD_OFF_REASONS - 428];
  stepmod_reason_t reasons[2]; /* section 3.4: axis/channel 1 and 2 */
  uint32_t lease_holder;       /* section 3.5: pid of the tool holding the lease, 0 = free */
  uint32_t lease_seq;          /* +1 by the tool at each take */
  uint64_t lease_expiry_ns;    /* CLOCK_MONOTONIC; at most 500 ms ahead, renewed every 100 ms */
  stepmod_unit_state_t units[2]; /* section 3.6: axis/channel 1 and 2 */
  uint8_t unused[STEPMOD_IMAGE_SIZE - STEPMOD_OFF_END_OF_FIELDS];
} stepmod_image_t;

STEPMOD_STATIC_ASSERT(sizeof(stepmod_image_t) == STEPMOD_IMAGE_SIZE, "image size");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, magic) == STEPMOD_OFF_MAGIC, "magic");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, version) == STEPMOD_OFF_VERSION, "version");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, module_type) == STEPMOD_OFF_MODULE_TYPE, "type");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, word_bytes) == STEPMOD_OFF_WORD_BYTES, "wbytes");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, output_words) == STEPMOD_OFF_OUTPUT_WORDS, "ow");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, input_words) == STEPMOD_OFF_INPUT_WORDS, "iw");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, reserved28) == STEPMOD_OFF_RESERVED28, "r28");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, scan_counter) == STEPMOD_OFF_SCAN_COUNTER, "scan");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, plc_heartbeat) == STEPMOD_OFF_PLC_HEARTBEAT, "hb");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, output_seq) == STEPMOD_OFF_OUTPUT_SEQ, "oseq");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, input_seq) == STEPMOD_OFF_INPUT_SEQ, "iseq");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, owner_pid) == STEPMOD_OFF_OWNER_PID, "pid");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, output_image) == STEPMOD_OFF_OUTPUT_IMAGE, "out");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, input_image) == STEPMOD_OFF_INPUT_IMAGE, "in");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, msg_request_seq) == STEPMOD_OFF_MSG_REQUEST_SEQ,
                      "msg req");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, msg_done_seq) == STEPMOD_OFF_MSG_DONE_SEQ,
                      "msg done");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, msg_result) == STEPMOD_OFF_MSG_RESULT, "msg res");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, reserved204) == STEPMOD_OFF_RESERVED204, "r204");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, msg_data) == STEPMOD_OFF_MSG_DATA, "msg data");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, health_flags) == STEPMOD_OFF_HEALTH_FLAGS, "hf");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, late_faults) == STEPMOD_OFF_LATE_FAULTS, "lf");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, worst_late_us) == STEPMOD_OFF_WORST_LATE_US, "wl");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, reasons) == STEPMOD_OFF_REASONS, "reasons");
STEPMOD_STATIC_ASSERT(sizeof(stepmod_reason_t) == STEPMOD_REASON_STRIDE, "reason stride");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, lease_holder) == STEPMOD_OFF_LEASE_HOLDER, "lh");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, lease_seq) == STEPMOD_OFF_LEASE_SEQ, "ls");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, lease_expiry_ns) == STEPMOD_OFF_LEASE_EXPIRY, "le");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, units) == STEPMOD_OFF_UNITS, "units");
STEPMOD_STATIC_ASSERT(sizeof(stepmod_unit_state_t) == STEPMOD_UNIT_STRIDE, "unit stride");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_image_t, unused) == STEPMOD_OFF_END_OF_FIELDS, "end");

/* ---------------------------------------------------------------------------------------------
 * Section 3.1: sequence locks
 *
 * Writer: seq+1 (odd), word stores (release), seq+1 (even) with release.
 * Reader: seq (acquire), word loads (acquire), seq again; retry if odd or changed.
 * The release stores / acquire loads on the words do what the textbook's two fences do (a reader
 * that sees a new word also sees the odd sequence) without fences, which ThreadSanitizer does
 * not support; on x86 and ARMv8 they cost the same as plain accesses or an ldar/stlr.
 *
 * The words themselves are accessed with relaxed __atomic loads/stores: a reader racing a writer
 * may see a mix of old and new words, which the sequence check detects, but no single access is a
 * data race (so ThreadSanitizer and the C11 memory model agree with the protocol).
 *
 * stepmod_seq_write_begin() claims the lock with a compare-and-swap rather than a plain store, so
 * that two cooperating writers (a PLC program and `stepmodctl`) never interleave their updates;
 * a single writer behaves exactly as the plain protocol of docs/interface.md 3.1. A writer that
 * died holding the lock (sequence stuck odd) is taken over after stale_ns.
 * ------------------------------------------------------------------------------------------- */
/* The magic is written last, as one 8-byte release store, by the creator of an object; a reader
 * whose acquire load sees it sees the whole header (8-byte aligned: it starts the mapping). */
static inline void stepmod_publish_magic(char* field, const char* magic) {
  uint64_t v = 0;
  memcpy(&v, magic, sizeof v);
  __atomic_store_n((uint64_t*)(void*)field, v, __ATOMIC_RELEASE);
}
static inline int stepmod_magic_is(const char* field, const char* magic) {
  uint64_t m = 0;
  memcpy(&m, magic, sizeof m);
  return __atomic_load_n((const uint64_t*)(const void*)field, __ATOMIC_ACQUIRE) == m;
}

static inline int64_t stepmod_monotonic_ns(void) {
  struct timespec ts = {0, 0};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Claims the lock: returns the odd value now held. A sequence that stays odd for stale_ns
 * (another writer died in the middle of a write) is taken over as it is; a writer that is merely
 * preempted holds it for far less than the STEPMOD_SEQ_STALE_NS default. */
#define STEPMOD_SEQ_STALE_NS 500000000 /* 0.5 s */
static inline uint32_t stepmod_seq_write_begin(uint32_t* seq, int64_t stale_ns) {
  uint32_t s = __atomic_load_n(seq, __ATOMIC_RELAXED);
  unsigned spins = 0;
  int64_t since = 0;
  for (;;) {
    if ((s & 1u) == 0u) {
      if (__atomic_compare_exchange_n(seq, &s, s + 1u, 0, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
        s += 1u;
        break;
      }
      continue; /* s was reloaded by the failed CAS */
    }
    /* Odd: another writer is inside. Spin briefly, then yield the CPU to it. */
    if (++spins > 64u) {
      const int64_t now = stepmod_monotonic_ns();
      if (since == 0) since = now;
      if (now - since >= stale_ns) break; /* stale: keep the odd value and proceed */
      sched_yield();
    }
    s = __atomic_load_n(seq, __ATOMIC_RELAXED);
  }
  return s; /* the word stores that follow are release stores: none can pass the odd value */
}

static inline void stepmod_seq_write_end(uint32_t* seq, uint32_t odd_value) {
  __atomic_store_n(seq, odd_value + 1u, __ATOMIC_RELEASE);
}

static inline int32_t stepmod_word_load(const stepmod_words_t* w, unsigned word_bytes, unsigned i) {
  return word_bytes == 2u ? (int32_t)__atomic_load_n(&w->w16[i], __ATOMIC_ACQUIRE)
                          : __atomic_load_n(&w->w32[i], __ATOMIC_ACQUIRE);
}

/* Stores the low 16 bits (2-byte words) or all 32 bits of v. */
static inline void stepmod_word_store(stepmod_words_t* w, unsigned word_bytes, unsigned i,
                                      int32_t v) {
  if (word_bytes == 2u) {
    __atomic_store_n(&w->w16[i], (int16_t)(uint16_t)((uint32_t)v & 0xFFFFu), __ATOMIC_RELEASE);
  } else {
    __atomic_store_n(&w->w32[i], v, __ATOMIC_RELEASE);
  }
}

/* The reader's side of every sequence lock in this file, written once: `copy` copies what the
 * lock guards from `from` into `to`, with acquire loads, so the second sequence load cannot move
 * before any of them. Returns 1 on a consistent snapshot, 0 if every one of max_tries attempts
 * overlapped a write (the caller keeps its previous copy). */
typedef void (*stepmod_seq_copy_fn)(const void* from, void* to);
static inline int stepmod_seq_read_with(const uint32_t* seq, stepmod_seq_copy_fn copy,
                                        const void* from, void* to, unsigned max_tries) {
  unsigned t = 0;
  for (t = 0; t < max_tries; ++t) {
    /* On a single-CPU board a writer preempted inside its write only finishes once this reader
     * gives the CPU up: spin a little, then yield. */
    if (t > 0 && (t % 32u) == 0u) sched_yield();
    const uint32_t s0 = __atomic_load_n(seq, __ATOMIC_ACQUIRE);
    if (s0 & 1u) continue;
    copy(from, to);
    if (__atomic_load_n(seq, __ATOMIC_RELAXED) == s0) return 1;
  }
  return 0;
}
#define STEPMOD_SEQ_READ_TRIES 1000u

/* n words of a word block, for stepmod_seq_read. */
typedef struct stepmod_word_span {
  const stepmod_words_t* words;
  unsigned word_bytes;
  unsigned n;
} stepmod_word_span_t;
static inline void stepmod_copy_words(const void* from, void* to) {
  const stepmod_word_span_t* s = (const stepmod_word_span_t*)from;
  int32_t* out = (int32_t*)to;
  unsigned i = 0;
  for (i = 0; i < s->n; ++i) out[i] = stepmod_word_load(s->words, s->word_bytes, i);
}

/* Copies n words (sign-extended to int32) into out, under the sequence lock `seq`. */
static inline int stepmod_seq_read(const uint32_t* seq, const stepmod_words_t* w,
                                   unsigned word_bytes, unsigned n, int32_t* out,
                                   unsigned max_tries) {
  const stepmod_word_span_t span = {w, word_bytes, n};
  return stepmod_seq_read_with(seq, stepmod_copy_words, &span, out, max_tries);
}

/* Writes n words under the sequence lock. */
static inline void stepmod_seq_write(uint32_t* seq, stepmod_words_t* w, unsigned word_bytes,
                                     unsigned n, const int32_t* in) {
  unsigned i = 0;
  const uint32_t odd = stepmod_seq_write_begin(seq, STEPMOD_SEQ_STALE_NS);
  for (i = 0; i < n; ++i) stepmod_word_store(w, word_bytes, i, in[i]);
  stepmod_seq_write_end(seq, odd);
}

/* PLC side, the usual calls. */
static inline int stepmod_read_inputs(const stepmod_image_t* im, int32_t* out /* [16] */) {
  return stepmod_seq_read(&im->input_seq, &im->input_image, im->word_bytes, im->input_words, out,
                          STEPMOD_SEQ_READ_TRIES);
}
static inline void stepmod_write_outputs(stepmod_image_t* im, const int32_t* in /* [16] */) {
  stepmod_seq_write(&im->output_seq, &im->output_image, im->word_bytes, im->output_words, in);
}
/* Section 3.3: the health flags and the late-edge fault count of one input publication (the
 * same seqlock as the input words). Returns 0 if a write overlapped every attempt. */
typedef struct stepmod_health_copy {
  uint32_t flags;
  uint32_t late_faults;
} stepmod_health_copy_t;
static inline void stepmod_copy_health(const void* from, void* to) {
  const stepmod_image_t* im = (const stepmod_image_t*)from;
  stepmod_health_copy_t* out = (stepmod_health_copy_t*)to;
  out->flags = __atomic_load_n(&im->health_flags, __ATOMIC_ACQUIRE);
  out->late_faults = __atomic_load_n(&im->late_faults, __ATOMIC_ACQUIRE);
}
static inline int stepmod_read_health(const stepmod_image_t* im, uint32_t* flags,
                                      uint32_t* late_faults) {
  stepmod_health_copy_t h = {0u, 0u};
  if (!stepmod_seq_read_with(&im->input_seq, stepmod_copy_health, im, &h, STEPMOD_SEQ_READ_TRIES))
    return 0;
  *flags = h.flags;
  *late_faults = h.late_faults;
  return 1;
}
/* Section 3.4: the reason block of axis `axis` (0-based) as of one input publication. The text
 * is copied with relaxed byte loads (the seqlock decides). Returns 0 if a write overlapped every
 * attempt. */
static inline void stepmod_copy_reason(const void* from, void* to) {
  const stepmod_reason_t* r = (const stepmod_reason_t*)from;
  stepmod_reason_t* out = (stepmod_reason_t*)to;
  unsigned i = 0;
  out->seq = __atomic_load_n(&r->seq, __ATOMIC_ACQUIRE);
  out->item = __atomic_load_n(&r->item, __ATOMIC_ACQUIRE);
  for (i = 0; i < STEPMOD_REASON_TEXT; ++i) {
    out->text[i] = __atomic_load_n(&r->text[i], __ATOMIC_ACQUIRE);
  }
}
static inline int stepmod_read_reason(const stepmod_image_t* im, unsigned axis,
                                      stepmod_reason_t* out) {
  if (axis >= 2u) return 0;
  if (!stepmod_seq_read_with(&im->input_seq, stepmod_copy_reason, &im->reasons[axis], out,
                             STEPMOD_SEQ_READ_TRIES))
    return 0;
  out->text[STEPMOD_REASON_TEXT - 1] = '\0';
  return 1;
}
/* Section 3.6: the unit-state block of axis `axis` (0-based) as of one input publication.
 * Returns 0 if a write overlapped every attempt. */
static inline void stepmod_copy_unit_state(const void* from, void* to) {
  const stepmod_unit_state_t* u = (const stepmod_unit_state_t*)from;
  stepmod_unit_state_t* out = (stepmod_unit_state_t*)to;
  unsigned i = 0;
  out->config_seq = __atomic_load_n(&u->config_seq, __ATOMIC_ACQUIRE);
  out->inputs = __atomic_load_n(&u->inputs, __ATOMIC_ACQUIRE);
  out->drive_enable = __atomic_load_n(&u->drive_enable, __ATOMIC_ACQUIRE);
  out->reserved = 0;
  for (i = 0; i < STEPMOD_UNIT_CONFIG_WORDS; ++i) {
    out->config_words[i] = __atomic_load_n(&u->config_words[i], __ATOMIC_ACQUIRE);
  }
}
static inline int stepmod_read_unit_state(const stepmod_image_t* im, unsigned axis,
                                          stepmod_unit_state_t* out) {
  if (axis >= 2u) return 0;
  return stepmod_seq_read_with(&im->input_seq, stepmod_copy_unit_state, &im->units[axis], out,
                               STEPMOD_SEQ_READ_TRIES);
}
static inline uint64_t stepmod_scan_counter(const stepmod_image_t* im) {
  return __atomic_load_n(&im->scan_counter, __ATOMIC_ACQUIRE);
}
/* Section 3.2: bump once per PLC scan while the PLC is in Run mode. */
static inline void stepmod_heartbeat(stepmod_image_t* im) {
  __atomic_fetch_add(&im->plc_heartbeat, 1u, __ATOMIC_RELEASE);
}

/* ---------------------------------------------------------------------------------------------
 * Section 4: the simulator panel
 * ------------------------------------------------------------------------------------------- */
#define STEPMOD_PANEL_SIZE 4096u
#define STEPMOD_PANEL_MAGIC "STEPSIM" /* 8 bytes with its NUL */
#define STEPMOD_PANEL_VERSION 1u
#define STEPMOD_PANEL_MAX_AXES 2u

/* Force-mask / level bits (docs/interface.md 4), the order of InputLine. */
enum stepmod_panel_input {
  STEPMOD_IN_CAPTURE = 0,
  STEPMOD_IN_EXTERNAL = 1,
  STEPMOD_IN_HOME = 2,
  STEPMOD_IN_ESTOP = 3,
  STEPMOD_IN_CW_LIMIT = 4,
  STEPMOD_IN_CCW_LIMIT = 5,
  STEPMOD_PANEL_INPUTS = 6
};
/* Output-level bits. */
enum stepmod_panel_output { STEPMOD_OUT_STEP = 0, STEPMOD_OUT_DIR = 1, STEPMOD_OUT_GPO = 2 };

enum stepmod_panel_offset {
  STEPMOD_PANEL_OFF_MAGIC = 0,
  STEPMOD_PANEL_OFF_VERSION = 8,
  STEPMOD_PANEL_OFF_AXES = 12,
  STEPMOD_PANEL_OFF_OWNER_PID = 16, /* extension */
  STEPMOD_PANEL_OFF_AXIS0 = 64,
  STEPMOD_PANEL_AXIS_STRIDE = 64,
  /* within one axis block */
  STEPMOD_PANEL_AXOFF_POSITION = 0,
  STEPMOD_PANEL_AXOFF_ENCODER = 8,
  STEPMOD_PANEL_AXOFF_FORCE_MASK = 16,
  STEPMOD_PANEL_AXOFF_FORCE_LEVELS = 20,
  STEPMOD_PANEL_AXOFF_OUTPUTS = 24
};

typedef struct stepmod_panel_axis {
  int64_t position;      /* simulated motor position, steps (daemon writes) */
  int64_t encoder;       /* simulated encoder count (daemon writes) */
  uint32_t force_mask;   /* bit per input: forced (clients write) */
  uint32_t force_levels; /* electrical level of the forced inputs, 1 = high (clients write) */
  uint32_t outputs;      /* output levels now (daemon writes) */
  uint8_t reserved[36];
} stepmod_panel_axis_t;

typedef struct stepmod_panel {
  char magic[8];
  uint32_t version;
  uint32_t axes;
  uint64_t owner_pid; /* extension */
  uint8_t reserved[40];
  stepmod_panel_axis_t axis[STEPMOD_PANEL_MAX_AXES];
  uint8_t unused[STEPMOD_PANEL_SIZE - 64 - 64 * STEPMOD_PANEL_MAX_AXES];
} stepmod_panel_t;

STEPMOD_STATIC_ASSERT(sizeof(stepmod_panel_axis_t) == STEPMOD_PANEL_AXIS_STRIDE, "axis stride");
STEPMOD_STATIC_ASSERT(sizeof(stepmod_panel_t) == STEPMOD_PANEL_SIZE, "panel size");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_t, magic) == STEPMOD_PANEL_OFF_MAGIC, "magic");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_t, version) == STEPMOD_PANEL_OFF_VERSION, "ver");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_t, axes) == STEPMOD_PANEL_OFF_AXES, "axes");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_t, owner_pid) == STEPMOD_PANEL_OFF_OWNER_PID, "pid");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_t, axis) == STEPMOD_PANEL_OFF_AXIS0, "axis 0");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_axis_t, position) == STEPMOD_PANEL_AXOFF_POSITION,
                      "pos");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_axis_t, encoder) == STEPMOD_PANEL_AXOFF_ENCODER,
                      "enc");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_axis_t, force_mask) == STEPMOD_PANEL_AXOFF_FORCE_MASK,
                      "mask");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_axis_t, force_levels) ==
                          STEPMOD_PANEL_AXOFF_FORCE_LEVELS,
                      "levels");
STEPMOD_STATIC_ASSERT(offsetof(stepmod_panel_axis_t, outputs) == STEPMOD_PANEL_AXOFF_OUTPUTS,
                      "outputs");

/* Forcing sets the level before the mask bit, so the daemon never applies a forced bit with a
 * stale level; atomic read-modify-write keeps concurrent clients (two shells) from undoing each
 * other's bits. */
static inline void stepmod_panel_force(stepmod_panel_t* p, unsigned axis, unsigned input,
                                       int level) {
  const uint32_t bit = 1u << input;
  if (level) {
    __atomic_fetch_or(&p->axis[axis].force_levels, bit, __ATOMIC_RELEASE);
  } else {
    __atomic_fetch_and(&p->axis[axis].force_levels, ~bit, __ATOMIC_RELEASE);
  }
  __atomic_fetch_or(&p->axis[axis].force_mask, bit, __ATOMIC_RELEASE);
}
static inline void stepmod_panel_release(stepmod_panel_t* p, unsigned axis, unsigned input) {
  __atomic_fetch_and(&p->axis[axis].force_mask, ~(1u << input), __ATOMIC_RELEASE);
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* STEPMOD_IMAGE_H */
