// The live page: one WebSocket carries the sample batches (25 a second, samples every 1 ms) and
// the page's requests. Controls act only under the commissioning lease; while this page holds it
// and has the focus it sends keep-alives 20 times a second, and stepmod-web renews the lease
// only while they arrive (the deadman). A jog button acts only while it is held down.
// The page says how old its data is: "stale" when no update came for STALE_MS, "daemon
// stopped" (or frozen) when the daemon's image stopped advancing, "no connection" when the
// WebSocket closed and "console restarted" when the stepmod-web it reconnects to is another
// process (or no longer knows the session). Take control is offered only on a live view with
// the lease free, and a page that saw no update for BLIND_MS stops its keep-alives (its operator
// no longer sees the axes: the lease expires and the daemon stops them). The lease shown is the
// image's holder, compared with the console's process id (the hello), never the page's memory.
"use strict";

const STALE_MS = 500;
const BLIND_MS = 1000;
const state = { ws: null, module: null, units: [], holding: false, myLease: false,
                leaseSeen: false, takenAt: 0, lastBatchAt: 0, daemon: null, blindSaid: false,
                console: null, restarted: false, holder: 0, reasons: null, reasonSeq: [],
                batches: 0, samples: 0, rateT0: performance.now(), jog: null,
                pendingSince: 0, lastReply: null, lastReason: null };
// A reason recorded between a command and a second after its reply is that command's
// consequence (a configuration's Position Invalid is noted as the module leaves configuration
// mode, after the reply; a forced limit stops the axis): the message line gives the reply, then
// the reason, whichever of the two (from two threads of stepmod-web) the page hears first.
const CONSEQUENCE_MS = 1000;
const $ = (id) => document.getElementById(id);
window.consoleStats = { batches: 0, samples: 0, rate: 0, sampleRate: 0,
                        view: { state: "connecting", since: Date.now() } };

// The message area has a fixed height (style.css): a long message never moves the buttons
// (a held jog button that moved from under the pointer would end the jog); its whole text is
// the area's tooltip.
function say(text, bad) {
  const m = $("msg"); m.textContent = text; m.title = text; m.style.color = bad ? "#ff8a80" : "#b9f6ca";
}

function send(obj) {
  if (!state.ws || state.ws.readyState !== WebSocket.OPEN) return false;
  state.ws.send(JSON.stringify(obj));
  return true;
}

function num(root, cls) { return parseInt(root.querySelector(cls).value, 10); }

function profile(root) {
  return { speed: num(root, ".f-speed"), accel: num(root, ".f-accel"),
           decel: num(root, ".f-decel"), profile: num(root, ".f-profile") };
}

// Every command is sent whatever the lease or the view (an immediate stop above all: it is the
// daemon that decides); one that cannot be sent says so.
function command(unit, cmd, extra) {
  state.lastUnit = unit;
  state.pendingSince = performance.now();  // until its reply
  if (!send(Object.assign({ op: "cmd", unit: unit, cmd: cmd }, extra || {}))) {
    state.pendingSince = 0;
    say(`${cmd}: NOT SENT: no connection to stepmod-web`, true);
  }
}

function jogButton(root, u, dir) {
  const b = root.querySelector(".b-jog-" + dir);
  const press = (e) => {
    e.preventDefault();
    if (state.jog) return;
    state.jog = { unit: u, button: b }; b.classList.add("active");
    command(u, "jog_press", Object.assign({ dir: dir }, profile(root)));
  };
  b.addEventListener("pointerdown", press);
  for (const ev of ["pointerup", "pointerleave", "pointercancel"]) {
    b.addEventListener(ev, () => endJog());
  }
}

function endJog() {
  if (!state.jog) return;
  command(state.jog.unit, "jog_release");
  state.jog.button.classList.remove("active");
  state.jog = null;
}

