"""Helpers shared by several test modules (import as ``support``: tests/ is on the path)."""
import stat
import zipfile

SYMLINK = (stat.S_IFLNK | 0o777) << 16  # a Unix symbolic link's st_mode in a zip entry


def with_entry(fmu, out, name, mode):
    """A copy of ``fmu`` at ``out`` with one more entry ``name`` (Unix ``mode`` in the high bits
    of its external attributes; a link's data is its target)."""
    with zipfile.ZipFile(fmu) as src, zipfile.ZipFile(out, "w") as dst:
        for info in src.infolist():
            dst.writestr(info, src.read(info))
        info = zipfile.ZipInfo(name)
        info.create_system, info.external_attr = 3, mode
        dst.writestr(info, "/etc/passwd" if mode == SYMLINK else "x")
    return out
