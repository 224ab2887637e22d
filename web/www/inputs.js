// The inputs panel of each axis/channel, on real hardware and on the simulated machine alike:
// every input line the daemon's configuration wires or the module's configuration uses, with its
// electrical level, whether the module takes it as active (used, at its configured level: the
// polarity applied by the module, not by the page) and, on the simulated machine, whether it is
// forced (buttons 1 / 0 / free force it as `stepmodctl panel force` does: "force_input", under
// the lease). Below: the drive-enable output where one is wired, and the simulated drive's
// outputs. The levels come from the image's unit-state block (docs/interface.md 3.6, the batch's
// status[u].machine), the forcing from the simulator panel (the batch's "sim", null on hardware).
"use strict";

const INPUT_LABELS = { capture: "capture", external: "external", home: "home", estop: "E-stop",
                       cw_limit: "CW limit", ccw_limit: "CCW limit" };

function buildInputs(box, u, names, sim) {
  box.textContent = "";
  const h = document.createElement("h3");
  h.textContent = sim ? "Inputs (simulated machine: force them), drive enable, outputs"
                      : "Inputs (real hardware), drive enable";
  box.appendChild(h);
  for (const name of names) {
    const row = document.createElement("div"); row.className = "sim-in"; row.dataset.input = name;
    const label = document.createElement("span"); label.className = "sim-state"; row.appendChild(label);
    if (sim) {
      for (const [text, level] of [["1", 1], ["0", 0], ["free", null]]) {
        const b = document.createElement("button"); b.textContent = text; b.className = "f-" + (level === null ? "free" : level);
        b.addEventListener("click", () => command(u, "force_input", { input: name, level: level }));
        row.appendChild(b);
      }
    }
    box.appendChild(row);
  }
  for (const cls of ["in-enable", "sim-out"]) {
    const d = document.createElement("div"); d.className = cls; box.appendChild(d);
  }
  box.dataset.names = names.join(",") + (sim ? ":sim" : "");
}

// The text of one line: "home: level 1, active, forced 1" / "CW limit: level 0, inactive, free";
// a line wired but not used by the configuration: "not used by the configuration".
function inputText(line, forced, sim) {
  const name = INPUT_LABELS[line.name] || line.name;
  const wire = line.wired ? `level ${line.level ? 1 : 0}` : "not wired";
  const act = line.used ? (line.active ? "ACTIVE" : "inactive") : "not used (configuration)";
  const force = sim ? (line.name in forced ? `, forced ${forced[line.name]}` : ", free") : "";
  return `${name}: ${wire}, ${act}${force}`;
}

function setText(el, text) { if (el && el.textContent !== text) el.textContent = text; }

function showInputs(box, u, machine, sim) {
  if (!machine) { if (box.childElementCount) box.textContent = ""; return; }
  const simU = sim && sim[u] ? sim[u] : null;
  const lines = machine.inputs.filter((l) => l.wired || l.used || (simU && l.name in simU.forced));
  const key = lines.map((l) => l.name).join(",") + (simU ? ":sim" : "");
  if (box.dataset.names !== key) buildInputs(box, u, lines.map((l) => l.name), !!simU);
  const forced = simU ? simU.forced : {};
  for (const line of lines) {
    const row = box.querySelector(`.sim-in[data-input=${line.name}]`);
    setText(row.querySelector(".sim-state"), inputText(line, forced, !!simU));
    row.classList.toggle("forced", line.name in forced);
    row.classList.toggle("active", !!line.active);
  }
  const e = machine.enable;
  setText(box.querySelector(".in-enable"), e.wired
    ? `drive enable: ${e.asserted ? "ASSERTED (drive on)" : "released (drive off)"}`
    : "drive enable: no enable line wired (axis.enable)");
  const o = simU ? simU.outputs : null;
  setText(box.querySelector(".sim-out"), o ? `outputs: step/CW ${o.step}, dir/CCW ${o.dir}, GPO ${o.gpo}` : "");
}
