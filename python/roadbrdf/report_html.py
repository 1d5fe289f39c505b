"""HTML building blocks of the sample report (``roadbrdf report``, :mod:`roadbrdf.report`).

The page is self-contained: the style sheet is inline, figures are PNG images embedded as base64
``data:`` URIs, and the page loads nothing else (no script, no font, no network access). Every number
that comes from a computation is written in a cell (or span) with ``data-key`` naming it and
``data-value`` holding it at full precision (``repr``), so that a test or a script can read the
report's values back without parsing the rounded text.
"""

from __future__ import annotations

import base64
import html
import io
import math
from typing import Iterable, NamedTuple, Sequence

__all__ = ["Cell", "Section", "cell", "number", "table", "figure", "figure_png", "caveats", "page", "esc",
           "definition_list"]

_CSS = """
:root { --ink: #1d2733; --muted: #5b6b7c; --rule: #d5dde6; --band: #f3f6f9; --warn: #9a3b00;
        --warn-bg: #fff4e5; --ok: #1f6f3f; }
* { box-sizing: border-box; }
body { font: 14px/1.45 "DejaVu Sans", "Liberation Sans", Arial, sans-serif; color: var(--ink);
       margin: 0 auto; max-width: 1100px; padding: 24px 32px 48px; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 34px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--rule); }
h3 { font-size: 15px; margin: 20px 0 8px; }
p { margin: 6px 0 10px; }
.subtitle { color: var(--muted); margin-bottom: 16px; }
nav ol { columns: 2; margin: 8px 0 0; padding-left: 22px; }
nav { background: var(--band); padding: 10px 16px; border-radius: 4px; }
div.table { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; margin: 8px 0 14px; font-size: 13px; }
th, td { border: 1px solid var(--rule); padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: var(--band); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.dense { font-size: 11px; }
table.dense th, table.dense td { padding: 1px 3px; }
tr.best td { background: #eef7f0; }
dl { display: grid; grid-template-columns: max-content auto; gap: 2px 16px; margin: 8px 0 14px; }
dt { color: var(--muted); }
dd { margin: 0; word-break: break-all; }
figure { margin: 12px 0 20px; page-break-inside: avoid; break-inside: avoid; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--rule); }
figcaption { color: var(--muted); font-size: 12px; margin-top: 4px; }
.caveats { background: var(--warn-bg); border-left: 4px solid var(--warn); padding: 6px 12px; margin: 10px 0; }
.caveats li { margin: 2px 0; }
.caveats.info { background: var(--band); border-left-color: var(--muted); }
.flag { color: var(--warn); font-weight: 600; }
.ok { color: var(--ok); }
pre { background: var(--band); padding: 8px 10px; overflow-x: auto; font-size: 12px; }
details { margin: 8px 0; }
summary { cursor: pointer; color: var(--muted); }
.summary-grid { display: grid; grid-template-columns: repeat(auto-fit, minmax(190px, 1fr)); gap: 10px; margin: 14px 0; }
.summary-grid div { background: var(--band); padding: 8px 12px; border-radius: 4px; }
.summary-grid .label { color: var(--muted); font-size: 12px; display: block; }
.summary-grid .value { font-size: 17px; font-weight: 600; }
footer { margin-top: 40px; color: var(--muted); font-size: 12px; border-top: 1px solid var(--rule); padding-top: 8px; }
@media print {
  body { max-width: none; padding: 0 10mm; font-size: 11px; }
  nav { display: none; }
  h2 { page-break-after: avoid; break-after: avoid; }
  table { page-break-inside: auto; }
  div.table { overflow: visible; }
  tr { page-break-inside: avoid; }
}
"""


class Html(str):
    """Text that is already HTML (what :func:`esc` returns): not escaped again where it is placed."""


def esc(text) -> str:
    """Text as HTML (escaped), once: HTML made by esc is returned as it is."""
    if isinstance(text, Html):
        return text
    return Html(html.escape(str(text), quote=True))


class Cell(NamedTuple):
    """A table cell: its HTML ``text``; ``key``/``value`` become ``data-key``/``data-value``; ``numeric``
    right-aligns it."""
    text: str
    key: str | None = None
    value: float | None = None
    numeric: bool = False
    title: str | None = None


class Section(NamedTuple):
    """One section of the page: its anchor ``id``, heading ``title`` and body ``html``."""
    id: str
    title: str
    html: str


def number(value, digits: int = 4, fixed: bool = False) -> str:
    """A number as text: ``digits`` significant digits (``fixed``: digits after the point); NaN/None as
    an en dash."""
    if value is None:
        return "–"
    try:
        v = float(value)
    except (TypeError, ValueError):
        return esc(value)
    if not math.isfinite(v):
        return "–"
    return f"{v:.{digits}f}" if fixed else f"{v:.{digits}g}"


