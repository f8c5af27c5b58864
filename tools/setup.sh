#!/usr/bin/env bash
# Installs what lamina needs on Debian 12, and only what is missing: Debian packages through
# apt, and the pinned npm packages of package-lock.json. Quiet when there is nothing to do.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake ninja-build g++ libembree-dev libopenimageio-dev openimageio-tools nlohmann-json3-dev
  libglm-dev libpng-dev doctest-dev libcli11-dev libbenchmark-dev clang-format glslang-tools
  fonts-dejavu-core
  # clang with its sanitizer and libFuzzer runtimes: the asan build and the fuzzers of tests/fuzz
  clang libclang-rt-14-dev
  # headless OpenGL and GL ES on the CPU (Mesa llvmpipe through EGL) for the GLSL parity tests
  libegl-dev libgl-dev libopengl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# node and npm may come from another package than Debian's (e.g. a newer nodejs); ask for the commands.
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# npm packages, exactly as locked; reinstalled only when the lock file changes.
stamp=node_modules/.lamina-lock-stamp
if [ -f package-lock.json ] && ! cmp -s package-lock.json "$stamp" 2>/dev/null; then
  echo "setup: installing npm packages from package-lock.json"
  npm ci --no-audit --no-fund --loglevel=error >/dev/null
  cp package-lock.json "$stamp"
fi
