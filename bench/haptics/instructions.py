#!/usr/bin/env python3
"""Instructions per haptic step, ours and MuJoCo's, for bench_haptics' BM_Scale_* scenes.

This VM has no hardware counters (perf_event_open fails), so callgrind counts them: the benchmark
runs twice under it (WYSIWYF_BENCH_COUNT=ours, then mujoco), each time collecting only that
one's steps (bench_scale.cpp toggles collection around them) and dumping each scene's count under
its name. Instruction counts do not depend on the machine's load, so they compare runs and
machines where the timings cannot.

Usage: instructions.py BENCH_HAPTICS OUT.json    (scripts/bench haptics runs it)
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile


def count(bench, who, work):
    """{scene: instructions per step} for `who` ("ours" or "mujoco")."""
    out = os.path.join(work, who)
    env = dict(os.environ, WYSIWYF_BENCH_SMOKE="1", WYSIWYF_BENCH_COUNT=who)
    run = subprocess.run(
        ["valgrind", "--tool=callgrind", "--collect-atstart=no", "--callgrind-out-file=" + out, bench,
         "--benchmark_filter=BM_Scale_"],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if run.returncode != 0:
        sys.exit("instructions.py: callgrind run of %s failed:\n%s" % (bench, run.stdout[-3000:]))
    counts = {}
    for name in sorted(os.listdir(work)):
        if not name.startswith(who + "."):
            continue
        with open(os.path.join(work, name), errors="replace") as f:  # (symbol names need not be UTF-8)
            text = f.read()
        trigger = re.search(r"^desc: Trigger: Client Request: (\S+) steps=(\d+)$", text, re.M)
        total = re.search(r"^(?:totals|summary): (\d+)", text, re.M)
        if trigger and total:
            counts[trigger.group(1)] = int(total.group(1)) / int(trigger.group(2))
    if not counts:
        sys.exit("instructions.py: callgrind dumped no scene's count (was the benchmark built with valgrind's "
                 "callgrind.h?)")
    return counts


def growth(rows, kind):
    """Least-squares slope of log(instructions) against log(N) over one kind's scenes."""
    points = [(math.log(int(n)), math.log(v)) for name, v in rows.items()
              for k, n in [name.split("/")] if k == kind and v > 0]
    if len(points) < 2:
        return float("nan")
    mx = sum(x for x, _ in points) / len(points)
    my = sum(y for _, y in points) / len(points)
    return sum((x - mx) * (y - my) for x, y in points) / sum((x - mx) ** 2 for x, _ in points)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    bench, out_json = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as work:
        ours = count(bench, "ours", work)
        theirs = count(bench, "mujoco", work)
    scenes = sorted(ours, key=lambda s: (s.split("/")[0], int(s.split("/")[1])))
    print("%-10s %14s %14s %7s" % ("scene", "ours Ir/step", "MuJoCo Ir/step", "ratio"))
    for s in scenes:
        t = theirs.get(s, float("nan"))
        print("%-10s %14.0f %14.0f %6.2fx" % (s, ours[s], t, ours[s] / t))
    result = {"scenes": {s: {"ours_instructions": ours[s], "mujoco_instructions": theirs.get(s)} for s in scenes},
              "growth": {}}
    for kind in ("Grid", "Stack"):
        g_ours, g_theirs = growth(ours, kind), growth(theirs, kind)
        result["growth"][kind] = {"ours": g_ours, "mujoco": g_theirs}
        print("%s growth: ours N^%.2f, MuJoCo N^%.2f" % (kind, g_ours, g_theirs))
    with open(out_json, "w") as f:
        json.dump(result, f, indent=1)
    print("wrote " + out_json)


if __name__ == "__main__":
    main()
