// The simulated machine's inputs and outputs, per axis/channel, where the daemon runs the sim
// backend (the batch's "sim"; null on real hardware: the box stays empty): each input forced to
// 1 or 0, or free (the simulation drives it); buttons force it as `stepmodctl panel force`
// does ("force_input", under the lease). The outputs as the simulated drive sees them.
"use strict";

const SIM_INPUTS = ["capture", "external", "home", "estop", "cw_limit", "ccw_limit"];

function buildSim(box, u) {
  box.textContent = "";
  const h = document.createElement("h3"); h.textContent = "Simulated machine: inputs (force), outputs"; box.appendChild(h);
  for (const name of SIM_INPUTS) {
    const row = document.createElement("div"); row.className = "sim-in"; row.dataset.input = name;
    const label = document.createElement("span"); label.className = "sim-state"; row.appendChild(label);
    for (const [text, level] of [["1", 1], ["0", 0], ["free", null]]) {
      const b = document.createElement("button"); b.textContent = text; b.className = "f-" + (level === null ? "free" : level);
      b.addEventListener("click", () => command(u, "force_input", { input: name, level: level }));
      row.appendChild(b);
    }
    box.appendChild(row);
  }
  const out = document.createElement("div"); out.className = "sim-out"; box.appendChild(out);
}

function showSim(box, u, sim) {
  if (!sim || !sim[u]) { if (box.childElementCount) box.textContent = ""; return; }
  if (!box.childElementCount) buildSim(box, u);
  const forced = sim[u].forced;
  for (const row of box.querySelectorAll(".sim-in")) {
    const n = row.dataset.input;
    const text = `${n}: ${n in forced ? "forced " + forced[n] : "free"}`;
    const label = row.querySelector(".sim-state");
    if (label.textContent !== text) { label.textContent = text; row.classList.toggle("forced", n in forced); }
  }
  const o = sim[u].outputs;
  const text = `outputs: step/CW ${o.step}, dir/CCW ${o.dir}, GPO ${o.gpo}`;
  const out = box.querySelector(".sim-out");
  if (out.textContent !== text) out.textContent = text;
}
