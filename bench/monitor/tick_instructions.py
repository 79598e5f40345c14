#!/usr/bin/env python3
"""Instructions per tick of the 1 kHz admittance_sim, with nothing attached and with each monitor.

What a monitor in another process costs the loop's own work, in a figure the machine's noise
does not move: callgrind counts the instructions of every AdmittanceSim::tick (collection
toggled on around it, callees included) of config/pipelines/admittance-push.yaml on the sim
clock, while the monitor (itself not under callgrind) reads the pipeline's topics over DDS.
`nothing_again` is a second run with nothing attached: instruction counts repeat to within the
run's own variation (the physics is deterministic; what differs is the kernel's and Fast DDS's
work inside the tick, which a reader on the domain can change). This VM has no hardware
counters (perf_event_open finds none), hence callgrind.

Writes Google Benchmark-shaped JSON (benchmarks: TickInstructions/<condition> with
instructions_per_tick, vs_nothing and ticks) for scripts/performance-page.

Usage: tick_instructions.py WYSIWYF_CLI FOXGLOVE_SINK OUT.json    (scripts/bench monitor runs it)
"""
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PIPELINE = os.path.join(ROOT, "config", "pipelines", "admittance-push.yaml")
DOMAIN = "204"
PORT = "18204"
TICK = "wysiwyf::haptics::AdmittanceSim::tick*"


def conditions(cli, sink, work):
    tool = ["--domain", DOMAIN, "--transport", "local"]
    return [
        ("nothing", []),
        ("nothing_again", []),
        ("topic_hz", [[cli, "topic", "hz", "robot/setpoint"] + tool]),
        ("topic_echo", [[cli, "topic", "echo", "haptics/objects", "--timeout", "120"] + tool]),
        ("record_all", [[cli, "record", "--all", "-o", os.path.join(work, "record.mcap"), "--no-progress"] + tool]),
        ("bridge_all", [[cli, "bridge", "--port", PORT] + tool, [sink, PORT]]),
    ]


def count(cli, name, monitors, work):
    """(instructions per tick, ticks) of one run with `monitors` attached.

    The pipeline starts first (under callgrind it takes seconds to load), the monitors once its
    DDS is coming up, and its clock starts 12 s after DDS is up, so every monitor has found it."""
    out = os.path.join(work, "callgrind." + name)
    pipeline = subprocess.Popen(
        ["valgrind", "--tool=callgrind", "--collect-atstart=no", "--toggle-collect=" + TICK,
         "--callgrind-out-file=" + out, cli, "run", PIPELINE, "--set", "domain=" + DOMAIN,
         "--set", "dds.transport=local", "--set", "clock.pace=0", "--set", "clock.duration=3s",
         "--set", "physics.priority=~", "--start-after", "12", "--no-progress"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    procs, logs = [], []
    try:
        time.sleep(4)
        for i, argv in enumerate(monitors):
            log = open(os.path.join(work, "%s-%d.txt" % (name, i)), "w")
            logs.append(log)
            procs.append(subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT))
            time.sleep(1.0)  # (the bridge listens before its client connects)
        text, _ = pipeline.communicate(timeout=600)
    finally:
        if pipeline.poll() is None:
            pipeline.kill()
        for p in reversed(procs):  # the client first, then the bridge
            p.send_signal(signal.SIGINT)
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        for log in logs:
            log.close()
    if pipeline.returncode != 0:
        sys.exit("tick_instructions.py: %s: the run failed:\n%s" % (name, text[-3000:]))
    ticks = re.search(r"^physics\s+admittance_sim\s+(\d+)", text, re.M)
    with open(out, errors="replace") as f:
        total = re.search(r"^(?:totals|summary): (\d+)", f.read(), re.M)
    if not ticks or not total:
        sys.exit("tick_instructions.py: %s: no tick count or callgrind total:\n%s" % (name, text[-3000:]))
    return int(total.group(1)) / int(ticks.group(1)), int(ticks.group(1))


def proof(name, work):
    """The monitor saw the loop's samples (its last process's output), or why not."""
    wanted = {"topic_hz": "rate ", "topic_echo": "child_frame_id", "record_all": "haptics/objects: ",
              "bridge_all": "received "}.get(name)
    if not wanted:
        return None
    path = os.path.join(work, "%s-%d.txt" % (name, 1 if name == "bridge_all" else 0))
    with open(path, errors="replace") as f:
        text = f.read()
    return None if wanted in text else "%s saw no samples of the loop; its output:\n%s" % (name, text[-2000:])


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    cli, sink, out_json = sys.argv[1:]
    rows = {}
    with tempfile.TemporaryDirectory() as work:
        for name, monitors in conditions(cli, sink, work):
            rows[name] = count(cli, name, monitors, work)
            why = proof(name, work)
            if why:
                sys.exit("tick_instructions.py: " + why)
    nothing = rows["nothing"][0]
    print("%-14s %16s %10s" % ("attached", "Ir per tick", "vs nothing"))
    benchmarks = []
    for name, (ir, ticks) in rows.items():
        print("%-14s %16.0f %9.4fx" % (name, ir, ir / nothing))
        benchmarks.append({"name": "TickInstructions/" + name, "instructions_per_tick": ir,
                           "vs_nothing": ir / nothing, "ticks": ticks})
    with open(out_json, "w") as f:
        json.dump({"context": {"date": time.strftime("%Y-%m-%dT%H:%M:%S")}, "benchmarks": benchmarks}, f, indent=1)
    print("wrote " + out_json)


if __name__ == "__main__":
    main()
