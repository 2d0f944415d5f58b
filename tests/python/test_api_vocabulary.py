"""One vocabulary in C++ and Python, held by docs/api.md: this reads the public headers
(include/particles/*.hpp) and the Python face (the type stubs python/particles/_particles.pyi and
the package's own Python), and fails when a public name has no row in docs/api.md, when a C++ name's
snake_case is a Python name of the paired class but their rows differ, or when a name one side
lacks is not marked "only in C++" or "only in Python" in its row.
"""

import ast
import pathlib
import re

import pytest

from conftest import SOURCE_DIR

HEADERS = SOURCE_DIR / "include" / "particles"
PACKAGE = SOURCE_DIR / "python" / "particles"
DOC = SOURCE_DIR / "docs" / "api.md"

# C++ class (or struct, or a namespace's functions) → the Python class, function or module whose
# names pair with its names. Point and BodyState are tuples in Python (their row says so).
PAIRS = {
    "Scenario": "Scenario", "Simulation": "Simulation", "Renderer": "Renderer", "VideoWriter": "VideoWriter",
    "RenderSettings": "Renderer.__init__", "VideoSettings": "VideoWriter.__init__", "Image": "Frame",
    "Energy": "Energy", "Report": "GoldenReport", "FrameCheck": "FrameCheck", "StateCheck": "StateCheck",
    "Options": "check", "ScenarioError": "ScenarioError", "SimulationError": "SimulationError",
    "particles": "particles", "golden": "golden", "Point": None, "BodyState": None, "Shard": None,
    "Integrator": "Integrator", "Theme": "Theme", "Background": "Background", "Raster": "Raster",
    "GlBackend": "GlBackend", "Outcome": "Outcome",
}


def snake(name):
    return re.sub(r"(?<=[a-z0-9])([A-Z])", r"_\1", name).lower()


def without_templates(text):
    while True:
        shorter = re.sub(r"<[^<>]*>", "", text)
        if shorter == text:
            return text
        text = shorter


def cpp_names():
    """{class or namespace: its public methods, fields and free functions} of the public headers."""
    names = {}
    for header in sorted([*HEADERS.glob("*.hpp"), *HEADERS.glob("*.hpp.in")]):  # version.hpp.in: CMake fills it in
        text = re.sub(r"//[^\n]*", "", header.read_text(encoding="utf-8"))
        text = re.sub(r"#[^\n]*", "", text)
        namespace = "golden" if "namespace particles::golden" in text else "particles"
        # Class bodies, outermost first; what is left outside them is the namespace's.
        outside = text
        for match in re.finditer(r"\b(class|struct)\s+(?:PARTICLES_API\s+)?(\w+)[^;{]*\{", text):
            kind, name = match.groups()
            depth, i = 1, match.end()
            while depth:
                depth += {"{": 1, "}": -1}.get(text[i], 0)
                i += 1
            body = text[match.end():i - 1]
            outside = outside.replace(text[match.start():i], "")
            public = kind == "struct" or text[max(0, match.start() - 5):match.start()] == "enum "
            members = names.setdefault(name, set())
            for part in re.split(r"\b(public|private|protected)\s*:", body):
                if part in ("public", "private", "protected"):
                    public = part == "public"
                    continue
                if not public:
                    continue
                part = re.sub(r"\{[^{}]*\}", ";", without_templates(part))  # inline bodies, initialiser braces
                for declaration in part.split(";"):
                    declaration = " ".join(declaration.split())
                    if not declaration or declaration.startswith(("using ", "friend ", "struct ", "class ")) or \
                            "operator" in declaration:
                        continue
                    call = re.match(r"^(?:static |virtual |explicit |PARTICLES_API |const |inline )*"
                                    r"[\w:]+(?: const)?[\s*&]+(\w+)\s*\(", declaration)
                    if call:
                        if call.group(1) != name:  # not `explicit Name(…)`, a constructor
                            members.add(call.group(1))
                        continue
                    if "(" in declaration.split("=")[0] or declaration.startswith(("~", name)):
                        continue  # a constructor, destructor or operator
                    for field in re.findall(r"(?:^|,)\s*(?:[\w:]+[\s*&]+)?(\w+)\s*(?:=[^,]*)?(?=,|$)",
                                            declaration.split("=")[0] if "," not in declaration else declaration):
                        members.add(field)
        for function in re.findall(r"PARTICLES_API\s+[\w:*\s&]+?[\s*&]+(\w+)\s*\(", outside):
            names.setdefault(namespace, set()).add(function)
    return names


