// An axis' last error reason as the page shows it: the image's sentence (56 bytes: "…" where the
// daemon's log has more), the item's condition in full and what to do (the hello's reason table,
// from the item tables the daemon raises them from) and a link to the item on /reasons. It is
// shown red only while the error bit of its list is set: once Reset Errors (or a home, for
// Position Invalid) cleared it, it is the last reason, greyed.
"use strict";

// In the order of the item codes' list digits (docs/error-reasons.md).
const ERROR_BITS = ["Configuration Error", "Command Error", "Invalid Profile", "Input Error",
                    "Home Invalid", "Position Invalid"];

// The table's row for an item code; an item the table does not list (a configuration check)
// answers with its list's row.
function reasonRow(table, code) {
  if (!table || !code) return null;
  return table[String(code)] || table[String(code - (code % 100))] || null;
}

// Whether the error bit of the reason's list (the item code's list digit) is still set.
function reasonActive(words, r) {
  if (!r || !r.item) return false;
  const name = ERROR_BITS[Math.floor(r.item / 100) % 100 - 1];
  for (const w of words) {
    for (const b of w.bits) if (b.value && b.name === name) return true;
  }
  return false;
}

// One line of text for the message area: the sentence and what to do.
function reasonLine(table, r) {
  const row = reasonRow(table, r.item);
  return r.text + (r.cut ? "…" : "") + (row ? ` — ${row.fix}` : "");
}

// Fills the unit's reason cell (only when something changed: 25 batches a second).
function showReason(cell, table, r, active) {
  const key = r && r.seq ? `${r.seq}/${active}` : "none";
  if (cell.dataset.key === key) return;
  cell.dataset.key = key;
  cell.textContent = "";
  cell.classList.toggle("active", !!(r && r.seq && active));
  if (!r || !r.seq) { cell.textContent = "none"; return; }
  const row = reasonRow(table, r.item);
  const add = (cls, text) => {
    const d = document.createElement("div"); d.className = cls; d.textContent = text;
    cell.appendChild(d); return d;
  };
  add("r-text", (active ? "" : "(cleared) ") + r.text + (r.cut ? "…" : ""));
  if (!row) return;
  // The item's condition in full, unless the image's sentence already says exactly that.
  const condition = row.id + ": " + row.condition;
  if (!r.text.startsWith(condition)) add("r-cond", condition);
  add("r-fix", "What to do: " + row.fix);
  const a = document.createElement("a");
  a.href = "/reasons#" + encodeURIComponent(row.id); a.target = "_blank"; a.className = "r-link";
  a.textContent = "about " + row.id + " (docs/error-reasons.md)";
  cell.appendChild(a);
}
