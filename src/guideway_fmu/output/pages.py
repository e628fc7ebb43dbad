"""Static HTML pages written with the standard library: the page around a body, tables and
figures, every text escaped with ``html.escape``. Shared by the diagnosis report
(diagnose/report.py) and the demo's index page (demo/page.py)."""
from __future__ import annotations

import html

STYLE = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto}"
         "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;"
         "padding:3px 8px;text-align:left;vertical-align:top}img{max-width:100%}"
         "pre{background:#f4f4f4;padding:6px 8px;overflow-x:auto}")


def page(title: str, body: list[str]) -> str:
    """A whole HTML document titled ``title`` (escaped) around the HTML fragments ``body``."""
    return "\n".join([f"<!DOCTYPE html><html><head><meta charset='utf-8'>"
                      f"<title>{html.escape(title)}</title><style>{STYLE}</style></head><body>",
                      *body, "</body></html>"])


def table(rows, header) -> str:
    """An HTML table: the ``header`` cells, then one row per item of ``rows``; cells as str()."""
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def figure(src: str, alt: str) -> str:
    """An image at the URL ``src`` (a relative path or a data: URL) with the text ``alt``."""
    return f"<img alt='{html.escape(alt)}' src='{html.escape(src)}'>"
