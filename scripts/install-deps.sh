#!/usr/bin/env bash
# Installs the Debian packages lumaslam needs. Idempotent and quiet when all are present.
# Works as root or through sudo; anything else fails with a message naming the packages.
# --fuzz also installs clang with libFuzzer, for `make fuzz` only (not needed to build or test).
set -euo pipefail

packages=(
  build-essential cmake make pkg-config
  libopencv-dev          # core, imgproc, imgcodecs, videoio, calib3d, features2d, dnn
  libeigen3-dev
  libceres-dev libsuitesparse-dev
  libcli11-dev libspdlog-dev nlohmann-json3-dev libtbb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcereal-dev          # map files
  pybind11-dev python3-dev python3-numpy  # the Python module (python/)
  libcpp-httplib-dev libjs-three  # the live viewer (docs/viewer.md): HTTP server, 3D drawing
  chromium               # browser tests: the viewer's page and `lumaslam report` pages, headless
  parallel               # GNU parallel: `lumaslam experiment --emit parallel` jobs (and its test)
)
if [[ "${1:-}" == "--fuzz" ]]; then
  # libFuzzer's runtime is in libclang-rt, not in clang; `make fuzz` configures with -G Ninja
  packages+=(clang libclang-rt-dev ninja-build)
elif [[ $# -gt 0 ]]; then
  echo "install-deps: unknown option '$1' (known: --fuzz)" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  as_root=(sudo)
else
  echo "install-deps: these Debian packages are missing: ${missing[*]}" >&2
  echo "install-deps: run this script as root or with password-less sudo, or install them with:" >&2
  echo "  sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
