#!/usr/bin/env bash
# Times what a golden CI job of docs/ci/ does before it checks a frame, the way the recipes did it
# (build particles) and the way they do it now (unpack a release archive), each in its own fresh
# copy of a Debian 12 root (debootstrap --variant=minbase, plus git, ca-certificates and sudo: a
# CI image with the checkout done), run by chroot as root, every package downloaded by apt:
#   before  this repository's HEAD cloned from a bundle (as bench/fresh-machine.sh does), then
#           .particles/scripts/deps, then the old recipe's configure and build of the `particles`
#           target (-G Ninja, RelWithDebInfo, -DPARTICLES_TESTS=OFF -DPARTICLES_BENCH=OFF,
#           -j $(nproc)) with nothing cached: a pipeline's first run for a particles commit.
#   after   apt-get install curl xz-utils ca-certificates (GitLab's debian:12 lacks curl and xz;
#           GitHub's runner has them: subtract this phase there), the archive copied in place of
#           the download (NOT timed: its size is printed, so that a network's time can be added),
#           then unpacked by the recipe's tar -xJ --strip-components=1 into .particles/.
# Then, in each root, `particles golden check golden/golden.yaml -o report` on the checkout's
# golden/ and scenarios/ (HEAD's), which must pass in both. Prints the wall and CPU seconds of each
# phase (CPU time moves less than wall time on a machine others load); each phase's output goes to
# OUT/before.log or OUT/after.log.
#
# usage (as root, on a Debian machine): bench/ci-setup.sh OUT ARCHIVE
#   OUT      a new folder: the roots go to OUT/before (2 GB) and OUT/after (0.7 GB), the logs
#            beside them; unmounted at the end, remove it with rm -rf --one-file-system OUT.
#   ARCHIVE  a particles-VERSION-linux-x86_64.tar.xz (scripts/release).
#   A Debian 12 root to copy instead of running debootstrap: BASE_ROOT=DIR. Another commit than
#   HEAD: REV=COMMIT. Only one of the two: ONLY=before or ONLY=after.
# Not part of scripts/test: it needs root and a Debian mirror; bench/README.md has its results
# ("Golden CI job set-up").
set -euo pipefail
[ $# -eq 2 ] || { sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
out="$1" archive="$2"
[ "$(id -u)" -eq 0 ] || { echo "bench/ci-setup.sh needs root (debootstrap, chroot, mounts)" >&2; exit 2; }
[ -f "$archive" ] || { echo "no archive $archive" >&2; exit 2; }
case "$(basename "$archive")" in
  particles-*-linux-x86_64.tar.xz) ;;
  *) echo "$archive is not a particles-VERSION-linux-x86_64.tar.xz" >&2; exit 2 ;;
esac
case "${ONLY:-both}" in before|after|both) ;; *) echo "ONLY is before or after, not '$ONLY'" >&2; exit 2 ;; esac
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -e "$out" ] && { echo "$out exists: give a new folder" >&2; exit 2; }
if [ -n "${BASE_ROOT:-}" ]; then
  base_release=$(. "$BASE_ROOT/etc/os-release" 2>/dev/null && echo "${VERSION_CODENAME:-}")
  [ "$base_release" = bookworm ] ||
    { echo "BASE_ROOT $BASE_ROOT is Debian '${base_release:-unknown}', not bookworm (12)" >&2; exit 2; }
fi
rev="${REV:-HEAD}"
git -C "$repo" rev-parse --verify --quiet "$rev^{commit}" >/dev/null || { echo "no commit $rev" >&2; exit 2; }
mkdir -p "$out"
out="$(cd "$out" && pwd)"
archive="$(cd "$(dirname "$archive")" && pwd)/$(basename "$archive")"

# shellcheck source=../scripts/lib/debian-root
. "$repo/scripts/lib/debian-root"
trap debian_root_leave EXIT

# A new root at $1, as bench/fresh-machine.sh makes one, ready to enter (scripts/lib/debian-root).
new_root() {
  local root="$1"
  if [ -n "${BASE_ROOT:-}" ]; then
    cp -a "$BASE_ROOT" "$root"
  else
    debootstrap --variant=minbase --include=ca-certificates,git,sudo bookworm "$root" \
      http://deb.debian.org/debian >"$root.debootstrap.log"
  fi
  debian_root_enter "$root"
}

# Runs bash -c "$3" in root $1 from the checkout /root/work as phase $2, output to $log; prints
# the phase's wall and CPU seconds (user + system, of every process it ran) and stops the script
# when it fails.
phase() {
  local root="$1" name="$2" status=0 wall user system TIMEFORMAT='%R %U %S'
  echo "== $name" >>"$log"
  { time chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      LANG=C.UTF-8 bash -c "set -eo pipefail; cd /root/work; $3" >>"$log" 2>&1; } 2>"$out/phase.time" || status=$?
  read -r wall user system <"$out/phase.time"
  awk -v n="$name" -v w="$wall" -v c="$(echo "$user $system" | awk '{ print $1 + $2 }')" \
    'BEGIN { printf "  %-52s %7.1f s  (CPU %.1f s)\n", n, w, c }'
  [ "$status" -eq 0 ] || { echo "$name failed (exit $status): $log" >&2; exit 1; }
}

git -C "$repo" branch -f ci-setup-measured "$rev" >/dev/null
git -C "$repo" bundle create "$out/head.bundle" ci-setup-measured >/dev/null 2>&1
git -C "$repo" branch -D ci-setup-measured >/dev/null

# The CI's checkout of the repository with the manifest (here: this one), not timed: both recipes
# begin after it.
checkout() {
  cp "$out/head.bundle" "$1/tmp/head.bundle"
  chroot "$1" git clone -q -b ci-setup-measured /tmp/head.bundle /root/work
}

check='particles golden check golden/golden.yaml -o report'
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg); $(nproc) CPUs"

if [ "${ONLY:-both}" != before ]; then
  root="$out/after" log="$out/after.log"
  new_root "$root"
  checkout "$root"
  echo "after (the archive, $(stat -c %s "$archive") bytes, copied in place of the download: add its download time):"
  phase "$root" "apt-get install curl xz-utils ca-certificates" \
    'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends curl xz-utils ca-certificates'
  cp "$archive" "$root/tmp/particles.tar.xz"
  phase "$root" "unpack (tar -xJ)" \
    'mkdir -p .particles && tar -xJ --strip-components=1 -C .particles -f /tmp/particles.tar.xz && rm /tmp/particles.tar.xz'
  phase "$root" "particles --version" '.particles/bin/particles --version'
  phase "$root" "$check" "PATH=\"\$PWD/.particles/bin:\$PATH\" $check"
fi

if [ "${ONLY:-both}" != after ]; then
  root="$out/before" log="$out/before.log"
  new_root "$root"
  checkout "$root"
  echo "before (particles built, nothing cached):"
  phase "$root" "git clone (particles, from a bundle)" 'git clone -q -b ci-setup-measured /tmp/head.bundle .particles'
  phase "$root" ".particles/scripts/deps" '.particles/scripts/deps'
  phase "$root" "cmake configure" \
    'cmake -S .particles -B .particles/build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPARTICLES_TESTS=OFF -DPARTICLES_BENCH=OFF'
  # shellcheck disable=SC2016  # $(nproc) is the root's, expanded there
  phase "$root" "cmake --build --target particles" 'cmake --build .particles/build -j "$(nproc)" --target particles'
  phase "$root" "particles --version" '.particles/build/particles --version'
  phase "$root" "$check" "PATH=\"\$PWD/.particles/build:\$PATH\" $check"
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
