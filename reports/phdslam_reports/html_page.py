"""A self-contained HTML page: inline CSS, figures as base64 PNG, no scripts, no external links."""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass, field
from typing import Sequence

STYLE = """
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 24px auto; max-width: 1320px;
       color: #1d1d1d; line-height: 1.45; padding: 0 16px; }
h1 { font-size: 1.7em; margin-bottom: 0.2em; }
h2 { font-size: 1.3em; border-bottom: 2px solid #d0d0d0; padding-bottom: 4px; margin-top: 1.8em; }
h3 { font-size: 1.1em; margin-top: 1.4em; }
.meta { color: #555; font-size: 0.92em; }
.table-box { max-width: 100%; overflow-x: auto; margin: 10px 0 14px; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { border: 1px solid #c8c8c8; padding: 3px 7px; text-align: right; vertical-align: top;
         white-space: nowrap; }
th { background: #eef1f5; text-align: center; }
td.name { text-align: left; white-space: nowrap; }
td.flag { background: #fde2e1; color: #8a1111; font-weight: bold; }
td.ok { background: #e6f4e6; }
td .sub { font-size: 0.85em; color: #555; white-space: nowrap; }
td.flag .sub { color: #8a1111; }
tr:nth-child(even) td:not(.flag):not(.ok) { background: #fafafa; }
.note { background: #fff8e1; border-left: 4px solid #f0b400; padding: 6px 10px; margin: 8px 0; }
.skipped { color: #5b5b5b; font-style: italic; }
figure { margin: 12px 0 20px; }
figure img { max-width: 100%; height: auto; border: 1px solid #e2e2e2; }
figcaption { font-size: 0.9em; color: #444; margin-top: 4px; }
nav ul { columns: 2; font-size: 0.92em; }
code { background: #f2f2f2; padding: 0 3px; overflow-wrap: anywhere; }
p, li, figcaption { overflow-wrap: anywhere; }
"""


@dataclass
class Section:
    """One report section: shown with content, or skipped with a short note."""

    id: str
    title: str
    body: str = ""
    skipped_note: str = ""
    level: int = 2
    figures: list[str] = field(default_factory=list)

    @property
    def shown(self) -> bool:
        """True when the section has content."""
        return not self.skipped_note

    def render(self) -> str:
        """The section as HTML."""
        status = "shown" if self.shown else "skipped"
        heading = f"<h{self.level}>{html.escape(self.title)}</h{self.level}>"
        if self.shown:
            content = self.body
        else:
            content = f'<p class="skipped">Skipped: {html.escape(self.skipped_note)}</p>'
        return (f'<section id="{html.escape(self.id)}" data-status="{status}">\n'
                f"{heading}\n{content}\n</section>")


def escape(text: object) -> str:
    """HTML-escaped text."""
    return html.escape(str(text))


def figure_html(png: bytes, file_name: str, caption: str, alt: str) -> str:
    """An embedded PNG with its caption; the file beside the page is named for reference."""
    encoded = base64.b64encode(png).decode("ascii")
    return (f'<figure><img src="data:image/png;base64,{encoded}" alt="{escape(alt)}">'
            f"<figcaption>{escape(caption)} <span class=\"meta\">({escape(file_name)})</span>"
            f"</figcaption></figure>")


def note_html(text: str) -> str:
    """A highlighted note paragraph."""
    return f'<p class="note">{escape(text)}</p>'


def _cell_html(cell: Sequence[str]) -> str:
    text, css = cell[0], cell[1]
    content = escape(text)
    if len(cell) > 2 and cell[2]:
        content += f'<br><span class="sub">{escape(cell[2])}</span>'
    return f'<td class="{css}">{content}</td>' if css else f"<td>{content}</td>"


def table_html(
    headers: Sequence[str],
    rows: Sequence[Sequence[Sequence[str]]],
    header_rows: Sequence[Sequence[tuple[str, int]]] = (),
) -> str:
    """A table of (text, css class[, second line]) cells, optional grouped header rows, in a
    box that scrolls sideways when the table is wider than the page (the page never does).

    ``header_rows`` hold (text, colspan) pairs drawn above ``headers``.
    """
    parts = ['<div class="table-box"><table>']
    for header_row in header_rows:
        cells = "".join(
            f'<th colspan="{span}">{escape(text)}</th>' if span > 1 else f"<th>{escape(text)}</th>"
            for text, span in header_row
        )
        parts.append(f"<tr>{cells}</tr>")
    if headers:
        parts.append("<tr>" + "".join(f"<th>{escape(h)}</th>" for h in headers) + "</tr>")
    for row in rows:
        cells = "".join(_cell_html(cell) for cell in row)
        parts.append(f"<tr>{cells}</tr>")
    parts.append("</table></div>")
    return "\n".join(parts)


def render_page(title: str, intro_html: str, sections: Sequence[Section]) -> str:
    """The whole page: title, introduction, a table of contents and the sections."""
    toc = "".join(
        f'<li><a href="#{escape(s.id)}">{escape(s.title)}</a>'
        f'{"" if s.shown else " (skipped)"}</li>'
        for s in sections if s.level == 2
    )
    body = "\n".join(s.render() for s in sections)
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{escape(title)}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
        f"<h1>{escape(title)}</h1>\n{intro_html}\n<nav><h2>Contents</h2><ul>{toc}</ul></nav>\n"
        f"{body}\n</body>\n</html>\n"
    )
