#!/bin/sh
# help2man.sh — make the shlab(1) man page from `shlab --help` and every
# command's --help, so the manual never drifts from the program.
set -eu
bin=$1
ver=$("$bin" --version | awk '{print $2}')
esc() { sed -e 's/\\/\\e/g' -e 's/^\./\\\&./' -e "s/^'/\\\\\\&'/"; }
echo ".TH SHLAB 1 \"\" \"shlab $ver\" \"User Commands\""
echo ".SH NAME"
echo "shlab \\- numerical verification workbench for real spherical harmonics"
echo ".SH SYNOPSIS"
echo ".B shlab"
echo "COMMAND [OPTIONS]"
echo ".SH DESCRIPTION"
echo ".nf"
"$bin" --help | esc
echo ".fi"
for c in $("$bin" --help | awk '/^Commands:/{on=1;next} on&&/^  [a-z]/{print $1} on&&/^$/{on=0}'); do
    echo ".SH COMMAND: $c"
    echo ".nf"
    "$bin" "$c" --help | esc
    echo ".fi"
done
