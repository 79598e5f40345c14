// Reads a `wysiwyf record` file with the official MCAP reader (@mcap/core) and decodes its
// messages with Foxglove's OMG IDL decoder from the schemas in the file. Chunks compressed with
// zstd or lz4 are decompressed by Foxglove's WebAssembly builds of the reference libraries (the
// handlers @mcap/support gives @mcap/core). Prints JSON.
//   node read_mcap.mjs summary FILE      indexed read (summary, chunk indexes, CRCs): per topic
//                                        the schema, the count, and every message decoded; the
//                                        chunks per compression ("" for none)
//   node read_mcap.mjs stream FILE       front-to-back read of a file that may be cut short;
//                                        the chunks per compression; the foxglove::CompressedImage
//                                        and CompressedVideo messages per format, and those whose
//                                        data is not what the format says (its magic number)
//   node read_mcap.mjs compare A B TOPIC the TOPIC messages of A and B with equal stamps: equal bytes?
//   node read_mcap.mjs psnr A B TOPIC    the TOPIC Image messages of A and B with equal stamps:
//                                        the lowest PSNR of B's pixels against A's (dB)
import { readFileSync } from "node:fs";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";
import decompressLz4 from "@foxglove/wasm-lz4";
import * as zstd from "@foxglove/wasm-zstd";

await Promise.all([zstd.isLoaded, decompressLz4.isLoaded]);
const decompressHandlers = {
  zstd: (buffer, size) => zstd.decompress(buffer, Number(size)),
  lz4: (buffer, size) => decompressLz4(buffer, Number(size)),
};
const countBy = (values) => values.reduce((n, v) => ({ ...n, [v]: (n[v] ?? 0) + 1 }), {});

const json = (v) =>
  JSON.stringify(v, (k, x) => (typeof x === "bigint" ? Number(x) : ArrayBuffer.isView(x) ? `<${x.length} bytes>` : x));

