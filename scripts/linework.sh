#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine (2 cores, maybe no GPU, maybe no display):
#
#   scripts/linework.sh run    install what is missing, build, run the main job on the demo study
#   scripts/linework.sh test   install what is missing, build, run the whole test suite (CTest),
#                              then the same suite built with AddressSanitizer + UBSan (build/asan)
#                              and each fuzz target for a bounded time (scripts/fuzz.sh, clang)
#
# Both are idempotent: packages already present are not reinstalled, builds are incremental.
# Both build into one folder, so `test` after `run` (or the reverse) only builds what is new:
# `run` builds the two programs it needs, `test` everything.
# Environment: LINEWORK_BUILD_DIR (default build/linework), LINEWORK_JOBS (default: cores),
# LINEWORK_CUDA_ARCHITECTURES (default 90, the H100/H200 of the GPU machine and what CI
# compiles; e.g. "75;80;86;89;90" for other GPUs). For `test`: LINEWORK_SANITIZERS=0 skips the
# sanitizer build and suite, LINEWORK_FUZZ_SECONDS (default 45; 0 skips) bounds each fuzz target,
# LINEWORK_FUZZ_STRICT=1 makes a fuzz finding fail the command (fuzz targets that do not build
# with clang always fail it).
set -euo pipefail

command=${1:-}
case "$command" in
  run|test) ;;
  *) echo "usage: scripts/linework.sh run|test" >&2; exit 2 ;;
esac
shift || true

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

packages=(build-essential cmake ninja-build file pkg-config zlib1g-dev libpng-dev nlohmann-json3-dev libgtest-dev
          qt6-base-dev qt6-tools-dev qt6-l10n-tools libqt6opengl6-dev libqt6sql6-sqlite
          libdcmtk-dev dcmtk libopenjp2-7-dev libglm-dev libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
          xvfb xauth python3-numpy desktop-file-utils appstream clang libclang-rt-14-dev
          poppler-utils dicom3tools) # the report tests read the PDF and validate the DICOM SC
packages+=(lintian) # tests/installer checks the Debian package with it
packages+=(orthanc) # tests/pacs start their own Orthanc (a real PACS) on free loopback ports

install_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "linework: installing ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
    sudo -v # ask for the password here, not inside the silenced apt-get below
  fi
  # dpkg prints about a thousand lines of progress: keep them in a log, show its end on failure.
  local log
  log=$(mktemp "${TMPDIR:-/tmp}/linework-apt.XXXXXX")
  if ! { $sudo apt-get update -qq &&
         DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
           "${missing[@]}"; } >"$log" 2>&1; then
    echo "linework: installing the packages failed; the end of $log:" >&2
    tail -n 40 "$log" >&2
    exit 1
  fi
  rm -f "$log"
}

# Debian's orthanc package enables and starts a system Orthanc on 4242/8042 (systemd; in a
# container policy-rc.d usually forbids the start). The tests start their own on free ports and
# must leave no PACS listening on the machine, so the system one is stopped and disabled; a
# site that wants it back runs `systemctl enable --now orthanc`.
stop_system_orthanc() {
  [ -e /lib/systemd/system/orthanc.service ] || [ -e /etc/init.d/orthanc ] || return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  if [ -d /run/systemd/system ]; then # systemd is the init
    if systemctl is-enabled --quiet orthanc 2>/dev/null || systemctl is-active --quiet orthanc; then
      echo "linework: stopping and disabling the system Orthanc (the tests start their own)"
      $sudo systemctl disable --now --quiet orthanc
    fi
  else # sysvinit or a container: the init script, if it runs
    if [ -e /etc/init.d/orthanc ] && /etc/init.d/orthanc status >/dev/null 2>&1; then
      echo "linework: stopping the system Orthanc (the tests start their own)"
      $sudo /etc/init.d/orthanc stop >/dev/null
    fi
    if ls /etc/rc[2-5].d/S*orthanc >/dev/null 2>&1; then
      $sudo update-rc.d orthanc disable >/dev/null 2>&1 || true
    fi
  fi
}

install_packages
stop_system_orthanc

jobs=${LINEWORK_JOBS:-$(nproc)}
build_dir=${LINEWORK_BUILD_DIR:-build/linework}
cuda_archs=${LINEWORK_CUDA_ARCHITECTURES:-90}

cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      "-DCMAKE_CUDA_ARCHITECTURES=$cuda_archs" "$@"
if [ "$command" = run ]; then
  # The main job needs the two programs only; the GUI exists where Qt 6 and DCMTK were found.
  targets=(linework-cli)
  ninja -C "$build_dir" -t query linework >/dev/null 2>&1 && targets+=(linework)
  cmake --build "$build_dir" --parallel "$jobs" --target "${targets[@]}"
else
  cmake --build "$build_dir" --parallel "$jobs"
fi

demo=resources/demo/ct_head_ge_tilt
if [ "$command" = run ]; then
  # The main job. With a display: the workstation on the bundled demo study, its series already
  # in review at the bone preset. Without one: the same review headless, as a PNG.
  gui="$build_dir/app/gui/linework"
  if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -x "$gui" ]; then
    echo "linework: opening the demo study in the workstation"
    exec "$gui" "$demo"
  fi
  cli="$build_dir/app/cli/linework-cli"
  "$cli" info "$demo"
  mkdir -p out
  "$cli" render "$demo" --iso 400 --method 3 --panel both --view 30,20 --size 900x900 \
         -o out/demo_review.png
  echo "linework: no display, so the review was rendered headless: $root/out/demo_review.png"
  echo "linework: with a display this command opens the workstation ($gui)"
  exit 0
fi

# Tests: GL and GUI tests need a display; give them a virtual one when there is none.
run_ctest() { # BUILD_DIR [ctest arguments...]
  local ctest_cmd=(ctest --test-dir "$1" --output-on-failure --parallel "$jobs" --timeout 1500 "${@:2}")
  if [ -z "${DISPLAY:-}" ] && command -v xvfb-run >/dev/null; then
    xvfb-run -a -s "-screen 0 1920x1080x24" "${ctest_cmd[@]}"
  else
    "${ctest_cmd[@]}"
  fi
}
failed=()
run_ctest "$build_dir" || failed+=("test suite")

# The same suite under AddressSanitizer + UndefinedBehaviorSanitizer (CMake preset `asan`: no
# CUDA, -O1). The package test is left out: it packs and unpacks the build, it reads no input.
# So are the `big` tests (4 GiB volumes): ASan's shadow memory and -O1 would make them minutes
# longer and gigabytes larger, and their code paths are the ones the small tests run.
if [ "${LINEWORK_SANITIZERS:-1}" != 0 ]; then
  echo "linework: the test suite with AddressSanitizer + UndefinedBehaviorSanitizer (build/asan)"
  started=$(date +%s)
  if cmake --preset asan >/dev/null && cmake --build build/asan --parallel "$jobs"; then
    run_ctest build/asan -E '^installer_package_test$' -LE '^big$' || failed+=("sanitizer suite")
  else
    failed+=("sanitizer build")
  fi
  echo "linework: sanitizer build and suite took $(( $(date +%s) - started )) s"
fi

# Each fuzz target for a bounded time (scripts/fuzz.sh; nothing without clang).
if [ "${LINEWORK_FUZZ_SECONDS:-45}" != 0 ]; then
  started=$(date +%s)
  # A new finding is a bug to fix (and then a regression input in tests/data/fuzz, replayed by
  # every build), but the mutations are random: one run may find what the last did not. It fails
  # the command only with LINEWORK_FUZZ_STRICT=1, so CI stays a function of the commit; the
  # finding and its log are printed either way (build/fuzz/findings). Known findings do gate:
  # lw_fuzz_regression_tests replays tests/data/fuzz in both suites above.
  # The fuzz targets' build (clang) is not random: it failing fails the command.
  fuzz_status=0
  LINEWORK_JOBS=$jobs scripts/fuzz.sh "${LINEWORK_FUZZ_SECONDS:-45}" || fuzz_status=$?
  if [ "$fuzz_status" = 2 ]; then
    failed+=("fuzz targets' build (clang)")
  elif [ "$fuzz_status" != 0 ]; then
    if [ "${LINEWORK_FUZZ_STRICT:-0}" = 1 ]; then
      failed+=("fuzzing")
    else
      echo "linework: WARNING: fuzzing found something (see above and build/fuzz/findings)" >&2
    fi
  fi
  echo "linework: fuzzing took $(( $(date +%s) - started )) s"
fi

if [ ${#failed[@]} -ne 0 ]; then
  echo "linework: FAILED: ${failed[*]}" >&2
  exit 1
fi
