#!/usr/bin/env bash
# DICOM import benchmark (issue 2): linework-cli bench-import against dcm2niix on the same series,
# files in the page cache, in the same run. Prints a Markdown table for docs/BENCHMARKS.md.
#   scripts/bench_import.sh BUILD_DIR [REPEAT]
# Needs ../shared/data, dcm2niix and dcmcjpls (Debian: dcm2niix, dcmtk).
set -euo pipefail
build=${1:?usage: scripts/bench_import.sh BUILD_DIR [REPEAT]}
repeat=${2:-15}
cli="$build/app/cli/linework-cli"
data=$(cd "$(dirname "$0")/../../shared/data" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

ge="$data/dicom/ct_head_ge_hispeed_tilt_varspacing"
philips="$data/dicom/ct_headphantom_philips_dicomdir_export/DICOM/S21610/S2010"    # tilted
philips_flat="$data/dicom/ct_headphantom_philips_dicomdir_export/DICOM/S21570/S2010" # no tilt
# JPEG-LS copies made here so both tools read the same compressed bytes.
mkdir -p "$work/ge_jls" "$work/philips_jls" "$work/philips" "$work/philips_flat"
for f in "$ge"/*.dcm; do dcmcjpls --encode-lossless "$f" "$work/ge_jls/$(basename "$f")"; done
# The Philips folder also holds a DIRFILE (a DICOMDIR); copy only the images.
for f in "$philips_flat"/I*; do cp "$f" "$work/philips_flat/"; done
for f in "$philips"/I*; do cp "$f" "$work/philips/"; dcmcjpls --encode-lossless "$f" "$work/philips_jls/$(basename "$f")"; done

median_ms() { sort -n | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

time_dcm2niix() { # prints the median wall time in ms of `repeat` conversions (NIfTI written, uncompressed)
  local dir=$1 out="$work/nii"
  mkdir -p "$out"
  dcm2niix -z n -b n -o "$out" -f x "$dir" >/dev/null 2>&1 # warm the page cache
  for _ in $(seq "$repeat"); do
    rm -f "$out"/*
    local t0 t1
    t0=$(date +%s%N); dcm2niix -z n -b n -o "$out" -f x "$dir" >/dev/null 2>&1; t1=$(date +%s%N)
    echo $(( (t1 - t0) / 1000 ))
  done | median_ms | awk '{printf "%.1f", $1/1000}'
}

time_linework() { # median ms of scan + assemble + decode, from bench-import --json
  "$cli" bench-import "$1" --repeat "$repeat" --json 2>/dev/null |
    python3 -c 'import json,sys; d=json.load(sys.stdin); print("%.1f" % (d["median_s"] * 1000))'
}

echo "| series | slices | dcm2niix ms | dcm2niix slices/s | linework ms | linework slices/s |"
echo "|---|---|---|---|---|---|"
# dcm2niix resamples gantry-tilted series (linework keeps them sheared, without resampling), so
# the untilted Philips series is the like-for-like comparison. Debian's dcm2niix is built
# without JPEG-LS: on those rows it fails fast and converts nothing (marked "n/a").
for entry in "Philips head phantom 5 mm, no tilt, uncompressed:$work/philips_flat" "GE head CT, uncompressed:$ge" "GE head CT, JPEG-LS lossless:$work/ge_jls" \
             "Philips head phantom, uncompressed:$work/philips" "Philips head phantom, JPEG-LS lossless:$work/philips_jls"; do
  name=${entry%%:*}; dir=${entry#*:}
  n=$(ls "$dir" | wc -l)
  l=$(time_linework "$dir")
  probe=$(dcm2niix -z n -b n -o "$work" -f probe "$dir" 2>&1 || true)
  if grep -q "No valid DICOM images" <<<"$probe"; then
    printf '| %s | %d | n/a (cannot decode) | n/a | %s | %.0f |\n' "$name" "$n" "$l" "$(echo "$n*1000/$l" | bc -l)"
    continue
  fi
  d=$(time_dcm2niix "$dir")
  printf '| %s | %d | %s | %.0f | %s | %.0f |\n' "$name" "$n" "$d" "$(echo "$n*1000/$d" | bc -l)" \
         "$l" "$(echo "$n*1000/$l" | bc -l)"
done
