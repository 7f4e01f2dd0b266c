#!/usr/bin/env bash
# Where the GPU time goes (issue 11): Nsight Compute's kernel durations for the 512^3 phantom, one
# bench frame per method, and the accuracy sweep with the CUDA back-end at sizes 32 and 256.
# Run on the GPU machine after scripts/gpu_run.sh has built build-gpu (same device call):
#   scripts/gpu_run.sh test && scripts/gpu_profile.sh "$OUT" [mc m1a m2a m3b accuracy]
# (default: all of them). PROFILE_SIZE (default 512, e.g. 1024x1024x2048) and PROFILE_ARGS (more
# bench arguments, e.g. "--gpu-budget 2048") profile other volumes. ncu runs with --clock-control none (the clocks the bench sees), one
# warm-up frame and two measured ones (--repeat 2); its report (CSV, after the bench's own output)
# goes to ncu_<what>.csv, a summary per kernel to stdout.
set -uo pipefail
out=${1:-out/gpu}
shift || true
what=${*:-mc m1a m2a m3b accuracy}
wanted() { [[ " $what " == *" $1 "* ]]; }
cli=build-gpu/app/cli/linework-cli
mkdir -p "$out"
ncu=$(command -v ncu || ls /usr/local/cuda/bin/ncu 2>/dev/null || true)
rc=0
profile() { # NAME METHOD MODE [more bench arguments]
    local name=$1 method=$2 mode=$3
    shift 3
    wanted "$name" || return 0
    if [ -z "$ncu" ]; then echo "ncu not found: no kernel profile"; return; fi
    "$ncu" --clock-control none --metrics gpu__time_duration.sum --csv \
        "$cli" bench --backend cuda --sizes "${PROFILE_SIZE:-512}" --methods "$method" --variants S --modes "$mode" \
        --repeat 2 --image 1024x1024 ${PROFILE_ARGS:-} "$@" > "$out/ncu_$name.csv" 2> "$out/ncu_$name.log" || rc=1
    python3 - "$out/ncu_$name.csv" "$name" <<'PY'
import csv, sys, collections
path, name = sys.argv[1], sys.argv[2]
lines = [l for l in open(path, errors="replace") if l.startswith('"')]
total = collections.OrderedDict()
count = collections.Counter()
for row in csv.DictReader(lines):
    if row.get("Metric Name") != "gpu__time_duration.sum":
        continue
    kernel = row["Kernel Name"].split("(")[0][:70]
    value = float(row["Metric Value"].replace(",", ""))
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "nsecond": 1e-6, "usecond": 1e-3,
             "msecond": 1.0}.get(row.get("Metric Unit"), 1e-6)
    total[kernel] = total.get(kernel, 0.0) + value * scale
    count[kernel] += 1
print(f"== {name}: kernel time per kernel, mean over its launches (ms)")
for kernel, ms in sorted(total.items(), key=lambda kv: -kv[1]):
    print(f"  {ms / count[kernel]:8.4f} ms x{count[kernel]:<3} {kernel}")
PY
}
profile mc mc b
profile m2a 2 a
profile m3b 3 b
profile m1a 1 a
# The accuracy sweep (32 views, every shape) with the CUDA back-end at 32 and 256 (64: gpu_bench).
wanted accuracy || exit $rc
for size in 32 256; do
    timeout 240 "$cli" accuracy --backend cuda --methods 1,2,3 --sizes "$size" --views sweep --json \
        > "$out/accuracy_cuda_$size.json" 2> "$out/accuracy_cuda_$size.log" || rc=1
    python3 - "$out/accuracy_cuda_$size.json" "$size" <<'PY'
import json, sys
try:
    rows = json.load(open(sys.argv[1])).get("rows", [])
except Exception as e:
    print("accuracy", sys.argv[2], "unreadable:", e); sys.exit(0)
worst = {}
for r in rows:
    key = (r.get("method"), r.get("variant"), r.get("visibility"), r.get("backend"))
    w = worst.setdefault(key, [1.0, 1.0, None])
    if r.get("precision", 1.0) < w[1]:
        w[2] = (r.get("shape"), r.get("view"))
    w[0] = min(w[0], r.get("recall", 1.0)); w[1] = min(w[1], r.get("precision", 1.0))
print(f"== accuracy size {sys.argv[2]}: {len(rows)} rows")
for key, (rec, prec, where) in sorted(worst.items(), key=str):
    print("  worst", key, f"recall {rec:.4f} precision {prec:.4f} at {where}")
PY
done
exit $rc
