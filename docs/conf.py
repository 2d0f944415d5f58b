# The documentation site (scripts/docs builds it into build/docs/html): Sphinx reads the markdown
# pages of docs/ as they are (MyST), the C++ reference from the public headers through Doxygen's XML
# (Breathe), and the Python reference from the module's docstrings (autodoc), with the furo theme.
# scripts/docs passes where the built pieces are in the environment.
import os
import re
import sys

project = "particles"
author = "the particles authors"
copyright = "the particles authors"
release = os.environ.get("PARTICLES_VERSION", "")
version = release

extensions = ["myst_parser", "breathe", "sphinx.ext.autodoc"]
source_suffix = {".md": "markdown"}
# The source folder is the repository's root (`sphinx-build -c docs . OUT`), so that the pages'
# links to each other and to the guides beside the code (golden/README.md, bench/README.md, …)
# are the same on the site as in the repository. These are the pages:
include_patterns = [
    "README.md",
    "CHANGELOG.md",
    "docs/**.md",
    "golden/README.md",
    "bench/README.md",
    "tests/fuzz/README.md",
    "python/README.md",
    "examples/**/README.md",
]
root_doc = "docs/index"

myst_heading_anchors = 4  # `page.md#a-heading` links, as GitHub writes them
myst_enable_extensions = ["colon_fence"]

html_theme = "furo"
html_title = f"particles {release}".strip()
html_static_path = []
html_show_sourcelink = False

# C++: Doxygen's XML of include/particles/ (docs/Doxyfile).
breathe_projects = {"particles": os.environ.get("PARTICLES_DOXYGEN_XML", "")}
breathe_default_project = "particles"
breathe_default_members = ("members",)

# Python: the module as built (build/python), imported by autodoc.
python_path = os.environ.get("PARTICLES_PYTHON_PATH")
if python_path:
    sys.path.insert(0, python_path)
autodoc_member_order = "bysource"

# Warnings are errors (scripts/docs: -W -n), cross-references included; these names are not this
# project's and have no page here (no intersphinx: the build is offline): pybind11's base class and
# its `handle` (an argument that takes any Python object), numpy's array, os.PathLike; and the
# namespaces, which the C++ reference shows as the prefix of each name, not as pages.
nitpick_ignore = [
    ("py:class", "pybind11_builtins.pybind11_object"),
    ("py:class", "handle"),
    ("py:class", "numpy.ndarray"),
    ("py:class", "os.PathLike"),
    ("cpp:identifier", "particles"),
    ("cpp:identifier", "particles::golden"),
    ("cpp:identifier", "golden"),
]
autodoc_typehints = "signature"


# Debian's furo ships its script unbundled (furo.js imports gumshoe-patched.js as an ES module, which
# a page opened from a folder may not load) and its style sheet importing normalize.css from the web
# server's /javascript/ (Debian's packaged copy): as built, a site opened from disk or published on
# GitHub Pages showed a script error and missed normalize.css. After the build, the site gets its
# own bundle and its own copy; a furo that bundles them itself is left as it is. Debian 12's furo
# (2022.12) imports gumshoe's default export and loads furo.js as a plain script; Debian 13's
# (2024.08) imports it as a namespace, which is no constructor ("Gumshoe is not a constructor": the
# UMD file exports nothing to a module), and has the pages load furo.js as a module, which Chromium
# refuses from a file:// page: bundled, it is a plain script on every page, as on Debian 12.
NORMALIZE_CSS = "/usr/share/javascript/normalize.css/normalize.css"
DEBIAN_NORMALIZE_IMPORT = "@import url(/javascript/normalize.css/normalize.css);"
GUMSHOE_IMPORTS = ('import Gumshoe from "./gumshoe-patched.js";', 'import * as Gumshoe from "./gumshoe-patched.js";')
FURO_MODULE_TAG = re.compile(r'(<script\b[^>]*?)\s+type="module"([^>]*\bsrc="[^"]*_static/scripts/furo\.js[^"]*"[^>]*>)')


def load_furo_as_plain_script(outdir):
    for folder, _, files in os.walk(outdir):
        for name in files:
            if not name.endswith(".html"):
                continue
            page = os.path.join(folder, name)
            with open(page, encoding="utf-8") as f:
                text = f.read()
            plain = FURO_MODULE_TAG.sub(r"\1\2", text)
            if plain != text:
                with open(page, "w", encoding="utf-8") as f:
                    f.write(plain)


def bundle_debian_furo(app, exception):
    if exception is not None or app.builder.format != "html":
        return
    static = os.path.join(app.outdir, "_static")
    styles, scripts = os.path.join(static, "styles"), os.path.join(static, "scripts")
    furo_css = os.path.join(styles, "furo.css")
    if os.path.exists(furo_css):
        with open(furo_css, encoding="utf-8") as f:
            css = f.read()
        if DEBIAN_NORMALIZE_IMPORT in css:
            with open(NORMALIZE_CSS, encoding="utf-8") as f:
                normalize = f.read()
            with open(os.path.join(styles, "normalize.css"), "w", encoding="utf-8") as f:
                f.write(normalize)
            with open(furo_css, "w", encoding="utf-8") as f:
                f.write(css.replace(DEBIAN_NORMALIZE_IMPORT, "@import url(normalize.css);"))
    furo_js = os.path.join(scripts, "furo.js")
    if os.path.exists(furo_js):
        with open(furo_js, encoding="utf-8") as f:
            js = f.read()
        imports = [line for line in GUMSHOE_IMPORTS if line in js]
        if imports:
            # gumshoe-patched.js is UMD: as a plain script it defines window.Gumshoe.
            with open(os.path.join(scripts, "gumshoe-patched.js"), encoding="utf-8") as f:
                gumshoe = f.read()
            with open(furo_js, "w", encoding="utf-8") as f:
                f.write(gumshoe + "\n" + js.replace(imports[0], ""))
            load_furo_as_plain_script(app.outdir)


def setup(app):
    app.connect("build-finished", bundle_debian_furo)
