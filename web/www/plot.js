// A small canvas plotter for the live page: position, speed and (where an encoder is configured)
// the following error of one axis over the last
// `seconds`, redrawn at most once per animation frame. Chosen over Chart.js because the page
// appends 1,000 samples a second to a fixed time window and redraws 20+ times a second: two
// polylines on a canvas do exactly that, with no animation, parsing or decimation to configure.
"use strict";

// The speed is the position's slope over 50 ms: the samples come every 1 ms and the position
// moves by whole scans, so over 20 ms a 4,000 steps/s jog read 4,000 +- 300; over 50 ms +- 2 %.
const SPEED_WINDOW_US = 50000;
const MAX_SPEED = 2000000; // steps/s: above every module's range

class LivePlot {
  constructor(canvas, seconds, speedMax) {
    this.canvas = canvas;
    this.span = seconds * 1e6; // µs
    this.t = []; this.pos = []; this.speed = []; this.ferr = [];
    this.pending = false;
    this.speedMax = speedMax || MAX_SPEED;
    this.breakAt = -Infinity; // time of the last jump no motor makes (a preset, a configuration)
  }

  // Speed from position and time: the slope over about `window` µs (many module scans), so
  // that a scan's quantisation does not show as noise, from samples at `from` or later: a jump
  // no motor makes (a preset, a configuration zeroing the position) is no speed.
  static slope(t, pos, i, window, from) {
    const start = from === undefined ? -Infinity : from;
    let j = i;
    while (j > 0 && t[j - 1] >= start && t[i] - t[j - 1] <= window) j--;
    if (j === i) { // no sample within the window: the previous one, unless across a jump
      if (i === 0 || t[i - 1] < start) return 0;
      j = i - 1;
    }
    const v = (pos[i] - pos[j]) * 1e6 / (t[i] - t[j]);
    return Math.abs(v) > MAX_SPEED ? 0 : v;
  }

  // `fe`: the following error of each sample (position - encoder, steps), or null (no encoder
  // configured: the trace is cleared).
  push(ts, ps, fe) {
    if (!fe) this.ferr = [];
    for (let k = 0; k < ts.length; k++) {
      const n = this.t.length;
      // A step between two samples faster than the module can move is a preset or a
      // configuration's zero: the speed's window starts after it.
      if (n && Math.abs(ps[k] - this.pos[n - 1]) > this.speedMax * (ts[k] - this.t[n - 1]) * 1.1e-6 + 8) this.breakAt = ts[k];
      this.t.push(ts[k]); this.pos.push(ps[k]);
      if (fe) this.ferr.push(fe[k]);
      this.speed.push(LivePlot.slope(this.t, this.pos, n, SPEED_WINDOW_US, this.breakAt));
    }
    const cut = this.t.length ? this.t[this.t.length - 1] - this.span : 0;
    let drop = 0;
    while (drop < this.t.length && this.t[drop] < cut) drop++;
    if (drop) { this.t.splice(0, drop); this.pos.splice(0, drop); this.speed.splice(0, drop); }
    // The following error's samples are the last ones of the window (fewer after a clear).
    if (this.ferr.length > this.t.length) this.ferr.splice(0, this.ferr.length - this.t.length);
    if (!this.pending) { this.pending = true; requestAnimationFrame(() => this.draw()); }
  }

  lastSpeed() { return this.speed.length ? this.speed[this.speed.length - 1] : 0; }
  lastFollowingError() { return this.ferr.length ? this.ferr[this.ferr.length - 1] : null; }

