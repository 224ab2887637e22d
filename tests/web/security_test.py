#!/usr/bin/python3
"""stepmod-web under hostile, broken and slow clients (docs/hardening.md, "The web console"):
raw-socket clients (python3 only) and Debian's headless chromium through python3-selenium,
against a real stepmodd on the simulated machine.

Usage: security_test.py STEPMODD STEPMODCTL STEPMOD_WEB WWW_DIR SOURCE_DIR [test names]
The chromium cases are skipped where chromium, chromedriver or python3-selenium is missing.
"""
import base64
import http.client
import http.server
import os
import re
import select
import signal
import socket
import struct
import subprocess
import sys
import threading
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402  (Machine, Console, wait_for: the same argv)

PORT = 18621        # the console under test
LIMIT_PORT = 18622  # a second console of the same module, for the login rate limit
EVIL_PORT = 18629   # another site's page, on the same host (so the same "site" for cookies)
FIRST_START_PORT = 18660  # 18660-18669: consoles started and logged into at once
MACHINE = None


def origin(port=PORT):
    return "http://127.0.0.1:%d" % port


def login(token, port=PORT, with_origin=True):
    """POST /login as the login form does: (status, "stepmod_web=..." or None, headers)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    headers = {"Content-Type": "application/x-www-form-urlencoded"}
    if with_origin:
        headers["Origin"] = origin(port)
    conn.request("POST", "/login", body="token=" + token, headers=headers)
    r = conn.getresponse()
    r.read()
    cookie = r.getheader("Set-Cookie")
    conn.close()
    return r.status, (cookie.split(";")[0] if cookie else None), r


def get(path, cookie=None, host=None, timeout=10):
    conn = http.client.HTTPConnection("127.0.0.1", PORT, timeout=timeout)
    headers = {"Cookie": cookie} if cookie else {}
    if host:
        conn.putrequest("GET", path, skip_host=True)
        conn.putheader("Host", host)
        for k, v in headers.items():
            conn.putheader(k, v)
        conn.endheaders()
    else:
        conn.request("GET", path, headers=headers)
    r = conn.getresponse()
    body = r.read()
    conn.close()
    return r, body


class Ws:
    """A WebSocket client on a raw socket: the frames exactly as a test wants them."""

    def __init__(self, cookie, org="self", port=PORT, rcvbuf=None, timeout=10):
        self.s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if rcvbuf:
            self.s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
        self.s.settimeout(timeout)
        self.s.connect(("127.0.0.1", port))
        key = base64.b64encode(os.urandom(16)).decode()
        lines = ["GET /ws HTTP/1.1", "Host: 127.0.0.1:%d" % port, "Upgrade: websocket",
                 "Connection: Upgrade", "Sec-WebSocket-Key: " + key, "Sec-WebSocket-Version: 13"]
        if org:
            lines.append("Origin: " + (origin(port) if org == "self" else org))
        if cookie:
            lines.append("Cookie: " + cookie)
        self.s.sendall(("\r\n".join(lines) + "\r\n\r\n").encode())
        self.buf = b""
        while b"\r\n\r\n" not in self.buf:
            try:
                chunk = self.s.recv(4096)
            except OSError:
                chunk = b""
            if not chunk:
                break
            self.buf += chunk
        head, _, self.buf = self.buf.partition(b"\r\n\r\n")
        first = head.split(b"\r\n")[0].split()
        self.status = int(first[1]) if len(first) > 1 else 0

    @staticmethod
    def header(opcode, length, fin=True):
        """A masked client frame's header; the mask key is 0 (so the payload goes as it is)."""
        b0 = (0x80 if fin else 0) | opcode
        if length < 126:
            h = struct.pack("!BB", b0, 0x80 | length)
        elif length < 65536:
            h = struct.pack("!BBH", b0, 0x80 | 126, length)
        else:
            h = struct.pack("!BBQ", b0, 0x80 | 127, length)
        return h + b"\0\0\0\0"

    def send(self, payload, opcode=1, fin=True):
        if isinstance(payload, str):
            payload = payload.encode()
        self.s.sendall(self.header(opcode, len(payload), fin) + payload)

    def _need(self, n, deadline):
        while len(self.buf) < n:
            self.s.settimeout(max(0.01, deadline - time.monotonic()))
            chunk = self.s.recv(65536)
            if not chunk:
                raise EOFError("the server closed the connection")
            self.buf += chunk

    def frame(self, timeout=10):
        """(opcode, payload) of the next server frame."""
        deadline = time.monotonic() + timeout
        self._need(2, deadline)
        n = self.buf[1] & 0x7F
        hdr = 2 + {126: 2, 127: 8}.get(n, 0)
        self._need(hdr, deadline)
        if n == 126:
            n = struct.unpack("!H", self.buf[2:4])[0]
        elif n == 127:
            n = struct.unpack("!Q", self.buf[2:10])[0]
        self._need(hdr + n, deadline)
        op, payload = self.buf[0] & 0x0F, self.buf[hdr:hdr + n]
        self.buf = self.buf[hdr + n:]
        return op, payload

    def message(self, kind, timeout=10):
        """The next text message of JSON type `kind` (others skipped), as a dict."""
        import json
        deadline = time.monotonic() + timeout
        while True:
            op, payload = self.frame(max(0.01, deadline - time.monotonic()))
            if op == 8:
                raise EOFError("closed by the server: %r" % payload)
            if op == 1:
                m = json.loads(payload)
                if m.get("type") == kind:
                    return m

    def close(self):
        self.s.close()


