#!/usr/bin/env bash
# Times the README's two commands as a new user meets them: a fresh Debian root (debootstrap
# --variant=minbase, plus git, ca-certificates and sudo), `git clone` of this repository's HEAD
# into it, then `scripts/demo` or `scripts/test` run inside it by chroot, every package downloaded
# and installed by the script itself. Prints the wall time from the clone to the script's end;
# the script's own output goes to OUT/SCRIPT.log, each line after the seconds since the clone began
# (so the stages of any version of the scripts can be timed).
#
# usage (as root, on a Debian machine with debootstrap): bench/fresh-machine.sh OUT demo|test [RELEASE]
#   RELEASE  bookworm or 12 (the default), trixie or 13: the Debian release of the root.
#   OUT      a new folder: the root file system goes to OUT/root (a few GB), the log beside it.
#            A debootstrapped root (of RELEASE) to copy instead of downloading one: BASE_ROOT=DIR.
#            Another commit than HEAD: REV=COMMIT.
# Not part of scripts/test: it needs root and a network mirror; bench/README.md has its results.
# Slurm's daemons need more than a chroot gives (their own host name, systemd-less munged), so the
# Slurm test may report itself skipped in here; it runs on a real machine (CI).
set -euo pipefail
[ $# -eq 2 ] || [ $# -eq 3 ] || { sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
out="$1" script="$2"
case "$script" in demo|test) ;; *) echo "expected demo or test, got '$script'" >&2; exit 2 ;; esac
case "${3:-bookworm}" in
  bookworm|12) release=bookworm version=12 ;;
  trixie|13) release=trixie version=13 ;;
  *) echo "expected the release bookworm (12) or trixie (13), got '$3'" >&2; exit 2 ;;
esac
[ "$(id -u)" -eq 0 ] || { echo "bench/fresh-machine.sh needs root (debootstrap, chroot, mounts)" >&2; exit 2; }
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -e "$out" ] && { echo "$out exists: give a new folder" >&2; exit 2; }
if [ -n "${BASE_ROOT:-}" ]; then
  # A root of another release would be timed under this one's name.
  base_release=$(. "$BASE_ROOT/etc/os-release" 2>/dev/null && echo "${VERSION_CODENAME:-}")
  [ "$base_release" = "$release" ] ||
    { echo "BASE_ROOT $BASE_ROOT is Debian '${base_release:-unknown}', not $release" >&2; exit 2; }
fi
mkdir -p "$out"
out="$(cd "$out" && pwd)"
root="$out/root"

if [ -n "${BASE_ROOT:-}" ]; then
  cp -a "$BASE_ROOT" "$root"
else
  debootstrap --variant=minbase --include=ca-certificates,git,sudo "$release" "$root" \
    http://deb.debian.org/debian >"$out/debootstrap.log"
fi
# Name resolution, localhost, this network's CAs, /proc /sys /dev mounted: scripts/lib/debian-root.
# shellcheck source=../scripts/lib/debian-root
. "$repo/scripts/lib/debian-root"
trap debian_root_leave EXIT
debian_root_enter "$root"

rev="${REV:-HEAD}"
git -C "$repo" rev-parse --verify --quiet "$rev^{commit}" >/dev/null || { echo "no commit $rev" >&2; exit 2; }
git -C "$repo" branch -f fresh-machine-measured "$rev" >/dev/null
git -C "$repo" bundle create "$out/head.bundle" fresh-machine-measured >/dev/null 2>&1
git -C "$repo" branch -D fresh-machine-measured >/dev/null
cp "$out/head.bundle" "$root/tmp/head.bundle"
start=$(date +%s)
status=0
chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  LANG=C.UTF-8 bash -c 'git clone -q -b fresh-machine-measured /tmp/head.bundle /root/particles &&
    cd /root/particles && "scripts/$1"' fresh-machine "$script" 2>&1 |
  while IFS= read -r line; do printf '%5d %s\n' "$(($(date +%s) - start))" "$line"; done >"$out/$script.log" ||
  status=$?
end=$(date +%s)
echo "scripts/$script on a new Debian $version ($release) root: $((end - start)) s from git clone to its end (exit $status);" \
     "log: $out/$script.log"
exit "$status"
