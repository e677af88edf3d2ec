#!/usr/bin/env bash
# The GPU check: where a CUDA GPU is at hand, run the C/Warp agreement tests on it, render the four scenes' stills
# and run the four viewer benchmarks with --device cuda:0 --no-window, and write one JSON of the results.
#
#   tools/gpu_check.sh [OUT.json]      (default gpu_check.json; needs the project installed: pip install ".[test]")
#
# Each step's wall time, exit status and (for the benchmarks) JSON line are recorded; a failing step does not stop
# the others. Exit status: 0 when every step passed.
set -u
out=${1:-gpu_check.json}
py=${PYTHON:-python}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
device=${GPU_CHECK_DEVICE:-cuda:0}
$py - "$device" <<'PY' || { echo "gpu_check: no CUDA device $device here" >&2; exit 2; }
import sys, warp as wp
wp.init()
sys.exit(0 if sys.argv[1] in [d.alias for d in wp.get_devices()] else 1)
PY
status=0
steps=()
run() {  # name, command...
  local name=$1; shift
  local t0=$(date +%s%N)
  "$@" >"$tmp/$name.log" 2>&1
  local rc=$?
  local t1=$(date +%s%N)
  [ $rc = 0 ] || status=1
  steps+=("$name|$rc|$(( (t1 - t0) / 1000000 ))")
}
run agreement env PYWARP_TEST_DEVICE="$device" $py -m pytest -q -p no:cacheprovider tests/kernels tests/hardening/test_fuzz_findings.py
for sc in clouds terrain rain flight; do
  run "still_$sc" $py -m pywarp render "$sc" --width 640 --height 360 --device "$device" --out "$tmp/$sc.png" --no-progress
  run "view_$sc" $py -m pywarp view "$sc" --benchmark 10 --json --no-window --device "$device"
done
$py - "$tmp" "$out" "$device" "${steps[@]}" <<'PY'
import json, sys, platform
tmp, out, device, *steps = sys.argv[1:]
res = {"device": device, "machine": platform.platform(), "steps": {}}
for s in steps:
    name, rc, secs = s.split("|")
    log = open(f"{tmp}/{name}.log", encoding="utf-8", errors="replace").read().splitlines()
    step = {"exit_status": int(rc), "seconds": round(int(secs) / 1000.0, 2), "log_tail": log[-3:]}
    if name.startswith("view_") and log:
        try:
            step["benchmark"] = json.loads(log[-1])
        except ValueError:
            pass
    res["steps"][name] = step
json.dump(res, open(out, "w"), indent=1)
print(f"gpu_check: wrote {out}")
PY
exit $status
