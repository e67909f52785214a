#!/usr/bin/env bash
# One-command setup for a fresh Debian bookworm machine (and CI).
#  - Mesa >= 25 lavapipe: Dawn rejects bookworm's Mesa 22.3, so on a machine without a GPU the
#    Vulkan software driver comes from bookworm-backports.
#  - Debian's chromium for the browser tests (never a downloaded browser build).
#  - Debian's redis-server for the render farm's tests, and openssl for their TLS certificate.
#  - npm dependencies, including Node.js 24 (the `node` package) that every npm script runs on.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" != "0" ] && command -v sudo >/dev/null 2>&1; then SUDO="sudo"; fi

mesa_major() {
  dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null | sed -E 's/^([0-9]+).*/\1/' || true
}

if command -v apt-get >/dev/null 2>&1; then
  need_update=1
  major="$(mesa_major)"
  if [ -z "$major" ] || [ "$major" -lt 25 ]; then
    if grep -q bookworm /etc/os-release 2>/dev/null && ! grep -rqs bookworm-backports /etc/apt/sources.list /etc/apt/sources.list.d/; then
      echo "deb http://deb.debian.org/debian bookworm-backports main" | $SUDO tee /etc/apt/sources.list.d/bookworm-backports.list >/dev/null
    fi
    $SUDO apt-get update -qq; need_update=0
    if grep -q bookworm /etc/os-release 2>/dev/null; then
      DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq -t bookworm-backports mesa-vulkan-drivers
    else
      DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq mesa-vulkan-drivers
    fi
  fi
  if ! command -v chromium >/dev/null 2>&1; then
    if [ "$need_update" = 1 ]; then $SUDO apt-get update -qq; need_update=0; fi
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium
  fi
  # The render farm tests start their own redis-server on a free loopback port (any system service is left alone).
  if ! command -v redis-server >/dev/null 2>&1; then
    if [ "$need_update" = 1 ]; then $SUDO apt-get update -qq; need_update=0; fi
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq redis-server
  fi
  # The farm's TLS test makes a self-signed certificate for its redis-server with openssl.
  if ! command -v openssl >/dev/null 2>&1; then
    if [ "$need_update" = 1 ]; then $SUDO apt-get update -qq; need_update=0; fi
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq openssl
  fi
fi

if [ -f package-lock.json ]; then npm ci --no-fund --no-audit; else npm install --no-fund --no-audit; fi
echo "setup: mesa-vulkan-drivers $(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || echo n/a), node $(node_modules/.bin/node --version), chromium $(command -v chromium || echo missing), redis-server $(command -v redis-server || echo missing), openssl $(command -v openssl || echo missing)"