  static range(a) {
    let lo = Infinity, hi = -Infinity;
    for (const v of a) { if (v < lo) lo = v; if (v > hi) hi = v; }
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi - lo < 1) { lo -= 1; hi += 1; }
    return [lo, hi];
  }

  // `ys` are the values of the last ys.length samples.
  line(ctx, ys, range, x0, w, h, color) {
    const t1 = this.t[this.t.length - 1], t0 = t1 - this.span, off = this.t.length - ys.length;
    ctx.strokeStyle = color; ctx.lineWidth = 1.5; ctx.beginPath();
    for (let i = 0; i < ys.length; i++) {
      const x = x0 + (this.t[i + off] - t0) / this.span * w;
      const y = 10 + (1 - (ys[i] - range[0]) / (range[1] - range[0])) * (h - 20);
      if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y);
    }
    ctx.stroke();
  }

  // "Nice" grid steps (1, 2, 5 x 10^k) for a range, about `n` of them.
  static ticks(range, n) {
    const raw = (range[1] - range[0]) / n, p = Math.pow(10, Math.floor(Math.log10(raw)));
    const st = [1, 2, 5, 10].map((m) => m * p).find((v) => v >= raw);
    const out = [];
    for (let v = Math.ceil(range[0] / st) * st; v <= range[1]; v += st) out.push(v);
    return out;
  }

  // Position (left scale) and speed (right scale) with a grid: a line per position tick and per
  // second, speed ticks on the right edge.
  draw() {
    this.pending = false;
    const c = this.canvas, ctx = c.getContext("2d");
    const x0 = 70, w = c.width - 140, h = c.height - 20;
    ctx.clearRect(0, 0, c.width, c.height);
    ctx.strokeStyle = "#dde"; ctx.strokeRect(x0, 10, w, h - 20);
    if (this.t.length < 2) return;
    const pr = LivePlot.range(this.pos), sr = LivePlot.range(this.speed);
    const yOf = (v, r) => 10 + (1 - (v - r[0]) / (r[1] - r[0])) * (h - 20);
    ctx.font = "11px sans-serif"; ctx.lineWidth = 1;
    this.lastTicks = LivePlot.ticks(pr, 5);
    for (const v of this.lastTicks) {
      ctx.strokeStyle = "#eceef4"; ctx.beginPath(); ctx.moveTo(x0, yOf(v, pr)); ctx.lineTo(x0 + w, yOf(v, pr)); ctx.stroke();
      ctx.fillStyle = "#1565c0"; ctx.textAlign = "right"; ctx.fillText(String(v), x0 - 4, yOf(v, pr) + 4);
    }
    for (const v of LivePlot.ticks(sr, 5)) {
      ctx.strokeStyle = "#c62828"; ctx.beginPath(); ctx.moveTo(x0 + w, yOf(v, sr)); ctx.lineTo(x0 + w + 4, yOf(v, sr)); ctx.stroke();
      ctx.fillStyle = "#c62828"; ctx.textAlign = "left"; ctx.fillText(String(v), x0 + w + 6, yOf(v, sr) + 4);
    }
    const secs = this.span / 1e6;
    ctx.fillStyle = "#555"; ctx.textAlign = "center";
    for (let k = 0; k <= secs; k++) {
      const x = x0 + k / secs * w;
      ctx.strokeStyle = "#eceef4"; ctx.beginPath(); ctx.moveTo(x, 10); ctx.lineTo(x, h - 10); ctx.stroke();
      ctx.fillText(k === secs ? "now" : `${k - secs} s`, x, c.height - 4);
    }
    this.line(ctx, this.pos, pr, x0, w, h, "#1565c0");
    this.line(ctx, this.speed, sr, x0, w, h, "#c62828");
    if (this.ferr.length > 1) this.drawFollowingError(ctx, x0, w, h, yOf);
  }

  // The following error on its own scale, its ticks in green inside the right edge.
  drawFollowingError(ctx, x0, w, h, yOf) {
    const fr = LivePlot.range(this.ferr);
    ctx.fillStyle = "#2e7d32"; ctx.textAlign = "right";
    for (const v of LivePlot.ticks(fr, 4)) ctx.fillText(String(v), x0 + w - 4, yOf(v, fr) + 4);
    this.line(ctx, this.ferr, fr, x0, w, h, "#2e7d32");
  }
}
window.LivePlot = LivePlot;
