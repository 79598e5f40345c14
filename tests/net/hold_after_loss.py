#!/usr/bin/env python3
"""The arm's hold after a lost setpoint stream, judged from a monitor's records.

Usage: hold_after_loss.py JOINT_STATES SETPOINTS STATUSES   (`wysiwyf topic echo` YAML records)

The arm's first "setpoint stream lost" status after the last recorded setpoint is stamped at
the tick that noticed the loss, and its reason gives N (no setpoint for N ms: since the tick
that took the last setpoint, its arrival), P (the stream's period the arm learned: the longest
of the last 8 intervals between the stamps it got) and L (the timeout: 3 P, capped). Two
checks, one line each:
- the hold: P is the stream's as the monitor recorded it (the last 8 intervals up to the last
  setpoint stamped before the arrival, within 1 ms: P is in whole ms), L is at most 3 (P + 1), and
  the arm noticed at its first tick after L (no joint state, one a tick, stamped between; on this
  VM a tick has run up to 27 ms late, so N itself is not bounded). The stream's
  period is what the sender made of it: a loaded 2-core machine has made a 100 Hz stream's 10 ms
  into 25, so it is measured, not assumed;
- no speed-up: the tracker carries the arm on along the last setpoint for P from its arrival, no
  longer; the first tick after that stops it, and the next joint state carries that tick's
  velocity: due = arrival + P + 3 ms (1 for N and P in whole ms, 2 for the two ticks). From then
  on no joint may speed up by more than 1 mrad/s + 1 % of the fastest joint's speed (the
  simulated arm's rule). The arrival is the arm's own, not the sender's stamp plus a guess at the
  delivery, which a loaded machine has stretched past 5 ms.
Prints "FAILED: " before a check that fails; exits with the number of failed checks.
"""
import re
import sys
from dataclasses import dataclass

import yaml


def docs(path):
    """The samples of an echo record, one YAML document each (a cut-off last one skipped)."""
    out = []
    with open(path) as f:
        text = f.read()
    for chunk in text.split("\n---\n"):
        chunk = chunk.strip()
        if chunk.startswith("---"):
            chunk = chunk[3:]
        try:
            d = yaml.safe_load(chunk)
        except yaml.YAMLError:
            continue
        if isinstance(d, dict) and "header" in d:
            out.append(d)
    return out


def stamp(d):
    return d["header"]["stamp_ns"]


@dataclass
class Loss:
    """The arm's "setpoint stream lost" fault: N, P, L in whole ms, times in ns."""
    n: int
    p: int
    l: int
    reason: str
    stamp_ns: int  # the arm's tick that noticed the loss
    arrival_ns: int  # the arm's tick that took the last setpoint: the fault's stamp - N


def the_loss(statuses, setpoints):
    """The first "setpoint stream lost" fault after the last recorded setpoint, or None. (An
    earlier one is a loss the arm recovered from: a loaded machine makes a 250 Hz stream miss its
    3 periods now and then, and the display starts the arm again.)"""
    last = max(map(stamp, setpoints), default=0)
    for s in sorted(statuses, key=stamp):
        if stamp(s) <= last:
            continue
        reason = s.get("reason", "")
        m = re.search(r"no setpoint for (\d+) ms.*came every (\d+) ms; lost after (\d+) ms", reason)
        if s.get("state") == "ARM_FAULT" and "setpoint stream lost" in reason and m:
            n, p, l = (int(g) for g in m.groups())
            return Loss(n, p, l, reason, stamp(s), stamp(s) - n * 1_000_000)
    return None


def hold(setpoints, joints, loss):
    got = sorted(t for t in map(stamp, setpoints) if t <= loss.arrival_ns)
    if len(got) < 9:
        return False, f"the record does not span the stream before the loss ({len(got)} setpoints): {loss.reason}"
    longest = max(b - a for a, b in zip(got[-9:-1], got[-8:])) * 1e-6
    # The arm's ticks between the timeout and the one that noticed, from its joint states (one
    # each tick, stamped with it): N and L are whole ms, so the timeout is within 1 ms of
    # arrival + L. A tick the machine ran late makes N late, not the hold.
    timeout_ns = loss.arrival_ns + (loss.l + 1) * 1_000_000
    missed = sum(1 for t in map(stamp, joints) if timeout_ns < t < loss.stamp_ns)
    text = (f"{loss.reason}; the stream as recorded: its last 8 intervals at most {longest:.1f} ms, the last "
            f"setpoint taken {(loss.arrival_ns - got[-1]) * 1e-6:.0f} ms after its stamp; noticed "
            + ("at the arm's first tick after the timeout" if not missed else
               f"{missed} of the arm's ticks after the timeout"))
    return abs(loss.p - longest) <= 1.0 and loss.l <= 3 * (loss.p + 1) and not missed, text


def speeds(joints, loss):
    due = loss.arrival_ns + (loss.p + 3) * 1_000_000
    joints = sorted(joints, key=stamp)
    before = [d for d in joints if stamp(d) <= due]
    after = [d for d in joints if stamp(d) > due]
    if not before or len(after) < 100:
        return False, f"the record does not span the loss: {len(before)} joint states before, {len(after)} after"
    at_due = [abs(v) for v in before[-1]["velocity"]]
    peak = [max(abs(d["velocity"][j]) for d in after) for j in range(6)]
    speed_up = max(pk - v for pk, v in zip(peak, at_due))
    still = next((stamp(d) for d in after if max(abs(v) for v in d["velocity"]) < 1e-3), None)
    still_ms = f"{(still - loss.arrival_ns) * 1e-6:.0f} ms" if still else "not within the record"
    tolerance = 1e-3 + 0.01 * max(at_due)
    text = ("speeds when the tracker stopped carrying the arm on [rad/s]: " + " ".join(f"{v:.3f}" for v in at_due) +
            "; largest after: " + " ".join(f"{v:.3f}" for v in peak) +
            f"; largest speed-up {speed_up:.4f} rad/s (allowed {tolerance:.4f}); still (< 1 mrad/s) {still_ms} "
            f"after the last setpoint's arrival ({len(after)} joint states after)")
    return speed_up <= tolerance, text


def main():
    joints, setpoints, statuses = (docs(p) for p in sys.argv[1:4])
    loss = the_loss(statuses, setpoints)
    if loss is None:
        print(f"FAILED: no 'setpoint stream lost' fault after the last of {len(setpoints)} setpoints among the "
              f"{len(statuses)} statuses recorded")
        return 2
    failed = 0
    for what, (ok, text) in (("the arm holds within 3 of the stream's periods", hold(setpoints, joints, loss)),
                             ("no joint sped up after the loss", speeds(joints, loss))):
        print(("" if ok else "FAILED: ") + f"{what}: {text}")
        failed += not ok
    return failed


if __name__ == "__main__":
    sys.exit(main())
