// The official Foxglove client (@foxglove/ws-protocol) on `wysiwyf bridge`'s connectionGraph and
// time capabilities: subscribes to the connection graph (the whole of it first, then changes,
// merged here as a client does) and to one topic, and collects the Time messages. Prints JSON:
//   {capabilities, published: {topic: [ids]}, subscribed: {topic: [ids]}, times: [ns...],
//    messages: [receive ns...]}
//   node graph_and_time.mjs ws://127.0.0.1:PORT SECONDS TOPIC
import wsProtocol from "@foxglove/ws-protocol"; // (CommonJS)
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;
const [url, seconds, topic] = process.argv.slice(2);
const result = { capabilities: [], published: {}, subscribed: {}, times: [], messages: [] };
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });

function finish(code) {
  process.stdout.write(JSON.stringify(result) + "\n");
  client.close();
  process.exit(code);
}
setTimeout(() => finish(1), Number(seconds) * 1000);
const done = () =>
  result.times.length >= 5 && result.messages.length >= 5 && (result.published[topic] ?? []).length > 0;

client.on("serverInfo", (info) => {
  result.capabilities = info.capabilities;
  if (info.capabilities.includes("connectionGraph")) client.subscribeConnectionGraph();
});
client.on("advertise", (channels) => {
  for (const ch of channels) if (ch.topic === topic) client.subscribe(ch.id);
});
client.on("connectionGraphUpdate", (u) => {
  for (const t of u.publishedTopics) result.published[t.name] = t.publisherIds;
  for (const t of u.subscribedTopics) result.subscribed[t.name] = t.subscriberIds;
  for (const name of u.removedTopics) delete result.published[name], delete result.subscribed[name];
});
client.on("time", ({ timestamp }) => {
  result.times.push(Number(timestamp));
  if (done()) finish(0);
});
client.on("message", ({ timestamp }) => {
  result.messages.push(Number(timestamp));
  if (done()) finish(0);
});