def vm_kb(pid, field):
    with open("/proc/%d/status" % pid) as f:
        return int(re.search(r"(?m)^%s:\s+(\d+) kB" % field, f.read()).group(1))


def lease_holder(name):
    with open("/dev/shm/stepmod." + name, "rb") as f:
        return struct.unpack_from("<I", f.read(580), 576)[0]


def web_log():
    with open(os.path.join(MACHINE.dir, "w.log")) as f:
        return f.read()


class SocketClients(unittest.TestCase):
    """Clients on raw sockets: what a browser never sends, and what a hostile program does."""

    def setUp(self):
        self.m = MACHINE
        if self.m.web.poll() is not None:  # an earlier case killed it (a failure of that case)
            self.m.start_web()
        status, self.cookie, _ = login(self.m.token)
        self.assertEqual(status, 303)

    def tearDown(self):
        # Whatever the case did, stepmod-web is still there (a crash is no stop).
        self.assertIsNone(self.m.web.poll(), "stepmod-web died")

    def test_1_websocket_needs_the_consoles_own_origin(self):
        for org in (origin(EVIL_PORT), "http://evil.example", "null", None):
            ws = Ws(self.cookie, org=org)
            self.assertNotEqual(ws.status, 101, "a WebSocket with Origin %r" % org)
            ws.close()
        ws = Ws(self.cookie)  # the console's own page
        self.assertEqual(ws.status, 101)
        self.assertEqual(ws.message("hello")["type"], "hello")
        ws.close()
        self.assertIn("refused: not from this console's own page", web_log())

    def test_2_invalid_utf8_bad_json_and_unknown_ops_get_an_error_reply(self):
        ws = Ws(self.cookie)
        for payload, opcode, why in ((b'{"op": "\xff\xfe"}', 1, "not valid UTF-8"),
                                     (b"\xc0\xaf", 1, "not valid UTF-8"),
                                     (b"not json", 1, "not JSON"),
                                     (b"[1, 2]", 1, "a JSON object"),
                                     (b'{"op": 5}', 1, "a JSON object"),
                                     (b'{"op": "take"}', 2, "binary"),
                                     (b'{"op": "\xe2\x82\xac"}', 1, "unknown op")):
            ws.send(payload, opcode)
            r = ws.message("reply")
            self.assertFalse(r["ok"], payload)
            self.assertIn(why, r["message"], payload)
        ws.close()

    def test_3_a_64_mb_message_is_refused_with_1009(self):
        pid = self.m.web.pid
        before = vm_kb(pid, "VmHWM")
        ws = Ws(self.cookie)
        ws.message("hello")
        size = 64 << 20
        ws.s.sendall(Ws.header(1, size) + b'{"op": "')
        sent, chunk, code = 0, b"a" * 65536, None
        ws.s.settimeout(10)
        while sent < size - 8 and code is None:
            try:
                ws.s.sendall(chunk)
                sent += len(chunk)
            except OSError:
                break  # the server has closed
            if select.select([ws.s], [], [], 0)[0]:
                code = self.close_code(ws, 1)
        if code is None:
            code = self.close_code(ws, 10)
        ws.close()
        self.assertEqual(code, 1009, "close code (%d bytes of the message sent)" % sent)
        grown = vm_kb(pid, "VmHWM") - before
        self.assertLess(grown, 16 * 1024, "stepmod-web's peak RSS grew by %d kB" % grown)

    @staticmethod
    def close_code(ws, timeout):
        """The code of a close frame waiting (or arriving within timeout), else None."""
        deadline = time.monotonic() + timeout
        while True:
            try:
                op, payload = ws.frame(max(0.01, deadline - time.monotonic()))
            except (socket.timeout, BlockingIOError):
                return None
            except (EOFError, OSError):
                return -1  # closed without a close frame
            if op == 8:
                return struct.unpack("!H", payload[:2])[0] if len(payload) >= 2 else 1005

    def test_4_a_client_that_stops_reading_stalls_no_other(self):
        # It asks and asks (30 kB replies: "unknown op" repeats the op) and never reads: its
        # replies pile up at the server. (Before, the server's write to it blocked, holding
        # the connection's lock, and with it the broadcaster: every page stopped updating.)
        stalled = Ws(self.cookie, rcvbuf=4096)
        reader = Ws(self.cookie)
        reader.message("hello")

        def flood():
            req = ('{"op": "%s"}' % ("x" * 30000)).encode()
            stalled.s.settimeout(20)
            try:
                for _ in range(200):
                    stalled.send(req)
            except OSError:
                pass  # closed by the server: what the limit is for
        t = threading.Thread(target=flood, daemon=True)
        t.start()
        gaps, last, end = [], time.monotonic(), time.monotonic() + 5
        while time.monotonic() < end:
            try:
                reader.message("batch", timeout=3)
            except socket.timeout:
                self.fail("no batch for 3 s while another client does not read")
            now = time.monotonic()
            gaps.append(now - last)
            last = now
        reader.close()
        stalled.close()
        t.join()
        # 25 batches a second; a generous bound for this loaded machine.
        self.assertLess(max(gaps), 1.5, "the longest gap between batches")
        self.assertIn("bytes waiting for it", web_log())

    def test_5_every_answer_forbids_framing(self):
        answers = {"/login": get("/login")[0], "/ (no session)": get("/")[0],
                   "/ (session)": get("/", self.cookie)[0],
                   "/console.js": get("/console.js", self.cookie)[0],
                   "/nosuch": get("/nosuch", self.cookie)[0]}
        for what, r in answers.items():
            self.assertEqual(r.getheader("X-Frame-Options"), "DENY", what)
            self.assertIn("frame-ancestors 'none'", r.getheader("Content-Security-Policy") or "",
                          what)

    def test_6_a_host_name_the_console_does_not_serve_is_refused(self):
        r, _ = get("/login", host="evil.example:%d" % PORT)  # DNS rebinding
        self.assertEqual(r.status, 421)
        r, _ = get("/login", host="localhost:%d" % PORT)
        self.assertEqual(r.status, 200)
        status, cookie, _ = login(self.m.token, with_origin=False)
        self.assertEqual((status, cookie), (403, None), "a login without Origin")

    def test_7_wrong_tokens_are_rate_limited_and_logged(self):
        web = subprocess.Popen(
            [bt.WEB, "--name", self.m.name, "--port", str(LIMIT_PORT), "--token-file",
             self.m.token_file, "--www", bt.WWW],
            stderr=open(os.path.join(self.m.dir, "limit.log"), "w"))
        try:
            bt.wait_for(lambda: self.connects(LIMIT_PORT), 10, "the second console")
            t0 = time.monotonic()
            wrong = [login("0" * 48, LIMIT_PORT)[0] for _ in range(5)]
            # Then wrong and right tokens in turn: all refused unheard, but for one try every
            # 2 s (a loaded machine may take that long for these).
            later = [login(tok, LIMIT_PORT) for _ in range(8) for tok in ("0" * 48, self.m.token)]
            refills = int((time.monotonic() - t0) / 2) + 1
            self.assertEqual(wrong, [401] * 5)
            refused = [r for r in later if r[0] == 429]
            self.assertGreaterEqual(len(refused), len(later) - refills, [r[0] for r in later])
            self.assertTrue(any(r[0] == 429 for r in later[1::2]), "the right token refused too")
            wait = int(refused[-1][2].getheader("Retry-After"))
            self.assertLessEqual(wait, 3)
            time.sleep(wait)
            self.assertEqual(login(self.m.token, LIMIT_PORT)[0], 303)
        finally:
            web.terminate()
            web.wait(10)
        with open(os.path.join(self.m.dir, "limit.log")) as f:
            log = f.read()
        self.assertIn("login from 127.0.0.1: wrong token (5 in a row)", log)
        self.assertRegex(log, r"login from 127.0.0.1 refused: 5 wrong tokens")

    def test_8_a_login_the_moment_the_port_opens_is_answered(self):
        # The login is sent the instant the port accepts, 10 starts in a row: the console's
        # handlers are in place before its first connection is taken (once they were set just
        # after the port opened, and a login in between met a 404). A race: a regression shows
        # here on some runs, not on every one. Each start has a port of its own: civetweb takes
        # up to 2 s to stop, and they stop together at the end.
        webs = []
        try:
            for n in range(10):
                port = FIRST_START_PORT + n
                webs.append(subprocess.Popen(
                    [bt.WEB, "--name", self.m.name, "--port", str(port), "--token-file",
                     self.m.token_file, "--www", bt.WWW], stderr=subprocess.DEVNULL))
                deadline = time.monotonic() + 10
                while True:
                    try:
                        status = login(self.m.token, port)[0]
                        break
                    except ConnectionRefusedError:
                        self.assertLess(time.monotonic(), deadline, "the console never listened")
                        time.sleep(0.001)
                self.assertEqual(status, 303, "start %d" % n)
                webs[-1].terminate()
        finally:
            for web in webs:
                web.terminate()
                web.wait(10)

    @staticmethod
    def connects(port):
        try:
            socket.create_connection(("127.0.0.1", port), 0.2).close()
            return True
        except OSError:
            return False


