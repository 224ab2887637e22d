#!/usr/bin/env python3
"""The EDS files say what the adapter's code answers (issue 34).

packaging/eds/stepmod-<type>.eds, one per module type, is what Studio 5000 builds its module
definition and its Forward_Open from. A PLC keyed to a stale EDS is refused (0x0114/0x0116), one
sized from it gets 0x0127/0x0128. So each file is compared with the facts the code prints
(tests/enip/eds_facts.cpp: identity, instances, sizes, RPI range, connections):
  * [File], [Device], [Device Classification], [Params], [Assembly], [Connection Manager] and
    [Capacity] are there; the file is ASCII;
  * [Device]: vendor, device type, product code, revision and name as the Identity object's;
  * [Assembly]: the input, output, configuration and heartbeat instances with the code's sizes,
    their members INT (3601, 3602) or DINT (3202) words that fill them exactly;
  * [Connection Manager]: exclusive owner, input-only and listen-only, class 1 cyclic, T→O
    point-to-point only, the owner's O→T with the run/idle header, each path naming the code's
    instances; the RPI parameter's range the default [ethernetip] range;
  * [Capacity]: the connection table's slots.
Then the check is run on altered copies (another product code, a wrong size, a wrong instance
in a path) and must find each: a check that passes everything would pass a drifted file too.
Usage: eds_check.py SOURCE_DIR [EMULATOR...] EDS_FACTS_PROGRAM   (the emulator of a cross build)
"""
import json
import re
import subprocess
import sys
from pathlib import Path

SECTIONS = ("File", "Device", "Device Classification", "Params", "Assembly",
            "Connection Manager", "Capacity")
DATA_TYPE = {2: 0xC3, 4: 0xC4}  # CIP INT, DINT
RUN_IDLE_HEADER = 4             # the EDS real-time format of a 32-bit run/idle header
POINT_TO_POINT = 0x4            # connection type bits of one direction


def strip_comments(text):
    """The text without $ comments (a $ inside a string stays)."""
    out = []
    for line in text.splitlines():
        quoted, cut = False, len(line)
        for i, c in enumerate(line):
            if c == '"':
                quoted = not quoted
            elif c == "$" and not quoted:
                cut = i
                break
        out.append(line[:cut])
    return "\n".join(out)


def split_fields(value):
    """An entry's comma-separated fields, strings unquoted, blanks as ''."""
    fields, cur, quoted = [], "", False
    for c in value:
        if c == '"':
            quoted = not quoted
        elif c == "," and not quoted:
            fields.append(cur.strip())
            cur = ""
            continue
        cur += c
    fields.append(cur.strip())
    return [f[1:-1] if len(f) >= 2 and f[0] == f[-1] == '"' else f for f in fields]


def parse(text):
    """{section: {keyword: [fields]}}."""
    sections, current = {}, None
    body = strip_comments(text)
    for m in re.finditer(r'\[([^\]\n]+)\]|([A-Za-z_][\w]*)\s*=((?:[^;"]|"[^"]*")*);', body):
        if m.group(1):
            current = sections.setdefault(m.group(1).strip(), {})
        elif current is not None:
            current[m.group(2)] = split_fields(" ".join(m.group(3).split()))
    return sections


def num(field):
    return int(field, 0)


def path_bytes(field):
    return [int(b, 16) for b in field.split()]


def check_device(eds, mod, errors):
    dev = eds.get("Device", {})
    want = {"VendCode": mod["vendor"], "ProdType": mod["device_type"],
            "ProdCode": mod["product_code"], "MajRev": mod["major"], "MinRev": mod["minor"]}
    for key, value in want.items():
        got = dev.get(key, ["<none>"])[0]
        if not re.fullmatch(r"(0x)?[0-9A-Fa-f]+", got) or num(got) != value:
            errors.append(f"[Device] {key} = {got}, the code's is {value}")
    if dev.get("ProdName", [""])[0] != mod["name"]:
        errors.append(f"[Device] ProdName = {dev.get('ProdName')}, the code's is {mod['name']!r}")
    if eds.get("Device Classification", {}).get("Class1") != ["EtherNetIP"]:
        errors.append("[Device Classification] Class1 is not EtherNetIP")


