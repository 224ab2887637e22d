// A move's picture: a VCD trace of stepmodd (read in the browser, nothing is uploaded) as each
// axis' position, speed and motion phase over time, beside the manual's ideal trapezoid for the
// given Vs/Vp/accel/decel (Vp 0: not drawn); two axes also as an XY path (3602 interpolation).
// The parsing follows scripts/plot-axis and scripts/plot-path: position = rising edges of
// AXIS.step, +1 when AXIS.dir is high (CW), -1 when low, in step + direction mode; in CW/CCW
// mode +1 per rising edge of AXIS.step, -1 per rising edge of AXIS.dir (chosen per axis).
"use strict";

// The step outputs' rising edges per axis: each step edge with the dir level at that time, and
// the dir line's own rising edges (in CW/CCW mode the "step" line carries the CW pulses and the
// "dir" line the CCW pulses). The $dumpvars levels are no edges.
function parseVcd(text) {
  const names = {}, raw = {}, level = {}, dir = {};
  let scale = 1e-9, t = 0, initial = false;
  const unitScale = { s: 1, ms: 1e-3, us: 1e-6, ns: 1e-9, ps: 1e-12 };
  for (const rawLine of text.split("\n")) {
    const line = rawLine.trim();
    if (!line) continue;
    const f = line.split(/\s+/);
    if (f[0] === "$timescale") {
      const m = /(\d+)\s*(s|ms|us|ns|ps)/.exec(line);
      if (m) scale = parseInt(m[1], 10) * unitScale[m[2]];
    } else if (f[0] === "$var") {
      names[f[3]] = f[4];
    } else if (f[0] === "$dumpvars") initial = true;
    else if (f[0] === "$end" && initial) initial = false;
    else if (line[0] === "#") t = parseInt(line.slice(1), 10) * scale;
    else if (line[0] === "0" || line[0] === "1") {
      const v = line[0] === "1", n = names[line.slice(1)];
      if (!n) continue;
      const [axis, wire] = n.split(".");
      if (wire !== "dir" && wire !== "step") continue;
      const r = raw[axis] || (raw[axis] = { stepT: [], stepDir: [], dirT: [] });
      if (v && !level[n] && !initial) {
        if (wire === "step") { r.stepT.push(t); r.stepDir.push(!!dir[axis]); } else r.dirT.push(t);
      }
      if (wire === "dir") dir[axis] = v;
      level[n] = v;
    }
  }
  const mode = document.getElementById("i-mode").value, axes = {};
  for (const [name, r] of Object.entries(raw)) {
    const a = positions(r, outputMode(r, mode));
    if (a.t.length) axes[name] = a;
  }
  return axes;
}

// Step + direction or CW/CCW pulses. "auto": CW/CCW when the dir line pulses (at least 32 rising
// edges and 1 % of the step edges; a step/dir path reverses a few times). A move that only ran
// CW in CW/CCW mode looks like a CCW move in step/dir mode: choose the mode then.
function outputMode(r, mode) {
  if (mode !== "auto") return mode;
  return r.dirT.length >= 32 && r.dirT.length * 100 >= r.stepT.length ? "cwccw" : "stepdir";
}

function positions(r, mode) {
  const a = { t: [], pos: [], p: 0, mode: mode };
  if (mode === "stepdir") {
    for (let i = 0; i < r.stepT.length; i++) { a.p += r.stepDir[i] ? 1 : -1; a.t.push(r.stepT[i]); a.pos.push(a.p); }
    return a;
  }
  let i = 0, j = 0; // CW pulses on step (+1), CCW pulses on dir (-1), in time order
  while (i < r.stepT.length || j < r.dirT.length) {
    const cw = j >= r.dirT.length || (i < r.stepT.length && r.stepT[i] <= r.dirT[j]);
    a.p += cw ? 1 : -1; a.t.push(cw ? r.stepT[i++] : r.dirT[j++]); a.pos.push(a.p);
  }
  return a;
}

