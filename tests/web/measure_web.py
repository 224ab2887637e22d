#!/usr/bin/python3
"""Measures the console's cost (docs/web-console.md, "Measured"): a 3601 on the simulated
machine jogging, stepmod-web and one headless chromium page for SECONDS; prints the page's
update rate and samples per second, the position-to-page latency (from the position's change in
the image, seen by polling it every 0.2 ms, to the page's position text showing that value, seen
by a MutationObserver; both on the machine's clock) and the CPU time of stepmod-web and of the
headless chromium showing the page (all its processes) beside stepmodd's.

Usage: measure_web.py STEPMODD STEPMODCTL STEPMOD_WEB WWW_DIR SOURCE_DIR [SECONDS]
"""
import mmap
import os
import statistics
import struct
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402


def cpu_seconds(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def descendants(pid):
    """pid's child processes, theirs, and so on (chromedriver -> chromium's processes)."""
    parent = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open("/proc/%s/stat" % d) as f:
                    parent[int(d)] = int(f.read().rsplit(")", 1)[1].split()[1])
            except OSError:
                pass
    found, todo = [], [pid]
    while todo:
        p = todo.pop()
        kids = [c for c, pp in parent.items() if pp == p]
        found += kids
        todo += kids
    return found


def group_cpu(pids):
    total = 0.0
    for p in pids:
        try:
            total += cpu_seconds(p)
        except OSError:
            pass  # a helper process that ended
    return total


class ImageWatch(threading.Thread):
    """When each position value first appeared in the 3601's input image (words 2, 3: the
    position split in thousands), on the wall clock."""

    def __init__(self, name):
        super().__init__(daemon=True)
        self.f = open("/dev/shm/stepmod." + name, "rb")
        self.mm = mmap.mmap(self.f.fileno(), 4096, prot=mmap.PROT_READ)
        self.first = {}
        self.stop = False

    def run(self):
        while not self.stop:
            msw, lsw = struct.unpack_from("<hh", self.mm, 128 + 4)
            self.first.setdefault(msw * 1000 + lsw, time.time() * 1000)
            time.sleep(0.0002)


WATCH_PAGE = """window.posSeen = []; const e = document.querySelector('#unit-0 .pos');
new MutationObserver(() => window.posSeen.push([performance.timeOrigin + performance.now(),
  parseInt(e.textContent, 10)])).observe(e, {childList: true, characterData: true,
  subtree: true});"""


def latencies(c, watch):
    """Page time - image time of each position the page showed (ms)."""
    seen = c.d.execute_script("return window.posSeen")
    return [t - watch.first[v] for t, v in seen if v in watch.first and t >= watch.first[v]]


def main():
    bt.STEPMODD, bt.STEPMODCTL, bt.WEB, bt.WWW, bt.SRC = sys.argv[1:6]
    seconds = float(sys.argv[6]) if len(sys.argv) > 6 else 10.0
    m = bt.Machine("3601-sim.toml", 18640)
    c = None
    try:
        c = bt.Console(m)
        time.sleep(1.1)
        c.take()
        c.configure_plain()
        c.fill("#unit-0 .f-speed", 2000)
        bt.hold_button(c, "#unit-0 .b-jog-cw")
        time.sleep(1.0)
        procs = {"stepmodd": m.daemon.pid, "stepmod-web": m.web.pid}
        browser = descendants(c.d.service.process.pid)
        before = {k: cpu_seconds(p) for k, p in procs.items()}
        browser_before = group_cpu(browser)
        watch = ImageWatch(m.name)
        watch.start()
        c.d.execute_script(WATCH_PAGE)
        b0 = c.d.execute_script("return window.consoleStats.batches")
        t0 = time.monotonic()
        time.sleep(seconds)
        dt = time.monotonic() - t0
        watch.stop = True
        lat = sorted(latencies(c, watch))
        b1 = c.d.execute_script("return window.consoleStats.batches")
        srate = c.d.execute_script("return window.consoleStats.sampleRate")
        after = {k: cpu_seconds(p) for k, p in procs.items()}
        browser_after = group_cpu(browser)
        bt.release_button(c)
        print("page updates: %.1f /s, samples: %.0f /s (over %.0f s, jogging)" %
              ((b1 - b0) / dt, srate, dt))
        if lat:
            print("position to page: median %.1f ms, p90 %.1f ms, max %.1f ms (%d values)" %
                  (statistics.median(lat), lat[int(0.9 * (len(lat) - 1))], lat[-1], len(lat)))
        for k in procs:
            print("%-12s CPU %.1f %% of one core" % (k, 100.0 * (after[k] - before[k]) / dt))
        print("%-12s CPU %.1f %% of one core (%d processes)" %
              ("chromium", 100.0 * (browser_after - browser_before) / dt, len(browser)))
    finally:
        if c:
            c.close()
        m.close()


if __name__ == "__main__":
    main()
