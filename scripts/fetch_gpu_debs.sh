#!/usr/bin/env bash
# Fetches (here, once) the Debian packages the GPU machine lacks into .gpu/debs, which
# scripts/gpu_run.sh unpacks there: the GL/EGL loaders and headers and GLM (../shared/GPU.md),
# libpng (PNG) and nlohmann-json (JSON) for lw_core, plus GoogleTest and zlib's headers for the
# test suite. .gpu/ is kept out of git
# (.git/info/exclude) and carried to the device (`carry: [".gpu"]`).
set -euo pipefail
cd "$(dirname "$0")/.."
# Through git, not .git/info: in a worktree .git is a file, and the exclude file is shared.
exclude=$(git rev-parse --git-path info/exclude)
mkdir -p "$(dirname "$exclude")"
grep -qx '/.gpu/' "$exclude" 2>/dev/null || echo '/.gpu/' >> "$exclude"
mkdir -p .gpu/debs /tmp/amd64/partial
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
apt-get $o update > /dev/null
cd .gpu/debs
apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 \
    libglm-dev libegl-dev libgl-dev libopengl-dev libglvnd-dev libgles-dev libglx-dev \
    libpng-dev libpng16-16 nlohmann-json3-dev libgtest-dev zlib1g-dev
ls
