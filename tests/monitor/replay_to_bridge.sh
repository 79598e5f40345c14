#!/usr/bin/env bash
# A bridge that watched a live pipeline keeps every topic when a recording of it is played later:
#  1. `wysiwyf bridge` runs; puma-setpoints.yaml runs live (its robot/setpoint takes one writer:
#     exclusive ownership) while `wysiwyf record --all` records it and the official Foxglove
#     client reads robot/setpoint through the bridge;
#  2. the pipeline ends; `wysiwyf play` writes the recording onto the same domain, and the
#     official client, on the same bridge, receives robot/setpoint (the replay's writer matches
#     the reader the live writer shaped) and wysiwyf/diagnostics (a keyed type, played with its
#     keys) and decodes them;
#  3. a pipeline whose robot/setpoint writer shares ownership writes next: the bridge reads the
#     topic again with that writer's QoS, tells its clients, and the client receives it.
# Usage: replay_to_bridge.sh BUILD_DIR SOURCE_DIR DOMAIN
set -euo pipefail
build=$1 src=$2 domain=$3
source "$src/tests/monitor/bridge_test_setup.sh"
fail() { echo "FAIL: $*"; for f in bridge record run play; do echo "--- $f"; tail -20 "$work/$f.log" 2>/dev/null; done; exit 1; }
dds=(--domain "$domain" --transport local)

start_bridge

echo "== 1. live: the pipeline, the recorder and the official client on the bridge"
"$cli" record --all -o "$work/live.mcap" "${dds[@]}" --duration 12 >"$work/record.log" 2>&1 &
record=$!
pids+=($!)
sleep 1
"$cli" run "$src/config/pipelines/puma-setpoints.yaml" --set domain="$domain" --set dds.transport=local \
  --set clock.duration=10s --no-progress >"$work/run.log" 2>&1 &
pids+=($!)
node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 30 robot/setpoint >"$work/live.json" ||
  { cat "$work/live.json"; fail "the official client got no robot/setpoint from the live pipeline"; }
wait "$record" || fail "the recorder failed"
grep -q exclusive <(strings "$work/live.mcap") || fail "robot/setpoint's ownership is not recorded"
echo "ok: live robot/setpoint through the bridge; recorded $(stat -c %s "$work/live.mcap") bytes"

echo "== 2. the replay, through the same bridge"
"$cli" play "$work/live.mcap" "${dds[@]}" --loop >"$work/play.log" 2>&1 &
pids+=($!)
node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 30 robot/setpoint wysiwyf/diagnostics >"$work/replay.json" ||
  { cat "$work/replay.json"; fail "the official client did not get robot/setpoint and wysiwyf/diagnostics from the replay"; }
! grep -q "skipped" "$work/play.log" || fail "play skipped a topic: $(grep skipped "$work/play.log")"
python3 - "$work/replay.json" <<'EOF' || fail "the replayed messages"
import json, sys
d = json.load(open(sys.argv[1]))
s = d["messages"]["robot/setpoint"][-1]
g = d["messages"]["wysiwyf/diagnostics"]
assert s["header"]["stamp_ns"] > 0, s
names = {m["instance"] for m in g}
assert names <= {"setpoints", "arm"} and names, names
print("ok: the replay's robot/setpoint and wysiwyf/diagnostics (" + ", ".join(sorted(names)) + ") decoded")
EOF

echo "== 3. another writer, of other QoS, on the same topic"
# admittance-push writes robot/setpoint with shared ownership: the reader the exclusive writers
# shaped refuses it, and the bridge reads the topic again with the new writer's QoS and says so.
# A client stays subscribed across the change, so the bridge's reader stays open through it.
FOXGLOVE_CLIENT_MESSAGES=1000000 node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 60 robot/setpoint \
  >/dev/null 2>&1 &
pids+=($!)
sleep 2
kill -9 "${pids[-2]}"  # (play)
"$cli" run "$src/config/pipelines/admittance-push.yaml" --set domain="$domain" --set dds.transport=local \
  --set clock.duration=60s --no-progress >"$work/push.log" 2>&1 &
pids+=($!)
node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 30 robot/setpoint >"$work/push.json" ||
  { cat "$work/push.json"; fail "the official client got no robot/setpoint from a writer of shared ownership"; }
grep -Eq "topic 'robot/setpoint': a writer was refused \((OWNERSHIP|LIVELINESS)\); the bridge reads it again" "$work/bridge.log" ||
  fail "the bridge did not say it read robot/setpoint again"
echo "ok: $(grep -o "topic 'robot/setpoint': a writer was refused.*" "$work/bridge.log" | head -1)"
echo "PASS: the bridge kept every topic from the live run to its replay and to a writer of other QoS"
