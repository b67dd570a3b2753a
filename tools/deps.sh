#!/bin/sh
# deps.sh - install the Debian packages mpbench builds and tests with.
#
# Idempotent: asks dpkg first and installs only what is missing, so a second
# run costs a fraction of a second. Uses sudo when not run as root.
set -eu
. "$(dirname "$0")/usage.sh"
mpb_no_arguments "$@"

PACKAGES="
  build-essential cmake pkg-config
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev
  libfcl-dev libccd-dev
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev
  liburdfdom-dev libtinyxml-dev libassimp-dev libeigen3-dev
  libsqlite3-dev sqlite3 libcmocka-dev libyaml-dev libsodium-dev
  iproute2 iptables util-linux
  default-jdk-headless default-jre python3 python3-venv
  xvfb gnuplot-nox libjchart2d-java x11-apps netpbm
  clang libfuzzer-14-dev libclang-rt-14-dev
"

missing=""
for p in $PACKAGES; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
        missing="$missing $p"
    fi
done

if [ -z "$missing" ]; then
    echo "deps: all packages present"
    exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi

echo "deps: installing:$missing"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing
