#!/bin/bash
# A run whose arm faulted fails: config/pipelines/puma-setpoints.yaml with a first setpoint 56 cm
# from the arm, which its safety gate refuses (a fault); `wysiwyf run` must exit 1, its table's
# state column must give the arm's fault and its reason, and the unchanged pipeline must exit 0.
# Usage: run_faulting_arm.sh <build/bin dir> <config dir> <domain>
set -uo pipefail
bin=$1 config=$2 domain=$3
out=$(mktemp)
trap 'rm -f "$out"' EXIT
common=(--set domain="$domain" --set clock.duration=1s --set clock.pace=0 --set dds.transport=local --no-progress)
"$bin/wysiwyf" run "$config/pipelines/puma-setpoints.yaml" "${common[@]}" \
  --set 'setpoints.params.waypoints=[0, 0.45, 0.3, 0.6, 0, 0, 0, 1, 0.45, 0.3, 0.6, 0, 0, 0]' >"$out" 2>&1
rc=$?
cat "$out"
[ $rc -eq 1 ] || { echo "expected exit status 1 for a faulted arm, got $rc"; exit 1; }
grep -Eq "^arm +arm_sim .* fault: setpoint rejected: 0.5590 m from the arm's position" "$out" \
  || { echo "the table's state column does not give the arm's fault"; exit 1; }
grep -q "error: component 'arm' (arm_sim) faulted during the run" "$out" || { echo "no error line"; exit 1; }
"$bin/wysiwyf" run "$config/pipelines/puma-setpoints.yaml" "${common[@]}" >"$out" 2>&1
rc=$?
[ $rc -eq 0 ] || { cat "$out"; echo "the unchanged pipeline exited $rc"; exit 1; }
echo "faulted run: exit 1 with the fault in the table; clean run: exit 0"
