#!/usr/bin/env bash
# The Debian package: CPack builds it from the finished build, it holds both executables, the
# desktop entry, the AppStream metadata and the icons, those validate, and the programs run
# from the unpacked package. Usage: package_test.sh BUILD_DIR (CTest passes it).
set -euo pipefail
build_dir=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for tool in cpack dpkg-deb desktop-file-validate appstreamcli; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool is missing"
    exit 77
  fi
done

(cd "$work" && cpack -G DEB --config "$build_dir/CPackConfig.cmake" -B "$work/out" >"$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log"; echo "FAIL: cpack"; exit 1; }
deb=$(ls "$work"/out/linework_*.deb)
echo "package: $(basename "$deb") ($(du -h "$deb" | cut -f1))"

contents=$(dpkg-deb -c "$deb")
for file in ./usr/bin/linework ./usr/bin/linework-cli \
            ./usr/share/applications/linework.desktop \
            ./usr/share/metainfo/io.github.linework.Linework.metainfo.xml \
            ./usr/share/icons/hicolor/scalable/apps/linework.svg \
            ./usr/share/icons/hicolor/16x16/apps/linework.png \
            ./usr/share/icons/hicolor/256x256/apps/linework.png; do
  grep -q " $file\$" <<<"$contents" || { echo "FAIL: $file is not in the package"; exit 1; }
done
depends=$(dpkg-deb -f "$deb" Depends)
grep -q "libqt6widgets6" <<<"$depends" || { echo "FAIL: Depends lacks Qt: $depends"; exit 1; }

dpkg-deb -x "$deb" "$work/root"
desktop-file-validate "$work/root/usr/share/applications/linework.desktop"
appstreamcli validate --no-net "$work/root/usr/share/metainfo/io.github.linework.Linework.metainfo.xml"
"$work/root/usr/bin/linework-cli" help | grep -q "linework-cli" || { echo "FAIL: linework-cli help"; exit 1; }
version=$(QT_QPA_PLATFORM=offscreen "$work/root/usr/bin/linework" --version)
grep -q "linework" <<<"$version" || { echo "FAIL: linework --version said: $version"; exit 1; }
echo "PASS: $version"
