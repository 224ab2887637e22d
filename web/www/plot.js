// A small canvas plotter for the live page: position and speed of one axis over the last
// `seconds`, redrawn at most once per animation frame. Chosen over Chart.js because the page
// appends 1,000 samples a second to a fixed time window and redraws 20+ times a second: two
// polylines on a canvas do exactly that, with no animation, parsing or decimation to configure.
"use strict";

class LivePlot {
  constructor(canvas, seconds) {
    this.canvas = canvas;
    this.span = seconds * 1e6; // µs
    this.t = []; this.pos = []; this.speed = [];
    this.pending = false;
  }

  // Speed from position and time: the slope over about `window` µs (a few module scans), so
  // that a scan's quantisation does not show as noise.
  static slope(t, pos, i, window) {
    let j = i;
    while (j > 0 && t[i] - t[j - 1] <= window) j--;
    if (j === i) return i > 0 ? LivePlot.slope(t, pos, i, Infinity) : 0;
    return (pos[i] - pos[j]) * 1e6 / (t[i] - t[j]);
  }

  push(ts, ps) {
    for (let k = 0; k < ts.length; k++) {
      this.t.push(ts[k]); this.pos.push(ps[k]);
      this.speed.push(LivePlot.slope(this.t, this.pos, this.t.length - 1, 20000));
    }
    const cut = this.t.length ? this.t[this.t.length - 1] - this.span : 0;
    let drop = 0;
    while (drop < this.t.length && this.t[drop] < cut) drop++;
    if (drop) { this.t.splice(0, drop); this.pos.splice(0, drop); this.speed.splice(0, drop); }
    if (!this.pending) { this.pending = true; requestAnimationFrame(() => this.draw()); }
  }

  lastSpeed() { return this.speed.length ? this.speed[this.speed.length - 1] : 0; }

  static range(a) {
    let lo = Infinity, hi = -Infinity;
    for (const v of a) { if (v < lo) lo = v; if (v > hi) hi = v; }
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi - lo < 1) { lo -= 1; hi += 1; }
    return [lo, hi];
  }

  line(ctx, ys, range, x0, w, h, color) {
    const t1 = this.t[this.t.length - 1], t0 = t1 - this.span;
    ctx.strokeStyle = color; ctx.lineWidth = 1.5; ctx.beginPath();
    for (let i = 0; i < ys.length; i++) {
      const x = x0 + (this.t[i] - t0) / this.span * w;
      const y = 10 + (1 - (ys[i] - range[0]) / (range[1] - range[0])) * (h - 20);
      if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y);
    }
    ctx.stroke();
  }

  draw() {
    this.pending = false;
    const c = this.canvas, ctx = c.getContext("2d");
    const x0 = 70, w = c.width - 140, h = c.height - 20;
    ctx.clearRect(0, 0, c.width, c.height);
    ctx.strokeStyle = "#dde"; ctx.strokeRect(x0, 10, w, h - 20);
    if (this.t.length < 2) return;
    const pr = LivePlot.range(this.pos), sr = LivePlot.range(this.speed);
    ctx.font = "11px sans-serif";
    ctx.fillStyle = "#1565c0"; ctx.textAlign = "right";
    ctx.fillText(String(Math.round(pr[1])), x0 - 4, 16); ctx.fillText(String(Math.round(pr[0])), x0 - 4, h - 10);
    ctx.fillStyle = "#c62828"; ctx.textAlign = "left";
    ctx.fillText(String(Math.round(sr[1])), x0 + w + 4, 16); ctx.fillText(String(Math.round(sr[0])), x0 + w + 4, h - 10);
    ctx.fillStyle = "#555"; ctx.textAlign = "center";
    ctx.fillText("-5 s", x0, c.height - 4); ctx.fillText("now", x0 + w, c.height - 4);
    this.line(ctx, this.pos, pr, x0, w, h, "#1565c0");
    this.line(ctx, this.speed, sr, x0, w, h, "#c62828");
  }
}
window.LivePlot = LivePlot;
