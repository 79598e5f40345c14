#!/usr/bin/env python3
"""Joint speeds after a lost setpoint stream, from a monitor's records (`wysiwyf topic echo` YAML).

Usage: speeds_after_loss.py JOINT_STATES SETPOINTS PERIOD_MS
The loss is the last setpoint's stamp; the tracker may carry the arm on for one period of the
stream (PERIOD_MS: the period the arm measured, as its fault text gives it, rounded up) from the
setpoint's arrival, no longer: the next setpoint was due at the
last stamp + PERIOD_MS + the delivery (allowed 5 ms on a loaded machine). From then on no joint
may speed up beyond noise: prints each
joint's speed when the next setpoint was due and the largest speed after it, and exits 1 when a
joint sped up by more than 1 mrad/s + 1 % of the fastest joint's speed (the simulated arm's rule).
"""
import sys

import yaml

DELIVERY_MS = 5  # from the sender's stamp to the arm's tick that takes the setpoint, at most


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


def main():
    joints, setpoints, period_ms = docs(sys.argv[1]), docs(sys.argv[2]), float(sys.argv[3])
    if not joints or not setpoints:
        print(f"no record: {len(joints)} joint states, {len(setpoints)} setpoints")
        return 1
    last = max(s["header"]["stamp_ns"] for s in setpoints)
    due = last + int((period_ms + DELIVERY_MS) * 1e6)
    joints.sort(key=lambda d: d["header"]["stamp_ns"])
    before = [d for d in joints if d["header"]["stamp_ns"] <= due]
    after = [d for d in joints if d["header"]["stamp_ns"] > due]
    if not before or len(after) < 100:
        print(f"the record does not span the loss: {len(before)} joint states before, {len(after)} after")
        return 1
    at_due = [abs(v) for v in before[-1]["velocity"]]
    peak = [max(abs(d["velocity"][j]) for d in after) for j in range(6)]
    speed_up = max(p - v for p, v in zip(peak, at_due))
    still = next((d["header"]["stamp_ns"] for d in after if max(abs(v) for v in d["velocity"]) < 1e-3), None)
    still_ms = f"{(still - last) * 1e-6:.0f} ms" if still else "not within the record"
    tolerance = 1e-3 + 0.01 * max(at_due)
    print("speeds when the next setpoint was due [rad/s]: " + " ".join(f"{v:.3f}" for v in at_due) +
          "; largest after: " + " ".join(f"{v:.3f}" for v in peak) +
          f"; largest speed-up {speed_up:.4f} rad/s (allowed {tolerance:.4f}); still (< 1 mrad/s) {still_ms} "
          f"after the last setpoint ({len(after)} joint states after)")
    return 0 if speed_up <= tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
