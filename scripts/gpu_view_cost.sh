#!/usr/bin/env bash
# Issue 7's cost goal on the GPU machine: the time of a new view (bench mode a, 512^3 phantom,
# 1024x1024, methods 1-3 S) of a base commit's linework-cli against this tree's, built on the same
# machine and run interleaved (3 rounds): the base as it was, this tree closed at the border with
# strokes under 10 px pruned and coarse volumes oversampled (what the review draws; the 512^3
# phantom is fine enough to stay as it is), and open without pruning (as published).
# The device gets no .git: make the base's sources first, untracked in the repository root,
#   git archive e1013b8 | gzip > base_src.tar.gz
# then run `bash scripts/gpu_view_cost.sh` there (device tool, carry .gpu). Prints per method and
# visibility the medians and the median of the rounds' ratios closed+pruned / base.
set -uo pipefail
out=${OUT:?run on the GPU machine: OUT is its output folder}
bash scripts/gpu_run.sh none > $OUT/run.log 2>&1 || { tail -20 $OUT/run.log; exit 1; }
rm -rf /tmp/base && mkdir -p /tmp/base && tar xzf base_src.tar.gz -C /tmp/base
(cd /tmp/base && cmake --preset engine -DLINEWORK_CUDA=ON > $OUT/base_configure.log 2>&1 && cmake --build build-gpu --target linework-cli -j16 > $OUT/base_build.log 2>&1) || { tail -20 $OUT/base_build.log; exit 1; }
base=/tmp/base/build-gpu/app/cli/linework-cli
new=$PWD/build-gpu/app/cli/linework-cli
common="--sizes 512 --backend cuda --methods 1,2,3 --variants S --modes a --repeat 15 --json"
for round in 1 2 3; do
  $base bench $common > $OUT/base_$round.json 2>/dev/null
  $new bench $common --border closed --min-stroke 10 --oversample auto > $OUT/closed_$round.json 2>/dev/null
  $new bench $common --border open --min-stroke 0 > $OUT/open_$round.json 2>/dev/null
done
python3 - <<'PY'
import json, os, statistics
out = os.environ['OUT']
def rows(name):
    d = json.load(open(f'{out}/{name}.json'))
    return {(r['method'], r['visibility']): r['ms_median'] for r in d['rows']}
for key in sorted(rows('base_1')):
    b = [rows(f'base_{i}')[key] for i in (1, 2, 3)]
    c = [rows(f'closed_{i}')[key] for i in (1, 2, 3)]
    o = [rows(f'open_{i}')[key] for i in (1, 2, 3)]
    ratios = [ci / bi for ci, bi in zip(c, b)]
    print(f'method {key[0]} vis {key[1]}: base {statistics.median(b):.3f}  closed+pruned {statistics.median(c):.3f}  open {statistics.median(o):.3f}  ratio {statistics.median(ratios):.2f} (rounds {", ".join(f"{r:.2f}" for r in ratios)})')
PY
