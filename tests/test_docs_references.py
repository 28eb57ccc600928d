"""Every reference the docs and the code make to a file or a section exists: markdown links
(file and #anchor), repository paths named in prose, docstrings and comments (docs/model.md,
control/noise_thresholds.py, analysis/make_table1.py, ...) and named sections
(docs/model.md, "Drive vibration"; README, "Set-up")."""

import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "tegrasp_drake"
TOP_FOLDERS = ("tegrasp_drake", "docs", "analysis", "events", "tests", "models", "benchmarks",
               "emulators", ".ci")
SUBPACKAGES = tuple(sorted(p.name for p in PACKAGE.iterdir()
                           if p.is_dir() and (p / "__init__.py").exists()))
# A path: a top folder or subpackage, then name parts, ending in a file extension or "/".
_PATH = re.compile(
    r"(?<![\w./-])((?:%s)/[\w./-]*?\w\.(?:py|md|yaml|yml|json|csv|sh|toml|sdf|npz|png|txt))"
    r"(?![\w/])" % "|".join(re.escape(p) for p in TOP_FOLDERS + SUBPACKAGES))
_LINK = re.compile(r"\]\(([^)\s]+)\)")
# A named section: a markdown file (or README) then a quoted heading.
_SECTION = re.compile(r"((?:docs/)?[\w-]+\.md|README)(?: ?\(?[, ]+| section | under | in )"
                      r"\"([^\"]{3,80})\"")


def _sources() -> list[pathlib.Path]:
    files = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    files += sorted(PACKAGE.rglob("*.py"))
    files += sorted((ROOT / "analysis").glob("*.py")) + sorted((ROOT / "analysis").glob("*.md"))
    return [f for f in files if f.is_file()]


def _slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*]", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def _headings(markdown: pathlib.Path) -> list[str]:
    return [line.lstrip("#").strip() for line in markdown.read_text().splitlines()
            if line.startswith("#")]


def _resolve(reference: str, source: pathlib.Path) -> pathlib.Path | None:
    """The file a path reference names: relative to the repository, to the package (a
    subpackage path like control/x.py), or to the source's folder; None if none exists."""
    reference = reference.rstrip("/")
    candidates = [ROOT / reference, PACKAGE / reference, source.parent / reference]
    return next((c for c in candidates if c.exists()), None)


def _markdown_named(name: str) -> pathlib.Path:
    if name == "README":
        return ROOT / "README.md"
    return ROOT / name if name.startswith("docs/") else (
        ROOT / name if (ROOT / name).exists() else ROOT / "docs" / name)


def _dead_references(source: pathlib.Path) -> list[str]:
    text = source.read_text()
    label = source.relative_to(ROOT) if source.is_relative_to(ROOT) else source.name
    dead = []
    for match in _PATH.finditer(text):
        reference = match.group(1)
        if "*" in reference or "{" in reference or reference.startswith("tests/"):
            continue  # a pattern, or a test the suite itself proves
        if _resolve(reference, source) is None:
            dead.append(f"{label}: {reference}")
    if source.suffix == ".md":
        for match in _LINK.finditer(text):
            target = match.group(1)
            if re.match(r"[a-z]+:", target):
                continue  # a URL
            path, _, anchor = target.partition("#")
            file = (source.parent / path).resolve() if path else source
            if not file.exists():
                dead.append(f"{label}: link {target}")
            elif anchor and file.suffix == ".md" and anchor not in map(_slug, _headings(file)):
                dead.append(f"{label}: anchor {target}")
    for match in _SECTION.finditer(text):
        if match.group(1) == "README" and re.search(r"`|driver ", text[match.start() - 12:
                                                                     match.start()]):
            continue  # another project's README (Kinova's `kinova-ros` driver README)
        markdown = _markdown_named(match.group(1))
        if not markdown.exists():
            continue  # a path check above reports a missing file
        heading = " ".join(match.group(2).split())
        if not any(heading.lower() in " ".join(h.split()).lower()
                   for h in _headings(markdown)):
            dead.append(f"{label}: section {match.group(1)}, \"{heading}\"")
    return dead


@pytest.mark.parametrize("source", _sources(), ids=lambda p: str(p.relative_to(ROOT)))
def test_every_file_and_section_named_exists(source):
    assert _dead_references(source) == []


def test_the_checker_finds_a_dead_path_a_dead_anchor_and_a_dead_section(tmp_path):
    sample = tmp_path / "sample.md"
    model = ROOT / "docs" / "model.md"
    sample.write_text(f"See control/no_such_module.py, [the model]({model}#no-such-heading)"
                      ' and (docs/model.md, "No such section").\n'
                      f"But control/noise_thresholds.py, [the model]({model}#the-scene) and "
                      '(docs/model.md, "Drive vibration") exist.\n')
    dead = _dead_references(sample)
    assert len(dead) == 3
    assert any("no_such_module" in d for d in dead)
    assert any("no-such-heading" in d for d in dead)
    assert any("No such section" in d for d in dead)