function wireControls(root, u, ranges) {
  const click = (cls, fn) => root.querySelector(cls).addEventListener("click", fn);
  click(".b-abs", () => command(u, "move", Object.assign({ absolute: true, target: num(root, ".f-target") }, profile(root))));
  click(".b-rel", () => command(u, "move", Object.assign({ absolute: false, target: num(root, ".f-target") }, profile(root))));
  click(".b-home-cw", () => command(u, "home", Object.assign({ dir: "cw" }, profile(root))));
  click(".b-home-ccw", () => command(u, "home", Object.assign({ dir: "ccw" }, profile(root))));
  click(".b-hold", () => command(u, "hold"));
  click(".b-resume", () => command(u, "resume"));
  click(".b-stop", () => command(u, "stop"));
  click(".b-reset", () => command(u, "reset"));
  click(".b-preset", () => command(u, "preset", { position: num(root, ".f-preset") }));
  click(".b-config", () => command(u, "configure", configRequest(root)));
  click(".b-readback", () => readBack(state.units[u]));
  jogButton(root, u, "cw"); jogButton(root, u, "ccw");
  root.querySelector(".f-speed").max = ranges.speed_max;
  for (const c of [".f-accel", ".f-decel"]) {
    const f = root.querySelector(c);
    f.min = ranges.accel_min; f.max = ranges.accel_max; f.value = ranges.accel_default;
    f.title = ranges.accel_unit;
  }
  for (const c of root.querySelectorAll(".accel-unit")) c.textContent = ranges.accel_unit;
  const target = root.querySelector(".f-target");
  target.min = ranges.target_min; target.max = ranges.target_max;
  root.querySelector(".mranges").textContent =
    `ranges: speed ..${ranges.speed_max} steps/s, accel/decel ${ranges.accel_min}..${ranges.accel_max} ` +
    `${ranges.accel_unit}, target ${ranges.target_min}..${ranges.target_max}`;
}

function buildUnits(hello) {
  const c = hello.console;
  if (state.console && c && (c.pid !== state.console.pid || c.started_ms !== state.console.started_ms)) {
    state.restarted = true;
    say(`console restarted (process ${state.console.pid} → ${c.pid}): this page's lease ended`, true);
  }
  state.console = c || null; state.reasons = hello.reasons || null; state.reasonSeq = [];
  state.module = hello.module;
  $("title").textContent = `stepmod console: ${hello.name} (AMCI ${hello.module.type})`;
  const main = $("units"); main.textContent = "";
  state.units = [];
  const noun = hello.module.unit_noun;  // "axis" or "channel", as the module's manual says
  const word = noun.charAt(0).toUpperCase() + noun.slice(1);
  for (let u = 0; u < hello.module.units; u++) {
    const root = $("unit-template").content.firstElementChild.cloneNode(true);
    root.id = "unit-" + u;
    root.querySelector(".unit-title").textContent = `${word} ${u + 1}`;
    buildConfigForm(root, hello.module);
    wireControls(root, u, hello.module.ranges);
    main.appendChild(root);
    state.units.push({ root: root, plot: new LivePlot(root.querySelector("canvas"), 5, hello.module.ranges.speed_max) });
  }
  state.xy = hello.module.type === 3602 ? buildPath(main) : null;
}

// Display units, the console's own setting (kept in this browser): steps per mm, degree, ... The
// module's words stay in steps; only this row converts.
function displayUnits() {
  const spu = parseFloat($("spu").value);
  return { spu: spu > 0 ? spu : 1, name: $("uname").value || "step" };
}

// The following error where the module took a configuration with the encoder: the position
// less the encoder in steps (the console's own setting: encoder counts per step).
function followingError(unit, u, b) {
  if (!b.enc || !b.enc[u] || !encoderConfigured(unit)) return null;
  const cps = parseFloat($("cps").value) > 0 ? parseFloat($("cps").value) : 1;
  return b.pos[u].map((p, k) => p - b.enc[u][k] / cps);
}

function showInUnits(root, steps) {
  const u = displayUnits();
  const text = `${+(steps / u.spu).toFixed(4)} ${u.name}`;
  const cell = root.querySelector(".upos");
  if (cell.textContent !== text) cell.textContent = text;
}

