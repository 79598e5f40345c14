#!/usr/bin/env bash
# Watching the running demo (demo-sim.yaml) as a user would, from outside its process:
#  1. the official Foxglove WebSocket client (@foxglove/ws-protocol) connects to `wysiwyf bridge`,
#     lists every topic with its schema, subscribes, and decodes a JointState and an Image with
#     the advertised OMG IDL;
#  2. headless Chromium loads the bridge's web dashboard: the page's DOM holds every component of
#     the demo with live rates, a plot with data and video frames (a screenshot is kept in
#     BUILD_DIR/Testing/monitor/dashboard.png);
#  3. `wysiwyf monitor` in tmux shows every component of the running pipeline, redrawn in place,
#     and at 80x24, 100x30 and 200x50 every component on a row of its own, none wrapped.
# Usage: watch_demo.sh BUILD_DIR SOURCE_DIR DOMAIN
set -euo pipefail
build=$1 src=$2 domain=$3
cli=$build/bin/wysiwyf
js=$build/npm/monitor
[[ -d $js/node_modules/@foxglove/ws-protocol ]] ||
  { echo "FAIL: $js/node_modules has no @foxglove/ws-protocol: scripts/test installs tests/monitor/js (npm ci)"; exit 1; }
cp "$src"/tests/monitor/js/*.mjs "$js/"
work=$(mktemp -d)
tmux_socket="wysiwyf-monitor-$$"
pids=()
cleanup() {
  tmux -L "$tmux_socket" kill-server 2>/dev/null || true
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }
json() { python3 -c "import json,sys; d=json.load(open('$1')); print($2)"; }
# Every component of the demo, from the pipeline itself.
mapfile -t components < <("$cli" validate "$src/config/pipelines/demo-sim.yaml" --print-components 2>/dev/null ||
  fail "wysiwyf validate --print-components")
(( ${#components[@]} >= 10 )) || fail "the demo has only ${#components[@]} components?"

echo "== the demo, and the bridge on it"
"$cli" run "$src/config/pipelines/demo-sim.yaml" --set domain="$domain" --set dds.transport=local \
  --set record.params.path="$work/demo.mp4" --set metrics.params.summary="$work/metrics.json" \
  --set clock.duration=600s --no-progress >"$work/run.log" 2>&1 &
demo=$!
pids+=($!); disown
"$cli" bridge --domain "$domain" --transport local --port 0 >"$work/bridge.log" 2>&1 &
pids+=($!); disown
for _ in $(seq 100); do grep -q "ws://" "$work/bridge.log" && break; sleep 0.1; done
port=$(sed -n 's|.*ws://127.0.0.1:\([0-9]*\).*|\1|p' "$work/bridge.log" | head -1)
[[ -n $port ]] || { cat "$work/bridge.log"; fail "the bridge did not say where it listens"; }
cat "$work/bridge.log"

echo "== 1. Foxglove's client"
node "$js/foxglove_client.mjs" "ws://127.0.0.1:$port" 60 robot/joint_state camera/image >"$work/fox.json" ||
  { cat "$work/fox.json"; fail "the Foxglove client did not get 3 messages of each topic"; }
[[ $(json "$work/fox.json" "d['channels']['robot/joint_state']['schemaName']") == wysiwyf::msg::JointState ]] ||
  fail "robot/joint_state is not advertised with its schema"
[[ $(json "$work/fox.json" "d['channels']['camera/image']['schemaEncoding']") == omgidl ]] || fail "schema encoding"
n=$(json "$work/fox.json" "len(d['channels'])")
(( n >= 20 )) || fail "only $n topics advertised"
joint=$(json "$work/fox.json" "(lambda m: ' '.join(map(str, [m['header']['frame_id'], m['position']['bytes'], m['header']['stamp_ns'] > 0])))(d['messages']['robot/joint_state'][-1])")
[[ $joint == "base 6 True" ]] || fail "JointState decodes to: $joint"
image=$(json "$work/fox.json" "(lambda m: ' '.join(map(str, [m['encoding'], m['width'], m['height'], m['data']['bytes'] == m['step'] * m['height'], m['data']['sum'] > 0])))(d['messages']['camera/image'][-1])")
[[ $image == "rgb8 640 480 True True" ]] || fail "Image decodes to: $image"
echo "ok: $n topics advertised; JointState ($joint) and Image ($image) decode with the advertised IDL"

echo "== 2. the web dashboard in Chromium"
mkdir -p "$build/Testing/monitor"
shot=$build/Testing/monitor/dashboard.png
node "$js/dashboard_check.mjs" "http://127.0.0.1:$port/" "$shot" 60 >"$work/dom.json" ||
  { cat "$work/dom.json"; fail "the dashboard did not show live data within 60 s"; }
cat "$work/dom.json"
[[ $(json "$work/dom.json" "d['page_errors']") == "[]" ]] || fail "the page threw"
[[ $(json "$work/dom.json" "d['connection']") == live ]] || fail "the page is not connected"
shown=$(json "$work/dom.json" "' '.join(sorted(c['instance'] for c in d['components']))")
for c in "${components[@]}"; do [[ " $shown " == *" $c "* ]] || fail "component $c is not in the dashboard's table ($shown)"; done
physics=$(json "$work/dom.json" "[c for c in d['components'] if c['instance'] == 'physics'][0]")
[[ $physics == *"'state': 'active'"* ]] || fail "physics: $physics"
[[ $(json "$work/dom.json" "d['mode']") =~ ^(idle|surface|admittance)$ ]] || fail "no display mode shown"
(( $(json "$work/dom.json" "max(p['points'] for p in d['plots'])") >= 20 )) || fail "no plot has data"
[[ $(json "$work/dom.json" "d['video']['width'] == 640 and d['video']['frames'] >= 3") == True ]] || fail "no video"
echo "ok: ${#components[@]} components, mode, plots and video live; screenshot $shot"

echo "== 3. wysiwyf monitor in tmux"
tmux -L "$tmux_socket" new-session -d -s monitor -x 180 -y 40 \
  "$cli monitor --domain $domain --transport local --interval 0.5"
seen=""
for _ in $(seq 150); do
  tmux -L "$tmux_socket" capture-pane -p -t monitor >"$work/pane.txt"
  missing=0
  for c in "${components[@]}"; do grep -q "^$c " "$work/pane.txt" || missing=1; done
  ((missing)) || { seen=yes; break; }
  sleep 0.2
done
cat "$work/pane.txt"
[[ -n $seen ]] || fail "the monitor does not show every component"
sleep 1.5  # three more redraws: still one table, drawn in place
tmux -L "$tmux_socket" capture-pane -p -t monitor >"$work/pane.txt"
[[ $(grep -c "^wysiwyf monitor" "$work/pane.txt") == 1 ]] || fail "the table is not redrawn in place"
grep -q "^physics  *admittance_sim  *main  *active" "$work/pane.txt" || fail "physics is not shown active"
echo "ok: the monitor shows all ${#components[@]} components, in place"
# At 80x24, 100x30 and 200x50 (resized as a user would): every component on one row of its own,
# no row wrapped (a wrapped row would add a line), the table redrawn whole after each resize (in
# whatever state: the demo may have ended its script by now).
for size in 80x24 100x30 200x50; do
  tmux -L "$tmux_socket" resize-window -t monitor -x "${size%x*}" -y "${size#*x}"
  sleep 1.5
  tmux -L "$tmux_socket" capture-pane -p -t monitor >"$work/pane.txt"
  for c in "${components[@]}"; do
    grep -Eq "^$c +([a-z0-9_]+ +)?main +[a-z]+ " "$work/pane.txt" || { cat "$work/pane.txt"; fail "at $size, no row for $c"; }
  done
  lines=$(grep -c . "$work/pane.txt")
  ((lines == ${#components[@]} + 2)) ||
    { cat "$work/pane.txt"; fail "at $size, $lines lines for ${#components[@]} components and 2 headings"; }
  echo "ok: at $size, ${#components[@]} rows, none wrapped: $(sed -n 2p "$work/pane.txt" | tr -s ' ')"
done
# Watching never hurts the watched (a tool announcing type objects once crashed a pipeline).
kill -0 "$demo" 2>/dev/null || { tail -20 "$work/run.log"; fail "the demo died while it was watched"; }
