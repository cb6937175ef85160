#!/usr/bin/env bash
# Installs the Debian packages named that are not installed yet (apt-get update first), as root or
# through sudo; installs nothing when all are there. Every script of the package installs through it.
#
#   bash scripts/install_packages.sh WHO PACKAGE...   WHO prefixes the one line it prints
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
who=$1
shift
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
echo "$who: installing ${#missing[@]} Debian packages: ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo=sudo
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
