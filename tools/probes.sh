#!/bin/sh
# probes.sh DIR — fetch Blender's eight CC0 HDR world probes (the lat-long
# "studio light" worlds shipped in Debian's blender-data package) into DIR.
#
#   apt-get download blender-data           (into a temporary directory)
#   dpkg-deb --fsys-tarfile | tar -x '*studiolights/world/*.exr'
#   copy the .exr files into DIR
#
# Idempotent: does nothing when the eight files are already there.  Needs
# apt (apt-get update is run once when the package is unknown and we are
# root; as non-root the existing package lists must already know it).
set -eu
dest=${1:-data/probes}
want=8

count_exr() {
    n=0
    for f in "$1"/*.exr; do [ -f "$f" ] && n=$((n + 1)); done
    echo "$n"
}

mkdir -p "$dest"
have=$(count_exr "$dest")
if [ "$have" -ge "$want" ]; then
    echo "probes: all $have present in $dest:"
    ls -l "$dest"/*.exr
    exit 0
fi

if ! command -v apt-get >/dev/null 2>&1 || ! command -v dpkg-deb >/dev/null 2>&1; then
    echo "probes: error: apt-get and dpkg-deb are needed (Debian/Ubuntu); install the" >&2
    echo "probes: error: blender-data package's studiolights/world/*.exr by hand into $dest" >&2
    exit 1
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/shlab-probes.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

if ! apt-cache show blender-data >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ]; then
        echo "probes: blender-data unknown to apt; running apt-get update"
        apt-get update -qq
    else
        echo "probes: error: apt does not know blender-data; run 'apt-get update' as root first" >&2
        exit 1
    fi
fi

echo "probes: downloading blender-data (about 31 MB)"
# apt-get download writes into the current directory; as root it may drop
# privileges to _apt, so make the temporary directory writable for it.
chmod 0777 "$tmp"
if ! (cd "$tmp" && apt-get download -q blender-data); then
    echo "probes: error: apt-get download blender-data failed" >&2
    exit 1
fi
deb=$(ls "$tmp"/blender-data_*.deb 2>/dev/null | head -1)
if [ -z "$deb" ]; then
    echo "probes: error: no blender-data .deb downloaded" >&2
    exit 1
fi
echo "probes: got $(basename "$deb")"
mkdir -p "$tmp/x"
dpkg-deb --fsys-tarfile "$deb" | (cd "$tmp/x" && tar -x --wildcards '*studiolights/world/*.exr')
got=0
for f in "$tmp"/x/usr/share/blender/*/datafiles/studiolights/world/*.exr \
         "$tmp"/x/usr/share/blender/datafiles/studiolights/world/*.exr; do
    [ -f "$f" ] || continue
    cp "$f" "$dest/"
    got=$((got + 1))
done
if [ "$got" -eq 0 ]; then
    echo "probes: error: the package holds no studiolights/world/*.exr" >&2
    exit 1
fi
echo "probes: copied $got file(s) into $dest:"
ls -l "$dest"/*.exr
have=$(count_exr "$dest")
if [ "$have" -lt "$want" ]; then
    echo "probes: warning: expected $want probes, have $have" >&2
fi
