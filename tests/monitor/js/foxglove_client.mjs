// Connects to `wysiwyf bridge` with the official Foxglove WebSocket client (@foxglove/ws-protocol
// on the `ws` package), lists the advertised channels, subscribes to the given topics and decodes
// their first messages with Foxglove's OMG IDL decoder from the advertised schema. Prints JSON:
//   {server, channels: {topic: {schemaName, encoding, schemaEncoding}}, messages: {topic: [decoded...]}}
//   node foxglove_client.mjs ws://127.0.0.1:PORT SECONDS TOPIC...
import wsProtocol from "@foxglove/ws-protocol"; // (CommonJS)
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;

const [url, seconds, ...topics] = process.argv.slice(2);
const perTopic = Number(process.env.FOXGLOVE_CLIENT_MESSAGES ?? 3); // messages to decode per topic
const result = { server: null, channels: {}, messages: {}, statuses: [] };
const summarise = (k, x) =>
  typeof x === "bigint" ? Number(x) : ArrayBuffer.isView(x) ? { bytes: x.length, sum: x.reduce((a, b) => a + b, 0) } : x;

const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
const readers = new Map(); // subscription id -> {topic, reader}
let subscribed = false;

function finish(code) {
  process.stdout.write(JSON.stringify(result, summarise) + "\n");
  client.close();
  process.exit(code);
}
setTimeout(() => finish(1), Number(seconds) * 1000);

client.on("error", (e) => {
  result.statuses.push(`error: ${e}`);
});
client.on("serverInfo", (info) => {
  result.server = info;
});
client.on("status", (s) => result.statuses.push(s.message));
client.on("advertise", (channels) => {
  for (const ch of channels) {
    result.channels[ch.topic] = { id: ch.id, schemaName: ch.schemaName, encoding: ch.encoding, schemaEncoding: ch.schemaEncoding };
    if (!topics.includes(ch.topic)) continue;
    const reader = new MessageReader(ch.schemaName, parseIDL(ch.schema));
    const id = client.subscribe(ch.id);
    readers.set(id, { topic: ch.topic, reader });
    result.messages[ch.topic] = [];
  }
});
client.on("message", ({ subscriptionId, data }) => {
  const r = readers.get(subscriptionId);
  if (!r) return;
  const list = result.messages[r.topic];
  if (list.length < perTopic) list.push(r.reader.readMessage(new Uint8Array(data.buffer, data.byteOffset, data.byteLength)));
  if (topics.every((t) => (result.messages[t] ?? []).length >= perTopic)) finish(0);
});
