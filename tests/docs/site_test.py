#!/usr/bin/python3
"""Opens the documentation site that scripts/docs built in headless Chromium, as a reader would,
and checks what they would see on its front page, the library's guide, both references and the
gallery:

  - the page loads, with the site's title, and the browser's console holds no error;
  - every picture has loaded (naturalWidth > 0);
  - every link inside the site leads to a page that exists, and to an element of that page with
    the link's #fragment; no link leads to a markdown source (`.md`) left unconverted;
and, on the pages' HTML files:
  - the C++ reference names every class, struct, enum, function and member that Doxygen found in
    include/particles/ (its XML), and shows no HTML entity as text; the Python reference has a
    section for every public name of `import particles` and `particles.golden`.

usage: site_test.py SITE_FOLDER DOXYGEN_XML_FOLDER PYTHON_PATH
Debian's chromium, chromium-driver and python3-selenium (scripts/deps test). Exit 0 when every
check passes, 1 with one line per failed check.
"""
import functools
import html
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import urllib.parse
import xml.etree.ElementTree as ElementTree

sys.dont_write_bytecode = True
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "golden"))
from browser_test import check_console, images_state, start_browser, wait_for  # noqa: E402
from checklist import check, finish  # noqa: E402

PAGES = ["index.html", "docs/index.html", "docs/api.html", "docs/reference/cpp.html",
         "docs/reference/python.html", "docs/gallery.html"]


@functools.lru_cache(maxsize=None)
def ids_of(page):
    """The ids (and old-style anchor names) an HTML file defines."""
    text = page.read_text(encoding="utf-8", errors="replace")
    return frozenset(html.unescape(m) for m in re.findall(r'\s(?:id|name)="([^"]+)"', text))


def check_links(driver, site, which):
    # Every link's resolved address, as the browser reads it, in one call (one WebDriver call per
    # link took 8 ms each, over a thousand links). An SVG link's href is an SVGAnimatedString.
    hrefs = driver.execute_script(
        "return Array.from(document.getElementsByTagName('a'), a => typeof a.href === 'string' ? a.href :"
        " a.href && a.href.baseVal ? new URL(a.href.baseVal, document.baseURI).href : '')")
    hrefs = [h for h in hrefs if h]
    inside = [h for h in hrefs if h.startswith("file://")]
    check(len(inside) > 0, f"{which}: the page links within the site ({len(inside)} links)")
    broken = []
    for href in inside:
        parts = urllib.parse.urlsplit(href)
        target = pathlib.Path(urllib.parse.unquote(parts.path))
        if target.suffix == ".md":
            broken.append(f"{href} (a markdown source)")
        elif site.resolve() not in target.resolve().parents:
            broken.append(f"{href} (outside the site)")
        elif not target.is_file():
            broken.append(f"{href} (no such file)")
        elif parts.fragment and urllib.parse.unquote(parts.fragment) not in ids_of(target):
            broken.append(f"{href} (no element #{parts.fragment})")
    check(not broken, f"{which}: every link within the site leads somewhere"
          + (": " + "; ".join(sorted(set(broken))[:20]) if broken else ""))


def check_page(driver, site, page):
    driver.get_log("browser")  # what earlier pages logged
    driver.get(pathlib.Path(site / page).resolve().as_uri())
    if page == "index.html":  # leads to docs/index.html
        wait_for(lambda: driver.current_url.endswith("docs/index.html"), seconds=10)
        check(driver.current_url.endswith("docs/index.html"),
              f"{page}: leads to the front page ({driver.current_url})")
        return
    check("particles" in driver.title, f"{page}: the title names the site ({driver.title!r})")
    wait_for(lambda: all(complete for _, complete, _ in images_state(driver)), interval=0.2)
    state = images_state(driver)
    broken = [src for src, complete, width in state if not complete or width <= 0]
    check(not broken, f"{page}: every picture loaded ({len(state)})" + (f"; not: {broken}" if broken else ""))
    if page in ("docs/index.html", "docs/gallery.html"):
        check(len(state) > 0, f"{page}: has its pictures ({len(state)})")
    check_links(driver, site, page)
    check_console(driver, page)


def public_cpp_names(xml_folder):
    """Qualified names of the public headers' public declarations, from Doxygen's XML: classes,
    structs, their public members (destructors and the opaque Impl aside), the namespaces'
    functions (a template's specialisations under its own name) and enums, and the macros."""
    names = set()
    for path in pathlib.Path(xml_folder).glob("*.xml"):
        root = ElementTree.parse(path).getroot()
        for compound in root.findall("compounddef"):
            kind, name = compound.get("kind"), compound.findtext("compoundname")
            if kind in ("class", "struct"):
                names.add(name)
            for member in compound.iter("memberdef"):
                member_name = member.findtext("name")
                if member.get("prot") != "public" or member_name.startswith("~"):
                    continue
                if member.get("kind") == "define":
                    names.add(member_name)
                elif kind in ("class", "struct", "namespace") and member.get("kind") != "friend":
                    # A template's specialisations share its entry: fromName<Theme> is fromName.
                    names.add(f"{name}::{re.sub(r'<.*>$', '', member_name).strip()}")
    return {n for n in names if not n.endswith("::Impl")}


def check_references(site, xml_folder, python_path):
    cpp = html.unescape((site / "docs/reference/cpp.html").read_text(encoding="utf-8"))
    text = re.sub(r"\s+", "", re.sub(r"<[^>]+>", "", cpp))
    names = public_cpp_names(xml_folder)
    # An entity shown as text (`&#8212;` where Doxygen read `--` as a dash): escaped twice.
    check("&#" not in text, "C++ reference: no HTML entity shown as text"
          + (f" (first: {text[text.find('&#') - 40:text.find('&#') + 20]!r})" if "&#" in text else ""))
    # Each name's last part as the page shows it (templates without spaces), and its scope.
    missing = sorted(n for n in names if re.sub(r"\s+", "", n.split("::")[-1]) not in text or
                     ("::" in n and n.split("::")[-2] not in text))
    check(len(names) > 50 and not missing,
          f"C++ reference: names every public name of include/particles/ ({len(names)} names)"
          + (f"; missing: {missing}" if missing else ""))
    listing = subprocess.run(
        [sys.executable, "-c", "import particles, particles.golden\n"
         "print('\\n'.join(['particles.' + n for n in particles.__all__] + "
         "['particles.golden.' + n for n in particles.golden.__all__]))"],
        env={**os.environ, "PYTHONPATH": python_path, "PYTHONDONTWRITEBYTECODE": "1"},
        capture_output=True, text=True, check=True).stdout.split()
    python_ids = ids_of(site / "docs/reference/python.html")
    # A module's section is `module-NAME`.
    missing = sorted(n for n in listing if n not in python_ids and f"module-{n}" not in python_ids)
    check(len(listing) > 10 and not missing,
          f"Python reference: a section for every public name of particles ({len(listing)} names)"
          + (f"; missing: {missing}" if missing else ""))


def main():
    site, xml_folder, python_path = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
    from selenium import webdriver

    check_references(site, xml_folder, python_path)
    with tempfile.TemporaryDirectory() as profile:
        driver = start_browser(webdriver, profile, javascript=True)
        try:
            for page in PAGES:
                if check((site / page).is_file(), f"{page}: exists"):
                    check_page(driver, site, page)
        finally:
            driver.quit()
    return finish("site_test.py", site)


if __name__ == "__main__":
    sys.exit(main())