function loadDisplayUnits() {
  for (const id of ["spu", "uname", "cps"]) {
    const saved = localStorage.getItem("stepmod." + id);
    if (saved !== null) $(id).value = saved;
    $(id).addEventListener("change", () => localStorage.setItem("stepmod." + id, $(id).value));
  }
}

// The bit lists are built once (the first batch) and then only their values change, rather than
// rebuilding every list item of every unit 25 times a second. (Measured on the 3601 page, the
// browser's CPU did not change measurably: the page's stalls on the loaded test machine came
// from the machine's load.)
function showWords(box, words) {
  if (box.childElementCount !== words.length) buildWords(box, words);
  const items = box.querySelectorAll("li");
  let i = 0;
  for (const w of words) {
    for (const b of w.bits) {
      const li = items[i++];
      const text = `${b.bit} ${b.name}` + (b.value > 1 ? ` = ${b.value}` : "");
      if (li.textContent !== text) li.textContent = text;
      const cls = b.value ? "on" : "";
      if (li.className !== cls) li.className = cls;
    }
  }
}

function buildWords(box, words) {
  box.textContent = "";
  for (const w of words) {
    const d = document.createElement("div");
    const h = document.createElement("h3"); h.textContent = w.word; d.appendChild(h);
    const ul = document.createElement("ul");
    for (const b of w.bits) {
      const li = document.createElement("li");
      li.dataset.name = b.name;
      ul.appendChild(li);
    }
    d.appendChild(ul); box.appendChild(d);
  }
}

function showBatch(b) {
  state.batches++; state.samples += b.t_us.length;
  const now = performance.now();
  state.lastBatchAt = now; state.daemon = b.daemon || null; state.blindSaid = false;
  if (now - state.rateT0 >= 1000) {
    const s = (now - state.rateT0) / 1000;
    window.consoleStats.rate = state.batches / s; window.consoleStats.sampleRate = state.samples / s;
    $("rate").textContent = window.consoleStats.rate.toFixed(1);
    $("srate").textContent = Math.round(window.consoleStats.sampleRate);
    state.batches = 0; state.samples = 0; state.rateT0 = now;
  }
  window.consoleStats.batches++;
  if (b.pos.length >= 2 && b.pos[0].length) {
    state.lastPos = [b.pos[0][b.pos[0].length - 1], b.pos[1][b.pos[1].length - 1]];
    if (state.xy) state.xy.push(b.pos[0], b.pos[1]);
  }
  b.status.forEach((s, u) => {
    const unit = state.units[u]; if (!unit) return;
    showConfig(unit, s.machine, s.words);
    unit.plot.push(b.t_us, b.pos[u], followingError(unit, u, b));
    const r = unit.root;
    r.querySelector(".pos").textContent = s.position;
    showInUnits(r, s.position);
    r.querySelector(".enc").textContent = state.module.has_encoder ? s.encoder : "— (no encoder input)";
    r.querySelector(".cap").textContent = s.capture;
    r.querySelector(".speed").textContent = Math.round(unit.plot.lastSpeed());
    const fe = unit.plot.lastFollowingError();
    r.querySelector(".ferr").textContent = fe === null ? "— (no encoder configured)" : fe.toFixed(1);
    showReason(r.querySelector(".reason"), state.reasons, s.reason, reasonActive(s.words, s.reason));
    newReason(u, s.reason);
    showWords(r.querySelector(".words"), s.words);
    showInputs(r.querySelector(".sim"), u, s.machine, b.sim);
  });
  $("health").textContent = `${b.health.names} (16#${b.health.flags.toString(16)})`;
  $("plc").textContent = b.plc.stale ? "heartbeat stale" :
    (b.plc.quiet_ms < 1000 ? `heartbeat live (${b.plc.heartbeat})` : `no heartbeat for ${(b.plc.quiet_ms / 1000).toFixed(1)} s`);
  showLease(b.lease.holder);
}