def check_assembly(eds, instance, size, word_bytes, errors):
    entry = eds.get("Assembly", {}).get(f"Assem{instance}")
    if entry is None or len(entry) < 6:
        errors.append(f"[Assembly] Assem{instance} missing or short")
        return
    if path_bytes(entry[1]) != [0x20, 0x04, 0x24, instance, 0x30, 0x03]:
        errors.append(f"Assem{instance}: path {entry[1]} is not instance {instance}'s data")
    if num(entry[2]) != size:
        errors.append(f"Assem{instance}: size {entry[2]} bytes, the code's is {size}")
    members = entry[6:]
    bits = sum(num(members[i]) for i in range(0, len(members) - 1, 2))
    if bits != 8 * size:
        errors.append(f"Assem{instance}: members of {bits} bits fill {size} bytes")
    for i in range(1, len(members), 2):
        param = eds.get("Params", {}).get(members[i])
        if param is None or num(param[4]) != DATA_TYPE[word_bytes] or num(param[5]) != word_bytes:
            errors.append(f"Assem{instance}: member {members[i]} is not a {word_bytes}-byte word")


def check_rpi(eds, param_name, facts, errors):
    param = eds.get("Params", {}).get(param_name)
    if param is None or len(param) < 12:
        errors.append(f"RPI parameter {param_name} missing")
        return
    if (num(param[9]), num(param[10])) != (facts["rpi_min_us"], facts["rpi_max_us"]):
        errors.append(f"{param_name}: RPI {param[9]}..{param[10]} us, the code's "
                      f"{facts['rpi_min_us']}..{facts['rpi_max_us']}")


def check_connection(eds, name, entry, facts, errors):
    """One ConnectionN entry: 0 trigger and transport, 1 connection parameters, 2-4 O->T RPI,
    size, format, 5-7 T->O RPI, size, format, 8-11 configuration, 12 name, 13 help, 14 path.
    Returns its kind (None when it is none the adapter serves)."""
    inst = facts["instances"]
    trigger, params = num(entry[0]), num(entry[1])
    kinds = {1 << 26: ("owner", inst["output"]), 1 << 25: ("input_only", inst["input_only"]),
             1 << 24: ("listen_only", inst["listen_only"])}
    kind, ot_point = kinds.get(trigger & 0x0F000000, (None, None))
    if kind is None or trigger & 0xFFFF != 0x0002 or not trigger & (1 << 16) or trigger >> 31:
        errors.append(f"{name}: {entry[0]} is not one class 1 cyclic client connection")
        return None
    if (params >> 20) & 0xF != POINT_TO_POINT:
        errors.append(f"{name}: T->O must be point-to-point only (the adapter refuses multicast)")
    want_path = [0x20, 0x04, 0x24, inst["config"], 0x2C, ot_point, 0x2C, inst["input"]]
    if path_bytes(entry[14]) != want_path:
        errors.append(f"{name}: path {entry[14]}, the code's is "
                      + " ".join(f"{b:02X}" for b in want_path))
    if entry[6] or entry[7] != f"Assem{inst['input']}":
        errors.append(f"{name}: T->O is not Assem{inst['input']}")
    if kind == "owner":
        if (params >> 8) & 0x7 != RUN_IDLE_HEADER:
            errors.append(f"{name}: O->T without the 32-bit run/idle header")
        if entry[3] or entry[4] != f"Assem{inst['output']}":
            errors.append(f"{name}: O->T is not Assem{inst['output']}")
    elif entry[3] != "0" or entry[4]:
        errors.append(f"{name}: a heartbeat's O->T size must be 0, with no assembly")
    if any(entry[8:12]):
        errors.append(f"{name}: configuration data, but instance {inst['config']} has size 0")
    check_rpi(eds, entry[2], facts, errors)
    check_rpi(eds, entry[5], facts, errors)
    return kind


