#!/usr/bin/env bash
# The Debian package: CPack builds it from the finished build; it holds both executables, their
# manual pages, the desktop entry, the AppStream metadata, the icons, the translations, the
# copyright file and the changelog; those validate; its dependencies exist in the archive; the
# programs run from the unpacked package (no display, the installed translations found); and
# lintian reports no error or warning. Usage: package_test.sh BUILD_DIR (CTest passes it).
# Exits with 77 (SKIP) when a tool is missing: lintian only after every other check passed.
set -euo pipefail
build_dir=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "FAIL: $*"
  exit 1
}

for tool in cpack dpkg-deb desktop-file-validate appstreamcli; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool is missing"
    exit 77
  fi
done

(cd "$work" && cpack -G DEB --config "$build_dir/CPackConfig.cmake" -B "$work/out" >"$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log"; fail "cpack"; }
deb=$(ls "$work"/out/linework_*.deb)
version=$(dpkg-deb -f "$deb" Version)
echo "package: $(basename "$deb") ($(du -h "$deb" | cut -f1))"

contents=$(dpkg-deb -c "$deb")
icons=./usr/share/icons/hicolor
for file in ./usr/bin/linework ./usr/bin/linework-cli \
            ./usr/share/man/man1/linework.1.gz ./usr/share/man/man1/linework-cli.1.gz \
            ./usr/share/applications/linework.desktop \
            ./usr/share/metainfo/io.github.linework.Linework.metainfo.xml \
            $icons/scalable/apps/linework.svg \
            $icons/{16x16,32x32,48x48,64x64,128x128,256x256}/apps/linework.png \
            ./usr/share/linework/translations/linework_de.qm \
            ./usr/share/linework/translations/linework_ro.qm \
            ./usr/share/doc/linework/copyright ./usr/share/doc/linework/changelog.gz \
            ./usr/share/linework/demo/ct_head_ge_tilt/01.dcm; do
  grep -q " $file\$" <<<"$contents" || fail "$file is not in the package"
done
if grep -v ' root/root ' <<<"$contents"; then
  fail "files not owned by root (above)"
fi
depends=$(dpkg-deb -f "$deb" Depends)
for package in libqt6widgets6 libqt6sql6-sqlite libdcmtk libpng16-16; do
  grep -q "$package" <<<"$depends" || fail "Depends lacks $package: $depends"
done
grep -q "qt6-translations-l10n" <<<"$(dpkg-deb -f "$deb" Recommends)" ||
  fail "Recommends lacks qt6-translations-l10n"
# Every dependency is a package apt knows, in a version it has: what `apt-get install ./deb` needs.
if ! apt-get install --simulate --no-install-recommends "$deb" >"$work/apt.log" 2>&1; then
  cat "$work/apt.log"
  fail "apt-get cannot install the package's dependencies"
fi

dpkg-deb -x "$deb" "$work/root"
root=$work/root
desktop-file-validate "$root/usr/share/applications/linework.desktop"
appstreamcli validate --no-net "$root/usr/share/metainfo/io.github.linework.Linework.metainfo.xml"
changelog_head=$(zcat "$root/usr/share/doc/linework/changelog.gz" | head -n 1)
grep -q "^linework ($version) " <<<"$changelog_head" ||
  fail "the changelog's newest entry is not version $version: $changelog_head"

# The programs from the unpacked package, with no display and settings of their own.
run() { env -u DISPLAY -u WAYLAND_DISPLAY -u LANGUAGE XDG_CONFIG_HOME="$work/config" "$@"; }
cli_help=$(run "$root/usr/bin/linework-cli" help) || fail "linework-cli help"
run "$root/usr/bin/linework-cli" info "$root/usr/share/linework/demo/ct_head_ge_tilt" >"$work/info.txt" ||
  { cat "$work/info.txt"; fail "linework-cli info on the installed demo study"; }
grep -q "512" "$work/info.txt" || { cat "$work/info.txt"; fail "linework-cli info: no 512x512 series"; }
gui_version=$(run "$root/usr/bin/linework" --version) || fail "linework --version"
[ "$gui_version" = "linework $version" ] || fail "linework --version said: $gui_version"
german_help=$(run env LC_ALL=de_DE.UTF-8 "$root/usr/bin/linework" --help 2>/dev/null) ||
  fail "linework --help"
grep -q "Isoflächen- und Silhouettenbefundung" <<<"$german_help" ||
  fail "linework --help under a German locale is not German (installed .qm not found): $german_help"

# The manual page describes every command linework-cli has.
manual=$(zcat "$root/usr/share/man/man1/linework-cli.1.gz" | sed 's/\\-/-/g') # roff's \- is a -
commands=$(sed -n '/^commands:/,/^$/s/^  \([a-z][a-z-]*\)\( .*\)\?$/\1/p' <<<"$cli_help")
[ -n "$commands" ] || fail "no commands found in linework-cli help"
for command in $commands; do
  grep -q "^\.SS $command\b" <<<"$manual" || fail "linework-cli.1 lacks the command $command"
done

if ! command -v lintian >/dev/null; then
  echo "SKIP: lintian is missing (every other check passed)"
  exit 77
fi
# Info tags are printed for the record; an error or a warning fails. The info tags that remain
# and why: docs/packaging.md.
lintian_status=0
lintian --display-info --fail-on error,warning "$deb" >"$work/lintian.log" 2>&1 || lintian_status=$?
grep -v "^running with root privileges" "$work/lintian.log" || true
[ "$lintian_status" -eq 0 ] || fail "lintian exited with $lintian_status: errors or warnings (above)"
echo "PASS: $gui_version, $(wc -w <<<"$commands") CLI commands documented, lintian clean"
