#!/usr/bin/env bash
# `wysiwyf record --images` on the simulated demo's images, as a user runs it, checked with the
# official MCAP reader (@mcap/core) and Foxglove's OMG IDL decoder (tests/monitor/js):
#  1. the first second of the demo recorded three times at once: `--images raw`, `lossless` (the
#     default) and `video`; the lossless file is smaller than the raw one, the video file smaller
#     still; every message of both decodes; the noisy camera images are WebP and the rendered depth
#     PNG foxglove::CompressedImage messages (lossless), H.264 CompressedVideo ones (video), whose
#     bytes are what their format says;
#  2. `play` of the lossless file onto another domain, recorded raw there: each image equals the
#     live one of the same stamp byte for byte (the Image samples `play` decodes are the ones
#     `record` packed). The recorder there may miss a topic's first images: play's writer of a
#     topic appears with its first sample, and the recorder reads a topic once it has seen a writer.
#  3. `play` of the video file, the same way: each image comes back with its stamp, seq, frame,
#     size and encoding, its pixels within a PSNR bound;
#  4. `play --into` a pipeline of the demo's keyer alone, fed the lossless file's camera images:
#     the matte it makes equals the live demo's, image for image.
# Usage: record_images.sh BUILD_DIR SOURCE_DIR DOMAIN (uses DOMAIN to DOMAIN+3)
set -euo pipefail
build=$1 src=$2 d1=$3 d2=$(($3 + 1)) d3=$(($3 + 2)) d4=$(($3 + 3))
source "$src/tests/monitor/mcap_test_setup.sh"
pipeline=$src/config/pipelines/demo-sim.yaml
fail() { echo "FAIL: $*"; for f in raw lossless video run play replay play-video replay-video play-into replay-matte; do echo "--- $f"; tail -30 "$work/$f.log" 2>/dev/null; done; exit 1; }
images=(camera/image render/depth)  # a noisy camera's WebP, a float depth's PNG

echo "== 1. the demo's first second, recorded raw, lossless and as video"
"$cli" record --all --images raw -o "$work/raw.mcap" --domain "$d1" --transport local --no-progress >"$work/raw.log" 2>&1 &
raw=$!; pids+=("$raw")
"$cli" record --all -o "$work/lossless.mcap" --domain "$d1" --transport local --no-progress >"$work/lossless.log" 2>&1 &
lossless=$!; pids+=("$lossless")
"$cli" record --all --images video -o "$work/video.mcap" --domain "$d1" --transport local --no-progress >"$work/video.log" 2>&1 &
video=$!; pids+=("$video")
"$cli" run "$pipeline" --set domain="$d1" --set dds.transport=local --set clock.duration=1s --set clock.pace=0 \
  --set record.params.path="$work/demo.mp4" --start-after 2 --no-progress >"$work/run.log" 2>&1 || fail "the demo did not run"
kill -INT "$raw" "$lossless" "$video"
wait "$raw" || fail "the raw recorder exited non-zero"
wait "$lossless" || fail "the lossless recorder exited non-zero"
wait "$video" || fail "the video recorder exited non-zero"
grep -q "^  camera/image: 25 (webp, " "$work/lossless.log" || fail "camera/image: not 25 images packed as WebP"
grep -q "^  render/depth: 25 (float32-delta-planes-png, " "$work/lossless.log" || fail "render/depth: not 25 depth images packed as PNG"
grep -q "^  render/color: 25 (raw)" "$work/lossless.log" || fail "render/color (a rendered image) did not stay raw"
grep -q "^  camera/image: 25 (h264, " "$work/video.log" || fail "camera/image: not 25 images in an H.264 stream"
grep -q "^  render/depth: 25 (h264, " "$work/video.log" || fail "render/depth: not 25 depth images in an H.264 stream"
for f in lossless video; do
  grep -q "lost 0 before the recorder, 0 in it" "$work/$f.log" || fail "the $f recorder lost samples"
done
size_raw=$(stat -c %s "$work/raw.mcap") size_lossless=$(stat -c %s "$work/lossless.mcap") size_video=$(stat -c %s "$work/video.mcap")
(( size_lossless * 10 < size_raw * 8 )) || fail "lossless file $size_lossless bytes; raw $size_raw: expected at least 20 % smaller"
(( size_video * 2 < size_lossless )) || fail "video file $size_video bytes; lossless $size_lossless: expected under half"
node "$js/read_mcap.mjs" stream "$work/lossless.mcap" >"$work/stream.json" || fail "@mcap/core cannot read the lossless file"
cat "$work/stream.json"
[[ $(json "$work/stream.json" "d['decoded'] == d['messages'] and d['done']") == True ]] ||
  fail "not every message decodes: $(json "$work/stream.json" "(d['decoded'], d['messages'])")"
[[ $(json "$work/stream.json" "d['misformatted_images']") == 0 ]] || fail "CompressedImage data that is not its format"
[[ $(json "$work/stream.json" "d['images'].get('webp', 0) >= 50 and d['images'].get('png', 0) >= 25") == True ]] ||
  fail "images per format: $(json "$work/stream.json" "d['images']")"
