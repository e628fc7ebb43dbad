"""The docs cannot go stale unnoticed: every page a script writes carries the provenance record of
benchmarks/pages.py and matches the current tree, and every path a page names exists.

A stale page fails with the command that rewrites it; the benchmarks are not run here."""
from __future__ import annotations

import importlib.util
import re
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
DOCS = REPO / "docs"
PACKAGE = REPO / "src" / "guideway_fmu"
_spec = importlib.util.spec_from_file_location("docs_page_writer", REPO / "benchmarks" / "pages.py")
pages = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(pages)

GENERATED = sorted(p for p in DOCS.glob("*.md")
                   if pages.RECORD.search(t := p.read_text(encoding="utf-8"))
                   or pages.WRITTEN_BY.search(t))


def test_generated_pages_are_found():
    assert DOCS / "accuracy.md" in GENERATED and DOCS / "real-data.md" in GENERATED


@pytest.mark.parametrize("page", GENERATED, ids=lambda p: p.name)
def test_generated_page_is_current(page):
    assert pages.stale(page) is None, pages.stale(page)


def test_the_confidence_calibration_table_comes_from_the_run_that_wrote_its_page():
    # diagnose/calibration.json is counted by the run that writes diagnosis-calibration.md, whose
    # provenance covers the workflow's code and the table itself: a change of either makes the
    # page stale (above); the page's command must hold the fit that counted the table
    table = __import__("json").loads((PACKAGE / "diagnose" / "calibration.json").read_text())
    fit = re.search(r"--fit-seed \d+ --fit-draws \d+", table["command"]).group(0)
    written = pages.WRITTEN_BY.search((DOCS / "diagnosis-calibration.md").read_text())
    assert fit in written["command"], (
        f"src/guideway_fmu/diagnose/calibration.json ({table['command']}) was not counted by the "
        f"run that wrote docs/diagnosis-calibration.md ({written['command']}): rerun it with "
        f"{fit}")


# ------------------------------------------------------------------------ the hashing itself

LAW = '''"""A law."""

K = 2.0  # N/m


def force(x):
    """Force [N]."""
    return 2.0 * K * x
'''
SCRIPT = '''"""Writes a page."""
from guideway_fmu.physics import law


def main():
    from guideway_fmu.physics.late import scale
    return law.force(1.0) * scale()
'''


@pytest.fixture
def tree(tmp_path):
    """A repository with a package of three modules, a script and a data file."""
    physics = tmp_path / "src" / "guideway_fmu" / "physics"
    physics.mkdir(parents=True)
    (physics.parent / "__init__.py").write_text('"""The package."""\n')
    (physics / "__init__.py").write_text("")
    (physics / "law.py").write_text(LAW)
    (physics / "late.py").write_text("def scale():\n    return 3.0\n")
    (physics / "unused.py").write_text("X = 1\n")
    (tmp_path / "benchmarks").mkdir()
    (tmp_path / "benchmarks" / "figure.py").write_text(SCRIPT)
    (tmp_path / "case.toml").write_text("# the case\nload = 2000.0\n")
    return tmp_path


def digest(tree: Path) -> str:
    return pages.content_hash("benchmarks/figure.py", ("case.toml",), tree)


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_docstrings_comments_and_layout_keep_the_hash(tree):
    before = digest(tree)
    law = tree / "src" / "guideway_fmu" / "physics" / "law.py"
    edit(law, '"""Force [N]."""', '"""The spring force [N] at the displacement x [m]."""')
    edit(law, "# N/m", "# N/m, the spring's rate")
    edit(law, "return 2.0 * K * x", "return (2.0 *\n            K * x)")
    edit(tree / "benchmarks" / "figure.py", '"""Writes a page."""', '"""Writes the page."""')
    assert digest(tree) == before


def test_a_number_in_a_function_body_changes_the_hash(tree):
    before = digest(tree)
    edit(tree / "src" / "guideway_fmu" / "physics" / "law.py", "2.0 * K", "2.5 * K")
    assert digest(tree) != before


def test_an_import_inside_a_function_counts(tree):
    before = digest(tree)
    physics = tree / "src" / "guideway_fmu" / "physics"
    edit(physics / "late.py", "3.0", "3.5")
    after = digest(tree)
    assert after != before
    (physics / "unused.py").write_text("X = 2\n")  # reached by nothing
    assert digest(tree) == after