def check_connections(eds, facts, errors):
    cm = eds.get("Connection Manager", {})
    kinds = []
    for name, entry in cm.items():
        if not re.fullmatch(r"Connection\d+", name):
            continue
        if len(entry) != 15:
            errors.append(f"{name}: {len(entry)} fields, not 15")
            continue
        kinds.append(check_connection(eds, name, entry, facts, errors))
    if sorted(k for k in kinds if k) != ["input_only", "listen_only", "owner"]:
        errors.append(f"[Connection Manager]: connections {kinds}, want one owner, one "
                      "input-only, one listen-only")


def check(text, facts, mod):
    """The differences between one EDS and the code's facts for module `mod`."""
    errors = []
    if not text.isascii():
        errors.append("not ASCII")
    eds = parse(text)
    errors += [f"no [{s}] section" for s in SECTIONS if s not in eds]
    for key in ("DescText", "CreateDate", "CreateTime", "ModDate", "ModTime", "Revision"):
        if key not in eds.get("File", {}):
            errors.append(f"[File] has no {key}")
    check_device(eds, mod, errors)
    inst, wb = facts["instances"], mod["word_bytes"]
    check_assembly(eds, inst["input"], mod["input_bytes"], wb, errors)
    check_assembly(eds, inst["output"], mod["output_bytes"], wb, errors)
    for zero in ("config", "input_only", "listen_only"):
        check_assembly(eds, inst[zero], 0, wb, errors)
    check_connections(eds, facts, errors)
    cap = eds.get("Capacity", {})
    if cap.get("MaxIOProduceConsume", ["0"])[0] != str(facts["max_io_connections"]):
        errors.append(f"[Capacity] MaxIOProduceConsume is not {facts['max_io_connections']}")
    tspec = cap.get("TSpec1", [])
    if tspec[:2] != ["TxRx", str(max(mod["input_bytes"], mod["output_bytes"]))]:
        errors.append(f"[Capacity] TSpec1 {tspec} is not TxRx of the assembly size")
    return errors


def drifted_copies(text, mod):
    """Altered copies that the check must refuse: (what was altered, text)."""
    code = mod["product_code"]
    return [
        ("product code", text.replace(f"ProdCode = {code};", f"ProdCode = {code + 1};")),
        ("input size", re.sub(r'(Assem100 =\s*"[^"]*",\s*"[^"]*",\s*)(\d+)',
                              lambda m: m.group(1) + str(int(m.group(2)) + 2), text)),
        ("owner path", text.replace("2C 96 2C 64", "2C 97 2C 64")),
        ("revision", text.replace("MajRev = 1;", "MajRev = 2;")),
    ]


def main():
    if len(sys.argv) < 3:
        print("usage: eds_check.py SOURCE_DIR [EMULATOR...] EDS_FACTS_PROGRAM", file=sys.stderr)
        return 2
    facts = json.loads(subprocess.run(sys.argv[2:], capture_output=True, text=True,
                                      check=True).stdout)
    eds_dir = Path(sys.argv[1]) / "packaging" / "eds"
    failures = []
    want = {f"stepmod-{m['type']}.eds" for m in facts["modules"]}
    have = {p.name for p in eds_dir.glob("*.eds")}
    failures += [f"{eds_dir}/{n}: missing" for n in sorted(want - have)]
    failures += [f"{eds_dir}/{n}: no such module type in the code" for n in sorted(have - want)]
    for mod in facts["modules"]:
        path = eds_dir / f"stepmod-{mod['type']}.eds"
        if not path.exists():
            continue
        text = path.read_text(encoding="latin-1")
        errors = check(text, facts, mod)
        failures += [f"{path.name}: {e}" for e in errors]
        for what, copy in [] if errors else drifted_copies(text, mod):
            if copy == text or not check(copy, facts, mod):
                failures.append(f"{path.name}: the check does not notice a changed {what}")
    for f in failures:
        print(f"eds_check: {f}", file=sys.stderr)
    if failures:
        return 1
    print(f"eds_check: {len(facts['modules'])} EDS files match the adapter's identity, "
          "instances, sizes and RPI range")
    return 0


if __name__ == "__main__":
    sys.exit(main())
