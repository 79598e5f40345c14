// The dashboard's client: one WebSocket to the bridge (subprotocol wysiwyf.dashboard.v1), whose
// JSON ops (bridge/dashboard_feed.hpp) fill the component table, the mode, the plots; its binary
// frames are JPEGs of the video topic.
"use strict";

const PLOT_SECONDS = 20; // the plots show the last 20 s of their topic's clock
const rows = new Map(); // instance -> <tr>
const plots = new Map(); // "topic:field" -> {plot, t, v, element}
let videoUrl = null;

function text(id, value) {
  document.getElementById(id).textContent = value;
}

function fixed(v, digits) {
  return typeof v === "number" ? v.toFixed(digits) : "-";
}

// "dropped at image: 3, pose: 1": the input ports whose queues dropped samples.
function droppedByPort(ports) {
  const list = (ports || []).map((p) => `${p.port}: ${p.count}`);
  return list.length ? `dropped at ${list.join(", ")}` : "";
}

// An enumerator as a word: STATE_ACTIVE -> active, MODE_SURFACE -> surface.
function label(enumerator) {
  const s = String(enumerator ?? "?");
  return s.slice(s.indexOf("_") + 1).toLowerCase();
}

function componentRow(d) {
  const tbody = document.querySelector("#components tbody");
  let tr = rows.get(d.instance);
  if (!tr) {
    tr = document.createElement("tr");
    tr.dataset.instance = d.instance;
    for (let i = 0; i < 12; ++i) tr.appendChild(document.createElement("td"));
    rows.set(d.instance, tr);
    // Ordered by process group, then name.
    const key = (r) => `${r.dataset.process}/${r.dataset.instance}`;
    tr.dataset.process = d.process;
    const after = [...tbody.children].find((r) => key(r) > key(tr));
    tbody.insertBefore(tr, after || null);
    document.getElementById("no-components").hidden = true;
  }
  tr.dataset.updated = Date.now();
  const state = label(d.state);
  const cells = [
    d.instance, d.type, d.process, state,
    `${fixed(d.tick_rate_hz, 1)} / ${fixed(d.rate_hz, 0)}`,
    fixed(d.tick_time_p50_us, 1), fixed(d.tick_time_p99_us, 1),
    d.overruns, d.dropped_samples, d.rejected_samples, d.warnings,
    d.last_error || d.last_warning || droppedByPort(d.dropped_by_port),
  ];
  cells.forEach((c, i) => { tr.children[i].textContent = c; });
  tr.children[3].className = `state-${state}`;
  tr.dataset.tickRate = d.tick_rate_hz;
}

// A component whose process stopped reporting for 3 s is shown as silent.
setInterval(() => {
  for (const tr of rows.values()) {
    if (Date.now() - Number(tr.dataset.updated) > 3000) {
      tr.children[3].textContent = "silent";
      tr.children[3].className = "state-silent";
    }
  }
}, 1000);

function showMode(m) {
  const el = document.getElementById("mode");
  const mode = label(m.mode);
  el.textContent = mode;
  el.className = `mode mode-${mode}`;
  text("mode-reason", m.reason ? `(${m.reason})` : "");
}

function ensurePlot(key) {
  if (plots.has(key)) return plots.get(key);
  const div = document.createElement("div");
  div.className = "plot";
  div.dataset.plot = key;
  div.dataset.points = "0";
  const title = document.createElement("h3");
  title.textContent = key.replace(":", "  ");
  div.appendChild(title);
  document.getElementById("plots").appendChild(div);
  const width = Math.max(300, document.getElementById("plots").clientWidth - 8);
  const plot = new uPlot({
    width, height: 160,
    scales: { x: { time: false } },
    axes: [{ label: "t (s, the pipeline's clock)" }, {}],
    series: [{}, { label: key.split(":")[1], stroke: "#1565c0", width: 1.5 }],
  }, [[], []], div);
  const entry = { plot, t: [], v: [], element: div };
  plots.set(key, entry);
  return entry;
}

function addPoints(op) {
  const p = ensurePlot(op.plot);
  for (let i = 0; i < op.t.length; ++i) {
    p.t.push(op.t[i]);
    p.v.push(op.v[i]);
  }
  const tEnd = p.t[p.t.length - 1];
  let first = 0;
  while (first < p.t.length && p.t[first] < tEnd - PLOT_SECONDS) ++first;
  if (first > 0) {
    p.t.splice(0, first);
    p.v.splice(0, first);
  }
  p.element.dataset.points = String(Number(p.element.dataset.points) + op.t.length);
  p.element.dataset.last = String(p.v[p.v.length - 1]);
  p.plot.setData([p.t, p.v]);
}

function showFrame(blob) {
  const img = document.getElementById("video");
  const url = URL.createObjectURL(blob);
  img.onload = () => {
    if (videoUrl) URL.revokeObjectURL(videoUrl);
    videoUrl = url;
    img.dataset.frames = String(Number(img.dataset.frames) + 1);
  };
  img.src = url;
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/`, ["wysiwyf.dashboard.v1"]);
  ws.onopen = () => {
    text("connection", "live");
    document.getElementById("connection").className = "connection connection-open";
  };
  ws.onclose = () => {
    text("connection", "disconnected: retrying");
    document.getElementById("connection").className = "connection connection-closed";
    setTimeout(connect, 1000);
  };
  ws.onmessage = (ev) => {
    if (typeof ev.data !== "string") {
      showFrame(ev.data);
      return;
    }
    const op = JSON.parse(ev.data);
    if (op.op === "hello") {
      text("domain", `domain ${op.domain}`);
      text("video-topic", op.video);
      op.plots.forEach(ensurePlot);
    } else if (op.op === "diagnostics") {
      componentRow(op.sample);
    } else if (op.op === "mode") {
      showMode(op.sample);
    } else if (op.op === "points") {
      addPoints(op);
    }
  };
  document.getElementById("add-plot").onsubmit = (ev) => {
    ev.preventDefault();
    const topic = document.getElementById("plot-topic").value.trim();
    const field = document.getElementById("plot-field").value.trim();
    if (!topic || !field) return;
    ensurePlot(`${topic}:${field}`);
    ws.send(JSON.stringify({ op: "plot", topic, field }));
  };
}

connect();
