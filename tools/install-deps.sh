#!/usr/bin/env bash
# Installs the Debian packages shpb needs, only those that are missing. Idempotent, no prompts.
set -euo pipefail
packages=(g++ cmake make pkg-config libeigen3-dev nlohmann-json3-dev libfftw3-dev libcli11-dev catch2
          python3-matplotlib python3-numpy libceres-dev)
packages+=("$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}" >&2
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