class EvilSite(threading.Thread):
    """Another site's page on another port of 127.0.0.1: it tries the console's WebSocket with
    whatever the browser attaches (the operator's SameSite=Strict cookie: same site)."""
    PAGE = b"""<!doctype html><meta charset="utf-8"><title>evil</title><script>
window.result = {opened: false, closed: false, replies: []};
const ws = new WebSocket("ws://127.0.0.1:%d/ws");
ws.onopen = () => {
  window.result.opened = true;
  ws.send(JSON.stringify({op: "take"}));
  setInterval(() => ws.send(JSON.stringify({op: "keepalive"})), 50);
  ws.send(JSON.stringify({op: "cmd", unit: 0, cmd: "jog_press", dir: "cw", speed: 4000,
                          accel: 100, decel: 100, profile: 0}));
};
ws.onmessage = (e) => { if (!e.data.includes('"batch"')) window.result.replies.push(e.data); };
ws.onclose = (e) => { window.result.closed = true; window.result.code = e.code; };
</script>""" % PORT

    def __init__(self):
        super().__init__(daemon=True)
        page = self.PAGE

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                self.send_response(200)
                self.send_header("Content-Type", "text/html")
                self.end_headers()
                self.wfile.write(page)

            def log_message(self, *args):
                pass

        self.server = http.server.HTTPServer(("127.0.0.1", EVIL_PORT), Handler)

    def run(self):
        self.server.serve_forever()


