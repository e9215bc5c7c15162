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

With --bound causal it flies instead a loop that cannot see the future but knows the past
better than any real one: the swing's true offsets up to the frame just measured (no
measurement noise, no servo belief), forecast by the best fixed linear predictor of its last
--lags frames, fitted per axis by least squares on the whole flight (it knows the flight's
statistics in advance). --noise-px X Y lets it see that past through white measurement noise
instead, to ask what a loop's own measurements leave it. It aims at the same weighted mean as the oracle and commands nothing on
the reference frame, which shows no motion yet. It is not a strict bound (an adaptive forecast
may beat a fixed one where the swing's period drifts), but it is where a causal loop's figures
end up: what the latency jitter and the unforecastable wind leave. The swing before the
reference counts as still, so it is for the first-frame and moving starts only.

Usage: bench/loop-oracle-bound.py TRACE_DIR [--controller predictive] [--start first-frame]
                                   [--bound oracle|causal] [--lags 12] [--noise-px X Y]
                                   [--servo-play DEG] [--servo-dead-band DEG] [--through-play]
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


def aim_of_oracle(open_px, latency):
    """aim(t) [px]: the swing's mean over the frames a command sent after frame t may first
    act on, weighted by how often each is the one in effect."""
    n = len(open_px)
    lead = 1 + latency[0]  # frames from a capture to the first frame its command can show
    shares = delay_shares(latency[1] - latency[0])
    return lambda t: sum(w * open_px[min(t + lead + k, n - 1)] for k, w in enumerate(shares))


def solve(a, b):
    """x with a·x = b (Gaussian elimination with partial pivoting; a is small and square)."""
    m = [row[:] + [v] for row, v in zip(a, b)]
    size = len(m)
    for c in range(size):
        pivot = max(range(c, size), key=lambda r: abs(m[r][c]))
        m[c], m[pivot] = m[pivot], m[c]
        if abs(m[c][c]) < 1e-12:
            continue  # a direction the data never moves: its weight stays 0
        for r in range(size):
            if r != c and m[r][c]:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[r][size] / m[r][r] if abs(m[r][r]) >= 1e-12 else 0.0 for r in range(size)]


def aim_of_causal(open_px, latency, lags, noise_px=0.0, rng=None):
    """aim(t) [px]: the oracle's aim forecast from the swing's last `lags` offsets (the swing
    before frame 0 taken as still), seen through white measurement noise of noise_px RMS, by
    the least-squares linear predictor fitted on the whole flight; 0 on the reference frame,
    which shows no motion yet."""
    n = len(open_px)
    truth = aim_of_oracle(open_px, latency)
    lead = 1 + latency[0] + (latency[1] - latency[0])
    seen = [x + (rng.gauss(0.0, noise_px) if noise_px > 0 and t > 0 else 0.0)
            for t, x in enumerate(open_px)]

    def past(t):
        return [seen[t - i] if t - i >= 0 else 0.0 for i in range(lags)] + [1.0]

    rows = [(past(t), truth(t)) for t in range(1, n - lead)]
    size = lags + 1
    ata = [[sum(r[i] * r[j] for r, _ in rows) for j in range(size)] for i in range(size)]
    atb = [sum(r[i] * y for r, y in rows) for i in range(size)]
    weights = solve(ata, atb)
    return lambda t: sum(w * x for w, x in zip(weights, past(t))) if t >= 1 else 0.0


