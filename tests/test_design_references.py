"""The design lives in the repository: sources cite docs/DESIGN.md (never a file outside the
repository), and every section they cite exists there."""

import re

from conftest import REPO

SOURCES = [p for folder in ("crates", "python", "tests", "benches") for p in (REPO / folder).rglob("*")
           if p.suffix in (".rs", ".py", ".pyi") and "target" not in p.parts] + [REPO / "README.md"]
HEADINGS = set(re.findall(r"^#+ (§[0-9.]+[a-z]?)", (REPO / "docs" / "DESIGN.md").read_text(), re.M))


def test_no_source_cites_the_external_contract():
    citing = [str(p.relative_to(REPO)) for p in SOURCES if re.search(r"\bSPEC\b", p.read_text())
              and p.name != "test_design_references.py"]
    assert citing == []


def test_every_cited_design_section_exists():
    cited = {(m, str(p.relative_to(REPO))) for p in SOURCES
             for m in re.findall(r"DESIGN\.md §([0-9.]*[0-9][a-z]?)", p.read_text())}
    assert len(cited) > 50
    missing = sorted((f"§{section}", where) for section, where in cited if f"§{section}" not in HEADINGS)
    assert missing == []
