#!/bin/sh
# deps.sh — make sure the Debian packages shlab needs are installed.
# As root: installs what is missing (apt-get update first).  Otherwise: prints
# the exact command to run and fails.  --quiet: say nothing when all is there.
set -eu
PKGS="build-essential pkg-config libgsl-dev libopenexr-dev libjansson-dev libmpfr-dev check gnuplot-nox"
PKGS="$PKGS parallel" # GNU parallel: sweeps run as shards on one machine (README, make check)
missing=""
for p in $PKGS; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done
if [ -z "$missing" ]; then
    [ "${1:-}" = "--quiet" ] || echo "deps: all present ($PKGS)"
    exit 0
fi
cmd="apt-get update && apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" = 0 ]; then
    echo "deps: installing$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing
else
    echo "deps: missing packages:$missing" >&2
    echo "deps: run as root:  $cmd" >&2
    exit 1
fi
