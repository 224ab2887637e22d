// The configuration form of each axis/channel: every configuration bit of the module's manual by
// name (a field of several bits a select of every value), the starting speed and, on the 3602,
// the homing timeout, each with its range; filled from the configuration the module TOOK (the
// image's unit-state block, docs/interface.md 3.6: the words of its last configuration scan),
// again each time it takes a new one. A form being edited is not overwritten by the batches,
// only by a new configuration or by "Read back".
"use strict";

function configBits(box, bits, prefix) {
  for (const b of bits) {
    if (b.name === "Configuration Mode") continue; // added by the plc/ library
    const l = document.createElement("label");
    const c = b.width > 1 ? fieldSelect(b) : document.createElement("input");
    if (!(b.width > 1)) c.type = "checkbox";
    c.dataset.bit = b.bit; c.className = prefix;
    l.appendChild(c); l.appendChild(document.createTextNode(" " + b.name));
    box.appendChild(l);
  }
}

// A field of several bits: every value, named as the manual's name says ("(1 = limit,
// 2 = E-stop)"); 0 is "unused", a value the name does not give is reserved (a Configuration
// Error: the module's configuration check says which item).
function fieldSelect(b) {
  const names = { 0: "unused" };
  const m = /\(([^)]*)\)/.exec(b.name);
  if (m) for (const part of m[1].split(",")) {
    const kv = /^\s*(\d+)\s*=\s*(.+?)\s*$/.exec(part);
    if (kv) names[kv[1]] = kv[2];
  }
  const sel = document.createElement("select");
  sel.dataset.width = b.width;
  for (let v = 0; v < (1 << b.width); v++) {
    const o = document.createElement("option");
    o.value = v; o.textContent = `${v}: ${names[v] || "reserved"}`;
    sel.appendChild(o);
  }
  return sel;
}

function wordOf(root, cls) {
  let w = 0;
  for (const c of root.querySelectorAll("input." + cls)) if (c.checked) w |= 1 << c.dataset.bit;
  for (const c of root.querySelectorAll("select." + cls)) w |= parseInt(c.value, 10) << c.dataset.bit;
  return w;
}

// The reverse: each checkbox and select of `cls` from word `w`.
function fillWord(root, cls, w) {
  for (const c of root.querySelectorAll("input." + cls)) c.checked = ((w >>> c.dataset.bit) & 1) === 1;
  for (const c of root.querySelectorAll("select." + cls)) {
    c.value = String((w >>> c.dataset.bit) & ((1 << c.dataset.width) - 1));
  }
}

// The configuration request: MSW and LSW (3601, 3602) or one DINT (3202), the starting speed,
// the 3602's homing timeout.
function configRequest(root) {
  const req = state.module.config_bits.dint ? { bits: wordOf(root, "cd") >>> 0 }
    : { msw: wordOf(root, "cm"), lsw: wordOf(root, "cl") };
  req.start_speed = num(root, ".f-vs");
  if (state.module.ranges.homing_timeout_max > 0) req.homing_timeout = num(root, ".f-hto");
  return req;
}

function buildConfigForm(root, module) {
  const cfg = module.config_bits, r = module.ranges;
  if (cfg.dint) configBits(root.querySelector(".cfg-msw"), cfg.dint, "cd");
  else {
    configBits(root.querySelector(".cfg-msw"), cfg.msw, "cm");
    configBits(root.querySelector(".cfg-lsw"), cfg.lsw, "cl");
  }
  const vs = root.querySelector(".f-vs");
  vs.min = r.starting_speed_min; vs.max = r.starting_speed_max;
  const hto = root.querySelector(".f-hto");
  hto.min = 0; hto.max = r.homing_timeout_max;
  root.querySelector(".hto").style.display = r.homing_timeout_max > 0 ? "" : "none";
  root.querySelector(".ranges").textContent =
    `ranges: starting speed ${r.starting_speed_min}..${r.starting_speed_max} steps/s` +
    (r.homing_timeout_max > 0 ? `, homing timeout 0..${r.homing_timeout_max} s (0: none)` : "");
}

// The form from the configuration the module took (`c`: the batch's machine.config).
function fillConfig(root, c) {
  if ("bits" in c) fillWord(root, "cd", c.bits);
  else { fillWord(root, "cm", c.msw); fillWord(root, "cl", c.lsw); }
  if (c.start_speed !== null) root.querySelector(".f-vs").value = c.start_speed;
  if ("homing_timeout" in c) root.querySelector(".f-hto").value = c.homing_timeout;
}

// Each batch: a configuration the module took since the form was last filled fills it; the
// line under the form says what the form shows.
function showConfig(unit, machine, words) {
  const root = unit.root, c = machine ? machine.config : null;
  unit.cfgLast = c;
  const seq = c ? c.seq : 0;
  if (unit.cfgSeq !== seq) { unit.cfgSeq = seq; if (c) fillConfig(root, c); }
  const refused = words.some((w) => w.bits.some((b) => b.name === "Configuration Error" && b.value));
  const text = !machine ? "configuration: not known (no read of the image)"
    : !c ? "configuration: the module has taken none since the daemon started (the form shows defaults)"
    : refused ? `configuration #${seq}: REFUSED by the module (Configuration Error): the form shows the words it refused`
    : `configuration #${seq} read back: the form shows what the module took`;
  setText(root.querySelector(".cfg-state"), text);
  root.querySelector(".cfg-state").classList.toggle("bad", refused || !c);
}

function readBack(unit) { if (unit.cfgLast) fillConfig(unit.root, unit.cfgLast); }

// Whether the configuration the module took has the quadrature encoder (the following error is
// then shown): the bit named so in its word.
function encoderConfigured(unit) {
  const c = unit.cfgLast, cfg = state.module.config_bits;
  if (!c || !state.module.has_encoder) return false;
  const list = cfg.dint || cfg.msw;
  const b = list.find((x) => x.name === "Quadrature Encoder");
  if (!b) return false;
  return ((("bits" in c ? c.bits : c.msw) >>> b.bit) & 1) === 1;
}
