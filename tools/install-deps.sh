#!/usr/bin/env bash
# Installs the Debian packages shpb needs, only those that are missing. Idempotent, no prompts.
set -euo pipefail
packages=(g++ cmake make pkg-config libeigen3-dev nlohmann-json3-dev libfftw3-dev libcli11-dev catch2
          python3-matplotlib python3-numpy python3-pytest libzip-dev libexpat1-dev libfreexl-dev
          libceres-dev)
# The Python module (docs/python.md): pybind11 to build it; pytest, nbclient, ipykernel and pandas
# to test it and run its notebook.
packages+=(pybind11-dev python3-pybind11 python3-dev python3-pytest python3-nbclient python3-ipykernel
           python3-pandas)
packages+=("$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}" >&2
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
# Daemon packages (slurm-wlm, munge: `make test` starts its own in a temporary folder) must not
# start system services that linger: a policy-rc.d that denies every start while installing,
# unless the machine has one already.
policy=/usr/sbin/policy-rc.d
if [ ! -e "$policy" ]; then
  trap '$sudo rm -f "$policy"' EXIT
  printf '#!/bin/sh\nexit 101\n' | $sudo tee "$policy" >/dev/null
  $sudo chmod +x "$policy"
fi
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