def python_names():
    """{class, class.__init__, function or module: its public names} of the stubs and the package."""
    names = {}

    def visit(tree, module):
        for node in tree.body:
            if isinstance(node, ast.ClassDef):
                members = names.setdefault(node.name, set())
                for item in node.body:
                    if isinstance(item, ast.FunctionDef):
                        if item.name == "__init__":
                            names[f"{node.name}.__init__"] = {a.arg for a in item.args.args[1:] + item.args.kwonlyargs}
                        elif not item.name.startswith("_"):
                            members.add(item.name)
                    elif isinstance(item, ast.AnnAssign):
                        members.add(item.target.id)
            elif isinstance(node, ast.AnnAssign):  # __version__: str
                names.setdefault(module, set()).add(node.target.id)
            elif isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                names.setdefault(module, set()).add(node.name)
                names[node.name] = {a.arg for a in node.args.args[1:] + node.args.kwonlyargs}

    visit(ast.parse((PACKAGE / "_particles.pyi").read_text(encoding="utf-8")), "particles")
    visit(ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8")), "particles")
    visit(ast.parse((PACKAGE / "golden.py").read_text(encoding="utf-8")), "golden")
    return names


def doc_rows():
    """Each table row of docs/api.md as (names in its C++ cell, names in its Python cell, the row)."""
    rows = []
    for line in DOC.read_text(encoding="utf-8").splitlines():
        if not line.startswith("|") or line.startswith("| ---"):
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) < 3:
            continue

        def identifiers(cell):
            found = []
            for span in re.findall(r"`([^`]*)`", cell):
                for word in re.findall(r"[A-Za-z_][\w.:]*", span):
                    found += re.split(r"::|\.", word)
                for inner in re.findall(r"\{([^}]*)\}", span):  # Image {width, height, rgba}
                    found += re.findall(r"\w+", inner)
            return found

        rows.append((identifiers(cells[0]), identifiers(cells[1]), line))
    return rows


CPP = cpp_names()
PYTHON = python_names()
ROWS = doc_rows()


def rows_naming(name, column):
    return [row for row in ROWS if name in row[column]]


@pytest.mark.parametrize("cpp_class", sorted(PAIRS))
def test_every_cpp_name_has_a_row_and_its_python_name_is_its_snake_case(cpp_class):
    assert cpp_class in CPP, f"no class, struct or namespace {cpp_class} in {HEADERS}"
    python = PYTHON.get(PAIRS[cpp_class], set()) if PAIRS[cpp_class] else set()
    for name in sorted(CPP[cpp_class]):
        rows = rows_naming(name, 0)
        assert rows, f"{cpp_class}::{name} has no row in docs/api.md"
        wanted = snake(name)
        if wanted in python or f"__{wanted}__" in python:
            assert any(wanted in row[1] or f"__{wanted}__" in row[1] for row in rows), (
                f"{cpp_class}::{name}: its rows do not name Python's {wanted}: {rows[0][2]}")
        else:
            assert any("only in C++" in row[2] for row in rows), (
                f"{cpp_class}::{name} has no Python {PAIRS[cpp_class]}.{wanted}, and its row does not say "
                f"'only in C++': {rows[0][2]}")


@pytest.mark.parametrize("python_class", sorted({p for p in PAIRS.values() if p}))
def test_every_python_name_has_a_row_and_is_the_snake_case_of_a_cpp_name(python_class):
    cpp = set()
    for cpp_class, paired in PAIRS.items():
        if paired == python_class:
            cpp |= {snake(n) for n in CPP.get(cpp_class, set())}
    for name in sorted(PYTHON.get(python_class, set())):
        rows = rows_naming(name, 1)
        assert rows, f"Python's {python_class}.{name} has no row in docs/api.md"
        if name not in cpp and name.strip("_") not in cpp:
            assert any("only in Python" in row[2] for row in rows), (
                f"Python's {python_class}.{name} is the snake_case of no C++ name, and its row does not say "
                f"'only in Python': {rows[0][2]}")


def test_the_readers_find_the_api():
    # The parsers above must see the classes they check, or the cases pass for nothing.
    assert {"step", "advance", "advanceTo", "particleIndex", "setMouseTarget"} <= CPP["Simulation"]
    assert {"keyintSeconds", "fps", "crf"} <= CPP["VideoSettings"]
    assert {"savePng", "encodePng", "width", "rgba"} <= CPP["Image"]
    assert {"maxShare", "progress", "output"} <= CPP["Options"]
    assert {"defaultThreads", "version"} <= CPP["particles"] and "check" in CPP["golden"]
    assert {"advance_to", "particle_index", "time", "render", "close"} <= PYTHON["Simulation"]
    assert {"save_png", "encode_png"} <= PYTHON["Frame"] and "keyint_seconds" in PYTHON["VideoWriter.__init__"]
    assert "max_share" in PYTHON["check"] and {"message", "origin"} <= PYTHON["ScenarioError"]
    assert len(ROWS) > 40


def test_the_stubs_name_what_the_module_has():
    import particles
    from particles import _particles

    for cls_name, stub_members in PYTHON.items():
        if "." in cls_name or cls_name in ("particles", "golden", "check", "default_threads"):
            continue
        cls = getattr(_particles, cls_name, None) or getattr(particles, cls_name)
        if issubclass(cls, BaseException):
            continue  # their attributes are set on each exception raised (test_simulation.py checks them)
        module_members = {n for n in dir(cls) if not n.startswith("_")} - set(dir(Exception)) - set(dir(object))
        if cls_name == "Frame":
            module_members = {n for n in vars(cls) if not n.startswith("_")}
        elif hasattr(cls, "__members__"):  # an enum: its members
            module_members = set(cls.__members__)
        assert stub_members == module_members, f"{cls_name}: stubs {sorted(stub_members)} vs module {sorted(module_members)}"
