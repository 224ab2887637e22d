// gpiod_check: small checks of the kernel GPIO character device through libgpiod 1.6, run inside
// the test VM against the gpio-sim board (scripts/vm/guest/board-setup.sh). They prove the VM
// harness itself, before stepmod's own gpiod backend is tested there.
//
//   gpiod_check outputs CHIP SIMDIR OFFSET...  request outputs, read them back via sim_gpioN/value,
//                                              released lines return to their pull
//   gpiod_check edge CHIP SIMDIR OFFSET        pull changes give rising/falling edge events with
//                                              CLOCK_MONOTONIC timestamps close to clock_gettime
//   gpiod_check busy CHIP OFFSET               a line in use gives EBUSY to a second request
//   gpiod_check hold CHIP OFFSET               holds the line as an input (consumer
//                                              "stepmod-vm-test"), prints "held", waits to be killed
//   gpiod_check errors CHIP                    missing chip and out-of-range offset fail cleanly
//   gpiod_check burst CHIP SIMDIR OFFSET N MODE   N pull toggles as fast as possible, the reader
//                                              idle or reading meanwhile: count the events
//
// The last line printed says what was checked ("ok: ...") or what went wrong ("FAIL: ...");
// exit status 0 = pass, 1 = fail.
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <gpiod.h>
#include <sched.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static const char kConsumer[] = "stepmod-vm-test";

static void fail(const char* fmt, ...) __attribute__((noreturn, format(printf, 1, 2)));
static void fail(const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  printf("FAIL: ");
  vprintf(fmt, ap);
  printf("\n");
  va_end(ap);
  exit(1);
}

static int64_t now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static int64_t ts_ns(const struct timespec* ts) {
  return (int64_t)ts->tv_sec * 1000000000 + ts->tv_nsec;
}

static unsigned parse_offset(const char* s) {
  char* end = NULL;
  unsigned long v = strtoul(s, &end, 10);
  if (!*s || *end) fail("'%s' is not a line offset", s);
  return (unsigned)v;
}

// sim_gpioN/value (0/1) of the gpio-sim line.
static int sim_value(const char* simdir, unsigned off) {
  char path[512], buf[8] = {0};
  snprintf(path, sizeof path, "%s/sim_gpio%u/value", simdir, off);
  int fd = open(path, O_RDONLY);
  if (fd < 0) fail("open %s: %s", path, strerror(errno));
  ssize_t n = read(fd, buf, sizeof buf - 1);
  close(fd);
  if (n < 1) fail("read %s: %s", path, strerror(errno));
  return buf[0] == '1';
}

// Keeps the pull file open so that a burst is one write per edge.
static int sim_pull_open(const char* simdir, unsigned off) {
  char path[512];
  snprintf(path, sizeof path, "%s/sim_gpio%u/pull", simdir, off);
  int fd = open(path, O_WRONLY);
  if (fd < 0) fail("open %s: %s", path, strerror(errno));
  return fd;
}

static void sim_pull_fd(int fd, int up) {
  const char* s = up ? "pull-up" : "pull-down";
  if (pwrite(fd, s, strlen(s), 0) != (ssize_t)strlen(s)) fail("write %s: %s", s, strerror(errno));
}

static struct gpiod_chip* open_chip(const char* name) {
  struct gpiod_chip* chip = gpiod_chip_open_lookup(name);
  if (!chip) fail("gpiod_chip_open_lookup(%s): %s", name, strerror(errno));
  return chip;
}

static struct gpiod_line* get_line(struct gpiod_chip* chip, unsigned off) {
  struct gpiod_line* l = gpiod_chip_get_line(chip, off);
  if (!l) fail("gpiod_chip_get_line(%u): %s", off, strerror(errno));
  return l;
}

