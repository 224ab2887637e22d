// The EtherNet/IP clients the suite tests the adapter against, driven by the C++ tests
// (tests/enip/integration): pinned npm packages we did not write, installed into the build tree
// by `scripts/install-deps --enip-partners BUILD_DIR` (NODE_PATH points there). One JSON object
// per line on stdout.
//
//   node partner.js scanner '{"target":..,"local":..,"rpi":10,"in":16,"out":16,"multiplier":32}'
//       st-ethernet-ip's class 1 scanner, exclusive owner of assemblies 150/100/151, its
//       connection timing out after `multiplier` RPIs (32 when absent); then on
//       stdin: "set HEX" (the O→T words), "get" (the T→O words and sequence), "silent" (stop
//       sending O→T), "quit"
//   node partner.js open-once '{...same...}'   one Forward_Open; its status, then exit
//   node partner.js identity TARGET             ethernet-ip: Get_Attributes_All and
//                                               Get_Attribute_Single of the Identity object
//   node partner.js interface TARGET              ethernet-ip: Get_Attributes_All and
//                                               Get_Attribute_Single of the TCP/IP Interface
//                                               and Ethernet Link objects, and each class's
//                                               revision
//   node partner.js list-identity TARGET LOCAL udp|tcp   ListIdentity, parsed by
//                                               st-ethernet-ip's Browser
//   node partner.js browse LOCAL                 st-ethernet-ip's Browser as it finds devices:
//                                               ListIdentity broadcast to 255.255.255.255 from
//                                               LOCAL every 500 ms; each device found, a line
"use strict";
const net = require("net");
const readline = require("readline");

const say = (o) => process.stdout.write(JSON.stringify(o) + "\n");
const fail = (e) => {
  say({ error: String(e && e.message ? e.message : JSON.stringify(e)), detail: e });
  process.exit(3);
};

function assemblies(c) {
  return {
    configInstance: { assembly: 151, size: 0 },
    outputInstance: { assembly: 150, size: c.out },
    inputInstance: { assembly: 100, size: c.in },
  };
}

// The connection's timeout, c.multiplier RPIs (st-ethernet-ip asks for 32, and only 4, 8, ...
// 512 are codes a Forward_Open can carry): its Forward_Open is built with that multiplier.
function askForTimeout(multiplier) {
  const manager = require("st-ethernet-ip/dist/enip/cip/connection-manager");
  const build = manager.build_forwardOpen;
  manager.build_forwardOpen = (rpi, params, timeoutMs, _multiplier, ...rest) =>
    build(rpi, params, timeoutMs, multiplier, ...rest);
}

// st-ethernet-ip checks its T→O once a second and drops the connection when the last packet is
// older than 4 RPIs (40 ms at RPI 10): it stops sending O→T, the adapter's timeout stops the
// axes (the PLC left Run), and it connects again. A pause of this shared test machine was enough
// (a CI run stopped a move at step 5,654 so). The check here allows what its Forward_Open asks
// of the adapter, the connection's timeout: the tests are about the adapter's behaviour.
function allowTheConnectionsTimeout(conn, multiplier) {
  const check = conn._checkStatus;
  conn._checkStatus = (that) => {
    const age = Date.now() - that.lastDataTime;
    if (that.connected && age <= that.tcpController.rpi * multiplier) return;
    check.call(that, that);
  };
}

function scanner(c) {
  const { IO } = require("st-ethernet-ip");
  const multiplier = c.multiplier || 32;
  askForTimeout(multiplier);
  const io = new IO.Scanner(2222, c.local);
  const conn = io.addConnection(assemblies(c), c.rpi, c.target);
  allowTheConnectionsTimeout(conn, multiplier);
  conn.on("connected", () => say({ connected: true, ot: conn.OTid, to: conn.TOid }));
  conn.on("disconnected", () => say({ disconnected: true, last_to_ms_ago: Date.now() - conn.lastDataTime }));
  const rl = readline.createInterface({ input: process.stdin });
  rl.on("line", (line) => {
    const [cmd, arg] = line.trim().split(/\s+/);
    if (cmd === "set") {
      conn.outputData = Buffer.from(arg, "hex");
      say({ ok: true });
    } else if (cmd === "get") {
      say({ in: conn.inputData.toString("hex"), seq: conn.TOsequenceNum, run: conn.run });
    } else if (cmd === "silent") {
      conn.run = false;
      say({ ok: true });
    } else if (cmd === "quit") {
      process.exit(0);
    }
  });
  rl.on("close", () => process.exit(0));
}

async function openOnce(c) {
  const TCP = require("st-ethernet-ip/dist/io/tcp");
  const a = assemblies(c);
  const t = new TCP(true, a.configInstance, a.outputInstance, a.inputInstance);
  t.rpi = c.rpi;
  t.timeout_sp = 2000;
  try {
    const id = await t.connect(c.target, 0, c.local);
    say({ opened: true, ot: id });
  } catch (e) {
    say({ opened: false, general: e.generalStatusCode, extended: e.extendedStatus });
  }
  process.exit(0);
}

