// The 3602's interpolated moves from the page (line, arc by centre, radius or via point, full
// circle: a centre with the end at the start), each one "path" request that stepmod-web sends
// through module_types/m3602/plc_interp_3602 as stepmodctl's `path` does, under the lease; the GPO of each axis;
// and a live XY plot of both axes' positions (the samples of the batches, 1 ms apart) with the
// planned path drawn beside it, on a grid with its scales.
"use strict";

const XY_KEEP = 30000; // samples kept: 30 s at 1 kHz

class XyPlot {
  constructor(canvas) { this.canvas = canvas; this.x = []; this.y = []; this.plan = []; this.pending = false; }

  push(xs, ys) {
    for (let k = 0; k < xs.length; k++) { this.x.push(xs[k]); this.y.push(ys[k]); }
    if (this.x.length > XY_KEEP) { this.x.splice(0, this.x.length - XY_KEEP); this.y.splice(0, this.y.length - XY_KEEP); }
    this.redraw();
  }

  redraw() { if (!this.pending) { this.pending = true; requestAnimationFrame(() => this.draw()); } }

  // A square view holding the trace and the plan, with "nice" grid steps (1, 2, 5 x 10^k).
  bounds() {
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    const take = (x, y) => { x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y); };
    for (let i = 0; i < this.x.length; i++) take(this.x[i], this.y[i]);
    for (const p of this.plan) take(p[0], p[1]);
    if (!isFinite(x0)) { x0 = y0 = -1; x1 = y1 = 1; }
    const span = Math.max(x1 - x0, y1 - y0, 10) * 1.1;
    return { cx: (x0 + x1) / 2, cy: (y0 + y1) / 2, span: span };
  }

  static step(span) {
    const raw = span / 8, p = Math.pow(10, Math.floor(Math.log10(raw)));
    return [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw);
  }

  draw() {
    this.pending = false;
    const c = this.canvas, ctx = c.getContext("2d"), m = 50, side = Math.min(c.width, c.height) - 2 * m + 20;
    const b = this.bounds(), k = side / b.span;
    const px = (x) => m + (x - (b.cx - b.span / 2)) * k, py = (y) => m - 20 + side - (y - (b.cy - b.span / 2)) * k;
    ctx.clearRect(0, 0, c.width, c.height);
    ctx.font = "11px sans-serif"; ctx.lineWidth = 1;
    const st = XyPlot.step(b.span);
    for (let v = Math.ceil((b.cx - b.span / 2) / st) * st; v <= b.cx + b.span / 2; v += st) {
      ctx.strokeStyle = "#e4e6ee"; ctx.beginPath(); ctx.moveTo(px(v), py(b.cy - b.span / 2)); ctx.lineTo(px(v), py(b.cy + b.span / 2)); ctx.stroke();
      ctx.fillStyle = "#555"; ctx.textAlign = "center"; ctx.fillText(String(v), px(v), py(b.cy - b.span / 2) + 14);
    }
    for (let v = Math.ceil((b.cy - b.span / 2) / st) * st; v <= b.cy + b.span / 2; v += st) {
      ctx.strokeStyle = "#e4e6ee"; ctx.beginPath(); ctx.moveTo(px(b.cx - b.span / 2), py(v)); ctx.lineTo(px(b.cx + b.span / 2), py(v)); ctx.stroke();
      ctx.fillStyle = "#555"; ctx.textAlign = "right"; ctx.fillText(String(v), px(b.cx - b.span / 2) - 4, py(v) + 4);
    }
    ctx.fillText("axis 2 (steps)", m + 40, 12); ctx.textAlign = "right"; ctx.fillText("axis 1 (steps)", c.width - 4, c.height - 4);
    const poly = (xs, ys, color, dash) => {
      ctx.strokeStyle = color; ctx.lineWidth = 1.5; ctx.setLineDash(dash); ctx.beginPath();
      for (let i = 0; i < xs.length; i++) { if (i) ctx.lineTo(px(xs[i]), py(ys[i])); else ctx.moveTo(px(xs[i]), py(ys[i])); }
      ctx.stroke(); ctx.setLineDash([]);
    };
    poly(this.plan.map((p) => p[0]), this.plan.map((p) => p[1]), "#9e9e9e", [6, 4]);
    poly(this.x, this.y, "#1565c0", []);
    if (this.x.length) { ctx.fillStyle = "#c62828"; ctx.beginPath(); ctx.arc(px(this.x[this.x.length - 1]), py(this.y[this.y.length - 1]), 4, 0, 2 * Math.PI); ctx.fill(); }
  }
}