static int cmd_outputs(const char* chipname, const char* simdir, int n, char** offs) {
  if (n < 1 || n > 64) fail("outputs: 1 to 64 offsets");
  struct gpiod_chip* chip = open_chip(chipname);
  struct gpiod_line* lines[64];
  unsigned off[64];
  for (int i = 0; i < n; ++i) {
    off[i] = parse_offset(offs[i]);
    lines[i] = get_line(chip, off[i]);
    if (gpiod_line_request_output(lines[i], kConsumer, 0) < 0)
      fail("request line %u as output: %s", off[i], strerror(errno));
    if (sim_value(simdir, off[i]) != 0) fail("line %u requested low reads high", off[i]);
  }
  // Each line alone high: it reads high, every other one stays low.
  for (int i = 0; i < n; ++i) {
    if (gpiod_line_set_value(lines[i], 1) < 0) fail("set line %u: %s", off[i], strerror(errno));
    for (int j = 0; j < n; ++j) {
      int want = j == i;
      if (sim_value(simdir, off[j]) != want)
        fail("line %u set high: line %u reads %d, not %d", off[i], off[j], !want, want);
    }
    if (gpiod_line_get_value(lines[i]) != 1)
      fail("line %u: get_value of an output set high", off[i]);
    if (gpiod_line_set_value(lines[i], 0) < 0) fail("clear line %u: %s", off[i], strerror(errno));
    if (sim_value(simdir, off[i]) != 0) fail("line %u set low reads high", off[i]);
  }
  // All high, released: back to their pull (down).
  for (int i = 0; i < n; ++i) gpiod_line_set_value(lines[i], 1);
  for (int i = 0; i < n; ++i)
    if (sim_value(simdir, off[i]) != 1) fail("line %u: all set high, reads low", off[i]);
  for (int i = 0; i < n; ++i) gpiod_line_release(lines[i]);
  for (int i = 0; i < n; ++i)
    if (sim_value(simdir, off[i]) != 0)
      fail("line %u released high: does not return to its pull-down", off[i]);
  // Requested with default value 1: high at once.
  if (gpiod_line_request_output(lines[0], kConsumer, 1) < 0)
    fail("re-request %u: %s", off[0], strerror(errno));
  if (sim_value(simdir, off[0]) != 1) fail("line %u requested with default 1 reads low", off[0]);
  gpiod_line_release(lines[0]);
  gpiod_chip_close(chip);
  printf(
      "ok: %d outputs on %s read back through sim_gpioN/value; released lines return to "
      "pull-down\n",
      n, chipname);
  return 0;
}

// Waits for one event on `line` (1 s); returns its kernel timestamp.
static int64_t expect_event(struct gpiod_line* line, int type, const char* what) {
  struct timespec tmo = {1, 0};
  int r = gpiod_line_event_wait(line, &tmo);
  if (r < 0) fail("%s: event wait: %s", what, strerror(errno));
  if (r == 0) fail("%s: no event within 1 s", what);
  struct gpiod_line_event ev;
  if (gpiod_line_event_read(line, &ev) < 0) fail("%s: event read: %s", what, strerror(errno));
  if (ev.event_type != type)
    fail("%s: got a %s edge", what,
         ev.event_type == GPIOD_LINE_EVENT_RISING_EDGE ? "rising" : "falling");
  return ts_ns(&ev.ts);
}

static int cmd_edge(const char* chipname, const char* simdir, const char* offstr) {
  unsigned off = parse_offset(offstr);
  struct gpiod_chip* chip = open_chip(chipname);
  struct gpiod_line* line = get_line(chip, off);
  if (gpiod_line_request_both_edges_events(line, kConsumer) < 0)
    fail("request line %u for both edges: %s", off, strerror(errno));
  if (gpiod_line_get_value(line) != 0) fail("line %u does not start low", off);
  int pull = sim_pull_open(simdir, off);
  int64_t worst = 0;
  const int kRounds = 10;
  for (int i = 0; i < kRounds; ++i) {
    int up = i % 2 == 0;
    int64_t t0 = now_ns();
    sim_pull_fd(pull, up);
    int64_t t1 = now_ns();
    int64_t ts =
        expect_event(line, up ? GPIOD_LINE_EVENT_RISING_EDGE : GPIOD_LINE_EVENT_FALLING_EDGE,
                     up ? "pull-up" : "pull-down");
    // The edge is stamped while the pull is written (irq_sim fires from irq_work on the way out
    // of the write): within [t0, t1] on CLOCK_MONOTONIC, with a margin for the TCG clock.
    if (ts < t0 - 1000000 || ts > t1 + 5000000)
      fail("edge %d stamped %lld ns, the write took [%lld, %lld] ns: not CLOCK_MONOTONIC?", i,
           (long long)ts, (long long)t0, (long long)t1);
    int64_t d = ts < t0 ? t0 - ts : ts > t1 ? ts - t1 : 0;
    if (d > worst) worst = d;
    if (gpiod_line_get_value(line) != up)
      fail("line %u after pull-%s reads %d", off, up ? "up" : "down", !up);
  }
  struct timespec tmo = {0, 100000000};
  if (gpiod_line_event_wait(line, &tmo) != 0) fail("an extra event after %d edges", kRounds);
  close(pull);
  gpiod_line_release(line);
  gpiod_chip_close(chip);
  printf(
      "ok: %d edges on line %u, each stamped on CLOCK_MONOTONIC within the sysfs write (worst %lld "
      "ns outside)\n",
      kRounds, off, (long long)worst);
  return 0;
}

