#!/bin/sh
# models.sh DIR — fetch the real test meshes the scene tests and report use
# (from Debian's assimp-testmodels package: the Wuson model in PLY and OBJ,
# and the spider OBJ) into DIR.  Not committed.
#
#   copied from /usr/share/assimp/models when the package is installed, else
#   apt-get download assimp-testmodels (into a temporary directory) and
#   dpkg-deb --fsys-tarfile | tar -x of the files below.
#
# Idempotent: does nothing when every file is there.
set -eu
dest=${1:-data/models}
files="PLY/Wuson.ply OBJ/WusonOBJ.obj OBJ/spider.obj"

mkdir -p "$dest"
missing=""
for f in $files; do [ -f "$dest/$(basename "$f")" ] || missing="$missing $f"; done
if [ -z "$missing" ]; then
    echo "models: all present in $dest:"
    ls -l "$dest"
    exit 0
fi

src=/usr/share/assimp/models
tmp=""
if [ ! -d "$src" ]; then
    if ! command -v apt-get >/dev/null 2>&1 || ! command -v dpkg-deb >/dev/null 2>&1; then
        echo "models: error: apt-get and dpkg-deb are needed (Debian/Ubuntu); copy$missing" >&2
        echo "models: error: from the assimp-testmodels package into $dest by hand" >&2
        exit 1
    fi
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/shlab-models.XXXXXX")
    trap 'rm -rf "$tmp"' EXIT INT TERM
    if ! apt-cache show assimp-testmodels >/dev/null 2>&1; then
        if [ "$(id -u)" = 0 ]; then
            echo "models: assimp-testmodels unknown to apt; running apt-get update"
            apt-get update -qq
        else
            echo "models: error: apt does not know assimp-testmodels; run 'apt-get update' as root first" >&2
            exit 1
        fi
    fi
    echo "models: downloading assimp-testmodels"
    chmod 0777 "$tmp"
    if ! (cd "$tmp" && apt-get download -q assimp-testmodels); then
        echo "models: error: apt-get download assimp-testmodels failed" >&2
        exit 1
    fi
    deb=$(ls "$tmp"/assimp-testmodels_*.deb 2>/dev/null | head -1)
    [ -n "$deb" ] || { echo "models: error: no assimp-testmodels .deb downloaded" >&2; exit 1; }
    mkdir -p "$tmp/x"
    for f in $missing; do
        dpkg-deb --fsys-tarfile "$deb" | (cd "$tmp/x" && tar -x --wildcards "*/models/$f")
    done
    src="$tmp/x/usr/share/assimp/models"
fi
for f in $missing; do
    if [ ! -f "$src/$f" ]; then
        echo "models: error: $f is not in assimp-testmodels" >&2
        exit 1
    fi
    cp "$src/$f" "$dest/"
done
echo "models: copied into $dest:"
ls -l "$dest"