def cell(value, key: str | None = None, digits: int = 4, fixed: bool = False, suffix: str = "",
         title: str | None = None) -> Cell:
    """A numeric cell of ``value`` (rounded for display, exact in ``data-value``)."""
    try:
        v = None if value is None else float(value)
    except (TypeError, ValueError):
        return Cell(esc(value), key, None, False, title)
    text = number(v, digits, fixed)
    if text != "–":
        text += suffix
    return Cell(text, key, v, True, title)


def _attrs(c: Cell) -> str:
    out = ' class="num"' if c.numeric else ""
    if c.key is not None:
        out += f' data-key="{esc(c.key)}"'
        if c.value is not None and math.isfinite(c.value):
            out += f' data-value="{c.value!r}"'
    if c.title:
        out += f' title="{esc(c.title)}"'
    return out


def table(headers: Sequence[str], rows: Iterable[Sequence], row_classes: Sequence[str] | None = None,
          table_id: str | None = None, dense: bool = False) -> str:
    """An HTML table; ``headers`` are HTML, each row a sequence of :class:`Cell` or plain text (escaped).
    ``dense``: smaller type and padding, for a grid of many columns (the r-table's 20 β) to fit the page."""
    ident = f' id="{esc(table_id)}"' if table_id else ""
    ident += ' class="dense"' if dense else ""
    parts = [f'<div class="table"><table{ident}><thead><tr>']
    parts += [f"<th>{h}</th>" for h in headers]
    parts.append("</tr></thead><tbody>")
    for k, row in enumerate(rows):
        cls = row_classes[k] if row_classes and k < len(row_classes) and row_classes[k] else ""
        parts.append(f'<tr class="{cls}">' if cls else "<tr>")
        for c in row:
            if not isinstance(c, Cell):
                c = Cell(esc(c))  # plain text escaped; HTML from esc kept
            parts.append(f"<td{_attrs(c)}>{c.text}</td>")
        parts.append("</tr>")
    parts.append("</tbody></table></div>")
    return "".join(parts)


def definition_list(items: Iterable[tuple]) -> str:
    """``<dl>`` of (label, HTML value) pairs; a value may be a :class:`Cell`."""
    parts = ["<dl>"]
    for label, value in items:
        if isinstance(value, Cell):
            parts.append(f"<dt>{esc(label)}</dt><dd{_attrs(value)}>{value.text}</dd>")
        else:
            parts.append(f"<dt>{esc(label)}</dt><dd>{value}</dd>")
    parts.append("</dl>")
    return "".join(parts)


def figure_png(fig, dpi: int = 90) -> bytes:
    """The matplotlib figure as PNG bytes (the figure is closed)."""
    import matplotlib.pyplot as plt
    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=dpi, bbox_inches="tight")
    finally:
        plt.close(fig)
    return buffer.getvalue()


def figure(png: bytes, caption: str, alt: str, key: str) -> str:
    """A figure embedded as a data URI, with its caption (HTML) and ``data-figure`` = ``key``."""
    data = base64.b64encode(png).decode("ascii")
    return (f'<figure data-figure="{esc(key)}"><img src="data:image/png;base64,{data}" alt="{esc(alt)}">'
            f"<figcaption>{caption}</figcaption></figure>")


def caveats(items: Iterable[str], info: bool = False) -> str:
    """A highlighted list of caveats (plain text items, escaped); empty when there are none."""
    items = [i for i in items if i]
    if not items:
        return ""
    cls = "caveats info" if info else "caveats"
    return f'<div class="{cls}"><ul>' + "".join(f"<li>{esc(i)}</li>" for i in items) + "</ul></div>"


def page(title: str, subtitle: str, summary_html: str, sections: Sequence[Section], footer: str) -> str:
    """The whole document: heading, table of contents, summary, sections, footer."""
    toc = "".join(f'<li><a href="#{esc(s.id)}">{esc(s.title)}</a></li>' for s in sections)
    body = "".join(f'<section id="{esc(s.id)}"><h2>{esc(s.title)}</h2>{s.html}</section>' for s in sections)
    return ("<!DOCTYPE html>\n"
            '<html lang="en"><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>"
            f"<header><h1>{esc(title)}</h1><p class=\"subtitle\">{subtitle}</p></header>"
            f"{summary_html}<nav><strong>Contents</strong><ol>{toc}</ol></nav>{body}"
            f"<footer>{footer}</footer></body></html>\n")