// A reason recorded while the page looks (a limit stop under a held jog, say) replaces the
// message of the last command ("jog_press: done" is no longer true).
function newReason(u, r) {
  const seq = r && r.seq ? r.seq : 0;
  const before = state.reasonSeq[u];
  state.reasonSeq[u] = seq;
  if (before === undefined || seq === before || !seq) return;
  const text = unitReason(u, r), now = performance.now(), reply = state.lastReply;
  state.lastReason = { text: text, at: now };
  // Not while a command awaits its reply: that reply will take the reason (onReply).
  if (reply && !reply.withReason && !state.pendingSince && now - reply.at < CONSEQUENCE_MS) {
    reply.withReason = true;
    say(`${reply.text} — ${text}`, true);
  } else {
    say(text, true);
  }
}

function unitReason(u, r) {
  const noun = state.module.unit_noun;
  return `${noun.charAt(0).toUpperCase() + noun.slice(1)} ${u + 1}: ${reasonLine(state.reasons, r)}`;
}

// The lease as the image shows it: free, this console's (this page or another of its pages), or
// another process'.
function showLease(holder) {
  state.holder = holder;
  const mine = state.console && holder === state.console.pid;
  // The batches and the replies come from separate threads of stepmod-web: a batch sampled just
  // before the take can arrive after its reply. A lease not ours ends this page's hold only once
  // a batch has shown it ours, or a second after the take; else the page would stop its
  // keep-alives and the lease would expire under the operator.
  if (state.holding && mine) state.leaseSeen = true;
  const early = !state.leaseSeen && performance.now() - state.takenAt < 1000;
  if (state.holding && !mine && !early) {
    state.holding = false;
    say("the lease ended (expired or freed): the axes were stopped", true);
  }
  state.myLease = state.holding && mine;
  // A daemon gone leaves its image frozen: the holder there is no news (showView says so too).
  $("lease").textContent = state.daemon && state.daemon.gone ? "unknown: no live data" :
    holder === 0 ? "free" :
    (mine ? (state.holding ? `held by this console (process ${holder})` :
                             `held by this console, another page (process ${holder})`) :
            `held by process ${holder}`);
}

function onMessage(ev) {
  const m = JSON.parse(ev.data);
  if (m.type === "hello") buildUnits(m);
  else if (m.type === "batch") showBatch(m);
  else if (m.type === "reply") {
    if (m.op === "take" && m.ok) { state.holding = true; state.leaseSeen = false; state.takenAt = performance.now(); }
    if (m.op === "release" && m.ok) state.holding = false;
    onReply(m);
  }
}

function onReply(m) {
  const u = state.lastUnit, seq = m.reason && m.reason.seq ? m.reason.seq : 0;
  // The reply of a command (not of a take or a release) ends its wait.
  const pendingSince = m.op === "take" || m.op === "release" ? 0 : state.pendingSince;
  if (pendingSince) state.pendingSince = 0;
  // The reply's reason was read before the reply was sent; a batch sampled after it may have
  // reached the page first with a newer one. Only a newer reason is news.
  const newer = u !== undefined && seq > (state.reasonSeq[u] || 0);
  // A reason the reply carries is this command's (a configuration's Position Invalid, a
  // refusal's reason): the batches do not announce it again over the reply.
  if (newer) state.reasonSeq[u] = seq;
  // The plc/ library's message may quote the reason already: then only what to do is added.
  const row = seq ? reasonRow(state.reasons, m.reason.item) : null;
  let text = `${m.op}: ${m.message}`, withReason = false;
  if (!m.ok && seq) {
    text += m.message.includes(m.reason.text.trim())
      ? (m.reason.cut ? "…" : "") + (row ? ` — ${row.fix}` : "")
      : ` — ${reasonLine(state.reasons, m.reason)}`;
    withReason = true;
  } else if (newer) {
    text += ` — ${unitReason(u, m.reason)}`;  // recorded before the reply, not yet in a batch
    withReason = true;
  } else if (pendingSince && state.lastReason && state.lastReason.at >= pendingSince) {
    text += ` — ${state.lastReason.text}`;  // a batch announced it between command and reply
    withReason = true;
  }
  state.lastReply = { text: text, at: performance.now(), withReason: withReason };
  say(text, !m.ok || withReason);
}

