#!/usr/bin/env bash
# `wysiwyf bridge` against hostile and careless clients, on a running pipeline (admittance-push):
#  1. every malformed WebSocket frame that once crashed it, on both subprotocols, gets an error
#     reply naming what was wrong; a frame over the size bound closes only that client; a flood
#     is refused and said (js/hostile_client.mjs);
#  2. HTTP paths outside the web root (absolute, `..`, encoded, devices, hidden files) get a 404
#     and none of the file's bytes; the dashboard's own files are still served;
#  3. the bridge is still up, and the official Foxglove client (@foxglove/ws-protocol) still
#     subscribes and decodes the pipeline's topics;
#  4. the same client gets the connection graph (who publishes and reads what, by participant
#     name) and Time messages on the pipeline's (sim) clock, which the messages are stamped on.
# Usage: hostile_clients.sh BUILD_DIR SOURCE_DIR DOMAIN
set -euo pipefail
build=$1 src=$2 domain=$3
source "$src/tests/monitor/bridge_test_setup.sh"
fail() { echo "FAIL: $*"; echo "--- bridge log"; cat "$work/bridge.log"; exit 1; }

"$cli" run "$src/config/pipelines/admittance-push.yaml" --set domain="$domain" --set dds.transport=local \
  --set clock.duration=600s --no-progress >"$work/run.log" 2>&1 &
pids+=($!)
disown
start_bridge
alive() { kill -0 "$bridge" 2>/dev/null || fail "the bridge died after $1"; }

echo "== 1. malformed frames"
node "$js/hostile_client.mjs" "ws://127.0.0.1:$port" >"$work/hostile.json" ||
  { cat "$work/hostile.json"; fail "a frame did not get the reply it should (above: ok false)"; }
python3 -c "
import json
for r in json.load(open('$work/hostile.json')):
    print(f\"{r['protocol'][:9]:9} {r['frame'][:70]:72} -> {r.get('reply', r.get('close'))}\")"
alive "the malformed frames"

echo "== 2. HTTP paths"
http() { curl -s --path-as-is -o "$work/body" -w '%{http_code}' --max-time 5 "http://127.0.0.1:$port$1"; }
for path in //etc/passwd //proc/self/environ //root/.bashrc //dev/zero /../../../../etc/passwd \
            /%2e%2e/%2e%2e/etc/passwd /..%2f..%2fetc/passwd /vendor/../../../etc/passwd /index.html/../../etc/hostname \
            /.git/config /vendor /fifo; do
  code=$(http "$path") || fail "GET $path: no answer"
  [[ $code == 404 ]] || fail "GET $path: HTTP $code (expected 404)"
  ! grep -q "root:" "$work/body" || fail "GET $path: the body holds a file from outside the web root"
  (( $(stat -c %s "$work/body") < 100 )) || fail "GET $path: a body of $(stat -c %s "$work/body") bytes"
  echo "GET $path -> 404"
done
code=$(http /) && [[ $code == 200 ]] && grep -q "<html" "$work/body" || fail "GET /: HTTP $code, not the dashboard"
code=$(http /vendor/uplot/uPlot.iife.min.js) && [[ $code == 200 ]] || fail "GET the dashboard's script: HTTP $code"
echo "GET / and /vendor/uplot/uPlot.iife.min.js -> 200"
alive "the HTTP paths"

echo "== 3. the official client afterwards"
node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 60 robot/wrench robot/setpoint >"$work/fox.json" ||
  { cat "$work/fox.json"; fail "the Foxglove client did not get 3 messages of each topic after the hostile clients"; }
python3 - "$work/fox.json" <<'EOF' || fail "the official client's messages"
import json, sys
d = json.load(open(sys.argv[1]))
w = d["messages"]["robot/wrench"][-1]
s = d["messages"]["robot/setpoint"][-1]
assert d["channels"]["robot/wrench"]["schemaName"] == "wysiwyf::msg::WrenchStamped", d["channels"]["robot/wrench"]
assert abs(w["wrench"]["force"]["x"] + 11.343) < 1e-9, w
assert s["header"]["stamp_ns"] > 0, s
print("ok: robot/wrench and robot/setpoint decoded (force.x", w["wrench"]["force"]["x"], ")")
EOF
alive "the official client"

echo "== 4. the connection graph and the pipeline's clock (Foxglove's connectionGraph and time)"
node "$js/graph_and_time.mjs" "ws://127.0.0.1:$port" 30 robot/setpoint >"$work/graph.json" ||
  { cat "$work/graph.json"; fail "no connection graph, Time messages or robot/setpoint"; }
python3 - "$work/graph.json" <<'EOF' || fail "the connection graph or the clock"
import json, sys
d = json.load(open(sys.argv[1]))
assert {"connectionGraph", "time"} <= set(d["capabilities"]), d["capabilities"]
pub, sub = d["published"]["robot/setpoint"], d["subscribed"]["robot/setpoint"]
assert len(pub) == 1 and pub[0].startswith("admittance-push/"), pub
assert "wysiwyf-cli" in sub, sub  # (the tools' participant: this bridge)
t, m = d["times"], d["messages"]
assert t == sorted(t) and t[-1] > t[0], t
# The sim clock (from 0, seconds of the run), not the wall clock, for both.
assert t[-1] < 600e9 and max(m) < 600e9 and min(m) > 0, (t[-1], max(m))
print(f"ok: robot/setpoint published by {pub} and read by {sub}; Time {t[0]/1e9:.2f}..{t[-1]/1e9:.2f} s (sim)")
EOF
alive "the connection graph"
echo "PASS: the bridge answered every hostile frame and path and still serves"