class BrowserPage(unittest.TestCase):
    """The operator's page in a real chromium, beside hostile pages and connections. In order:
    the last case stops the daemon."""

    @classmethod
    def setUpClass(cls):
        missing = bt.browser_missing()
        if missing:
            raise unittest.SkipTest("%s not installed" % ", ".join(missing))
        cls.m = MACHINE
        cls.c = bt.Console(cls.m)

    @classmethod
    def tearDownClass(cls):
        cls.c.close()

    def stats(self, key):
        return self.c.d.execute_script("return window.consoleStats.%s" % key)

    def view(self):
        return self.c.d.execute_script("return window.consoleStats.view")

    def test_1_another_sites_page_cannot_use_the_operators_session(self):
        time.sleep(1.1)  # no PLC heartbeat for the quiet time: the lease could be given
        evil = EvilSite()
        evil.start()
        p0 = self.m.motor_position()
        try:
            self.c.d.get("http://127.0.0.1:%d/" % EVIL_PORT)  # the operator is lured there
            bt.wait_for(lambda: self.c.d.execute_script(
                "return window.result.opened || window.result.closed"), 10, "the evil page's try")
            time.sleep(1.0)  # what an opened socket would have done by now
            result = self.c.d.execute_script("return window.result")
        finally:
            evil.server.shutdown()
            self.c.d.get(self.m.url("/"))
            bt.wait_for(lambda: self.c.text("#conn") == "live", 15, "the console again")
        self.assertFalse(result["opened"], "the console's WebSocket opened for another site: %r"
                         % result)
        self.assertEqual(lease_holder(self.m.name), 0, "the lease")
        self.assertEqual(self.m.motor_position(), p0, "the motor")

    def test_2_fifty_idle_and_slow_connections_lock_nobody_out(self):
        idle = [socket.create_connection(("127.0.0.1", PORT), 5) for _ in range(25)]
        slow = [socket.create_connection(("127.0.0.1", PORT), 5) for _ in range(25)]
        stop = threading.Event()

        def dribble():  # slowloris: a request's header one byte at a time
            for s in slow:
                s.sendall(b"GET / HTTP/1.1\r\n")
            while not stop.wait(0.5):
                for s in slow:
                    try:
                        s.sendall(b"X")
                    except OSError:
                        pass
        t = threading.Thread(target=dribble, daemon=True)
        t.start()
        try:
            time.sleep(0.5)
            b0 = self.stats("batches")
            t0 = time.monotonic()
            r, body = get("/login", timeout=10)
            took = time.monotonic() - t0
            self.assertEqual(r.status, 200)
            self.assertLess(took, 2.0, "/login took %.1f s" % took)
            time.sleep(2.0)
            self.assertGreater(self.stats("batches") - b0, 10, "page updates in 2 s")
            self.c.d.refresh()  # a page loaded now: its files and its WebSocket
            bt.wait_for(lambda: self.c.text("#conn") == "live" and
                        self.c.text("#unit-0 .pos") != "", 10, "the reloaded page live")
        finally:
            stop.set()
            t.join()
            for s in idle + slow:
                s.close()

    def test_3_page_says_stale_then_daemon_stopped_within_a_second(self):
        bt.wait_for(lambda: self.view()["state"] == "live", 10, "the page live")
        t0 = time.time() * 1000
        self.m.web.send_signal(signal.SIGSTOP)  # stepmod-web frozen: no more updates
        try:
            bt.wait_for(lambda: self.view()["state"] == "stale", 5, "the page saying stale")
            stale = self.view()
            self.assertIn("stale: no data for", self.c.text("#conn"))
            self.assertTrue(self.c.d.execute_script("return document.getElementById('take')"
                                                    ".disabled"), "Take control on a stale view")
            self.assertEqual(self.c.text("#lease"), "unknown: no live data")
        finally:
            self.m.web.send_signal(signal.SIGCONT)
        print("stale shown after %d ms" % (stale["since"] - t0))
        self.assertLess(stale["since"] - t0, 1000, "stale after (ms)")
        bt.wait_for(lambda: self.view()["state"] == "live", 10, "the page live again")
        t0 = time.time() * 1000
        self.m.daemon.send_signal(signal.SIGKILL)  # the daemon gone; its image stays, frozen
        self.m.daemon.wait()  # reaped, as systemd does (a zombie still answers kill(pid, 0))
        bt.wait_for(lambda: self.view()["state"] == "daemon stopped", 5,
                    "the page saying daemon stopped")
        print("daemon stopped shown after %d ms" % (self.view()["since"] - t0))
        self.assertLess(self.view()["since"] - t0, 1000, "daemon stopped after (ms)")
        self.assertIn("daemon stopped: no scan for", self.c.text("#conn"))


class TimedResult(unittest.TextTestResult):
    """Each case's time after its verdict: where the time went on a loaded machine."""

    def startTest(self, test):
        self.t0 = time.monotonic()
        super().startTest(test)

    def stopTest(self, test):
        super().stopTest(test)
        self.stream.writeln("    (%.1f s)" % (time.monotonic() - self.t0))


if __name__ == "__main__":
    MACHINE = bt.Machine("3601-sim.toml", PORT)
    try:
        loader = unittest.TestLoader()
        suite = unittest.TestSuite([loader.loadTestsFromTestCase(SocketClients),
                                    loader.loadTestsFromTestCase(BrowserPage)])
        if len(sys.argv) > 6:  # only the cases named
            suite = unittest.TestSuite([case for cls in suite for case in cls
                                        if any(n in case.id() for n in sys.argv[6:])])
        ok = unittest.TextTestRunner(verbosity=2, resultclass=TimedResult).run(suite).wasSuccessful()
    finally:
        if os.environ.get("STEPMOD_WEB_TEST_LOGS"):
            print(web_log()[-4000:])
        MACHINE.close()
    sys.exit(0 if ok else 1)
