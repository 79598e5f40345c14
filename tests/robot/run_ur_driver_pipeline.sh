#!/bin/bash
# config/pipelines/ur-driver.yaml run by `wysiwyf run` against ur-emulator --lockstep: the
# pipeline runs its 2 s to the end (the arm never held) and every one of its 1000 ticks was one
# controller period, with no package refused.
# Usage: run_ur_driver_pipeline.sh <build/bin dir> <config dir> <domain>
set -euo pipefail
bin=$1 config=$2 domain=$3
log=$(mktemp)
trap 'kill $emulator 2>/dev/null || true; rm -f "$log"' EXIT
"$bin/ur-emulator" --lockstep --rtde-port 0 --script-port 0 --dashboard-port 0 >"$log" 2>&1 &
emulator=$!
for _ in $(seq 100); do grep -q "UR emulator on" "$log" && break; sleep 0.05; done
read -r rtde script dashboard < <(sed -n 's/.*rtde \([0-9]*\), script \([0-9]*\), dashboard \([0-9]*\).*/\1 \2 \3/p' "$log")
[ -n "${dashboard:-}" ] || { echo "the emulator did not start:"; cat "$log"; exit 1; }
"$bin/wysiwyf" run "$config/pipelines/ur-driver.yaml" --set domain="$domain" --set clock.duration=2s \
  --set clock.pace=0 --set dds.transport=local --set arm.params.rtde_port="$rtde" \
  --set arm.params.script_port="$script" --set arm.params.dashboard_port="$dashboard" --set arm.params.reply_timeout=5
kill -INT $emulator
wait $emulator || true
cat "$log"
periods=$(sed -n 's/^ran \([0-9]*\) periods.*/\1/p' "$log")
[ "${periods:-0}" -ge 1000 ] || { echo "expected >= 1000 controller periods, the emulator ran ${periods:-none}"; exit 1; }
grep -q " 0 packages refused" "$log" || { echo "the controller refused packages"; exit 1; }
