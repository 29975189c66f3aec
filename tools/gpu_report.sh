#!/usr/bin/env bash
# The figures of a GPU (issue 21, point 8), for docs/benchmarks.md: runs, on the Vulkan device
# planet picks (PLANET_DEVICE=NAME-SUBSTRING chooses another),
#   1. planet validate                     GPU noise against the CPU reference; the tolerance is
#                                          chosen by the device (bit-identical on lavapipe, 1e-4
#                                          relative on drivers that may fuse multiply-adds)
#   2. planet bench noise                  noise evaluations per second, GPU and CPU
#   3. planet bench --size 1920x1080 --compare
#                                          frame times along the default path, and the terrain
#                                          modes' ratios (vertex shader, CPU heights, no octave limit)
#   4. planet bench --size 1920x1080 --terrain-shading deferred
#                                          the same path with the ground shaded in a compute pass
#                                          over a G-buffer (against 3's forward frames)
#   5. planet bench --size 1920x1080 --in-flight 2 (forward and deferred)
#                                          the frames as the viewer draws them, two in flight: each
#                                          prepared while the one before executes, timed from that
#                                          one's end to its own on the GPU's clock
#   6. planet render of three views       OUT_DIR/orbit.png, land_1500m.png and ground_sunset.png
#                                          (960x540), to hold against lavapipe's pictures
# and writes OUT_DIR/gpu_report.json (the reports whole, the renders' exit codes, the device and
# the commit) and OUT_DIR/gpu_report.txt (a summary naming the device). A validation failure or a
# failed render is reported, not fatal: the rest still runs, and the script exits 1 at the end.
#
# Usage: tools/gpu_report.sh [OUT_DIR]     (default: ./gpu_report; after a build)
# Environment:
#   PLANET=path/to/planet       the binary (default: this checkout's build/release/apps/planet)
#   GPU_REPORT_QUICK=1          a check of the script itself in seconds, on lavapipe too: 160x90,
#                               3 timed frames, 4,096 validation points, 100,000 noise points
#   GPU_REPORT_SIZE=WxH         frame benchmark size (default 1920x1080)
#   GPU_REPORT_FRAMES=N         timed frames (default the benchmark's, 120)
#   GPU_REPORT_COMMIT=HASH      the commit to name when the checkout has no .git (a copied tree)
#   GPU_REPORT_VALIDATION=1     render the views with the Vulkan validation layers (any message
#                               fails that render)
set -euo pipefail
out=${1:-gpu_report}
root=$(cd "$(dirname "$0")/.." && pwd)
planet=${PLANET:-$root/build/release/apps/planet}
[ -x "$planet" ] || { echo "gpu_report: $planet not found; build first (./tools/setup.sh)" >&2; exit 1; }
command -v python3 > /dev/null || { echo "gpu_report: python3 is needed to merge the reports" >&2; exit 1; }

validate_args=()
noise_args=()
render_args=(--size 960x540)
bench_args=(--size "${GPU_REPORT_SIZE:-1920x1080}")
if [[ ${GPU_REPORT_QUICK:-0} == 1 ]]; then
  validate_args=(--points 4096)
  noise_args=(--points 100000 --repeats 5)
  bench_args=(--size "${GPU_REPORT_SIZE:-160x90}" --frames "${GPU_REPORT_FRAMES:-3}" --warmup 1)
  render_args=(--size 160x90)
elif [[ -n ${GPU_REPORT_FRAMES:-} ]]; then
  bench_args+=(--frames "$GPU_REPORT_FRAMES")
fi

mkdir -p "$out"
work=$(mktemp -d "$out/.gpu_report.XXXXXX")
trap 'rm -rf "$work"' EXIT

echo "gpu_report: planet validate ${validate_args[*]}" >&2
validate_status=0
"$planet" validate "${validate_args[@]}" --json "$work/validate.json" > "$work/validate.txt" || validate_status=$?
# Exit 1 is a result (out of tolerance, with its JSON written); anything else is a failure to run.
if [[ $validate_status -ne 0 && ! -s $work/validate.json ]]; then
  echo "gpu_report: planet validate failed (exit $validate_status); see above" >&2
  exit 1
fi
echo "gpu_report: planet bench noise ${noise_args[*]}" >&2
"$planet" bench noise "${noise_args[@]}" --json "$work/noise.json" > "$work/noise.txt"
echo "gpu_report: planet bench --compare ${bench_args[*]}" >&2
"$planet" bench --compare "${bench_args[@]}" --json "$work/frames.json" > "$work/frames.txt"
echo "gpu_report: planet bench --terrain-shading deferred ${bench_args[*]}" >&2
"$planet" bench --terrain-shading deferred "${bench_args[@]}" --json "$work/frames_deferred.json" \
  > "$work/frames_deferred.txt"
for shading in forward deferred; do
  echo "gpu_report: planet bench --in-flight 2 --terrain-shading $shading ${bench_args[*]}" >&2
  "$planet" bench --in-flight 2 --terrain-shading "$shading" "${bench_args[@]}" \
    --json "$work/frames_in_flight_$shading.json" > "$work/frames_in_flight_$shading.txt"
done