// The planned path from the start point, as the manual's methods define it (points are offsets
// from the start unless absolute; a centre arc whose end is its start is the full circle).
function plannedPath(req, sx, sy) {
  const at = (x, y) => req.absolute ? [x, y] : [sx + x, sy + y];
  const [ex, ey] = at(req.end_x, req.end_y);
  if (req.method === "line") return [[sx, sy], [ex, ey]];
  let cx, cy, ccw = req.sense === "ccw";
  if (req.method === "centre") [cx, cy] = at(req.point_x, req.point_y);
  else if (req.method === "via") {
    const [vx, vy] = at(req.point_x, req.point_y);
    const d = 2 * (sx * (vy - ey) + vx * (ey - sy) + ex * (sy - vy));
    if (!d) return [[sx, sy], [vx, vy], [ex, ey]];
    const s2 = sx * sx + sy * sy, v2 = vx * vx + vy * vy, e2 = ex * ex + ey * ey;
    cx = (s2 * (vy - ey) + v2 * (ey - sy) + e2 * (sy - vy)) / d;
    cy = (s2 * (ex - vx) + v2 * (sx - ex) + e2 * (vx - sx)) / d;
    ccw = (vx - sx) * (ey - sy) - (vy - sy) * (ex - sx) > 0;
  } else { // radius: > 0 the shorter arc, < 0 the longer one
    const dx = ex - sx, dy = ey - sy, dd = Math.hypot(dx, dy), r = Math.abs(req.radius);
    if (!dd || r < dd / 2) return [[sx, sy], [ex, ey]];
    const h = Math.sqrt(r * r - dd * dd / 4), left = (ccw === req.radius > 0) ? 1 : -1;
    cx = (sx + ex) / 2 - left * h * dy / dd; cy = (sy + ey) / 2 + left * h * dx / dd;
  }
  const r = Math.hypot(sx - cx, sy - cy), a0 = Math.atan2(sy - cy, sx - cx);
  let sweep = Math.atan2(ey - cy, ex - cx) - a0;
  if (ccw) { while (sweep <= 1e-9) sweep += 2 * Math.PI; } else { while (sweep >= -1e-9) sweep -= 2 * Math.PI; }
  const pts = [];
  for (let i = 0; i <= 180; i++) {
    const a = a0 + sweep * i / 180;
    pts.push([cx + r * Math.cos(a), cy + r * Math.sin(a)]);
  }
  return pts;
}

function pathRequest(root) {
  const n = (cls) => parseInt(root.querySelector(cls).value, 10);
  return { op: "cmd", unit: 0, cmd: "path", method: root.querySelector(".p-method").value,
           sense: root.querySelector(".p-sense").value, absolute: root.querySelector(".p-abs").checked,
           end_x: n(".p-ex"), end_y: n(".p-ey"), point_x: n(".p-px"), point_y: n(".p-py"),
           radius: n(".p-r"), speed: n(".p-speed"), accel: n(".p-accel"), decel: n(".p-decel"),
           profile: n(".p-profile") };
}

// The fields a method uses are shown; the others hidden (their values are not sent as used).
function showPathFields(root) {
  const m = root.querySelector(".p-method").value;
  root.querySelector(".p-point").style.visibility = m === "centre" || m === "via" ? "visible" : "hidden";
  root.querySelector(".p-radius").style.visibility = m === "radius" ? "visible" : "hidden";
  root.querySelector(".p-sense-l").style.visibility = m === "line" || m === "via" ? "hidden" : "visible";
}

function buildPath(main) {
  const root = $("path-template").content.firstElementChild.cloneNode(true);
  main.appendChild(root);
  const plot = new XyPlot(root.querySelector("canvas"));
  root.querySelector(".p-method").addEventListener("change", () => showPathFields(root));
  showPathFields(root);
  root.querySelector(".b-path").addEventListener("click", () => {
    const req = pathRequest(root);
    const sx = state.lastPos ? state.lastPos[0] : 0, sy = state.lastPos ? state.lastPos[1] : 0;
    plot.plan = plannedPath(req, sx, sy); plot.redraw();
    state.lastUnit = 0; // the reply's reason is axis 1's (a path is axis 1's command)
    state.pendingSince = performance.now();  // until its reply
    if (!send(req)) {
      state.pendingSince = 0;
      say("path: NOT SENT: no connection to stepmod-web", true);
    }
  });
  root.querySelector(".b-path-stop").addEventListener("click", () => command(0, "stop"));
  root.querySelector(".b-xy-clear").addEventListener("click", () => { plot.x = []; plot.y = []; plot.plan = []; plot.redraw(); });
  for (const u of [0, 1]) {
    const box = root.querySelector(".p-gpo" + u);
    box.addEventListener("change", () => command(u, "gpo", { on: box.checked }));
  }
  return plot;
}
