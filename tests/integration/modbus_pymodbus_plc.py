#!/usr/bin/python3
"""A PLC program for a 3601, written against Debian's python3-pymodbus and nothing of stepmod's:
it configures the module, runs a relative move, reads status and position, checks the header
registers and the exception codes, then starts a long move, keeps it alive with its writes (the
PLC heartbeat) and goes silent: the module must stop the axis on its own (plc_timeout_ms).

Run by tests/integration/daemon_modbus_test.cpp against a real stepmodd (loopback only). Exit
status 0 when every check passed; each failure is printed. Every loop is bounded in time.
Register counts are passed as `count=`: pymodbus 3.0 (Debian 12) takes it either way, 3.8
(Debian 13) only as a keyword."""
import argparse
import sys
import time

from pymodbus.client import ModbusTcpClient

# Debian 12 has pymodbus 3.0, Debian 13 3.8: `count` is passed by name (3.8 takes it by name
# only), the unit as `slave=` (both).

# 3601 words (module_types/m3601/words_3601.hpp, the manual's layout).
CFG_MODE = 0x8000
CFG_ALL_INPUTS_QUAD_STEPDIR = 0x003F | 0x0100 | 0x0400
ALL_ACTIVE_HIGH = 0x003F
CMD_RELATIVE = 0x0002
ST_MOVING = 0x0003
ST_MOVE_COMPLETE = 0x0080
ST_POSITION_INVALID = 0x0400
ST_CONFIG_ERROR = 0x2000
ST_CONFIG_MODE = 0x8000


def split(v):
    """The 3601's split format: thousands in the MSW, the rest in the LSW (v >= 0 here)."""
    return [v // 1000, v % 1000]


def joined(msw, lsw):
    s = lambda x: x - 0x10000 if x & 0x8000 else x
    return s(msw) * 1000 + s(lsw)


class Plc:
    def __init__(self, port, unit):
        self.c = ModbusTcpClient("127.0.0.1", port=port, timeout=2)
        self.unit = unit
        self.failures = 0
        self.out = [0] * 8  # the output words as last written
        if not self.c.connect():
            sys.exit("cannot connect to 127.0.0.1:%d" % port)

    def check(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        if not ok:
            self.failures += 1
        return ok

    def inputs(self):
        r = self.c.read_input_registers(0, count=8, slave=self.unit)
        if r.isError():
            raise RuntimeError("read input registers: %s" % r)
        return r.registers

    def write(self, words):
        r = self.c.write_registers(0, words, slave=self.unit)
        if r.isError():
            raise RuntimeError("write holding registers: %s" % r)
        self.out = list(words)

    def heartbeat(self):
        # As a PLC does every scan: the whole output image again. Unchanged words change nothing
        # for the module; as an accepted write it is the PLC heartbeat (docs/interface.md 3.2, 6).
        self.write(self.out)

    def wait(self, cond, seconds, alive=True):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            w = self.inputs()
            if cond(w):
                return w
            if alive:
                self.heartbeat()
            time.sleep(0.02)
        return None

    def command(self, words):
        """An edge-triggered command: the bit until the module has seen it, then released."""
        self.write(words)
        time.sleep(0.01)
        r = self.c.write_register(0, 0, slave=self.unit)
        if r.isError():
            raise RuntimeError("write register: %s" % r)
        self.out[0] = 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--unit", type=int, default=1)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--plc-timeout-ms", type=int, required=True)
    a = ap.parse_args()
    plc = Plc(a.port, a.unit)

    # Header registers: type, word size, word counts, a running scan counter.
    h = plc.c.read_input_registers(1000, count=16, slave=a.unit)
    plc.check(not h.isError() and h.registers[:4] == [3601, 2, 8, 8],
              "header registers 1000..1003 = 3601, 2, 8, 8: %s" % (h.registers[:4],))
    time.sleep(0.05)
    h2 = plc.c.read_input_registers(1000, count=16, slave=a.unit)
    scans = lambda r: r.registers[4] | (r.registers[5] << 16)
    plc.check(scans(h2) > scans(h), "scan counter advances: %d -> %d" % (scans(h), scans(h2)))

    # Exceptions.
    r = plc.c.read_input_registers(8, count=1, slave=a.unit)
    plc.check(r.isError() and r.exception_code == 2, "input register 8: exception 02 (%s)" % r)
    r = plc.c.read_coils(0, count=1, slave=a.unit)
    plc.check(r.isError() and r.exception_code == 1, "read coils: exception 01 (%s)" % r)
    r = plc.c.read_input_registers(0, count=1, slave=(a.unit + 1) % 256)
    plc.check(r.isError() and r.exception_code == 0x0B, "another unit id: exception 0B (%s)" % r)

    # Configuration mode, then back to command mode.
    plc.write([CFG_MODE | CFG_ALL_INPUTS_QUAD_STEPDIR, ALL_ACTIVE_HIGH] + split(1000) + [0] * 4)
    w = plc.wait(lambda w: w[0] & ST_CONFIG_MODE, 2.0)
    plc.check(w is not None and not (w[0] & ST_CONFIG_ERROR),
              "configuration accepted: status %s" % (None if w is None else hex(w[0])))
    plc.write([0] * 8)
    w = plc.wait(lambda w: not (w[0] & ST_CONFIG_MODE), 2.0)
    plc.check(w is not None, "back in command mode")

    # A relative move, kept alive by the heartbeat, to its end.
    plc.command([CMD_RELATIVE, 0] + split(a.steps) + split(10000) + [10, 10])
    w = plc.wait(lambda w: (w[0] & ST_MOVE_COMPLETE) and not (w[0] & ST_MOVING), 10.0)
    pos = None if w is None else joined(w[2], w[3])
    plc.check(w is not None and pos == a.steps,
              "relative move of %d steps complete, position %s" % (a.steps, pos))

    # A long move; then the PLC goes silent.
    plc.command([CMD_RELATIVE, 0] + split(400000) + split(5000) + [10, 10])
    w = plc.wait(lambda w: w[0] & ST_MOVING, 2.0)
    plc.check(w is not None, "long move started")
    alive_for = 3 * a.plc_timeout_ms / 1000.0
    w = plc.wait(lambda w: not (w[0] & ST_MOVING), alive_for)
    plc.check(w is None, "still moving after %.1f s of heartbeats" % alive_for)
    t0 = time.monotonic()
    w = plc.wait(lambda w: not (w[0] & ST_MOVING), a.plc_timeout_ms / 1000.0 + 2.0, alive=False)
    took = time.monotonic() - t0
    plc.check(w is not None and (w[0] & ST_POSITION_INVALID),
              "silent PLC: axis stopped after %.3f s, position invalid (status %s)"
              % (took, None if w is None else hex(w[0])))
    plc.check(took >= a.plc_timeout_ms / 1000.0 * 0.5, "not long before plc_timeout_ms")
    print("position after the stop: %s" % (None if w is None else joined(w[2], w[3])))
    return 1 if plc.failures else 0


if __name__ == "__main__":
    sys.exit(main())