def test_moving_a_module_keeps_the_hash(tree):
    before = digest(tree)
    physics = tree / "src" / "guideway_fmu" / "physics"
    (physics / "rigs").mkdir()
    (physics / "rigs" / "__init__.py").write_text("")
    shutil.move(physics / "late.py", physics / "rigs" / "late.py")
    edit(tree / "benchmarks" / "figure.py", "physics.late", "physics.rigs.late")
    assert digest(tree) == before


def test_data_counts_by_content_not_by_comments(tree):
    before = digest(tree)
    edit(tree / "case.toml", "# the case", "# the case of the paper's Fig. 3")
    assert digest(tree) == before
    edit(tree / "case.toml", "2000.0", "2500.0")
    assert digest(tree) != before


def test_the_command_line_and_discovered_modules_count(tree):
    """A script that runs `guideway-fmu` depends on cli.py and what it reaches; a module that
    imports pkgutil on every module of its package."""
    package = tree / "src" / "guideway_fmu"
    (package / "cli.py").write_text("from .physics import registry\n")
    (package / "physics" / "registry.py").write_text("import pkgutil\n")
    (tree / "benchmarks" / "run.py").write_text(
        'import subprocess\nsubprocess.run(["guideway-fmu"])\n')
    reached = pages.closure([tree / "benchmarks" / "run.py"], tree)
    assert {package / "cli.py", package / "physics" / "unused.py"} <= reached


def test_a_missing_module_or_name_is_an_error_naming_the_importer(tree):
    script = tree / "benchmarks" / "figure.py"
    edit(script, "from guideway_fmu.physics import law", "from guideway_fmu.physics import lawn")
    with pytest.raises(ValueError, match=r"figure\.py imports lawn from guideway_fmu\.physics"):
        digest(tree)
    edit(script, "import lawn", "import law")
    edit(script, "physics.late", "physics.later")
    with pytest.raises(ValueError, match=r"figure\.py imports guideway_fmu\.physics\.later"):
        digest(tree)


def test_a_written_page_is_current_until_what_it_was_computed_from_changes(tree):
    page = tree / "page.md"
    pages.write(page, "# Figure\n\nThe force is 12 N.\n", "python benchmarks/figure.py --n 3",
                tree / "benchmarks" / "figure.py", ("case.toml",), root=tree)
    text = page.read_text()
    assert text.startswith("# Figure\n\n<!-- provenance script=benchmarks/figure.py "
                           "inputs=case.toml hash=")
    assert "\nWritten by `python benchmarks/figure.py --n 3`" in text and "12 N" in text
    assert pages.stale(page, tree) is None
    edit(tree / "src" / "guideway_fmu" / "physics" / "late.py", "3.0", "4.0")
    why = pages.stale(page, tree)
    assert str(page) in why and "rerun `python benchmarks/figure.py --n 3`" in why


def test_a_page_that_says_written_by_without_a_record_is_stale(tmp_path):
    page = tmp_path / "old.md"
    page.write_text("# Old\n\nWritten by `python benchmarks/old.py`; do not edit.\n")
    assert "no provenance record" in pages.stale(page, tmp_path)
    with pytest.raises(ValueError, match="title"):
        pages.write(page, "No title\n", "python benchmarks/old.py", tmp_path / "old.py",
                    root=tmp_path)


# ------------------------------------------------------------------ paths the pages name

#: a path in backticks or a link: starts at a top folder of the repository or of the package
PATH = re.compile(r"(?<![\w./-])((?:src|tests|benchmarks|orchestration|docs|"
                  + "|".join(sorted(p.name for p in PACKAGE.iterdir() if p.is_dir()
                                    and p.name != "__pycache__"))
                  + r")/[\w./-]*)")


def named_paths(text: str) -> set[str]:
    """The repository paths ``text`` names in code spans and Markdown links."""
    spans = re.findall(r"`([^`\n]+)`", text) + re.findall(r"\]\(([^)\s#]+)", text)
    return {m.rstrip(".,:;") for span in spans for m in PATH.findall(span)
            if not re.search(r"[<>*{}]", span)}


@pytest.mark.parametrize("page", sorted(DOCS.glob("*.md")) + [REPO / "README.md"],
                         ids=lambda p: p.name)
def test_every_path_a_page_names_exists(page):
    text = page.read_text(encoding="utf-8")
    missing = [p for p in sorted(named_paths(text))
               if not any((base / p).exists() for base in (REPO, PACKAGE, page.parent))]
    links = [t for t in re.findall(r"\]\(([^)\s#]+)", text)
             if not re.match(r"[a-z]+:", t) and not (page.parent / t).exists()]
    assert not missing + links, f"{page.name} names paths that do not exist: {missing + links}"
