// A hostile or careless client of `wysiwyf bridge` (the `ws` package, no Foxglove library): sends
// each malformed frame on each subprotocol and records what the bridge answered. Every frame must
// get an error reply naming what was wrong (a Foxglove status of level 2, or the dashboard's
// {"op":"error"}); a frame over the size bound closes that client with 1009 (message too big);
// a flood is refused with one reply. Prints JSON: [{protocol, frame, reply | close}], exits 1 if
// any case went otherwise.
//   node hostile_client.mjs ws://127.0.0.1:PORT
import WebSocket from "ws";

const [url] = process.argv.slice(2);
const FOXGLOVE = "foxglove.websocket.v1";
const DASHBOARD = "wysiwyf.dashboard.v1";

// The frames that crashed the bridge, on either subprotocol.
const both = [
  '{"op":1}',
  '{"op":null}',
  '{"op":["subscribe"]}',
  '{"op":"subscribe","subscriptions":"x"}',
  '{"op":"subscribe","subscriptions":[1]}',
  '{"op":"subscribe","subscriptions":[{"id":"a","channelId":1}]}',
  '{"op":"unsubscribe","subscriptionIds":[12345,"a",null]}',
  "not json",
  "[]",
  // nested 30,000 deep: under the size bound, over the depth bound
  '{"op":"subscribe","subscriptions":' + "[".repeat(30000) + "]".repeat(30000) + "}",
];
const dashboardOnly = ['{"op":"plot","topic":1,"field":2}', '{"op":"plot","topic":"","field":"x"}'];
const foxgloveOnly = ['{"op":"subscribe","subscriptions":[{"id":1,"channelId":4000000}]}'];

function isReply(protocol, m) {
  return protocol === FOXGLOVE ? m.op === "status" && m.level === 2 : m.op === "error";
}

// Opens a client, sends `send(ws)` once it is open, and resolves with the first error reply, or
// the close, or a timeout.
function exchange(protocol, send, seconds = 5) {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, [protocol]);
    const done = (r) => {
      clearTimeout(timer);
      ws.removeAllListeners();
      ws.on("error", () => {});
      ws.terminate();
      resolve(r);
    };
    const timer = setTimeout(() => done({ timeout: true }), seconds * 1000);
    ws.on("open", () => send(ws));
    ws.on("message", (data, binary) => {
      if (binary) return;
      const m = JSON.parse(data.toString());
      if (isReply(protocol, m)) done({ reply: m.message });
    });
    ws.on("close", (code) => done({ close: code }));
    ws.on("error", (e) => done({ error: String(e) }));
  });
}

const results = [];
let failed = 0;
const record = (protocol, frame, r, ok) => {
  results.push({ protocol, frame: frame.length > 80 ? frame.slice(0, 60) + `... (${frame.length} bytes)` : frame, ...r, ok });
  if (!ok) failed++;
};

for (const protocol of [FOXGLOVE, DASHBOARD]) {
  const frames = [...both, ...(protocol === FOXGLOVE ? foxgloveOnly : dashboardOnly)];
  for (const frame of frames) {
    const r = await exchange(protocol, (ws) => ws.send(frame));
    record(protocol, frame, r, typeof r.reply === "string" && r.reply.length > 0);
  }
  // 200,000 deep (400 kB): over the size bound, the client is closed as the protocol says.
  const huge = '{"op":"subscribe","subscriptions":' + "[".repeat(200000) + "]".repeat(200000) + "}";
  const big = await exchange(protocol, (ws) => ws.send(huge));
  record(protocol, huge, big, big.close === 1009);
  // A binary frame: neither protocol takes one from this client.
  const bin = await exchange(protocol, (ws) => ws.send(Buffer.from([1, 2, 3, 4])));
  record(protocol, "<binary 4 bytes>", bin, typeof bin.reply === "string" && /binary|text requests only/.test(bin.reply));
  // A flood of valid, silent requests: refused beyond the budget, and said.
  const flood = await exchange(protocol, (ws) => {
    for (let i = 0; i < 2000; i++) ws.send(protocol === FOXGLOVE ? '{"op":"unsubscribe","subscriptionIds":[]}' : '{"op":"unplot","topic":"a","field":"b"}');
  });
  record(protocol, "<2000 requests at once>", flood, typeof flood.reply === "string" && /requests a second/.test(flood.reply));
}

process.stdout.write(JSON.stringify(results, null, 1) + "\n");
process.exit(failed ? 1 : 0);