static int cmd_busy(const char* chipname, const char* offstr) {
  unsigned off = parse_offset(offstr);
  // Two handles to the chip: the second request reaches the kernel (libgpiod would refuse a
  // second request of the same line object itself).
  struct gpiod_chip* a = open_chip(chipname);
  struct gpiod_chip* b = open_chip(chipname);
  struct gpiod_line* la = get_line(a, off);
  struct gpiod_line* lb = get_line(b, off);
  if (gpiod_line_request_output(la, kConsumer, 0) < 0)
    fail("first request of line %u: %s", off, strerror(errno));
  errno = 0;
  if (gpiod_line_request_input(lb, "second") == 0)
    fail("second request of line %u (in use) succeeded", off);
  if (errno != EBUSY) fail("second request of line %u: %s, not EBUSY", off, strerror(errno));
  errno = 0;
  if (gpiod_line_request_both_edges_events(lb, "second") == 0)
    fail("event request of line %u (in use) succeeded", off);
  if (errno != EBUSY) fail("event request of line %u: %s, not EBUSY", off, strerror(errno));
  // The line info shows who holds it.
  struct gpiod_chip* c = open_chip(chipname);
  struct gpiod_line* lc = get_line(c, off);
  if (!gpiod_line_is_used(lc)) fail("line %u in use: line info says it is free", off);
  const char* who = gpiod_line_consumer(lc);
  if (!who || strcmp(who, kConsumer) != 0)
    fail("line %u consumer '%s', not '%s'", off, who ? who : "", kConsumer);
  gpiod_chip_close(c);
  gpiod_line_release(la);
  if (gpiod_line_request_input(lb, "second") < 0)
    fail("request of line %u after release: %s", off, strerror(errno));
  gpiod_chip_close(b);
  gpiod_chip_close(a);
  printf(
      "ok: line %u in use: EBUSY for input and event requests, consumer '%s'; free again after "
      "release\n",
      off, kConsumer);
  return 0;
}

// Another program holding one line, for the cases that need a busy line (check_hardware_*).
static int cmd_hold(const char* chipname, const char* offset) {
  const unsigned off = parse_offset(offset);
  struct gpiod_chip* chip = open_chip(chipname);
  struct gpiod_line* line = get_line(chip, off);
  if (gpiod_line_request_input(line, kConsumer) < 0)
    fail("request of line %u: %s", off, strerror(errno));
  printf("held: line %u as '%s'\n", off, kConsumer);
  for (;;) pause();
}

static int cmd_errors(const char* chipname) {
  errno = 0;
  if (gpiod_chip_open_by_name("gpiochip99")) fail("gpiochip99 opened");
  int e1 = errno;
  if (e1 != ENOENT) fail("gpiod_chip_open_by_name(gpiochip99): %s, not ENOENT", strerror(e1));
  errno = 0;
  if (gpiod_chip_open("/dev/gpiochip99")) fail("/dev/gpiochip99 opened");
  if (errno != ENOENT) fail("gpiod_chip_open(/dev/gpiochip99): %s, not ENOENT", strerror(errno));
  errno = 0;
  if (gpiod_chip_open("/dev/null")) fail("/dev/null opened as a GPIO chip");
  int e3 = errno;
  if (e3 == 0) fail("gpiod_chip_open(/dev/null) failed without errno");
  struct gpiod_chip* chip = open_chip(chipname);
  unsigned n = gpiod_chip_num_lines(chip);
  errno = 0;
  if (gpiod_chip_get_line(chip, n)) fail("line %u of a %u-line chip exists", n, n);
  if (errno != EINVAL)
    fail("gpiod_chip_get_line(%u) of %u lines: %s, not EINVAL", n, n, strerror(errno));
  if (gpiod_chip_get_line(chip, 100000)) fail("line 100000 exists");
  gpiod_chip_close(chip);
  printf("ok: missing chip: ENOENT; not a GPIO chip: %s; offset %u of %u lines: EINVAL\n",
         strerror(e3), n, n);
  return 0;
}

