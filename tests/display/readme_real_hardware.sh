#!/bin/bash
# The README's "Real hardware" lines, run as a user would from the source tree (in a scratch
# folder, with build/bin and config/ pointing at this build and source, each `wysiwyf run` on
# the test's own DDS domain): the recording is made, both emulators start on their default
# ports, demo-real-emulated.yaml runs to the recording's end without a fault, its planner going
# for the knob the recorded hand comes toward.
# Usage: readme_real_hardware.sh <build/bin dir> <source dir> <domain>
set -euo pipefail
bin=$(realpath "$1") source=$(realpath "$2") domain=$3
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$work"' EXIT
block=$(awk '/docs.readme_real_hardware runs these lines/ {found=1; next}
             found && /^```/ {if (inside) exit; inside=1; next}
             inside {print}' "$source/README.md")
[ -n "$block" ] || { echo "README.md: no block after the docs.readme_real_hardware marker"; exit 1; }
script=$(printf '%s\n' "$block" | sed -e "s|build/bin/|$bin/|g" -e "s|config/|$source/config/|g" \
  -e "/wysiwyf run/s|\$| --set domain=$domain --set dds.transport=local|" \
  -e "/^diff /s|\$| \|\| [ \$? -eq 1 ]|")  # (diff says 1: the files differ, as they should)
echo "$script"
cd "$work"
# What the display planned, from another process: the knob the hand in the recording comes for.
"$bin/wysiwyf" topic echo display/planner --domain "$domain" --transport local --timeout 120 --field feature \
  >planner.txt 2>&1 &
echoing=$!
out=$(bash -c "set -e
$script" 2>&1) || { echo "$out"; echo "the README's lines failed"; exit 1; }
wait $echoing || true
echo "$out"
grep -q "\[supervisor\] idle -> surface" <<<"$out" || { echo "the display never went to surface mode"; exit 1; }
! grep -q -- "-> fault" <<<"$out" || { echo "the display faulted"; exit 1; }
grep -q "stopped by camera: end of out/left.mp4" <<<"$out" || { echo "the run did not end with the recording"; exit 1; }
grep -q "wrote 76 frames to out/left.mp4" <<<"$out" || { echo "the recording was not made"; exit 1; }
knob=$(grep -cx 'cube +x knob' planner.txt || true)
echo "display/planner: $knob samples with the +x knob as the target"
[ "$knob" -gt 100 ] || { head -20 planner.txt; echo "the display did not go for the knob"; exit 1; }
