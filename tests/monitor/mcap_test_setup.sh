# Sourced by the monitor tests that read recordings with the official MCAP reader (set -euo
# pipefail, and build and src set, before): the reader script copied next to its npm packages, a
# scratch folder, the background processes killed at exit, and json FILE EXPR (a Python
# expression over the file's JSON as d). Each test defines fail().
cli=$build/bin/wysiwyf
js=$build/npm/monitor
if [[ ! -d $js/node_modules/@mcap/core ]]; then
  echo "FAIL: $js/node_modules has no @mcap/core: scripts/test installs tests/monitor/js/package.json there (npm ci)"
  exit 1
fi
cp "$src/tests/monitor/js/read_mcap.mjs" "$js/"
work=$(mktemp -d)
pids=()
trap 'for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; rm -rf "$work"' EXIT
json() { python3 -c "import json,sys; d=json.load(open('$1')); print($2)"; }
