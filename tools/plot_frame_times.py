"""Frame times of `planet bench` along its camera path, as a PNG.

Embedded in the planet binary (planet bench --plot FILE.png runs it with python3); it also runs
on its own:  python3 tools/plot_frame_times.py OUT.png [TITLE] < bench.csv  (planet bench --csv).
Input: the CSV on stdin. Output: the PNG on stdout when OUT is '-', else in OUT.
Top panel: the first mode's GPU passes stacked, and on top of them the rest of the wall-clock
frame (CPU work, waiting, read-back); the camera's height above the ground on a log axis at the
right. Bottom panel, when the CSV holds several modes (--compare): terrain time per mode.
Exit status 3 when matplotlib is missing.
"""
import csv
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.stderr.write("matplotlib is not installed for this python3\n")
    sys.exit(3)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "-"
    title = sys.argv[2] if len(sys.argv) > 2 else "planet bench"
    reader = csv.DictReader(sys.stdin)
    rows = list(reader)
    if not rows:
        sys.stderr.write("no frames in the CSV\n")
        sys.exit(1)
    modes = []
    for row in rows:
        if row["mode"] not in modes:
            modes.append(row["mode"])
    first = [row for row in rows if row["mode"] == modes[0]]
    frames = [int(row["frame"]) for row in first]
    passes = [
        c for c in reader.fieldnames if c.startswith("pass_") and any(float(row[c]) > 0 for row in first)
    ]
    stack = [[float(row[c]) for row in first] for c in passes]
    rest = [
        max(0.0, float(row["frame_ms"]) - sum(float(row[c]) for c in passes)) for row in first
    ]
    labels = [c[len("pass_") : -len("_ms")] for c in passes] + ["rest of the frame (CPU, waiting, read-back)"]

    panels = 2 if len(modes) > 1 else 1
    fig, axes = plt.subplots(panels, 1, figsize=(8, 3.4 * panels), dpi=80, sharex=True, squeeze=False)
    top = axes[0][0]
    top.stackplot(frames, *stack, rest, labels=labels, alpha=0.85)
    top.set_ylabel("ms per frame")
    top.set_title(f"{title}: mode {modes[0]}", fontsize=10)
    top.legend(loc="upper left", fontsize=8)
    height = top.twinx()
    height.plot(frames, [float(row["height_m"]) for row in first], color="black", linestyle="--", linewidth=1)
    height.set_yscale("log")
    height.set_ylabel("height above ground (m, dashed)")
    if panels == 2:
        bottom = axes[1][0]
        for mode in modes:
            series = [row for row in rows if row["mode"] == mode]
            bottom.plot([int(r["frame"]) for r in series], [float(r["terrain_ms"]) for r in series], label=mode)
        bottom.set_yscale("log")
        bottom.set_ylabel("terrain time (ms)")
        bottom.legend(loc="upper left", fontsize=8)
    axes[-1][0].set_xlabel("frame (evenly spaced in path time)")
    fig.tight_layout()
    if out == "-":
        fig.savefig(sys.stdout.buffer, format="png")
    else:
        fig.savefig(out, format="png")


main()
