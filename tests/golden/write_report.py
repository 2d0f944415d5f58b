#!/usr/bin/python3
"""Writes DIR/report.html from the golden tests' results in DIR/results/*.txt (golden/README.md,
"The report"): every failing test with its golden, actual and diff pictures side by side, its
numbers and the commands that reproduce it, then one line per passing test. The pictures are
linked by file name, next to the report, so DIR is whole on its own: CI can hand it out as an
artefact and `scripts/update-golden --from DIR` can accept its frames.

One static file, inline CSS, no JavaScript; written under a temporary name and renamed over
report.html. Run by CTest's golden:report after every golden test (FIXTURES_CLEANUP), and by
tests/golden/report_test.py.

usage: write_report.py DIR
"""
import datetime
import html
import os
import sys
import tempfile
import urllib.parse

sys.dont_write_bytecode = True  # no __pycache__ in the source tree, whoever runs this
from results import FAILING_OUTCOMES, kept_file, read_results  # noqa: E402  (after the line above)

STYLE = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.5em; color: #1d1d1f; background: #fafafa; }
h1 { font-size: 1.5em; margin: 0 0 .3em; }
h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
section { background: #fff; border: 1px solid #ddd; border-left: 5px solid #c62828; margin: 1em 0; padding: .6em 1em; }
section h3 { margin: .2em 0 .5em; font-size: 1.05em; }
.frames { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; }
figure img { display: block; border: 1px solid #999; image-rendering: pixelated; max-width: 100%; }
figcaption { font-size: .9em; color: #555; }
table { border-collapse: collapse; }
td, th { padding: 2px 10px 2px 0; text-align: left; vertical-align: top; }
table.passing td, table.passing th { border-bottom: 1px solid #e4e4e4; }
code, pre { font: 12.5px ui-monospace, monospace; }
pre { background: #f3f3f3; padding: .4em .6em; overflow-x: auto; white-space: pre-wrap; }
.ok { color: #2e7d32; } .bad { color: #c62828; font-weight: bold; }
"""

DIFF_LEGEND = (
    "In the diff, magenta pixels differ by more than the threshold, teal ones by less, the yellow "
    "frame is their bounding box, over a dimmed grey copy of the golden frame."
)

OUTCOME_WORDS = {
    "failed": "fails",
    "error": "could not be compared",
    "unfinished": "did not finish (stopped by CTest, e.g. its timeout, or crashed)",
}


def e(text):
    return html.escape(str(text), quote=True)


def expectation(result):
    if result.get("expect") == "differ":
        return "must differ (a perturbation the goldens must see)"
    return "must match"


def pixels_text(result):
    """"18 of 76800 px (0.0234 %)": empty when the comparison did not run."""
    if "differing" not in result:
        return ""
    return f"{result['differing']} of {result.get('pixels', '?')} px ({result.get('share_percent', '?')} %)"


def largest_text(result):
    return f"{result['largest']} of 255" if "largest" in result else ""


def tolerance_text(result):
    if "threshold" not in result:
        return ""
    return f"threshold {result['threshold']}, bound {result.get('bound_percent', '?')} %"


def picture(directory, result, key, caption):
    """A figure for the picture the result names under KEY, if it is a file in DIRECTORY."""
    name = kept_file(directory, result, key)
    if name is None:
        return f"<figure><figcaption>{e(caption)}: not kept</figcaption></figure>"
    href = e(urllib.parse.quote(name))
    return (
        f'<figure><a href="{href}"><img src="{href}" alt="{e(caption)}"></a>'
        f"<figcaption>{e(caption)}: <code>{e(name)}</code></figcaption></figure>"
    )


def failing_section(directory, result):
    rows = [
        ("expects", expectation(result)),
        ("differing pixels", pixels_text(result) or "—"),
        ("largest channel difference", largest_text(result) or "—"),
        ("bounding box", result.get("box", "—")),
        ("tolerance", tolerance_text(result) or "—"),
        ("golden frame", result.get("golden", "?")),
    ]
    table = "".join(f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in rows)
    parts = [
        f'<section id="{e(result["test"])}">',
        f"<h3>{e(result['test'])}: {e(OUTCOME_WORDS.get(result['outcome'], result['outcome']))}</h3>",
        f"<table>{table}</table>",
    ]
    if "actual" in result or "diff" in result or "expected" in result:
        parts.append('<div class="frames">')
        parts.append(picture(directory, result, "expected", "expected (golden)"))
        parts.append(picture(directory, result, "actual", "actual"))
        parts.append(picture(directory, result, "diff", "diff"))
        parts.append("</div>")
    if result.get("message"):
        parts.append(f"<pre>{e(result['message'])}</pre>")
    parts.append("<p>Reproduce (from the top of the source tree):</p>")
    commands = [result.get("render_command", ""), result.get("compare_command", "")]
    parts.append(f"<pre>{e(chr(10).join(c for c in commands if c))}</pre>")
    parts.append("</section>")
    return "\n".join(parts)


def passing_row(directory, result):
    # Tests that must differ keep their frame and diff: what the comparison saw of the perturbation.
    links = [f'<a href="{e(urllib.parse.quote(name))}">{e(key)}</a>'
             for key in ("actual", "diff") if (name := kept_file(directory, result, key))]
    expects = "differ" if result.get("expect") == "differ" else "match"
    cells = [f"<code>{e(result['test'])}</code>", e(expects), e(pixels_text(result)), e(largest_text(result)),
             e(result.get("box", "")), e(tolerance_text(result)), " ".join(links)]
    return "<tr>" + "".join(f"<td>{cell}</td>" for cell in cells) + "</tr>"


def report_html(directory, results, unreadable):
    failing = [r for r in results if r["outcome"] in FAILING_OUTCOMES]
    passing = [r for r in results if r["outcome"] == "passed"]
    differ_count = sum(1 for r in passing if r.get("expect") == "differ")
    tests = f"{len(results)} test" + ("" if len(results) == 1 else "s")
    if failing:
        headline = f"Golden frames: {len(failing)} of {tests} failing"
    elif results:
        headline = f"Golden frames: {tests}, all pass"
    else:
        headline = "Golden frames: no results (no golden test ran)"
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    out = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{e(headline)}</title><style>{STYLE}</style></head><body>",
        f'<h1 class="{"bad" if failing or unreadable else "ok"}">{e(headline)}</h1>',
        f"<p>Written {e(now)} from the results in this folder ({tests}: "
        f"{len(failing)} fail, {len(passing)} pass, of which {differ_count} are perturbations that must differ "
        "from their golden frame and do). "
        "Tests that CTest did not run this time (<code>ctest -R</code> subsets) are not here.</p>",
    ]
    for path, why in unreadable:
        out.append(f'<p class="bad">Unreadable result <code>{e(path)}</code>: {e(why)}</p>')
    if failing:
        out.append("<h2>Failing</h2>")
        out.append(f"<p>Each with its golden frame, the frame rendered now, and their diff. {e(DIFF_LEGEND)}</p>")
        out.append(
            "<p>If the change is intended, accept the frames of the failing <em>must match</em> tests "
            "from this folder, without rendering them again: "
            "<code>scripts/update-golden --from THIS_FOLDER</code> (golden/README.md), and review them.</p>"
        )
        out.extend(failing_section(directory, r) for r in failing)
    if passing:
        out.append("<h2>Passing</h2>")
        out.append('<table class="passing"><tr><th>test</th><th>expects</th><th>differing pixels</th>'
                   "<th>largest difference</th><th>box</th><th>tolerance</th><th>kept</th></tr>")
        out.extend(passing_row(directory, r) for r in passing)
        out.append("</table>")
    out.append("</body></html>\n")
    return "\n".join(out)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[-1])
    directory = os.path.abspath(sys.argv[1])
    os.makedirs(directory, exist_ok=True)
    results, unreadable = read_results(directory)
    text = report_html(directory, results, unreadable)
    report = os.path.join(directory, "report.html")
    descriptor, temporary = tempfile.mkstemp(dir=directory, prefix=".report.html.")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(temporary, 0o644)  # mkstemp's 0600 would keep it from others where the folder is served
        os.replace(temporary, report)
    except BaseException:
        os.unlink(temporary)
        raise
    failing = sum(1 for r in results if r["outcome"] in FAILING_OUTCOMES)
    print(f"golden report: {report} ({failing} failing of {len(results)} tests)")


if __name__ == "__main__":
    main()
