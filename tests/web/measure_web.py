#!/usr/bin/python3
"""Measures the console's cost (docs/web-console.md, "Measured"): a 3601 on the simulated
machine jogging, stepmod-web and one headless chromium page for SECONDS; prints the page's
update rate and samples per second, and the CPU time of stepmod-web and of the headless
chromium showing the page (all its processes) beside stepmodd's.

Usage: measure_web.py STEPMODD STEPMODCTL STEPMOD_WEB WWW_DIR SOURCE_DIR [SECONDS]
"""
import os
import sys
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
        b0 = c.d.execute_script("return window.consoleStats.batches")
        t0 = time.monotonic()
        time.sleep(seconds)
        dt = time.monotonic() - t0
        b1 = c.d.execute_script("return window.consoleStats.batches")
        srate = c.d.execute_script("return window.consoleStats.sampleRate")
        after = {k: cpu_seconds(p) for k, p in procs.items()}
        browser_after = group_cpu(browser)
        bt.release_button(c)
        print("page updates: %.1f /s, samples: %.0f /s (over %.0f s, jogging)" %
              ((b1 - b0) / dt, srate, dt))
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
