#!/usr/bin/python3
"""The colormaps and colours of src/style/ against matplotlib (Debian's python3-matplotlib):

1. src/style/colormap_tables.cpp is what scripts/make-colormap-tables writes now, byte for byte, so
   the committed tables are matplotlib's.
2. The rule style/colormap.hpp states (entry floor(t * 256) in float64, clamped, 255 from t = 1 up;
   8 bits by truncating c * 255; `_r` the table read backwards, or matplotlib's own 8-bit colours
   where the tables give them) gives `matplotlib.colormaps[name](t, bytes=True)` for every map, at
   each entry's edges, the doubles either side of them and 20,000 values of t in and beyond [0, 1].
   tests/test_style_colormap.cpp checks that the C++ follows the rule, at values taken from here.
3. The CSS names of src/style/color.cpp are matplotlib's CSS4_COLORS, with their colours.

usage: check_colormaps.py SOURCE_DIR BUILD_DIR
"""
import os
import re
import subprocess
import sys

try:
    import matplotlib
    import numpy as np
except ImportError as error:
    sys.exit(f"check_colormaps.py: matplotlib is needed to check the colormap tables ({error}); "
             "install Debian's python3-matplotlib (scripts/deps test)")

NAMES = ["viridis", "magma", "inferno", "plasma", "cividis", "coolwarm", "gray"]
ENTRIES = 256


def check_generated(source, build, failures):
    generated = os.path.join(build, "colormap_tables.cpp")
    subprocess.run([sys.executable, os.path.join(source, "scripts", "make-colormap-tables"), generated], check=True)
    committed = os.path.join(source, "src", "style", "colormap_tables.cpp")
    with open(generated, "rb") as f:
        new = f.read()
    with open(committed, "rb") as f:
        old = f.read()
    if new == old:
        return
    new_lines, old_lines = new.split(b"\n"), old.split(b"\n")
    line = next((i for i, (a, b) in enumerate(zip(new_lines, old_lines)) if a != b), min(len(new_lines), len(old_lines)))
    failures.append(f"{committed} differs from matplotlib's tables ({generated}) from line {line + 1}: "
                    f"run scripts/make-colormap-tables src/style/colormap_tables.cpp")


def rule_bytes(name, reversed_map, t):
    """The 8-bit colours style/colormap.hpp's rule gives at the values t (an array)."""
    table = matplotlib.colormaps[name](np.arange(ENTRIES))[:, :3]
    scaled = t * ENTRIES
    index = np.where(scaled < 0, 0, np.where(scaled >= ENTRIES - 1, ENTRIES - 1, np.trunc(scaled))).astype(int)
    if reversed_map:
        own = matplotlib.colormaps[name + "_r"](np.arange(ENTRIES), bytes=True)[:, :3]
        forward = (table * 255).astype(np.uint8)
        if not np.array_equal(own, forward[::-1]):
            return own[index]  # the generator wrote matplotlib's own 8-bit colours for this map
        index = ENTRIES - 1 - index
    return (table[index] * 255).astype(np.uint8)


def check_rule(failures):
    edges = np.arange(ENTRIES + 1) / ENTRIES
    t = np.concatenate([edges, np.nextafter(edges, -np.inf), np.nextafter(edges, np.inf),
                        np.linspace(-0.25, 1.25, 20000), [-np.inf, np.inf, -1e300, 1e300, -0.0]])
    for name in NAMES:
        for reversed_map in (False, True):
            full = name + ("_r" if reversed_map else "")
            expected = matplotlib.colormaps[full](t, bytes=True)[:, :3]
            got = rule_bytes(name, reversed_map, t)
            wrong = np.nonzero((got != expected).any(axis=1))[0]
            if wrong.size:
                i = wrong[0]
                failures.append(f"{full}: the rule gives {got[i].tolist()} at t = {t[i]!r}, matplotlib "
                                f"{expected[i].tolist()} ({wrong.size} values differ)")


def check_css_names(source, failures):
    with open(os.path.join(source, "src", "style", "color.cpp"), encoding="utf-8") as f:
        rows = re.findall(r'\{"([a-z]+)", 0x([0-9a-f]{6})\}', f.read())
    ours = {name: "#" + rgb for name, rgb in rows}
    theirs = {name: rgb.lower() for name, rgb in matplotlib.colors.CSS4_COLORS.items()}
    if len(rows) != len(ours):
        failures.append("src/style/color.cpp names a colour twice")
    if ours != theirs:
        missing = sorted(set(theirs) - set(ours))
        extra = sorted(set(ours) - set(theirs))
        changed = sorted(n for n in set(ours) & set(theirs) if ours[n] != theirs[n])
        failures.append(f"src/style/color.cpp's names are not matplotlib's CSS4_COLORS: missing {missing[:5]}, "
                        f"extra {extra[:5]}, other colours {changed[:5]}")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: check_colormaps.py SOURCE_DIR BUILD_DIR")
    source, build = sys.argv[1], sys.argv[2]
    failures = []
    check_generated(source, build, failures)
    check_rule(failures)
    check_css_names(source, failures)
    for failure in failures:
        print("FAIL:", failure)
    if failures:
        sys.exit(1)
    print(f"colormap tables, rule and CSS names: as matplotlib {matplotlib.__version__}")


if __name__ == "__main__":
    main()
