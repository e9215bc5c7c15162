#!/usr/bin/env python3
"""What a loop that knew the future could do in the flights of `kapfix-bench-loop --trace`.

Issue 9 asks for a realistic-world median of 5 px. The aim floor (AimFloorRms) counts only the
latency jitter; from the first frame the loop also starts blind, with the swing already moving,
and its servos turn at a bounded rate. This flies, per traced flight, an oracle loop over the
same open-loop swing (the trace's open_x / open_y): after frame t it commands the angle that
would cancel the swing's mean over the frames the command may act on first, weighted by how
often each is (DelayShares: the aim that misses least), rate-limited like the agent's commands, through a servo
with the flight's latency draw rule (uniform over min…max, the newest arrived command wins)
and turning speed. It knows the swing exactly, frames not yet seen included, and the true
degrees per pixel, so no controller does better; it ignores dead band, play and dropped
frames, so it is a bound, not a prediction. Latency draws are random: it averages --draws.

Usage: bench/loop-oracle-bound.py TRACE_DIR [--controller predictive] [--start first-frame]
The servo figures default to the agent's built-in simulation (kapfix-bench-loop's header:
rate limit 90 deg/s at 30 frames/s, servos 4 deg/frame, latency 1…2 frames in the realistic
world).
"""
import argparse
import csv
import glob
import math
import os
import random
import statistics
import sys

SEGMENTS = [(0, 5), (5, 20), (20, 50), (50, 150), (150, None)]  # [frames] of the flight


def delay_shares(spread):
    """[1] how often a command is in effect lead + k frames after (ServoBelief's DelayShares)."""
    shares, none_before = [], 1.0
    for k in range(spread + 1):
        late = (spread - k) / (spread + 1)
        shares.append(none_before * (1 - late))
        none_before *= late
    return shares


def oracle_errors(open_px, px_per_deg, command_rate_deg, servo_rate_deg, latency, rng):
    """[px] the oracle's view error per frame over one axis's open-loop swing."""
    n = len(open_px)
    lead = 1 + latency[0]  # frames from a capture to the first frame its command can show
    shares = delay_shares(latency[1] - latency[0])

    def swing(i):
        return open_px[min(i, n - 1)]

    command = angle = target = 0.0
    newest = -1
    pending = []  # (frame it first acts on, order, angle [deg])
    errors = []
    for t in range(n):
        errors.append(open_px[t] + px_per_deg * angle)
        want = -sum(w * swing(t + lead + k) for k, w in enumerate(shares)) / px_per_deg
        command = max(command - command_rate_deg, min(command + command_rate_deg, want))
        pending.append((t + 1 + rng.randint(latency[0], latency[1]), t, command))
        for arrives, order, value in pending:
            if arrives <= t + 1 and order > newest:
                newest, target = order, value
        pending = [p for p in pending if p[0] > t + 1]
        angle += max(-servo_rate_deg, min(servo_rate_deg, target - angle))
    return errors


def read_trace(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "open_x" not in rows[0]:
        raise ValueError(f"{path}: not a kapfix-bench-loop trace (no open_x column)")
    return rows


def true_px_per_deg(rows):
    """[px/deg] from the trace itself: view error = open offset + px_per_deg · true angle."""
    ratios = []
    for r in rows:
        for axis, pan in (("x", "true_pan"), ("y", "true_tilt")):
            deg = float(r[pan])
            if abs(deg) > 2:
                ratios.append((float(r["err_" + axis]) - float(r["open_" + axis])) / deg)
    if not ratios:
        raise ValueError("the servos never turned more than 2 deg: cannot read the calibration")
    return statistics.median(ratios)


def rms(values):
    values = [v for v in values if math.isfinite(v)]
    return math.sqrt(sum(values) / len(values)) if values else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("trace_dir", help="the --out folder of kapfix-bench-loop --trace")
    parser.add_argument("--controller", default="predictive")
    parser.add_argument("--start", default="first-frame", choices=["first-frame", "ssp"])
    parser.add_argument("--command-rate-deg", type=float, default=3.0,
                        help="[deg/frame] the commands' rate limit (default 90 deg/s at 30 fps)")
    parser.add_argument("--servo-rate-deg", type=float, default=4.0,
                        help="[deg/frame] the servo's turning speed (default 4)")
    parser.add_argument("--latency", type=int, nargs=2, default=[1, 2], metavar=("MIN", "MAX"),
                        help="[frames] the servo's latency range (default 1 2: realistic)")
    parser.add_argument("--draws", type=int, default=20, help="latency draws averaged per flight")
    a = parser.parse_args()
    if a.command_rate_deg <= 0 or a.servo_rate_deg <= 0 or a.draws < 1:
        parser.error("rates must be > 0 and --draws ≥ 1")
    if not 0 <= a.latency[0] <= a.latency[1]:
        parser.error("--latency needs 0 ≤ MIN ≤ MAX")

    paths = sorted(glob.glob(os.path.join(a.trace_dir, f"trace_*_{a.controller}_{a.start}_*.csv")))
    if not paths:
        sys.exit(f"loop-oracle-bound: no {a.controller} {a.start} traces in {a.trace_dir} "
                 "(run kapfix-bench-loop with --trace --out DIR)")
    print(f"{'flight':52s} {'oracle':>7s} {'loop':>7s} {'ratio':>6s}   "
          + "  ".join(f"{s}-{e or 'end'} oracle/loop" for s, e in SEGMENTS))
    oracles, loops = [], []
    for path in paths:
        rows = read_trace(path)
        px_per_deg = true_px_per_deg(rows)
        seed = int(path.rsplit("_", 1)[1].split(".")[0])
        # Frame 0 is the reference: the swing's offsets start from 0 there.
        open_x = [0.0] + [float(r["open_x"]) for r in rows]
        open_y = [0.0] + [float(r["open_y"]) for r in rows]
        oracle_sq = [0.0] * len(rows)
        for draw in range(a.draws):
            rng = random.Random(seed * 1000 + draw)
            ex = oracle_errors(open_x, px_per_deg, a.command_rate_deg, a.servo_rate_deg,
                               a.latency, rng)
            ey = oracle_errors(open_y, px_per_deg, a.command_rate_deg, a.servo_rate_deg,
                               a.latency, rng)
            for k in range(len(rows)):
                oracle_sq[k] += (ex[k + 1] ** 2 + ey[k + 1] ** 2) / a.draws
        loop_sq = [float(r["err_x"]) ** 2 + float(r["err_y"]) ** 2 for r in rows]
        oracle, loop = rms(oracle_sq), rms(loop_sq)
        oracles.append(oracle)
        loops.append(loop)
        segments = "  ".join(f"{rms(oracle_sq[s:e]):6.2f}/{rms(loop_sq[s:e]):6.2f}"
                             for s, e in SEGMENTS)
        name = os.path.basename(path)[len("trace_"):-len(".csv")]
        print(f"{name:52s} {oracle:7.2f} {loop:7.2f} {loop / oracle:6.2f}   {segments}")
    print(f"median over {len(paths)} flights [px]: oracle {statistics.median(oracles):.2f}, "
          f"loop {statistics.median(loops):.2f}")


if __name__ == "__main__":
    main()