async function identity(target) {
  const { Controller, EthernetIP } = require("ethernet-ip");
  const { CIP } = EthernetIP;
  const plc = new Controller();
  let all = null;
  plc.on("Get Attribute All", (err, data) => { all = err ? null : data; });
  await plc.connect(target, 0);
  const { LOGICAL } = CIP.EPATH.segments;
  const single = async (attribute) => {
    const path = Buffer.concat([
      LOGICAL.build(LOGICAL.types.ClassID, 0x01),
      LOGICAL.build(LOGICAL.types.InstanceID, 0x01),
      LOGICAL.build(LOGICAL.types.AttributeID, attribute),
    ]);
    const got = new Promise((resolve, reject) => {
      plc.once("Get Attribute Single", (err, data) => (err ? reject(err) : resolve(data)));
    });
    plc.write_cip(CIP.MessageRouter.build(CIP.MessageRouter.services.GET_ATTRIBUTE_SINGLE, path, []));
    return (await got).toString("hex");
  };
  const singles = {};
  for (const a of [1, 2, 3, 4, 5, 6, 7]) singles[a] = await single(a);
  say({ all: all ? all.toString("hex") : null, properties: plc.properties, singles });
  plc.destroy();
  process.exit(0);
}

// The TCP/IP Interface (0xF5) and Ethernet Link (0xF6) objects as ethernet-ip's ENIP client
// reads them: Get_Attributes_All and Get_Attribute_Single of each attribute, as hex (or the
// general status of a refusal).
async function interfaceObjects(target) {
  const { Controller, EthernetIP } = require("ethernet-ip");
  const { CIP } = EthernetIP;
  const { LOGICAL } = CIP.EPATH.segments;
  const { GET_ATTRIBUTE_ALL, GET_ATTRIBUTE_SINGLE } = CIP.MessageRouter.services;
  const plc = new Controller();
  await plc.connect(target, 0);
  const ask = (service, event, classId, attribute, instance = 1) => {
    const segments = [
      LOGICAL.build(LOGICAL.types.ClassID, classId),
      // ethernet-ip builds no segment for 0 (the class itself): 8-bit instance segment by hand
      instance === 0 ? Buffer.from([0x24, 0x00]) : LOGICAL.build(LOGICAL.types.InstanceID, instance),
    ];
    if (attribute) segments.push(LOGICAL.build(LOGICAL.types.AttributeID, attribute));
    const got = new Promise((resolve) => {
      plc.once(event, (err, data) =>
        resolve(err ? "status " + err.generalStatusCode : data.toString("hex")));
    });
    plc.write_cip(CIP.MessageRouter.build(service, Buffer.concat(segments), []));
    return got;
  };
  const out = {};
  for (const [name, classId, last] of [["tcpip", 0xf5, 14], ["link", 0xf6, 12]]) {
    const singles = {};
    for (let a = 1; a <= last; ++a) {
      singles[a] = await ask(GET_ATTRIBUTE_SINGLE, "Get Attribute Single", classId, a);
    }
    const revision = await ask(GET_ATTRIBUTE_SINGLE, "Get Attribute Single", classId, 1, 0);
    out[name] = { all: await ask(GET_ATTRIBUTE_ALL, "Get Attribute All", classId), singles, revision };
  }
  say(out);
  plc.destroy();
  process.exit(0);
}

function listIdentity(target, local, how) {
  const { Browser, EthernetIP } = require("st-ethernet-ip");
  const { encapsulation } = EthernetIP;
  const request = encapsulation.header.build(encapsulation.commands.ListIdentity);
  const b = new Browser(0, local, false);
  const parse = (msg) => {
    const d = b._parseListIdentityResponse(msg);
    say({ device: d, via: how });
    process.exit(0);
  };
  if (how === "udp") {
    b.socket.on("message", parse);
    b.socket.on("listening", () => b.socket.send(request, 44818, target));
  } else {
    const s = net.connect({ host: target, port: 44818, localAddress: local }, () => s.write(request));
    s.on("data", parse);
    s.on("error", fail);
  }
}

function browse(local) {
  const { Browser } = require("st-ethernet-ip");
  const b = new Browser(0, local, true, 500);
  b.on("New Device", (d) => say({ device: d }));
}

process.on("unhandledRejection", fail);
const [mode, a1, a2, a3] = process.argv.slice(2);
if (mode === "scanner") scanner(JSON.parse(a1));
else if (mode === "open-once") openOnce(JSON.parse(a1));
else if (mode === "identity") identity(a1);
else if (mode === "interface") interfaceObjects(a1);
else if (mode === "list-identity") listIdentity(a1, a2, a3);
else if (mode === "browse") browse(a1);
else fail(new Error("unknown mode " + mode));
setTimeout(() => fail(new Error("partner.js: no result in 60 s")), 60000).unref();
