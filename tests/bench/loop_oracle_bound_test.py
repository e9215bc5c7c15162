#!/usr/bin/env python3
"""bench/loop-oracle-bound.py on synthetic traces (one behaviour per check).

Usage: loop_oracle_bound_test.py SCRIPT
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

COLUMNS = ["frame", "err_x", "err_y", "true_pan", "true_tilt", "open_x", "open_y"]
PX_PER_DEG = 10.0


def write_trace(folder, seed, open_x, servo_deg):
    """A trace whose loop turned the servo by servo_deg [deg] per frame (pan only)."""
    path = os.path.join(folder, f"trace_test_scene.jpg_predictive_first-frame_1.00_{seed}.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for k, (o, deg) in enumerate(zip(open_x, servo_deg), start=1):
            w.writerow([k, o + PX_PER_DEG * deg, 0, deg, 0, o, 0])


def run(script, folder, *args):
    return subprocess.run([sys.executable, script, folder, *args], capture_output=True, text=True)


def median_figures(stdout):
    """(bound, loop) from the script's last line: "median over N flights [px]: B x, loop y"."""
    last = stdout.strip().splitlines()[-1]
    bound = float(last.split(": ")[1].split(",")[0].split()[1])
    loop = float(last.split("loop ")[1])
    return bound, loop


def main():
    script = sys.argv[1]
    failures = []
    # A slow swing (period 200 frames, 50 px) that the loop followed one frame late.
    swing = [50 * math.sin(2 * math.pi * k / 200) for k in range(1, 401)]
    late = [-swing[k - 1] / PX_PER_DEG if k else 0.0 for k in range(len(swing))]
    # Turns the servo by more than 2 deg, so the script can read the calibration.
    with tempfile.TemporaryDirectory() as folder:
        write_trace(folder, 1, swing, late)
        # A fixed latency and a slow swing: the oracle cancels it after its first frames, far
        # below the loop that lagged a frame.
        r = run(script, folder, "--latency", "1", "1")
        if r.returncode != 0:
            failures.append(f"fixed latency run failed: {r.stderr}")
        else:
            oracle, loop = median_figures(r.stdout)
            if not oracle < 0.2 * loop:
                failures.append(f"oracle {oracle} px not well below the late loop's {loop} px")
        # Jitter costs even the oracle: it cannot know which latency a command takes.
        r_jitter = run(script, folder, "--latency", "1", "3")
        if r_jitter.returncode == 0 and r.returncode == 0:
            if not median_figures(r_jitter.stdout)[0] > median_figures(r.stdout)[0]:
                failures.append("latency jitter did not raise the oracle's figure")
        # A servo's play leaves the output behind the shaft; commanded through the play, the
        # output reaches the aim again.
        r_play = run(script, folder, "--latency", "1", "1", "--servo-play", "0.4")
        r_through = run(script, folder, "--latency", "1", "1", "--servo-play", "0.4",
                        "--through-play")
        if r_play.returncode != 0 or r_through.returncode != 0 or r.returncode != 0:
            failures.append(f"play runs failed: {r_play.stderr} {r_through.stderr}")
        else:
            none = median_figures(r.stdout)[0]
            play = median_figures(r_play.stdout)[0]
            through = median_figures(r_through.stdout)[0]
            if not play > none + 1.0:
                failures.append(f"0.4 deg of play did not raise the oracle: {play} against {none}")
            if not through < none + 0.25 * (play - none):
                failures.append(f"through the play the oracle stayed at {through} px "
                                f"(no play {none}, play {play})")
        # Servos that turn slowly cannot follow the swing even knowing it.
        r_slow = run(script, folder, "--latency", "1", "1", "--servo-rate-deg", "0.05")
        if r_slow.returncode == 0 and r.returncode == 0:
            if not median_figures(r_slow.stdout)[0] > 5 * median_figures(r.stdout)[0]:
                failures.append("a slow servo did not raise the oracle's figure")
    # The causal bound knows only the swing's past: under latency jitter it stays above the
    # oracle, yet at a fixed latency a swing its linear forecast can follow (a sinusoid is
    # exactly AR(2)) costs it far less than the loop that lagged a frame.
    with tempfile.TemporaryDirectory() as folder:
        write_trace(folder, 1, swing, late)
        oracle = run(script, folder, "--latency", "1", "2")
        causal = run(script, folder, "--latency", "1", "2", "--bound", "causal")
        if oracle.returncode != 0 or causal.returncode != 0:
            failures.append(f"causal run failed: {causal.stderr}")
        else:
            bound = median_figures(causal.stdout)[0]
            if not bound > median_figures(oracle.stdout)[0]:
                failures.append(f"the causal bound {bound} px is not above the oracle's")
        fixed = run(script, folder, "--latency", "1", "1", "--bound", "causal")
        if fixed.returncode != 0:
            failures.append(f"causal run at a fixed latency failed: {fixed.stderr}")
        else:
            bound, loop = median_figures(fixed.stdout)
            if not bound < 0.3 * loop:
                failures.append(f"the causal bound {bound} px is not well below the late loop's")
            # Seen through measurement noise, the same past forecasts worse.
            noisy = run(script, folder, "--latency", "1", "1", "--bound", "causal",
                        "--noise-px", "2", "2")
            if noisy.returncode != 0 or not median_figures(noisy.stdout)[0] > bound:
                failures.append(f"measurement noise did not raise the causal bound: {noisy.stderr}")
        # After SSP the swing before the reference was not still: refused, saying why.
        r = run(script, folder, "--bound", "causal", "--start", "ssp")
        if r.returncode == 0 or "SSP" not in r.stderr:
            failures.append(f"a causal bound after SSP was not refused: {r.stderr}")
    # No traces: a clear error naming the folder, and a non-zero exit.
    with tempfile.TemporaryDirectory() as empty:
        r = run(script, empty)
        if r.returncode == 0 or empty not in r.stderr:
            failures.append(f"an empty folder was not refused by name: {r.returncode} {r.stderr}")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
