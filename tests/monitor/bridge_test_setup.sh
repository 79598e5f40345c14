# Sourced by the monitor tests that drive `wysiwyf bridge` with Node clients (set -euo pipefail,
# and build, src and domain set, before): the npm clients copied next to their packages, a scratch
# folder, the background processes killed at exit, and start_bridge. Each test defines fail().
cli=$build/bin/wysiwyf
js=$build/npm/monitor
[[ -d $js/node_modules/@foxglove/ws-protocol && -d $js/node_modules/ws ]] ||
  { echo "FAIL: $js/node_modules lacks @foxglove/ws-protocol or ws: scripts/test installs tests/monitor/js (npm ci)"; exit 1; }
cp "$src"/tests/monitor/js/*.mjs "$js/"
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

# start_bridge: `wysiwyf bridge` on $domain (shared memory), its log in $work/bridge.log, its pid
# in $bridge and the port it listens on in $port.
start_bridge() {
  "$cli" bridge --domain "$domain" --transport local --port 0 >"$work/bridge.log" 2>&1 &
  bridge=$!
  pids+=($!)
  disown
  for _ in $(seq 100); do grep -q "ws://" "$work/bridge.log" && break; sleep 0.1; done
  port=$(sed -n 's|.*ws://127.0.0.1:\([0-9]*\).*|\1|p' "$work/bridge.log" | head -1)
  [[ -n $port ]] || fail "the bridge did not say where it listens"
}