function connect() {
  const ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws");
  state.ws = ws;
  ws.onclose = () => { state.holding = false; state.pendingSince = 0; showView(); checkConsole(); setTimeout(connect, 1000); };
  ws.onmessage = onMessage;
}

// After the WebSocket closed: is stepmod-web there, and the same process? A restarted one no
// longer knows this page's session (401) or names another process.
function checkConsole() {
  fetch("/api/hello", { cache: "no-store" }).then((r) => {
    if (r.status === 401) { state.restarted = "login"; showView(); return null; }
    return r.ok ? r.json() : null;
  }).then((h) => {
    if (h && h.console && state.console && h.console.started_ms !== state.console.started_ms) {
      state.restarted = true; showView();
    }
  }).catch(() => {});
}

function viewState(age) {
  const open = state.ws && state.ws.readyState === WebSocket.OPEN;
  if (state.restarted === "login" || (state.restarted && !open)) return "console restarted";
  if (!open) return "closed";
  if (!state.lastBatchAt) return "connecting";
  if (age > STALE_MS) return "stale";
  if (state.daemon && state.daemon.gone) return state.daemon.stopped ? "daemon stopped" : "daemon frozen";
  return "live";
}

// The view's state and the data's age, ten times a second.
function showView() {
  const age = state.lastBatchAt ? performance.now() - state.lastBatchAt : 0;
  const s = viewState(age);
  if (s !== window.consoleStats.view.state) window.consoleStats.view = { state: s, since: Date.now() };
  const secs = (ms) => `${(ms / 1000).toFixed(1)} s`;
  const quiet = secs((state.daemon ? state.daemon.quiet_ms : 0) + age);
  $("conn").textContent = {
    live: "live", connecting: "connecting",
    closed: `no connection to stepmod-web: reconnecting (no data for ${secs(age)})`,
    "console restarted": state.restarted === "login"
      ? "console restarted: log in again (reload the page)"
      : "console restarted: this page's lease and jog ended",
    stale: `stale: no data for ${secs(age)}`,
    "daemon stopped": `daemon stopped: no scan for ${quiet}`,
    "daemon frozen": `daemon frozen: its image stopped ${quiet} ago`,
  }[s];
  $("age").textContent = state.lastBatchAt ? `${Math.round(age)} ms` : "-";
  if (s !== "live") $("lease").textContent = "unknown: no live data";
  $("take").disabled = s !== "live" || state.holding || state.holder !== 0;
  $("release").disabled = !state.holding;
  document.body.classList.toggle("notlive", s !== "live");
}

// The deadman: keep-alives only while this page holds the lease, is visible and has the focus.
function keepAlive() {
  const now = performance.now();
  if (state.lastTick) {
    window.consoleStats.maxTickGap = Math.max(window.consoleStats.maxTickGap || 0, now - state.lastTick);
  }
  state.lastTick = now;
  if (state.holding && document.visibilityState === "visible" && document.hasFocus()) {
    if (now - state.lastBatchAt < BLIND_MS) send({ op: "keepalive" });
    else if (!state.blindSaid) {
      state.blindSaid = true;
      say("no update for 1 s: keep-alives stopped, the lease expires and the axes stop", true);
    }
  }
}

window.addEventListener("blur", endJog);
document.addEventListener("visibilitychange", () => { if (document.visibilityState !== "visible") endJog(); });
window.addEventListener("load", () => {
  $("take").addEventListener("click", () => send({ op: "take" }));
  $("release").addEventListener("click", () => { endJog(); send({ op: "release" }); });
  loadDisplayUnits();
  setInterval(keepAlive, 50);
  setInterval(showView, 100);
  connect();
});