// mode "idle": this thread toggles, nobody reads until the burst is over.
// mode "reading": a child process toggles while this thread reads the events as they come.
static int cmd_burst(const char* chipname, const char* simdir, const char* offstr, const char* nstr,
                     const char* mode) {
  unsigned off = parse_offset(offstr);
  int n = (int)parse_offset(nstr);
  int reading = !strcmp(mode, "reading");
  if (!reading && strcmp(mode, "idle")) fail("burst mode '%s': idle or reading", mode);
  struct gpiod_chip* chip = open_chip(chipname);
  struct gpiod_line* line = get_line(chip, off);
  if (gpiod_line_request_both_edges_events(line, kConsumer) < 0)
    fail("request line %u for both edges: %s", off, strerror(errno));
  int64_t t0 = now_ns();
  pid_t child = -1;
  if (reading) {
    child = fork();
    if (child < 0) fail("fork: %s", strerror(errno));
    if (child == 0) {
      // The lowest priority: on the VM's one CPU a toggler at nice 0 can outrun a reader at
      // SCHED_OTHER and overflow the kernel's 16-event buffer (seen on a loaded host).
      if (nice(19) == -1 && errno != 0) fail("nice: %s", strerror(errno));
      int pull = sim_pull_open(simdir, off);
      usleep(20000);
      for (int i = 0; i < n; ++i) sim_pull_fd(pull, i % 2 == 0);
      _exit(0);
    }
    // The reader (this process, after the fork: the toggler stays at nice 19) reads as events
    // come, whatever the emulated CPU's speed: real-time, so that a queued event wakes it before
    // the toggler's next write (at SCHED_OTHER under a loaded host 182 of 200 arrived: the
    // reader ran too late; the kernel path had not lost them). The toggler waits 20 ms first.
    struct sched_param sp = {.sched_priority = 20};
    if (sched_setscheduler(0, SCHED_FIFO, &sp) != 0) fail("SCHED_FIFO: %s", strerror(errno));
  } else {
    int pull = sim_pull_open(simdir, off);
    for (int i = 0; i < n; ++i) sim_pull_fd(pull, i % 2 == 0);
    close(pull);
  }
  // The v1 uAPI's per-line event buffer holds 16 events; when it is full the kernel drops new
  // edges, without telling anyone.
  int got = 0, order_ok = 1, expect_rise = 1;
  int64_t last = 0;
  struct gpiod_line_event ev[16];
  for (;;) {
    struct timespec tmo = {0, 300000000};
    int r = gpiod_line_event_wait(line, &tmo);
    if (r < 0) fail("event wait: %s", strerror(errno));
    if (r == 0) break;
    int k = gpiod_line_event_read_multiple(line, ev, 16);
    if (k < 0) fail("event read: %s", strerror(errno));
    for (int i = 0; i < k; ++i) {
      if ((ev[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE) != expect_rise) order_ok = 0;
      expect_rise = ev[i].event_type != GPIOD_LINE_EVENT_RISING_EDGE;
      if (ts_ns(&ev[i].ts) < last) order_ok = 0;
      last = ts_ns(&ev[i].ts);
    }
    got += k;
  }
  if (child > 0) {
    int st = 0;
    waitpid(child, &st, 0);
    if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) fail("toggling child failed");
  }
  int64_t t1 = now_ns();
  gpiod_line_release(line);
  gpiod_chip_close(chip);
  printf("burst (%s) of %d edges: %d events read in %lld us, %s\n",
         reading ? "reader running" : "reader idle", n, got, (long long)((t1 - t0) / 1000),
         order_ok ? "alternating and in time order" : "NOT alternating/in order");
  if (!order_ok) fail("events out of order or not alternating");
  if (got != n) fail("%d of %d edges arrived (v1 uAPI: 16-event kernel buffer per line)", got, n);
  printf("ok: %d edges, none lost (%s)\n", n, reading ? "reader running" : "reader idle");
  return 0;
}

int main(int argc, char** argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  const char* cmd = argc > 1 ? argv[1] : "";
  if (!strcmp(cmd, "outputs") && argc >= 5)
    return cmd_outputs(argv[2], argv[3], argc - 4, argv + 4);
  if (!strcmp(cmd, "edge") && argc == 5) return cmd_edge(argv[2], argv[3], argv[4]);
  if (!strcmp(cmd, "busy") && argc == 4) return cmd_busy(argv[2], argv[3]);
  if (!strcmp(cmd, "errors") && argc == 3) return cmd_errors(argv[2]);
  if (!strcmp(cmd, "hold") && argc == 4) return cmd_hold(argv[2], argv[3]);
  if (!strcmp(cmd, "burst") && argc == 7)
    return cmd_burst(argv[2], argv[3], argv[4], argv[5], argv[6]);
  fprintf(stderr,
          "usage: gpiod_check outputs CHIP SIMDIR OFFSET... | edge CHIP SIMDIR OFFSET | busy CHIP "
          "OFFSET |\n"
          "                   hold CHIP OFFSET |\n"
          "                   errors CHIP | burst CHIP SIMDIR OFFSET N idle|reading\n");
  return 2;
}
