#!/usr/bin/env bash
# The GPU machine's run in one command (each device call starts a bare machine): unpack the GL,
# EGL, GLM, libpng, nlohmann-json, GoogleTest and zlib packages carried in .gpu/debs
# (scripts/fetch_gpu_debs.sh fetches them; unpacked into / they sit where CMake looks, so the
# configure needs no paths), configure the engine preset with CUDA for sm_90, build, run the tests (all of them: the
# `gpu` ones run against the CPU reference there), then the CUDA benchmarks. Logs and the JSON go
# to $OUT (or out/gpu when run elsewhere).
#   scripts/gpu_run.sh [test|bench|all]   (default all)
set -uo pipefail
what=${1:-all}
out=${OUT:-$PWD/out/gpu}
mkdir -p "$out"
if [ -d .gpu/debs ]; then
    for f in .gpu/debs/*.deb; do dpkg -x "$f" / ; done
    ldconfig
fi
{ nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader; nvcc --version | tail -2;
  cmake --version | head -1; c++ --version | head -1; nproc; } 2>&1 | tee "$out/machine.txt"
export LINEWORK_SHARED_DATA=${LINEWORK_SHARED_DATA:-$PWD/shared/data}
cmake --preset engine -DLINEWORK_CUDA=ON > "$out/configure.log" 2>&1 || { tail -40 "$out/configure.log"; exit 1; }
cmake --build build-gpu -j"$(nproc)" > "$out/build.log" 2>&1 || { grep -E 'error|Error' "$out/build.log" | head -40; tail -20 "$out/build.log"; exit 1; }
echo "build ok"
rc=0
if [ "$what" = test ] || [ "$what" = all ]; then
    (cd build-gpu && ctest --output-on-failure -j8 --timeout 300) > "$out/ctest.log" 2>&1 || rc=1
    grep -E 'tests passed|Failed|\*\*\*|SKIP|Not Run' "$out/ctest.log" | tail -30
    (cd build-gpu && ctest -L gpu -V --timeout 300) > "$out/ctest_gpu.log" 2>&1 || rc=1
    grep -E '^\[  |PASSED|FAILED|Skipped|SKIP' "$out/ctest_gpu.log" | grep -vE '^\[ RUN' | tail -40
fi
if [ "$what" = bench ] || [ "$what" = all ]; then
    if [ -x scripts/gpu_bench.sh ]; then bash scripts/gpu_bench.sh "$out" || rc=1; fi
fi
# What comes back from the device is limited in number of files: the logs go as one archive.
(cd "$out" && tar czf logs.tgz --remove-files $(ls *.log machine.txt 2>/dev/null | grep -v '^run.log$') 2>/dev/null)
exit $rc
