#!/usr/bin/env bash
# `wysiwyf record` and `wysiwyf play` as a user runs them, each file checked with the official
# MCAP reader (@mcap/core) and Foxglove's OMG IDL decoder (tests/monitor/js, installed into the
# build tree by scripts/test):
#  1. the scripted push (admittance-push.yaml) recorded whole: every sample of every topic, the
#     chunks zstd-compressed (the default), every message decodes, the wrench decodes to the
#     script's values;
#  2. a recorder killed with SIGKILL leaves a file that reads up to its last complete chunk;
#  3. the recorded wrench played into admittance_sim on the sim clock reproduces the recorded
#     cube and setpoint bit for bit (recorded again with --compression lz4).
# Usage: record_play.sh BUILD_DIR SOURCE_DIR DOMAIN (uses DOMAIN and DOMAIN+1)
set -euo pipefail
build=$1 src=$2 d1=$3 d2=$(($3 + 1))
source "$src/tests/monitor/mcap_test_setup.sh"
pipeline=$src/config/pipelines/admittance-push.yaml
run_opts=(--set dds.transport=local --set clock.duration=3s --no-progress --start-after 2)
fail() { echo "FAIL: $*"; exit 1; }

echo "== 1. record the push"
"$cli" record --all -o "$work/run.mcap" --domain "$d1" --transport local --no-progress >"$work/record.log" 2>&1 &
rec=$!; pids+=("$rec")
"$cli" run "$pipeline" --set domain="$d1" "${run_opts[@]}" >"$work/run.log" 2>&1 || { cat "$work/run.log"; fail "the push did not run"; }
kill -INT "$rec"; wait "$rec" || { cat "$work/record.log"; fail "record exited non-zero"; }
cat "$work/record.log"
node "$js/read_mcap.mjs" summary "$work/run.mcap" >"$work/run.json" || fail "@mcap/core cannot read the file"
for topic in robot/wrench robot/setpoint haptics/objects; do
  n=$(json "$work/run.json" "d['topics']['$topic']['count']")
  [[ $n == 3000 ]] || fail "$topic: $n messages recorded; expected all 3000 (one per 1 ms step of 3 s)"
done
[[ $(json "$work/run.json" "d['topics']['robot/wrench']['schema']") == wysiwyf::msg::WrenchStamped ]] || fail "wrench schema"
[[ $(json "$work/run.json" "d['topics']['haptics/objects']['encoding']") == omgidl ]] || fail "schema encoding"
# The script: (-11.343, 0, -0.5) N between 0.6 and 1.0 s (sensor frame), the tool's moment about y.
wrench=$(json "$work/run.json" "[(m['wrench']['force'], m['wrench']['torque']['y']) for m in d['topics']['robot/wrench']['messages'] if m['header']['stamp_ns'] == 800000000][0]")
[[ $wrench == "({'x': -11.343, 'y': 0, 'z': -0.5}, -0.18887)" ]] || fail "the wrench at 0.8 s decodes to $wrench"
chunks=$(json "$work/run.json" "d['chunks']")
[[ $(json "$work/run.json" "d['compression']") == "{'zstd': $chunks}" ]] ||
  fail "chunks by compression: $(json "$work/run.json" "d['compression']"); expected all $chunks zstd"
undecoded=$(json "$work/run.json" "[t for t, v in d['topics'].items() if v['schema'] and len(v['messages']) != v['count']]")
[[ $undecoded == "[]" ]] || fail "topics whose messages do not all decode: $undecoded"
node "$js/read_mcap.mjs" stream "$work/run.mcap" >"$work/run-stream.json" || fail "@mcap/core cannot stream the file"
[[ $(json "$work/run-stream.json" "d['decoded'] == d['messages'] == $(json "$work/run.json" "d['messages']")") == True ]] ||
  fail "a front-to-back read decodes $(json "$work/run-stream.json" "(d['decoded'], d['messages'])") messages"
echo "ok: 3 x 3000 messages in $chunks zstd chunks, every message decodes, the wrench at 0.8 s is $wrench"

echo "== 2. a recorder killed with SIGKILL"
"$cli" record --all -o "$work/killed.mcap" --domain "$d2" --transport local --no-progress >"$work/killed.log" 2>&1 &
rec=$!; pids+=("$rec")
"$cli" run "$pipeline" --set domain="$d2" "${run_opts[@]}" >"$work/run2.log" 2>&1 &
run=$!; pids+=("$run")
sleep 3.7  # (2 s before t = 0, then well into the run: not a timing check, any point will do)
kill -9 "$rec"; wait "$rec" 2>/dev/null || true
wait "$run" || { cat "$work/run2.log"; fail "the second push did not run"; }
node "$js/read_mcap.mjs" stream "$work/killed.mcap" >"$work/killed.json" || fail "@mcap/core cannot read the killed recorder's file"
cat "$work/killed.json"
[[ $(json "$work/killed.json" "d['done']") == False ]] || fail "the killed file claims to be complete"
n=$(json "$work/killed.json" "d['messages']")
(( n > 0 )) || fail "no message readable in the killed recorder's file"
[[ $(json "$work/killed.json" "d['decoded']") == "$n" ]] || fail "not every message decodes"
[[ $(json "$work/killed.json" "list(d['compression'])") == "['zstd']" ]] || fail "the killed file's chunks are not zstd"
echo "ok: $n messages read up to the last complete chunk"

echo "== 3. play the wrench into admittance_sim"
"$cli" record haptics/objects robot/setpoint -o "$work/replay.mcap" --domain "$d2" --transport local --no-progress \
  --compression lz4 >"$work/replay-record.log" 2>&1 &
rec=$!; pids+=("$rec")
"$cli" play "$work/run.mcap" --into "$pipeline" --set push=null --set domain="$d2" --set dds.transport=local \
  --set clock.duration=3s --topics robot/wrench --rate 1 --start-after 2 >"$work/play.log" 2>&1 || { cat "$work/play.log"; fail "play failed"; }
cat "$work/play.log"
kill -INT "$rec"; wait "$rec" || { cat "$work/replay-record.log"; fail "the replay's recorder exited non-zero"; }
grep -q "^chunks lz4: " "$work/replay-record.log" || { cat "$work/replay-record.log"; fail "the replay is not lz4"; }
grep -q "^played 3000 of 3000 samples" "$work/play.log" || fail "play did not deliver the 3000 wrench samples"
for topic in haptics/objects robot/setpoint; do
  node "$js/read_mcap.mjs" compare "$work/run.mcap" "$work/replay.mcap" "$topic" >"$work/cmp.json"
  cat "$work/cmp.json"
  [[ $(json "$work/cmp.json" "d['common']") == 3000 && $(json "$work/cmp.json" "d['differ']") == 0 ]] ||
    fail "$topic: the replay differs from the recording"
done
echo "ok: the replay's cube and setpoint equal the recording's, bit for bit"
