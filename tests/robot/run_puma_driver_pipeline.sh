#!/bin/bash
# config/pipelines/puma-driver.yaml run by `wysiwyf run` against puma-link-emulator --lockstep:
# the pipeline runs its 2 s to the end and every one of its 2000 ticks reached the controller.
# Usage: run_puma_driver_pipeline.sh <build/bin dir> <config dir> <domain>
set -euo pipefail
bin=$1 config=$2 domain=$3
log=$(mktemp)
trap 'kill $emulator 2>/dev/null || true; rm -f "$log"' EXIT
"$bin/puma-link-emulator" --lockstep --port 0 >"$log" 2>&1 &
emulator=$!
for _ in $(seq 100); do grep -q "emulator on" "$log" && break; sleep 0.05; done
port=$(sed -n 's/.*on 127.0.0.1:\([0-9]*\).*/\1/p' "$log")
[ -n "$port" ] || { echo "the emulator did not start:"; cat "$log"; exit 1; }
"$bin/wysiwyf" run "$config/pipelines/puma-driver.yaml" --set domain="$domain" --set clock.duration=2s \
  --set clock.pace=0 --set dds.transport=local --set arm.params.port="$port" --set arm.params.reply_timeout=5
kill -INT $emulator
wait $emulator || true
cat "$log"
applied=$(sed -n 's/^applied \([0-9]*\) commands.*/\1/p' "$log")
[ "${applied:-0}" -ge 2000 ] || { echo "expected >= 2000 commands applied, the emulator saw ${applied:-none}"; exit 1; }
grep -q " 0 commands refused" "$log" || { echo "the controller refused commands"; exit 1; }