def oracle_errors(open_px, px_per_deg, command_rate_deg, servo_rate_deg, latency, rng, aim=None,
                  servo=(0.0, 0.0, False)):
    """[px] the view error per frame over one axis's open-loop swing of a loop that commands
    -aim(t) after frame t (default: the oracle's aim). servo = (play [deg], dead band [deg],
    through the play): the shaft moves only towards a target at least the dead band away, and
    drags the output (the camera) through the play; through the play, the command is sent half
    the play beyond the aim on the side the output must move to (ServoBelief::ShaftCommand)."""
    play_deg, dead_band_deg, through_play = servo
    n = len(open_px)
    aim = aim or aim_of_oracle(open_px, latency)
    command = angle = target = 0.0
    shaft = 0.0
    newest = -1
    pending = []  # (frame it first acts on, order, angle [deg])
    errors = []
    for t in range(n):
        errors.append(open_px[t] + px_per_deg * angle)
        want = -aim(t) / px_per_deg
        if through_play and want != angle:
            want += play_deg / 2 if want > angle else -play_deg / 2
        command = max(command - command_rate_deg, min(command + command_rate_deg, want))
        pending.append((t + 1 + rng.randint(latency[0], latency[1]), t, command))
        for arrives, order, value in pending:
            if arrives <= t + 1 and order > newest:
                newest, target = order, value
        pending = [p for p in pending if p[0] > t + 1]
        if abs(target - shaft) >= dead_band_deg:
            shaft += max(-servo_rate_deg, min(servo_rate_deg, target - shaft))
        angle = min(max(angle, shaft - play_deg / 2), shaft + play_deg / 2)
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
    parser.add_argument("--start", default="first-frame", choices=["first-frame", "ssp", "moving"])
    parser.add_argument("--command-rate-deg", type=float, default=3.0,
                        help="[deg/frame] the commands' rate limit (default 90 deg/s at 30 fps)")
    parser.add_argument("--servo-rate-deg", type=float, default=4.0,
                        help="[deg/frame] the servo's turning speed (default 4)")
    parser.add_argument("--latency", type=int, nargs=2, default=[1, 2], metavar=("MIN", "MAX"),
                        help="[frames] the servo's latency range (default 1 2: realistic)")
    parser.add_argument("--draws", type=int, default=20, help="latency draws averaged per flight")
    parser.add_argument("--bound", default="oracle", choices=["oracle", "causal"],
                        help="oracle: knows the future swing; causal: knows only its past, "
                             "exactly, with the best fixed linear forecast (see above)")
    parser.add_argument("--noise-px", type=float, nargs=2, default=[0.0, 0.0],
                        metavar=("X", "Y"),
                        help="[px RMS] the causal bound sees the past through white measurement "
                             "noise this large per axis (default 0 0: the true offsets)")
    parser.add_argument("--px-per-deg", type=float, default=None,
                        help="[px/deg] for flights whose servos never turned enough to read it "
                             "(default: the median read from the folder's other flights)")
    parser.add_argument("--lags", type=int, default=12,
                        help="[frames] the causal bound's forecast looks back this far")
    parser.add_argument("--servo-play", type=float, default=0.0,
                        help="[deg] the servo's play between shaft and output (default 0; the "
                             "simulated hobby servo's is 0.1)")
    parser.add_argument("--servo-dead-band", type=float, default=0.0,
                        help="[deg] the servo ignores targets nearer its shaft (default 0; the "
                             "simulated hobby servo's is 0.05)")
    parser.add_argument("--through-play", action="store_true",
                        help="command half the play beyond the aim on the side the output must "
                             "move to, as the agent does")
    a = parser.parse_args()
    if a.command_rate_deg <= 0 or a.servo_rate_deg <= 0 or a.draws < 1:
        parser.error("rates must be > 0 and --draws ≥ 1")
    if not 1 <= a.lags <= 100:
        parser.error("--lags must be 1…100")
    if not all(0 <= v < 100 for v in a.noise_px):
        parser.error("--noise-px must be 0…100 px per axis")
    if not (0 <= a.servo_play <= 10 and 0 <= a.servo_dead_band <= 10):
        parser.error("--servo-play and --servo-dead-band must be 0…10 deg")
    if a.px_per_deg is not None and not a.px_per_deg > 0:
        parser.error("--px-per-deg must be > 0")
    if a.bound == "causal" and a.start == "ssp":
        parser.error("--bound causal takes the swing before the reference as still, which after "
                     "SSP's free swing it is not: use --start first-frame or moving")
    if not 0 <= a.latency[0] <= a.latency[1]:
        parser.error("--latency needs 0 ≤ MIN ≤ MAX")

    paths = sorted(glob.glob(os.path.join(a.trace_dir, f"trace_*_{a.controller}_{a.start}_*.csv")))
    if not paths:
        sys.exit(f"loop-oracle-bound: no {a.controller} {a.start} traces in {a.trace_dir} "
                 "(run kapfix-bench-loop with --trace --out DIR)")
    print(f"{'flight':52s} {a.bound:>7s} {'loop':>7s} {'ratio':>6s}   "
          + "  ".join(f"{s}-{e or 'end'} {a.bound}/loop" for s, e in SEGMENTS))
    traces = {path: read_trace(path) for path in paths}
    calibrations = {}  # path: [px/deg] read from the flight itself
    for path, rows in traces.items():
        try:
            calibrations[path] = true_px_per_deg(rows)
        except ValueError:
            pass  # a flight whose servos never turned (lost from the start): see below
    fallback = a.px_per_deg
    if fallback is None and calibrations:
        fallback = statistics.median(calibrations.values())
    servo = (a.servo_play, a.servo_dead_band, a.through_play)
    bounds, loops = [], []
    by_scene = {}  # scene: [(bound, loop) per flight]
    for path, rows in traces.items():
        px_per_deg = calibrations.get(path, fallback)
        if px_per_deg is None:
            sys.exit(f"loop-oracle-bound: {path}: the servos never turned more than 2 deg, so "
                     "the calibration cannot be read from the trace: give --px-per-deg")
        if path not in calibrations:
            print(f"loop-oracle-bound: {os.path.basename(path)}: the servos never turned more "
                  f"than 2 deg; flown at {px_per_deg:.3g} px/deg", file=sys.stderr)
        seed = int(path.rsplit("_", 1)[1].split(".")[0])
        # Frame 0 is the reference: the swing's offsets start from 0 there.
        open_x = [0.0] + [float(r["open_x"]) for r in rows]
        open_y = [0.0] + [float(r["open_y"]) for r in rows]
        # The aims are the same in every draw unless the causal loop sees fresh noise in each.
        redrawn = a.bound == "causal" and any(noise > 0 for noise in a.noise_px)
        if a.bound == "oracle":
            aims = [aim_of_oracle(o, a.latency) for o in (open_x, open_y)]
        elif not redrawn:
            aims = [aim_of_causal(o, a.latency, a.lags) for o in (open_x, open_y)]
        bound_sq = [0.0] * len(rows)
        for draw in range(a.draws):
            rng = random.Random(seed * 1000 + draw)
            if redrawn:
                aims = [aim_of_causal(o, a.latency, a.lags, noise, rng)
                        for o, noise in zip((open_x, open_y), a.noise_px)]
            ex = oracle_errors(open_x, px_per_deg, a.command_rate_deg, a.servo_rate_deg,
                               a.latency, rng, aims[0], servo)
            ey = oracle_errors(open_y, px_per_deg, a.command_rate_deg, a.servo_rate_deg,
                               a.latency, rng, aims[1], servo)
            for k in range(len(rows)):
                bound_sq[k] += (ex[k + 1] ** 2 + ey[k + 1] ** 2) / a.draws
        loop_sq = [float(r["err_x"]) ** 2 + float(r["err_y"]) ** 2 for r in rows]
        bound, loop = rms(bound_sq), rms(loop_sq)
        bounds.append(bound)
        loops.append(loop)
        segments = "  ".join(f"{rms(bound_sq[s:e]):6.2f}/{rms(loop_sq[s:e]):6.2f}"
                             for s, e in SEGMENTS)
        name = os.path.basename(path)[len("trace_"):-len(".csv")]
        print(f"{name:52s} {bound:7.2f} {loop:7.2f} {loop / bound:6.2f}   {segments}")
        scene = name.split(f"_{a.controller}_{a.start}_")[0].split("_", 1)[-1]
        by_scene.setdefault(scene, []).append((bound, loop))
    # The figure: per scene the mean over seeds, then the median over scenes.
    if len(by_scene) > 1:
        print(f"median over {len(by_scene)} scenes of the mean over seeds [px]: {a.bound} "
              f"{statistics.median(statistics.mean(b for b, _ in v) for v in by_scene.values()):.2f}"
              f", loop "
              f"{statistics.median(statistics.mean(l for _, l in v) for v in by_scene.values()):.2f}")
    print(f"median over {len(paths)} flights [px]: {a.bound} {statistics.median(bounds):.2f}, "
          f"loop {statistics.median(loops):.2f}")


if __name__ == "__main__":
    main()