// Speed in time bins (about 800 over the trace, at least 2 ms each): steps in a bin over its
// width. Bins rather than groups of steps: an axis of an interpolated path steps irregularly
// (two steps close together at a reversal would read as a huge speed).
function speedOf(a) {
  const t0 = a.t[0], t1 = a.t[a.t.length - 1];
  const width = Math.max((t1 - t0) / 800, 0.002);
  const bins = Math.max(1, Math.ceil((t1 - t0) / width));
  const count = new Array(bins).fill(0);
  for (const t of a.t) count[Math.min(bins - 1, Math.floor((t - t0) / width))]++;
  return { t: count.map((_, i) => t0 + (i + 0.5) * width), v: count.map((n) => n / width) };
}

function phases(sp) {
  const max = Math.max(...sp.v, 1), out = [];
  for (let i = 0; i < sp.v.length; i++) {
    const dv = i ? sp.v[i] - sp.v[i - 1] : 0;
    out.push(sp.v[i] === 0 ? "idle" : sp.v[i] > 0.98 * max ? "at speed" :
             dv >= 0 ? "accelerating" : "decelerating");
  }
  return out;
}

// The manual's ideal: Vs to Vp at `acc`, at Vp, back to Vs at `dec`, over `steps` steps.
function ideal(vs, vp, acc, dec, steps) {
  const da = (vp * vp - vs * vs) / (2 * acc), dd = (vp * vp - vs * vs) / (2 * dec);
  let peak = vp, flat = steps - da - dd;
  if (flat < 0) { peak = Math.sqrt((2 * steps * acc * dec + vs * vs * (acc + dec)) / (acc + dec)); flat = 0; }
  const ta = (peak - vs) / acc, td = (peak - vs) / dec, tf = flat / peak;
  return { t: [0, ta, ta + tf, ta + tf + td], v: [vs, peak, peak, vs] };
}

function canvas(parent, title) {
  const h = document.createElement("h3"); h.textContent = title; parent.appendChild(h);
  const c = document.createElement("canvas"); c.width = 900; c.height = 220; c.className = "plot";
  parent.appendChild(c); return c;
}

function plotLines(c, series) {
  const ctx = c.getContext("2d"), x0 = 70, w = c.width - 90, h = c.height - 30;
  let tx = [Infinity, -Infinity], ty = [Infinity, -Infinity];
  for (const s of series) for (let i = 0; i < s.x.length; i++) {
    tx = [Math.min(tx[0], s.x[i]), Math.max(tx[1], s.x[i])];
    ty = [Math.min(ty[0], s.y[i]), Math.max(ty[1], s.y[i])];
  }
  if (ty[1] - ty[0] < 1) ty[1] = ty[0] + 1;
  if (tx[1] - tx[0] <= 0) tx[1] = tx[0] + 1;
  ctx.strokeStyle = "#dde"; ctx.strokeRect(x0, 10, w, h);
  ctx.fillStyle = "#555"; ctx.font = "11px sans-serif"; ctx.textAlign = "right";
  ctx.fillText(String(Math.round(ty[1])), x0 - 4, 16); ctx.fillText(String(Math.round(ty[0])), x0 - 4, h + 10);
  ctx.textAlign = "center";
  ctx.fillText(tx[0].toFixed(3) + " s", x0, c.height - 4); ctx.fillText(tx[1].toFixed(3) + " s", x0 + w, c.height - 4);
  for (const s of series) {
    ctx.strokeStyle = s.color; ctx.lineWidth = s.width || 1.5; ctx.beginPath();
    for (let i = 0; i < s.x.length; i++) {
      const X = x0 + (s.x[i] - tx[0]) / (tx[1] - tx[0]) * w, Y = 10 + (1 - (s.y[i] - ty[0]) / (ty[1] - ty[0])) * h;
      if (i) ctx.lineTo(X, Y); else ctx.moveTo(X, Y);
    }
    ctx.stroke();
  }
}