async function indexed(file) {
  const bytes = readFileSync(file);
  const readable = {
    size: async () => BigInt(bytes.byteLength),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  return McapIndexedReader.Initialize({ readable, decompressHandlers });
}

function decoderFor(schema) {
  return new MessageReader(schema.name, parseIDL(new TextDecoder().decode(schema.data)));
}

async function summary(file) {
  const reader = await indexed(file);
  const topics = {};
  const decoders = new Map();
  for (const [id, ch] of reader.channelsById) {
    const schema = reader.schemasById.get(ch.schemaId);
    topics[ch.topic] = { schema: schema?.name ?? null, encoding: schema?.encoding ?? null, metadata: Object.fromEntries(ch.metadata), count: 0, messages: [] };
    if (schema) decoders.set(id, decoderFor(schema));
  }
  for await (const m of reader.readMessages()) {
    const t = topics[reader.channelsById.get(m.channelId).topic];
    t.count++;
    if (decoders.has(m.channelId)) t.messages.push(decoders.get(m.channelId).readMessage(m.data));
  }
  return {
    messages: Number(reader.statistics.messageCount),
    chunks: reader.chunkIndexes.length,
    compression: countBy(reader.chunkIndexes.map((c) => c.compression)),
    topics,
  };
}

// Whether `data` starts as a file of `format` does (what a browser's decoder looks for).
function hasMagic(format, data) {
  const text = (from, to) => new TextDecoder().decode(data.subarray(from, to));
  if (format === "webp") return text(0, 4) === "RIFF" && text(8, 12) === "WEBP";
  if (format === "png") return data[0] === 0x89 && text(1, 4) === "PNG";
  if (format === "jpeg") return data[0] === 0xff && data[1] === 0xd8;
  if (format === "h264") return data[0] === 0 && data[1] === 0 && (data[2] === 1 || (data[2] === 0 && data[3] === 1));
  return false;
}

function stream(file) {
  const reader = new McapStreamReader({ validateCrcs: true, includeChunks: true, decompressHandlers });
  reader.append(readFileSync(file));
  const schemas = new Map(), channels = new Map(), decoders = new Map();
  const compressions = [];
  let messages = 0, decoded = 0, misformatted = 0;
  const images = [];
  for (let r; (r = reader.nextRecord()) !== undefined; ) {
    if (r.type === "Chunk") compressions.push(r.compression);
    else if (r.type === "Schema") schemas.set(r.id, r);
    else if (r.type === "Channel") channels.set(r.id, r);
    else if (r.type === "Message") {
      messages++;
      const schema = schemas.get(channels.get(r.channelId).schemaId);
      if (schema && !decoders.has(schema.id)) decoders.set(schema.id, decoderFor(schema));
      if (!schema) continue;
      const message = decoders.get(schema.id).readMessage(r.data);
      decoded++;
      if (schema.name === "foxglove::CompressedImage" || schema.name === "foxglove::CompressedVideo") {
        images.push(message.format);
        if (!hasMagic(message.format, message.data)) misformatted++;
      }
    }
  }
  return { messages, decoded, chunks: compressions.length, compression: countBy(compressions), done: reader.done(),
           images: countBy(images), misformatted_images: misformatted };
}

async function compare(a, b, topic) {
  const byStamp = async (file) => {
    const reader = await indexed(file);
    const ids = [...reader.channelsById].filter(([, ch]) => ch.topic === topic).map(([id]) => id);
    const out = new Map();
    for await (const m of reader.readMessages({ topics: [topic] })) if (ids.includes(m.channelId)) out.set(m.publishTime, Buffer.from(m.data));
    return out;
  };
  const [ma, mb] = [await byStamp(a), await byStamp(b)];
  let common = 0, differ = 0, first = null;
  for (const [stamp, bytes] of ma) {
    if (!mb.has(stamp)) continue;
    common++;
    if (!bytes.equals(mb.get(stamp))) { differ++; first ??= Number(stamp); }
  }
  return { a: ma.size, b: mb.size, common, differ, first_difference_ns: first };
}

async function psnr(a, b, topic) {
  const byStamp = async (file) => {
    const reader = await indexed(file);
    const out = new Map();
    for (const [id, ch] of reader.channelsById) {
      if (ch.topic !== topic) continue;
      const decoder = decoderFor(reader.schemasById.get(ch.schemaId));
      for await (const m of reader.readMessages({ topics: [topic] }))
        if (m.channelId === id) out.set(m.publishTime, decoder.readMessage(m.data));
    }
    return out;
  };
  const [ma, mb] = [await byStamp(a), await byStamp(b)];
  let common = 0, lowest = Infinity, same_header = 0;
  for (const [stamp, image] of ma) {
    const other = mb.get(stamp);
    if (!other) continue;
    common++;
    if (other.header.seq === image.header.seq && other.header.frame_id === image.header.frame_id &&
        other.width === image.width && other.height === image.height && other.encoding === image.encoding) same_header++;
    let se = 0;
    for (let i = 0; i < image.data.length; i++) se += (image.data[i] - other.data[i]) ** 2;
    const mse = se / image.data.length;
    lowest = Math.min(lowest, mse === 0 ? 99 : 10 * Math.log10((255 * 255) / mse));
  }
  return { a: ma.size, b: mb.size, common, same_header, lowest_psnr_db: common ? lowest : null };
}

const [mode, ...args] = process.argv.slice(2);
if (mode === "summary") console.log(json(await summary(args[0])));
else if (mode === "stream") console.log(json(stream(args[0])));
else if (mode === "compare") console.log(json(await compare(args[0], args[1], args[2])));
else if (mode === "psnr") console.log(json(await psnr(args[0], args[1], args[2])));
else { console.error("usage: read_mcap.mjs summary|stream FILE | compare|psnr A B TOPIC"); process.exit(2); }
