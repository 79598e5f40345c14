#!/usr/bin/env python3
"""Runs one benchmark binary in smoke mode (few iterations) and fails if it aborts or if any
benchmark reports an error: ctest runs this for every bench_* binary, so a broken benchmark
fails CI. Usage: run_smoke.py BINARY"""
import json
import os
import subprocess
import sys

binary = sys.argv[1]
env = dict(os.environ, WYSIWYF_BENCH_SMOKE="1")
# --benchmark_min_time covers the benchmarks that set neither iterations nor a minimum time.
run = subprocess.run([binary, "--benchmark_format=json", "--benchmark_min_time=0.01"], env=env,
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
sys.stderr.write(run.stderr)
if run.returncode != 0:
    sys.exit(f"{binary}: exited with {run.returncode}")
try:
    report = json.loads(run.stdout)
except json.JSONDecodeError as e:
    sys.exit(f"{binary}: no JSON report ({e}); output:\n{run.stdout[-2000:]}")
benchmarks = report.get("benchmarks", [])
errors = [f"{b['name']}: {b.get('error_message', '?')}" for b in benchmarks if b.get("error_occurred")]
for b in benchmarks:
    print(f"{b['name']}: {b.get('iterations', 0)} iterations" + (" ERROR" if b.get("error_occurred") else ""))
if not benchmarks:
    sys.exit(f"{binary}: ran no benchmark")
if errors:
    sys.exit(f"{binary}: {len(errors)} benchmark(s) reported an error:\n  " + "\n  ".join(errors))
print(f"{binary}: {len(benchmarks)} benchmarks ran to the end")
