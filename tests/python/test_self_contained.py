"""The project stands on its own: no source, test, script or doc file cites the design references that live outside
the repository (the team's shared reference folder and its files), and every citation of a numbered section of a
project doc (`docs/verification.md §2.3`) names a section that exists.

The expected values, derivations and conventions the tests rely on are in docs/verification.md, docs/conventions.md
and docs/robustness-notes.md. The forbidden names are assembled from pieces so that this file does not match itself.
"""
import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Names of the external reference files and of the folder that holds them.
FORBIDDEN = [
    ("../" + "shared", "the shared folder outside the repository"),
    ("shared/" + "reference", "the shared reference folder"),
    ("verification" + "-cases", "the external verification cases (use docs/verification.md)"),
    ("blender" + "-conventions", "the external Blender conventions (use docs/conventions.md)"),
    ("peers" + ".md", "the external peer survey"),
    ("integrator" + "-family", "the external design notes for the integrator family"),
]
# A numbered section of robustness.md (with or without ".md"): docs/robustness.md is a generated report without
# numbered sections, so such a citation can only mean the external file (use docs/robustness-notes.md instead).
FORBIDDEN_RE = [(re.compile(r"(?<![\w-])robustness(?:\.md)?\s*" + "\u00a7"), "a numbered section of robustness.md")]

SKIP_DIRS = {".git", "__pycache__", ".pytest_cache"}


def project_files():
    """Every text file of the working tree outside build trees (a directory holding a CMakeCache.txt, or a top-level
    build* directory) and VCS/cache folders."""
    for dirpath, dirnames, filenames in os.walk(ROOT):
        here = Path(dirpath)
        keep = []
        for d in dirnames:
            if d in SKIP_DIRS or (here == ROOT and d.startswith("build")):
                continue
            if (here / d / "CMakeCache.txt").exists():
                continue
            keep.append(d)
        dirnames[:] = sorted(keep)
        for name in sorted(filenames):
            path = here / name
            try:
                data = path.read_bytes()
            except OSError:
                continue
            if b"\0" in data[:8192]:
                continue  # binary (images, EXR, .npy)
            try:
                yield path, data.decode("utf-8")
            except UnicodeDecodeError:
                continue


def test_the_walk_sees_the_project():
    """A guard against a walk that silently finds nothing: the files that carry citations must be scanned."""
    seen = {p.relative_to(ROOT).as_posix() for p, _ in project_files()}
    for expected in ("tests/native/analytic_lights_test.cpp", "native/lights/spherical_sampling.h",
                     "addon/candela/params.py", "docs/verification.md", "docs/conventions.md",
                     "docs/robustness-notes.md", "tests/python/test_self_contained.py"):
        assert expected in seen, expected


def test_no_file_cites_the_external_references():
    found = []
    for path, text in project_files():
        for lineno, line in enumerate(text.splitlines(), 1):
            for needle, what in FORBIDDEN:
                if needle in line:
                    found.append(f"{path.relative_to(ROOT)}:{lineno}: cites {what}: {line.strip()}")
            for pattern, what in FORBIDDEN_RE:
                if pattern.search(line):
                    found.append(f"{path.relative_to(ROOT)}:{lineno}: cites {what}: {line.strip()}")
    assert not found, "cite the project's own docs instead:\n" + "\n".join(found)


def test_the_matcher_catches_what_it_must():
    """The patterns find the citations this test exists to keep out, and leave the project's own alone."""
    bad = ["see ../" + "shared/" + "reference/x.md", "(verification" + "-cases.md §2)", "(robustness.md " + "\u00a72)",
           "(robustness " + "\u00a75)", "blender" + "-conventions §7.1"]
    good = ["(docs/robustness-notes.md \u00a72)", "docs/robustness.md from a fresh run", "std::shared_ptr<Scene>"]

    def flagged(line):
        return any(n in line for n, _ in FORBIDDEN) or any(p.search(line) for p, _ in FORBIDDEN_RE)

    assert all(flagged(s) for s in bad)
    assert not any(flagged(s) for s in good)


# docs/NAME.md followed by one or more section numbers: "§2.3", "§2.2–§2.6", "§1, §7", "§2 and §3", "§2.1, §2.2".
CITATION = re.compile(r"docs/([\w.-]+\.md)((?:\s*(?:,|and|–|-|/)?\s*\u00a7\d+(?:\.\d+)*)+)")
SECTION = re.compile(r"\u00a7(\d+(?:\.\d+)*)")
HEADING = re.compile(r"^#{1,6}\s+(\d+(?:\.\d+)*)\.?\s", re.MULTILINE)


def doc_sections(doc):
    return set(HEADING.findall((ROOT / "docs" / doc).read_text(encoding="utf-8")))


def test_section_citations_of_project_docs_exist():
    sections, missing, count = {}, [], 0
    for path, text in project_files():
        # Join comment continuation lines, so "docs/verification.md\n// §8.2" reads as one citation.
        flat = re.sub(r"\n[ \t]*(?:///?|#|\*)?[ \t]*", " ", text)
        for m in CITATION.finditer(flat):
            doc = m.group(1)
            if doc not in sections:
                sections[doc] = doc_sections(doc) if (ROOT / "docs" / doc).exists() else None
            for number in SECTION.findall(m.group(2)):
                count += 1
                if sections[doc] is None:
                    missing.append(f"{path.relative_to(ROOT)}: docs/{doc} does not exist")
                elif number not in sections[doc]:
                    missing.append(f"{path.relative_to(ROOT)}: docs/{doc} has no section {number}")
    assert count > 40, f"only {count} section citations found: the matcher is broken"
    assert not missing, "\n".join(missing)


def test_docs_cross_references_exist():
    """Inside a doc, a bare "§N" refers to the doc itself (after removing the citations of other docs)."""
    missing = []
    for doc in sorted(p.name for p in (ROOT / "docs").glob("*.md")):
        text = (ROOT / "docs" / doc).read_text(encoding="utf-8")
        own = doc_sections(doc)
        for number in SECTION.findall(CITATION.sub(" ", text)):
            if number not in own:
                missing.append(f"docs/{doc}: \u00a7{number} is not a section of this page")
    assert not missing, "\n".join(missing)
