#!/usr/bin/env bash
# Issue 7's goal "a new view costs at most 20 % more than today with strokes and closing on":
# the time of a new view (bench mode a: surface kept, only the camera turns; mode b too) of
# methods 1, 2, 3 (S, 1024x1024) on the demo CT at 400 HU and the 256^3 phantom, for
#   base     BASE_CLI's bench as it is (before issue 7: surface open, no stroke pruning),
#   closed   NEW_CLI --border closed --min-stroke 10 --oversample auto (what the review draws:
#            a coarse or thick-slice volume oversampled, render/surface_sampling.h),
#   closed0  NEW_CLI --border closed --min-stroke 0 (closing alone; bench's default),
#   open     NEW_CLI --border open --min-stroke 0 (the methods as published),
# interleaved: each round runs every method once per configuration, one short bench per method
# and configuration, the order of the configurations turning each round, so that the load of a
# shared machine falls on all alike. Prints each round's load average and a Markdown table per
# volume: the median over the rounds of each run's median ms, the median of the rounds' paired
# ratios closed / base (the goal: <= 1.20) and the fastest frames (min over the rounds of each
# run's fastest frame), whose ratio the load disturbs least.
#   scripts/bench_view_cost.sh BASE_CLI NEW_CLI [ROUNDS] [REPEAT]
#   (ROUNDS default 9, REPEAT = bench --repeat, default 5; MODES=a leaves out mode b;
#    KEEP=DIR keeps every run's JSON there)
# BASE_CLI: any linework-cli with `bench --input FILE --iso HU --json` (docs/BENCHMARKS.md used
# one built at e1013b8, the parent of issue 7's first rendering commit); NEW_CLI needs --border,
# --min-stroke and `convert` (the demo DICOM series is converted to NRRD once, as bench reads
# volume files only; both binaries read that same file).
set -euo pipefail
usage="usage: scripts/bench_view_cost.sh BASE_CLI NEW_CLI [ROUNDS] [REPEAT]"
base_cli=$(realpath "${1:?$usage}")
new_cli=$(realpath "${2:?$usage}")
rounds=${3:-9}
repeat=${4:-5}
modes=${MODES:-a,b}
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$new_cli" convert "$repo/resources/demo/ct_head_ge_tilt" -o "$work/demo.nrrd" >/dev/null 2>&1
inputs=("demo|--input $work/demo.nrrd --iso 400" "phantom256|--sizes 256")
configs=(base closed closed0 open)
common="--variants S --modes $modes --repeat $repeat --image 1024x1024 --json"

run_one() { # CONFIG INPUT_ARGS OUT.json
  local cli=$new_cli extra=""
  case $1 in
  base) cli=$base_cli ;;
  closed) extra="--border closed --min-stroke 10 --oversample auto" ;;
  closed0) extra="--border closed --min-stroke 0" ;;
  open) extra="--border open --min-stroke 0" ;;
  esac
  # shellcheck disable=SC2086 # the arguments are words on purpose
  "$cli" bench $2 $common $extra >"$3" 2>/dev/null
}

echo "base:   $base_cli"
echo "new:    $new_cli"
echo "rounds: $rounds, bench --repeat $repeat, modes $modes; $(nproc) cores"
for round in $(seq "$rounds"); do
  echo "round $round: $(uptime | sed 's/.*load average/load average/')"
  for input in "${inputs[@]}"; do
    name=${input%%|*}
    for method in 1 2 3; do
      for k in 0 1 2 3; do # the order turns each round
        config=${configs[$(((k + round - 1) % 4))]}
        run_one "$config" "${input#*|} --methods $method" "$work/$name.$config.$method.$round.json"
      done
    done
  done
done
echo "after:   $(uptime | sed 's/.*load average/load average/')"
if [[ -n ${KEEP:-} ]]; then
  mkdir -p "$KEEP" && cp "$work"/*.json "$KEEP"/
fi

python3 - "$work" <<'EOF'
import glob, json, os, statistics, sys
from collections import defaultdict
configs = ("base", "closed", "closed0", "open")
runs = defaultdict(dict)  # (volume, method, mode, vis, config) -> {round: row}
for path in glob.glob(os.path.join(sys.argv[1], "*.json")):
    name, config, _, round_, _ = os.path.basename(path).split(".")
    for row in json.load(open(path))["rows"]:
        if row.get("ms_median") is not None:  # null: a skipped method (no GL)
            runs[(name, row["method"], row["mode"], row["visibility"], config)][round_] = row
cells = sorted({k[:4] for k in runs}, key=lambda k: (k[0], k[2], k[3] != "on", k[1]))
for volume in sorted({c[0] for c in cells}):
    print(f"\n{volume}: median ms over the rounds [fastest frame]; closed / base: median of the "
          "rounds' ratios [ratio of the fastest frames]")
    print("\n| method | mode | vis | base | closed, pruned 10 | closed / base | closed, unpruned "
          "| open, unpruned | closing (closed0 / open) | pruning and oversampling ms (closed - closed0) | rounds |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for cell in (c for c in cells if c[0] == volume):
        by = {c: runs.get(cell + (c,), {}) for c in configs}
        rounds = sorted(set.intersection(*(set(r) for r in by.values())))
        if not rounds:
            continue
        med = {c: statistics.median(by[c][r]["ms_median"] for r in rounds) for c in configs}
        fast = {c: min(by[c][r]["ms_min"] for r in rounds) for c in configs}
        ratio = statistics.median(by["closed"][r]["ms_median"] / by["base"][r]["ms_median"]
                                  for r in rounds)
        _, method, mode, vis = cell
        print(f"| {method} | {mode} | {vis} | {med['base']:.1f} [{fast['base']:.1f}] | "
              f"{med['closed']:.1f} [{fast['closed']:.1f}] | **{ratio:.2f}** "
              f"[{fast['closed'] / fast['base']:.2f}] | {med['closed0']:.1f} | {med['open']:.1f} | "
              f"{med['closed0'] / med['open']:.2f} | {med['closed'] - med['closed0']:+.1f} | "
              f"{len(rounds)} |")
EOF
