#!/usr/bin/env bash
# Installs the Debian bookworm packages the build and the tests need, and only those that are missing, then the
# browser test's npm package (tests/browser: playwright-core, which drives Debian's chromium).
#   scripts/install-deps.sh          everything `make test` needs
#   scripts/install-deps.sh --demo   only what `make demo` needs: the compilers, the libraries cbtl and cbtlc link,
#                                    ANTLR's tool; no test frameworks, SLURM, browser or Node.js
# Safe to run again: with everything present it only checks.
set -euo pipefail

demo_only=0
if [ "${1:-}" = "--demo" ]; then demo_only=1; fi

# What cbtl and cbtlc need to build and run.
packages=(
  build-essential cmake ninja-build pkg-config
  antlr4 default-jre-headless libantlr4-runtime-dev uuid-dev
  libeigen3-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libmujoco-dev libgl-dev libegl-dev libegl1 libgl1-mesa-dri
  libompl-dev libfcl-dev libccd-dev
  zlib1g-dev libexpat1-dev libcurl4-openssl-dev libssl-dev libsqlite3-dev libedit-dev libcpp-httplib-dev
  libcairo2-dev fonts-dejavu-core
)
if [ $demo_only -eq 0 ]; then
  # What the tests add: their frameworks, the tools they drive (git, python3 simulators, sqlite3, tmux for the
  # REPL, SLURM for sweeps, Chromium for the study's pages), the fuzzer's clang and the format check.
  packages+=(
    git python3 sqlite3 tmux
    libgtest-dev libgmock-dev libbenchmark-dev
    clang libclang-rt-14-dev clang-format
    slurm-wlm munge
    chromium
  )
  # Node.js for the browser test: Debian's, unless a node is there already (e.g. from NodeSource, whose package
  # conflicts with Debian's npm).
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    packages+=(nodejs npm)
  fi
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

browser_test_packages() {
  if [ $demo_only -eq 1 ]; then return 0; fi
  local dir
  dir="$(cd "$(dirname "$0")/.." && pwd)/tests/browser"
  local pinned installed=""
  pinned=$(grep -o '"playwright-core": "[^"]*"' "$dir/package.json" | cut -d'"' -f4)
  if [ -f "$dir/node_modules/playwright-core/package.json" ]; then
    installed=$(grep -o '"version": "[^"]*"' "$dir/node_modules/playwright-core/package.json" | head -1 | cut -d'"' -f4)
  fi
  if [ "$installed" != "$pinned" ]; then
    echo "install-deps: installing the browser test's npm packages in $dir (playwright-core $pinned)"
    npm ci --prefix "$dir" --no-audit --no-fund --loglevel=error
  fi
}

if [ ${#missing[@]} -eq 0 ]; then
  browser_test_packages
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
browser_test_packages
