#!/usr/bin/env bash
# Fuzzing (issue 10): builds the libFuzzer targets of tests/fuzz with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build/fuzz and runs each for a bounded time on seeds from
# ../shared/data (linked in place, not copied) and tests/data/fuzz.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET [TARGET...]]     default 45 s, every target
#
# Prints the edge coverage libFuzzer reports after reading the seeds (INITED cov) and at the
# end (DONE cov). A crash, a sanitizer finding, a leak or an input slower than 10 s is a
# finding: its input is kept in build/fuzz/findings/TARGET/ and the script fails; it belongs in
# tests/data/fuzz/TARGET/ with a regression test (exit 1). A build that fails exits 2. Without
# clang++ it says so and does nothing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
seconds=${1:-45}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(dicom_file dicomdir nrrd nifti pvm)

if ! command -v clang++ >/dev/null || ! command -v clang >/dev/null; then
  echo "fuzz: clang is not installed, the fuzz targets are not built or run"
  exit 0
fi
data=${LINEWORK_SHARED_DATA:-$(cd .. && pwd)/shared/data}
build=${LINEWORK_FUZZ_BUILD_DIR:-build/fuzz}
jobs=${LINEWORK_JOBS:-$(nproc)}

# A build that fails is no finding: it is the commit's (clang rejects what GCC took), so it
# exits 2, which scripts/linework.sh treats as a failure whatever LINEWORK_FUZZ_STRICT says.
kBuildFailed=2
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1" \
      -DLINEWORK_FUZZ=ON -DLINEWORK_SANITIZE=address,undefined -DLINEWORK_GUI=OFF \
      -DLINEWORK_CUDA=OFF "-DLINEWORK_SHARED_DATA=$data" >/dev/null || exit $kBuildFailed
cmake --build "$build" --parallel "$jobs" --target lw_fuzzers || {
  echo "fuzz: the fuzz targets do not build with clang (above)" >&2
  exit $kBuildFailed
}

# Seeds: links to the shared files a target reads. DICOM files over 300 KB are left out: under
# the sanitizers each costs ~0.1 s per run and the smaller ones cover the same syntaxes.
link_seeds() { # TARGET FIND-ARGS...
  local dir="$build/seeds/$1"
  shift
  rm -rf "$dir" && mkdir -p "$dir"
  [ -d "$data" ] || return 0
  local i=0
  while IFS= read -r -d '' file; do
    ln -s "$file" "$dir/$i-$(basename "$file")"
    i=$((i + 1))
  done < <(find "$@" -print0 | sort -z)
}
link_seeds dicom_file "$data/dicom" "$data/dicom-odd" -type f -size -300k -not -iname 'DICOMDIR*'
link_seeds dicomdir "$data/dicom" "$data/dicom-odd" -type f -iname 'DICOMDIR*'
link_seeds nrrd "$data/volumes" -type f \( -iname '*.nrrd' -o -iname '*.nhdr' \)
link_seeds nifti "$data/volumes" -type f \( -iname '*.nii' -o -iname '*.nii.gz' \)
link_seeds pvm "$data/volumes" -type f -iname '*.pvm'

export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LINEWORK_SHARED_DATA="$data"
failed=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target" findings="$build/findings/$target" log="$build/fuzz-$target.log"
  mkdir -p "$corpus" "$findings"
  seeds=("$build/seeds/$target")
  [ -d "tests/data/fuzz/$target" ] && seeds+=("tests/data/fuzz/$target")
  earlier=$(find "$corpus" -type f | wc -l) # kept from earlier runs in this build folder
  start=$(date +%s)
  status=0
  # The first folder receives what libFuzzer finds new; the seed folders are only read.
  "$build/tests/fuzz/lw_fuzz_$target" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2560 -print_final_stats=1 -artifact_prefix="$findings/" \
      >"$log" 2>&1 || status=$?
  seed_count=$(find -L "${seeds[@]}" -type f | wc -l)
  inited=$(grep -m1 -o 'INITED cov: [0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  done_cov=$(grep -o 'DONE *cov: [0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  echo "fuzz $target: $seed_count seeds + $earlier from earlier runs, edge coverage $inited" \
       "after reading them, $done_cov after $runs runs in $(( $(date +%s) - start )) s"
  if [ $status -ne 0 ]; then
    echo "fuzz $target: FINDING (exit $status), input in $findings/; the end of $log:" >&2
    tail -n 40 "$log" >&2
    failed+=("$target")
  fi
done
[ ${#failed[@]} -eq 0 ] || { echo "fuzz: findings in ${failed[*]}" >&2; exit 1; }