# Three views: Earth from 20,000 km, land from 1.5 km, the ground at sunset looking at the sun
# (about 2 m above the ground there, which lies at 494 m).
render_flags=()
[[ ${GPU_REPORT_VALIDATION:-0} == 1 ]] && render_flags=(--validation)
renders=()
render_failed=0
for view in "orbit|20,-30,2e7,0,-90|135,35" "land_1500m|33.82,-89.95,1500,60,-8|135,35" \
            "ground_sunset|33.82,-89.95,496,240,3|240,2"; do
  IFS='|' read -r name camera sun <<< "$view"
  echo "gpu_report: planet render --camera $camera --sun $sun ${render_args[*]}" >&2
  status=0
  "$planet" "${render_flags[@]}" render --camera "$camera" --sun "$sun" "${render_args[@]}" --out "$out/$name.png" \
    > "$work/render_$name.txt" 2>&1 || status=$?
  if [[ $status -ne 0 ]]; then
    render_failed=1
    echo "gpu_report: the $name render failed (exit $status):" >&2
    cat "$work/render_$name.txt" >&2
  fi
  renders+=("$name|$camera|$sun|$status")
done

commit=${GPU_REPORT_COMMIT:-$(git -C "$root" rev-parse --short HEAD 2> /dev/null || echo unknown)}
python3 - "$work" "$out" "$commit" "$validate_status" "${bench_args[*]}" "${GPU_REPORT_VALIDATION:-0}" "${renders[@]}" << 'EOF'
import datetime, json, sys
work, out, commit, validate_status, bench_args = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
validation = sys.argv[6] == "1"
renders = []
for entry in sys.argv[7:]:
    name, camera, sun, status = entry.split("|")
    renders.append({"file": f"{name}.png", "camera": camera, "sun": sun, "exit": int(status), "validation": validation})
load = lambda name: json.load(open(f"{work}/{name}.json"))
validate, noise, frames, deferred = load("validate"), load("noise"), load("frames"), load("frames_deferred")
in_flight = {shading: load(f"frames_in_flight_{shading}") for shading in ("forward", "deferred")}
report = {
    "device": frames["device"], "driver": frames["driver"], "commit": commit,
    "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    "validate": validate, "bench_noise": noise, "bench_frames": frames,
    "bench_frames_deferred": deferred, "bench_frames_in_flight": in_flight, "renders": renders,
}
json.dump(report, open(f"{out}/gpu_report.json", "w"), indent=2)

lines = [f"device: {frames['device']} ({frames['driver']}), commit {commit}, {report['date']}", ""]
cases = validate["cases"]
passed = sum(1 for c in cases if c.get("pass"))
lines.append(f"planet validate: {'PASS' if validate['pass'] else 'FAIL'}, {passed} of {len(cases)} cases within "
             f"tolerance ({validate['policy']})")
rates = {r["method"] + ("" if r["output"] == "value" else " (" + r["output"] + ")"): r["mevals_per_s"]
         for r in noise["results"]}
lines.append(f"planet bench noise ({noise['points']} points): " +
             ", ".join(f"{m} {v:.1f}" for m, v in rates.items()) + " M evaluations/s")
f = frames["frame_ms"]
gpu = frames["gpu_ms"]
lines.append(f"planet bench {bench_args} --compare ({frames['frames']} frames, {frames['width']}x{frames['height']}): "
             f"frame median {f['median']:.2f} ms, p99 {f['p99']:.2f} ms; GPU median {gpu['median']:.2f} ms")
lines.append("  passes (median ms): " + ", ".join(f"{n} {p['median']:.2f}" for n, p in frames["passes"].items()))
if frames["compare"]:
    lines.append("  terrain time ratios to compute: " +
                 ", ".join(f"{m} {r:.2f}x" for m, r in frames["compare"].items()))
d = deferred["frame_ms"]
lines.append(f"planet bench {bench_args} --terrain-shading deferred: frame median {d['median']:.2f} ms, "
             f"p99 {d['p99']:.2f} ms; GPU median {deferred['gpu_ms']['median']:.2f} ms")
lines.append("  passes (median ms): " + ", ".join(f"{n} {p['median']:.2f}" for n, p in deferred["passes"].items()))
for shading, run in in_flight.items():
    p = run["frame_ms"]
    lines.append(f"planet bench {bench_args} --in-flight 2 --terrain-shading {shading}: frame median {p['median']:.2f} ms "
                 f"(GPU clock, end to end), p99 {p['p99']:.2f} ms; GPU median {run['gpu_ms']['median']:.2f} ms, "
                 f"prepare {run['prepare_ms']['median']:.2f} ms")
if (frames["width"], frames["height"]) == (1920, 1080):
    best = min(f["median"], d["median"])
    best_in_flight = min(run["frame_ms"]["median"] for run in in_flight.values())
    met = "met" if best <= 3.3 else "not met"
    lines.append(f"  issue 21 target, 1080p median <= 3.3 ms: {met} one frame at a time (the faster shading's "
                 f"{best:.2f} ms); {'met' if best_in_flight <= 3.3 else 'not met'} with two in flight, as the viewer "
                 f"draws ({best_in_flight:.2f} ms)")
failed = [r["file"] for r in renders if r["exit"] != 0]
lines.append(f"planet render{' --validation' if validation else ''}: " + ", ".join(r["file"] for r in renders) +
             (f"; FAILED: {', '.join(failed)}" if failed else ", all written"))
open(f"{out}/gpu_report.txt", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
EOF
echo "gpu_report: wrote $out/gpu_report.json and $out/gpu_report.txt" >&2
exit $((validate_status == 0 && render_failed == 0 ? 0 : 1))