node "$js/read_mcap.mjs" summary "$work/lossless.mcap" >"$work/summary.json" || fail "@mcap/core cannot index the file"
[[ $(json "$work/summary.json" "d['topics']['camera/image']['schema']") == foxglove::CompressedImage ]] || fail "camera/image's schema"
node "$js/read_mcap.mjs" stream "$work/video.mcap" >"$work/stream-video.json" || fail "@mcap/core cannot read the video file"
cat "$work/stream-video.json"
[[ $(json "$work/stream-video.json" "d['decoded'] == d['messages'] and d['done'] and d['misformatted_images'] == 0") == True ]] ||
  fail "the video file: not every message decodes, or H.264 data that is not Annex B"
[[ $(json "$work/stream-video.json" "d['images'].get('h264', 0) >= 75") == True ]] ||
  fail "video messages per format: $(json "$work/stream-video.json" "d['images']")"
echo "ok: raw $size_raw bytes, lossless $size_lossless, video $size_video; every message decodes"

echo "== 2. play the lossless file; the images come back as recorded live"
"$cli" record "${images[@]}" --images raw -o "$work/replay.mcap" --domain "$d2" --transport local --no-progress \
  >"$work/replay.log" 2>&1 &
rec=$!; pids+=("$rec")
sleep 2  # (the recorder's readers up before the first sample: play does not wait for readers)
"$cli" play "$work/lossless.mcap" --topics "$(IFS=,; echo "${images[*]}")" --domain "$d2" --transport local \
  >"$work/play.log" 2>&1 || fail "play failed"
cat "$work/play.log"
sleep 1
kill -INT "$rec"; wait "$rec" || fail "the replay's recorder exited non-zero"
grep -q "not played" "$work/play.log" && fail "play skipped images"
for topic in "${images[@]}"; do
  node "$js/read_mcap.mjs" compare "$work/raw.mcap" "$work/replay.mcap" "$topic" >"$work/cmp.json"
  cat "$work/cmp.json"
  [[ $(json "$work/cmp.json" "d['a'] == 25 and d['common'] >= 20 and d['differ'] == 0") == True ]] ||
    fail "$topic: the replayed images differ from the live ones (or too few were replayed to tell)"
done
echo "ok: the camera's and the depth's images replayed byte for byte"

echo "== 3. play the video file; the images come back with their headers, pixels within a PSNR bound"
"$cli" record camera/image --images raw -o "$work/replay-video.mcap" --domain "$d3" --transport local --no-progress \
  >"$work/replay-video.log" 2>&1 &
rec=$!; pids+=("$rec")
sleep 2
"$cli" play "$work/video.mcap" --topics camera/image --domain "$d3" --transport local >"$work/play-video.log" 2>&1 ||
  fail "play of the video failed"
cat "$work/play-video.log"
sleep 1
kill -INT "$rec"; wait "$rec" || fail "the video replay's recorder exited non-zero"
grep -q "not played" "$work/play-video.log" && fail "play skipped video images"
node "$js/read_mcap.mjs" psnr "$work/raw.mcap" "$work/replay-video.mcap" camera/image >"$work/psnr.json"
cat "$work/psnr.json"
[[ $(json "$work/psnr.json" "d['a'] == 25 and d['common'] >= 20 and d['same_header'] == d['common'] and d['lowest_psnr_db'] > 30") == True ]] ||
  fail "camera/image from the video: headers or pixels not as recorded (PSNR bound 30 dB)"
echo "ok: camera/image from the video: $(json "$work/psnr.json" "d['common']") images, lowest PSNR $(json "$work/psnr.json" "round(d['lowest_psnr_db'], 1)") dB"

echo "== 4. play the lossless file's camera into the demo's keyer: the same matte as live"
cat >"$work/keyer.yaml" <<EOF
wysiwyf: 1
name: keyer-replay
domain: $d4
clock: {mode: sim, step: 1ms, duration: 1s, pace: 0}
components:
  keyer:  # as in config/pipelines/display/loop.yaml
    type: chroma_keyer
    rate: 25
    trigger: image
    params: {min_luma: 45}
    topics: {image: camera/image, hand: vision/hand, matte: vision/matte}
EOF
"$cli" record vision/matte --images raw -o "$work/replay-matte.mcap" --domain "$d4" --transport local --no-progress \
  >"$work/replay-matte.log" 2>&1 &
rec=$!; pids+=("$rec")
"$cli" play "$work/lossless.mcap" --into "$work/keyer.yaml" --topics camera/image --set dds.transport=local \
  --start-after 2 >"$work/play-into.log" 2>&1 || fail "play --into the keyer failed"
cat "$work/play-into.log"
sleep 1
kill -INT "$rec"; wait "$rec" || fail "the matte's recorder exited non-zero"
grep -q "^played 25 of 25 samples" "$work/play-into.log" || fail "play --into did not feed the 25 camera images"
node "$js/read_mcap.mjs" compare "$work/raw.mcap" "$work/replay-matte.mcap" vision/matte >"$work/cmp.json"
cat "$work/cmp.json"
[[ $(json "$work/cmp.json" "d['common'] >= 20 and d['differ'] == 0") == True ]] ||
  fail "vision/matte from the replayed images differs from the live one"
echo "ok: the keyer's matte from the replayed images equals the live one"
