#!/usr/bin/env bash
# Check the README's promise on a fresh Debian 12: make a minimal Debian 12
# root with debootstrap in DIR (a new, empty folder), clone this repository's
# HEAD into it, and run one of the README's two commands inside it (chroot),
# as a newcomer would on a new machine.  Needs root (debootstrap, mount,
# chroot) and the network to Debian's archive; the root stays in DIR.
# Usage: sudo scripts/fresh_root.sh DIR [scripts/reproduce.sh | scripts/test.sh] [its options...]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage() { echo "usage: sudo scripts/fresh_root.sh DIR [scripts/reproduce.sh | scripts/test.sh] [options...]" >&2; exit 2; }
[ $# -ge 1 ] || usage
DIR="$1"; shift
COMMAND=("${@:-scripts/reproduce.sh}")
case "${COMMAND[0]}" in scripts/reproduce.sh | scripts/test.sh) ;; *) echo "fresh_root.sh: ${COMMAND[0]}: not one of the README's two commands" >&2; exit 2 ;; esac
[ "$(id -u)" -eq 0 ] || { echo "fresh_root.sh: needs root (debootstrap, mount, chroot)" >&2; exit 2; }
if [ -e "$DIR" ] && [ -n "$(ls -A "$DIR")" ]; then echo "fresh_root.sh: $DIR: not empty (a fresh root needs a new folder)" >&2; exit 2; fi
command -v debootstrap >/dev/null || { apt-get update -q && apt-get install -y -q debootstrap; }

mkdir -p "$DIR"
DIR="$(cd "$DIR" && pwd)"
debootstrap --variant=minbase bookworm "$DIR" http://deb.debian.org/debian
git clone -q "$ROOT" "$DIR/home/superball"
cp /etc/resolv.conf "$DIR/etc/resolv.conf"
mounted=()
cleanup() { for m in "${mounted[@]}"; do umount "$m" || true; done; }
trap cleanup EXIT
for m in proc dev sys; do mount --bind "/$m" "$DIR/$m" && mounted+=("$DIR/$m"); done
# git as on a machine the repository was cloned on; then the command, timed.
chroot "$DIR" /bin/bash -c 'apt-get update -q >/dev/null && apt-get install -y -q git >/dev/null' </dev/null
chroot "$DIR" /bin/bash -c 'cd /home/superball && time "$@"' fresh_root "${COMMAND[@]}" </dev/null
