"""The documentation points at things that exist: every repository path in README.md and
docs/*.md (a `code span` or a link whose first component is a top-level folder of the
repository, e.g. `fast/src/global/piece_screen.h`, or a link relative to the page) names an
existing file or folder, and every bare source file name in a code span (`value_bounds.h`,
`solve_pair.cpp`) is the name of some file of the repository."""
import re

from conftest import SOURCE_DIR

SKIP = {".git", "build"}


def pages():
    return [SOURCE_DIR / "README.md", *sorted((SOURCE_DIR / "docs").glob("*.md"))]


def referenced(page):
    text = page.read_text()
    spans = set(re.findall(r"`([^`\s]+)`", text))
    links = {l.split("#")[0] for l in re.findall(r"\]\(([^)\s]+)\)", text)}
    return spans, {l for l in links if l and not l.startswith(("http:", "https:", "mailto:"))}


def missing_paths(page_list):
    tops = {p.name for p in SOURCE_DIR.iterdir() if p.name not in SKIP}
    names = {p.name for p in SOURCE_DIR.rglob("*") if not SKIP & set(p.relative_to(SOURCE_DIR).parts)}
    missing = []
    checked = 0
    for page in page_list:
        spans, links = referenced(page)
        for link in links:
            checked += 1
            if not (page.parent / link).exists():
                missing.append(f"{page.name}: link {link}")
        for tok in spans:
            tok = tok.rstrip(".,:;")
            first = tok.split("/")[0]
            if "/" in tok and first in tops and "*" not in tok and "..." not in tok:
                checked += 1
                if not (SOURCE_DIR / tok).exists():
                    missing.append(f"{page.name}: {tok}")
            elif re.fullmatch(r"[\w.-]+\.(h|cpp|py|sh|cmake)", tok):
                checked += 1
                if tok not in names:
                    missing.append(f"{page.name}: file name {tok}")
    return checked, missing


def test_every_path_exists():
    checked, missing = missing_paths(pages())
    assert checked > 50
    assert not missing, missing


def test_a_wrong_path_is_reported(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("See `fast/src/value_bounds.h`, `nowhere_at_all.h`, [x](no-such.md) and "
                    "`fast/src/certification/value_bounds.h`.\n")
    checked, missing = missing_paths([page])
    assert checked == 4 and len(missing) == 3, missing
