#!/usr/bin/env bash
# The run report's video plays in a browser: a 1 s demo run (demo-sim.yaml) writes its report,
# scripts/run-report draws index.html, and headless Chromium plays the video in that page
# (report_video.mjs: it loads, seeks, shows a frame; a screenshot is kept in
# BUILD_DIR/Testing/io/report_video.png).
# Usage: report_video.sh BUILD_DIR SOURCE_DIR DOMAIN
set -euo pipefail
build=$1 src=$2 domain=$3
js=$build/npm/monitor  # where scripts/test installs playwright-core (tests/monitor/js)
[[ -d $js/node_modules/playwright-core ]] ||
  { echo "FAIL: $js/node_modules has no playwright-core: scripts/test installs tests/monitor/js (npm ci)"; exit 1; }
cp "$src/tests/io/report_video.mjs" "$js/"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
report=$work/report
"$build/bin/wysiwyf" run "$src/config/pipelines/demo-sim.yaml" --set domain="$domain" --set dds.transport=local \
  --set clock.pace=0 --set clock.duration=1s --set metrics.params.report="$report" \
  --set metrics.params.summary="$work/metrics.json" --set record.params.path="$report/video.mp4" --no-progress \
  >"$work/run.log" 2>&1 || { cat "$work/run.log"; echo "FAIL: the demo run"; exit 1; }
"$src/scripts/run-report" "$report" >/dev/null
mkdir -p "$build/Testing/io"
if ! node "$js/report_video.mjs" "file://$report/index.html" "$build/Testing/io/report_video.png"; then
  echo "FAIL: Chromium does not play $report/video.mp4 in the report (see $build/Testing/io/report_video.png)"
  exit 1
fi
echo "PASS: the report's video plays in Chromium"
