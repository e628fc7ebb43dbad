"""`build.ensure` keeps an FMU folder in step with the package: it builds what is missing,
rebuilds FMUs built from other code, and leaves current FMUs and a user's replacements alone."""
from __future__ import annotations

import shutil
from pathlib import Path

from guideway_fmu.components import registry
from guideway_fmu.fmi.archive import rewrite
from guideway_fmu.fmu_build import build


def test_ensure_rebuilds_stale_and_missing_fmus_and_keeps_current_and_foreign_ones(
        fmu_dir, tmp_path, capsys):
    folder = tmp_path / "fmus"
    folder.mkdir()
    for name in ("FeedKinematics", "FrictionCoulomb", "ContactDryHertz"):
        shutil.copy2(fmu_dir / f"{name}.fmu", folder)
    current = build.built_tag(folder / "FeedKinematics.fmu")
    assert current == build.code_hash(build.shipped_files(
        build.registry.component("FeedKinematics")))

    # built from other code: the slave script carries another hash
    rewrite(folder / "FeedKinematics.fmu", folder / "FeedKinematics.fmu",
            lambda n, d: (n.replace(f"_{current}", "_0000000000"), d))
    assert build.built_tag(folder / "FeedKinematics.fmu") == "0000000000"
    # a user's replacement under a shipped name (another FMU's archive) is foreign
    shutil.copy2(fmu_dir / "FrictionStribeck.fmu", folder / "FrictionCoulomb.fmu")
    foreign = (folder / "FrictionCoulomb.fmu").read_bytes()
    assert build.built_tag(folder / "FrictionCoulomb.fmu") == build.FOREIGN
    untouched = (folder / "ContactDryHertz.fmu").stat().st_mtime_ns

    build.ensure(folder, ["FeedKinematics", "FrictionCoulomb", "ContactDryHertz", "Wear"])

    assert build.built_tag(folder / "FeedKinematics.fmu") == current
    assert "rebuilding" in capsys.readouterr().err
    assert (folder / "FrictionCoulomb.fmu").read_bytes() == foreign
    assert (folder / "ContactDryHertz.fmu").stat().st_mtime_ns == untouched
    assert build.built_tag(folder / "Wear.fmu") == build.code_hash(
        build.shipped_files(build.registry.component("Wear")))


def test_a_file_that_is_no_zip_archive_counts_as_foreign(tmp_path):
    fmu = tmp_path / "Wear.fmu"
    fmu.write_text("not an archive")
    assert build.built_tag(fmu) == build.FOREIGN
    assert build.built_tag(tmp_path / "Missing.fmu") is None


def test_a_failed_archive_rewrite_leaves_the_source_and_no_partial_file(tmp_path):
    import zipfile

    import pytest

    source = tmp_path / "A.fmu"
    with zipfile.ZipFile(source, "w") as archive:
        archive.writestr("modelDescription.xml", "<fmiModelDescription/>")
    before = source.read_bytes()

    def refuse(name, data):
        raise ValueError(f"{name}: refused")

    with pytest.raises(ValueError, match="modelDescription.xml: refused"):
        rewrite(source, source, refuse)
    assert source.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["A.fmu"]


def test_the_files_an_fmu_ships_are_found_beside_third_party_packages_as_in_site_packages(
        tmp_path, monkeypatch):
    # installed (not editable), the package sits in site-packages beside its dependencies; a
    # namespace package there (matplotlib's mpl_toolkits) made modulefinder fail with
    # "'NoneType' object has no attribute 'is_package'" in every command that builds FMUs
    site = tmp_path / "site-packages"
    shutil.copytree(build.PACKAGE_DIR, site / "guideway_fmu",
                    ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("numpy", "scipy", "fmpy", "mpl_toolkits"):
        (site / name / "inner").mkdir(parents=True)  # namespace packages: no __init__.py
    component = registry.component("VerticalDynamics")
    expected = [p.relative_to(build.PACKAGE_DIR) for p in build.shipped_files(component)]
    monkeypatch.setattr(build, "PACKAGE_DIR", site / "guideway_fmu")
    shipped = [p.relative_to(site / "guideway_fmu") for p in build.shipped_files(component)]
    assert shipped == expected
    assert Path("physics/roller_guide/carriage.py") in shipped
