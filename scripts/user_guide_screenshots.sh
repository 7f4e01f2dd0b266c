#!/usr/bin/env bash
# Regenerates docs/screenshots/{browser,review,review_annotations,settings,settings_appearance,
# thick_slices_smooth,thick_slices_linear}.png
# from the real windows: imports the demo study (and, when ../shared/data is beside the project, the Philips
# DICOMDIR export with its missing files) into a temporary database, opens the review (once more
# with a ruler, a label, an arrow and an angle placed by clicks) and the settings page under Xvfb
# and grabs what the X server shows; then opens the demo study by path and shows it smoothed across
# its thick slices and with straight lines between them. Run after `scripts/linework.sh test` (or give a build dir).
#
#   scripts/user_guide_screenshots.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${1:-$root/build/linework}
if ! log=$(cmake --build "$build_dir" --target linework-screenshots 2>&1); then
  echo "$log" >&2
  exit 1
fi
inputs=("$root/resources/demo/ct_head_ge_tilt")
philips="$(cd "$root/.." && pwd)/shared/data/dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR"
[ -f "$philips" ] && inputs+=("$philips")
xvfb-run -a -s "-screen 0 1920x1080x24" \
    "$build_dir/app/gui/linework-screenshots" "$root/docs/screenshots" "${inputs[@]}"
