#!/usr/bin/env bash
# The CUDA benchmarks of the GPU run (called by scripts/gpu_run.sh after the build and the tests):
# `linework-cli bench` on the phantom with the CUDA back-end (median of 20 runs after a warm-up,
# 1024x1024) and the same rows on the CPU for comparison (5 runs), JSON rows into $1.
set -uo pipefail
out=${1:-out/gpu}
cli=build-gpu/app/cli/linework-cli
mkdir -p "$out"
rc=0
"$cli" bench --backend cuda --sizes 256,512,512x512x140 --methods mc,1,2,3 --variants S --modes a,b \
    --repeat 20 --image 1024x1024 --json > "$out/bench_cuda.json" 2> "$out/bench_cuda.log" || rc=1
# Streamed L: methods 1 and 3 on 512 x 512 x 1024 under a 256 MiB device budget, and S beside it.
"$cli" bench --backend cuda --sizes 512x512x1024 --methods mc,1,3 --variants S,L --modes a,b \
    --repeat 20 --image 1024x1024 --gpu-budget 256 --json > "$out/bench_cuda_1024.json" \
    2> "$out/bench_cuda_1024.log" || rc=1
"$cli" bench --backend cpu --sizes 256,512,512x512x140 --methods mc,1,2,3 --variants S --modes a,b \
    --repeat 5 --image 1024x1024 --json > "$out/bench_cpu.json" 2> "$out/bench_cpu.log" || rc=1
# Accuracy with the CUDA back-end at every view of the sweep.
"$cli" accuracy --backend cuda --methods 1,2,3 --sizes 64 --views sweep --json \
    > "$out/accuracy_cuda.json" 2> "$out/accuracy_cuda.log" || rc=1
python3 - "$out" <<'PY'
import json, sys, os
out = sys.argv[1]
def rows(name):
    try:
        return json.load(open(os.path.join(out, name)))
    except Exception as e:
        print(name, "unreadable:", e); return {}
acc = rows("accuracy_cuda.json")
worst = {}
for r in acc.get("rows", []):
    key = (r.get("method"), r.get("variant"), r.get("visibility"), r.get("backend"))
    w = worst.setdefault(key, [1.0, 1.0])
    w[0] = min(w[0], r.get("recall", 1.0)); w[1] = min(w[1], r.get("precision", 1.0))
for key, (rec, prec) in sorted(worst.items(), key=str):
    print("accuracy worst over views/shapes/sizes", key, f"recall {rec:.4f} precision {prec:.4f}")
for name in ("bench_cuda.json", "bench_cuda_1024.json", "bench_cpu.json"):
    data = rows(name)
    for note in data.get("notes", []):
        print("note:", note)
    for r in data.get("rows", []):
        print(f"{r['backend']:5} {r['volume']:>14} m{r['method']!s:3} {r['variant']} {r.get('mode') or '-'} "
              f"vis={r.get('visibility') or '-':3} median {r['ms_median']!s:>10} ms  stages {r['stages']}  tris {r['triangles']} segs {r['segments']} dev_mib {r.get('device_mib', '-')}")
PY
exit $rc
