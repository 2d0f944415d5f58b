#!/usr/bin/env python3
"""The gallery's styled pictures are what the program draws now: runs scripts/make-gallery into a
scratch folder and compares each picture with the one committed in docs/gallery/.

    gallery_test.py PARTICLES SOURCE_DIR SCRATCH

Fails when a picture differs beyond the golden frames' tolerance (`particles compare`'s defaults,
golden/README.md: a pixel differs by more than 16 in a channel, more than 0.02 % of them; the
diff picture is kept in SCRATCH/diffs/), when a committed picture has no command of
docs/gallery.md that makes it (extra) or a command's picture is not committed (missing), when a
picture is over 150 KB, and when a style file of docs/gallery/ is not named by a command and
shown, as it is, in a ```yaml block of the page. SCRATCH's folders pictures/ and diffs/ are this
test's: their PNG files are removed before it runs, nothing else.
"""
import glob
import os
import subprocess
import sys

MAX_BYTES = 150 * 1024  # a picture of the page: 480×270 PNGs are 5 to 55 KB


def empty_folder(folder):
    """The folder, made or emptied of the PNG files an earlier run left (nothing else is removed)."""
    os.makedirs(folder, exist_ok=True)
    for path in glob.glob(os.path.join(folder, "*.png")):
        os.remove(path)
    others = os.listdir(folder)
    if others:
        sys.exit(f"gallery_test: {folder} holds files this test did not write: {', '.join(sorted(others))}")


def yaml_blocks(text):
    """The contents of a markdown page's ```yaml blocks, each as its lines joined with newlines."""
    blocks, current = [], None
    for line in text.split("\n"):
        if current is None and line.strip() == "```yaml":
            current = []
        elif current is not None and line.strip() == "```":
            blocks.append("\n".join(current) + "\n")
            current = None
        elif current is not None:
            current.append(line)
    return blocks


def style_file_failures(source):
    """Every style file of docs/gallery/ used by a command of the page and shown as it is."""
    with open(os.path.join(source, "docs", "gallery.md"), encoding="utf-8") as f:
        page = f.read()
    shown = yaml_blocks(page)
    failures = []
    for path in sorted(glob.glob(os.path.join(source, "docs", "gallery", "*.yaml"))):
        relative = "docs/gallery/" + os.path.basename(path)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        if f"--style {relative} " not in page:
            failures.append(f"{relative}: no command of docs/gallery.md takes it (--style {relative})")
        if text not in shown:
            failures.append(f"{relative}: docs/gallery.md shows no ```yaml block equal to it")
    return failures


def main():
    particles, source, scratch = sys.argv[1], sys.argv[2], sys.argv[3]
    made, diffs = os.path.join(scratch, "pictures"), os.path.join(scratch, "diffs")
    empty_folder(made)
    empty_folder(diffs)
    run = subprocess.run([sys.executable, os.path.join(source, "scripts", "make-gallery"), "--particles", particles,
                          "-o", made])
    failures = [] if run.returncode == 0 else [f"scripts/make-gallery exited {run.returncode}"]
    committed_folder = os.path.join(source, "docs", "gallery")
    committed = {os.path.basename(p) for p in glob.glob(os.path.join(committed_folder, "*.png"))}
    rendered = {os.path.basename(p) for p in glob.glob(os.path.join(made, "*.png"))}
    for name in sorted(committed - rendered):
        failures.append(f"docs/gallery/{name}: committed, but no command of docs/gallery.md made it "
                        "(remove it, or add its command)")
    for name in sorted(rendered - committed):
        failures.append(f"docs/gallery/{name}: made by docs/gallery.md but not committed "
                        "(run scripts/make-gallery and commit it)")
    for name in sorted(committed & rendered):
        expected = os.path.join(committed_folder, name)
        result = subprocess.run([particles, "compare", expected, os.path.join(made, name),
                                 "--diff", os.path.join(diffs, name)], capture_output=True, text=True)
        share = [line.strip() for line in result.stdout.split("\n") if line.strip().startswith("share:")]
        print(f"{name}: exit {result.returncode}, {share[0] if share else result.stderr.strip()}", flush=True)
        if result.returncode != 0:
            failures.append(f"docs/gallery/{name} differs from what the program draws now "
                            f"(diff: {os.path.join(diffs, name)}; if intended, run scripts/make-gallery "
                            f"and commit the picture): {(result.stdout + result.stderr).strip()}")
    for name in sorted(committed):
        size = os.path.getsize(os.path.join(committed_folder, name))
        if size > MAX_BYTES:
            failures.append(f"docs/gallery/{name}: {size} bytes, over the gallery's {MAX_BYTES}")
    failures += style_file_failures(source)
    print(f"{len(committed & rendered)} pictures compared")
    for failure in failures:
        print("FAILED: " + failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