function drawAxis(main, name, a) {
  const box = document.createElement("section"); box.className = "unit"; box.id = "pic-" + name;
  const sp = speedOf(a), ph = phases(sp);
  const counts = {};
  for (const p of ph) counts[p] = (counts[p] || 0) + 1;
  const h = document.createElement("h2");
  h.textContent = `${name}: ${a.pos.length} steps, end position ${a.p} (from the trace's start), ` +
    `${a.mode === "cwccw" ? "CW/CCW" : "step+dir"}, ` +
    `${a.t[0].toFixed(4)} s .. ${a.t[a.t.length - 1].toFixed(4)} s`;
  h.dataset.end = a.p;
  box.appendChild(h);
  plotLines(canvas(box, "position (steps)"), [{ x: a.t, y: a.pos, color: "#1565c0" }]);
  const series = [{ x: sp.t, y: sp.v, color: "#c62828" }];
  const vs = +document.getElementById("i-vs").value, vp = +document.getElementById("i-vp").value;
  const unit = +document.getElementById("i-unit").value;
  if (vp > 0) {
    const id = ideal(vs, vp, +document.getElementById("i-acc").value * unit,
                     +document.getElementById("i-dec").value * unit, a.pos.length);
    series.push({ x: id.t.map((t) => t + a.t[0]), y: id.v, color: "#f4a582", width: 3 });
  }
  plotLines(canvas(box, "speed (steps/s), red measured, orange the manual's ideal"), series);
  const p = document.createElement("p");
  p.textContent = "phases (share of the speed points): " +
    Object.entries(counts).map(([k, n]) => `${k} ${Math.round(100 * n / ph.length)} %`).join(", ");
  box.appendChild(p);
  main.appendChild(box);
}

function drawXY(main, ax, ay) {
  // Merge the two step trains in time order: (x, y) after every step, as scripts/plot-path.
  const xs = [], ys = [];
  let i = 0, j = 0, x = 0, y = 0;
  while (i < ax.t.length || j < ay.t.length) {
    if (j >= ay.t.length || (i < ax.t.length && ax.t[i] <= ay.t[j])) x = ax.pos[i++]; else y = ay.pos[j++];
    xs.push(x); ys.push(y);
  }
  const box = document.createElement("section"); box.className = "unit"; box.id = "pic-xy";
  const h = document.createElement("h2"); h.textContent = "XY path (axis1 = X, axis2 = Y)"; box.appendChild(h);
  const c = document.createElement("canvas"); c.width = 520; c.height = 520; c.className = "plot"; box.appendChild(c);
  const ctx = c.getContext("2d");
  // One scale for both axes (a circle stays round), each centred.
  const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
  const s = (c.width - 40) / Math.max(x1 - x0, y1 - y0, 1);
  const ox = (c.width - (x1 - x0) * s) / 2, oy = (c.height - (y1 - y0) * s) / 2;
  ctx.strokeStyle = "#1565c0"; ctx.beginPath();
  for (let k = 0; k < xs.length; k++) {
    const X = ox + (xs[k] - x0) * s, Y = c.height - oy - (ys[k] - y0) * s;
    if (k) ctx.lineTo(X, Y); else ctx.moveTo(X, Y);
  }
  ctx.stroke();
  main.appendChild(box);
}

function draw() {
  const f = document.getElementById("vcd").files[0], msg = document.getElementById("msg");
  if (!f) { msg.textContent = "pick a VCD trace first"; return; }
  f.text().then((text) => {
    const axes = parseVcd(text), main = document.getElementById("axes");
    main.textContent = "";
    const names = Object.keys(axes).sort();
    if (!names.length) { msg.textContent = `${f.name}: no steps of any axis (no AXIS.step wires with rising edges)`; return; }
    for (const n of names) drawAxis(main, n, axes[n]);
    if (axes.axis1 && axes.axis2) drawXY(main, axes.axis1, axes.axis2);
    msg.textContent = `${f.name}: ${names.join(", ")}`;
  });
}

window.addEventListener("load", () => {
  document.getElementById("draw").addEventListener("click", draw);
  document.getElementById("vcd").addEventListener("change", draw);
});
