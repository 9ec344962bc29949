#!/usr/bin/env bash
# Installs the Debian bookworm packages the build and the tests need, and only those that are missing.
# Safe to run again: with everything present it only checks.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git python3
  antlr4 default-jre-headless libantlr4-runtime-dev uuid-dev
  libeigen3-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libmujoco-dev libgl-dev libegl-dev libegl1 libgl1-mesa-dri
  libompl-dev libfcl-dev libccd-dev
  libcurl4-openssl-dev libssl-dev libsqlite3-dev sqlite3 libedit-dev libcpp-httplib-dev tmux
  libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev clang-format
  libcairo2-dev fonts-dejavu-core
  slurm-wlm munge
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
