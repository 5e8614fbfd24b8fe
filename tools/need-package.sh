#!/bin/sh
# need-package.sh PACKAGE FILE [HINT]: make sure FILE exists, installing the Debian PACKAGE
# that provides it with apt-get when we are root; otherwise stop with one line naming the
# package (and HINT, when given, at its end: what else the user can do).
pkg=$1 file=$2 hint=${3:-}
[ -e "$file" ] && exit 0
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "fogrt: installing $pkg (provides $file)" >&2
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$pkg"; } >/dev/null 2>&1
    [ -e "$file" ] && exit 0
fi
echo "fogrt: missing package $pkg: install it with 'sudo apt-get install $pkg'${hint:+, $hint}" >&2
exit 1
