#!/usr/bin/env bash
# The library as a user gets it: `cmake --install BUILD --prefix P` into a new folder,
# then examples/cpp built against P twice, by its CMake project (find_package(particles)) and by
# hand with pkg-config, and run on the cloth. Checks on the way:
#   - libparticles.so's SONAME is libparticles.so.MAJOR and it exports particles:: names alone;
#   - the installed headers include only the standard library and each other (a consumer needs
#     nothing but the package: the example is compiled with no other include folder);
#   - both builds print the same and save the same frame (a PNG), and the particle they print is the one `particles run --trace`
#     writes at the same time, to the bit (one truth for the command line and the library).
# usage: package_test.sh BUILD_DIR SOURCE_DIR PARTICLES_BINARY
set -euo pipefail
build=$1 source=$2 program=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
library=$(find "$prefix" -name 'libparticles.so.*.*' -type f)
[ -n "$library" ] || { echo "no libparticles.so.X.Y.Z under $prefix" >&2; exit 1; }
libdir=$(dirname "$library")
soname=$(readelf -d "$library" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
case "$soname" in
  libparticles.so.[0-9]*) ;;
  *) echo "SONAME is '$soname', expected libparticles.so.MAJOR" >&2; exit 1 ;;
esac
[ -e "$libdir/$soname" ] || { echo "no $soname link next to $library" >&2; exit 1; }
# Every symbol the library defines for others is the public API's (typeinfo and vtables included).
exported=$(nm -D --defined-only -C "$library")
others=$(echo "$exported" | sed 's/^[0-9a-f]* [A-Za-z] //' |
  grep -v -E '^((typeinfo|typeinfo name|vtable) for )?particles::' | grep -v -E '^PARTICLES_0$' || true)
if [ -n "$others" ]; then
  echo "libparticles.so exports names outside the public API:" >&2
  echo "$others" | head -20 >&2
  exit 1
fi
# The rooms' namespaces (particles::scenario::, particles::render::, …) stay inside. The golden
# room's namespace is also the API's particles::golden (include/particles/golden.hpp): its check()
# and the types of its options and report are the only particles::golden:: names let out.
rooms=$(grep -E 'particles::[a-z_]+::' <<<"$exported" |
  grep -v -E 'particles::golden::(check\(|Options|Report|FrameCheck|StateCheck|Outcome|Shard)\b' || true)
if [ -n "$rooms" ]; then
  echo "libparticles.so exports the rooms' names:" >&2
  echo "$rooms" | head -20 >&2
  exit 1
fi
for name in 'particles::Simulation::step(long)' 'particles::Scenario::load(' 'typeinfo for particles::ScenarioError'; do
  grep -q -F "$name" <<<"$exported" || { echo "libparticles.so does not export $name" >&2; exit 1; }
done
# The installed headers: only <particles/…> and the standard library's.
bad_includes=$(grep -h -E '^\s*#\s*include' "$prefix"/include/particles/*.hpp | grep -v -E '<particles/[a-z_]+\.hpp>' |
  grep -v -E '<(cstdint|functional|memory|optional|span|string|string_view|vector|stdexcept|utility)>' || true)
if [ -n "$bad_includes" ]; then
  echo "the installed headers include more than the standard library: $bad_includes" >&2
  exit 1
fi

cd "$source"
# find_package(particles), as examples/cpp/CMakeLists.txt does.
cmake -S examples/cpp -B "$work/cmake-build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/cmake-build" >/dev/null
"$work/cmake-build/cloth_example" scenarios/cloth.yaml "$work/cmake.png" >"$work/cmake.out"

# pkg-config, by hand. Its output is words for the compiler's command line, split where it puts spaces.
read -r -a flags < <(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags --libs particles)
# The flags carry -std=c++20: a program built with them alone compiles.
[[ " ${flags[*]} " == *" -std=c++20 "* ]] || { echo "pkg-config --cflags particles lacks -std=c++20: ${flags[*]}" >&2; exit 1; }
c++ examples/cpp/main.cpp "${flags[@]}" -o "$work/pkg-config-example"
# An older standard is told what the headers need, before any other error.
read -r -a cflags < <(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags particles)
if c++ -fsyntax-only "${cflags[@]}" -std=c++17 examples/cpp/main.cpp 2>"$work/cxx17.err"; then
  echo "the headers compiled as C++17" >&2
  exit 1
fi
first_error=$(grep -m1 'error' "$work/cxx17.err" || true)
[[ "$first_error" == *"particles' headers need C++20"* ]] ||
  { echo "C++17's first error is not the headers' own: $first_error" >&2; exit 1; }
LD_LIBRARY_PATH="$libdir" "$work/pkg-config-example" scenarios/cloth.yaml "$work/pkg-config.png" >"$work/pkg-config.out"
sed -i 's|saved to .*|saved|' "$work/cmake.out" "$work/pkg-config.out"
cmp "$work/cmake.out" "$work/pkg-config.out" || { echo "the two builds print differently" >&2; exit 1; }
cmp "$work/cmake.png" "$work/pkg-config.png" || { echo "the two builds save different frames" >&2; exit 1; }
[ "$(head -c 8 "$work/cmake.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  { echo "the example's frame is not a PNG" >&2; exit 1; }

# The particle printed against the command line's trace at the same time.
"$program" run scenarios/cloth.yaml --dt 0.005 --duration 0.5 --threads 2 --quiet \
  --trace "$work/trace.csv"
/usr/bin/python3 - "$work/cmake.out" "$work/trace.csv" <<'PY'
import csv, sys
out = open(sys.argv[1], encoding="utf-8").read().splitlines()
print("\n".join(out))
name, rest = out[1].split(" at (", 1)
x, y = (float(v) for v in rest.split(")")[0].split(", "))
t = float(out[0].split(" at t = ")[1].split(" s")[0])
rows = [r for r in csv.DictReader(open(sys.argv[2], encoding="utf-8")) if r["name"] == name]
last = rows[-1]
assert abs(float(last["t"]) - t) < 1e-9, (last["t"], t)
assert (float(last["x"]), float(last["y"])) == (x, y), ("library", x, y, "particles run --trace", last["x"], last["y"])
print(f"{name} at t = {t}: the same bits as particles run --trace")
PY
