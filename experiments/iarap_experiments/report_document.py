"""The report as a list of blocks (headings, paragraphs, tables, images), written as Markdown and as one
self-contained HTML file (images inlined as base64), so neither needs a Markdown converter."""
from __future__ import annotations

import base64
import html
import os
import re
from dataclasses import dataclass, field


@dataclass
class Heading:
    text: str
    level: int = 2


@dataclass
class Paragraph:
    text: str  # may use **bold** and `code`


@dataclass
class Table:
    header: list[str]
    rows: list[list[str]]
    caption: str = ""


@dataclass
class Image:
    path: str  # relative to the report folder
    caption: str


@dataclass
class Document:
    blocks: list = field(default_factory=list)

    def add(self, *blocks) -> None:
        self.blocks.extend(blocks)


def _md_cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def to_markdown(doc: Document) -> str:
    out = []
    for block in doc.blocks:
        if isinstance(block, Heading):
            out.append("#" * block.level + " " + block.text)
        elif isinstance(block, Paragraph):
            out.append(block.text)
        elif isinstance(block, Table):
            lines = []
            if block.caption:
                lines.append(block.caption + "\n")
            lines.append("| " + " | ".join(_md_cell(h) for h in block.header) + " |")
            lines.append("|" + "|".join("---" for _ in block.header) + "|")
            lines += ["| " + " | ".join(_md_cell(c) for c in row) + " |" for row in block.rows]
            out.append("\n".join(lines))
        elif isinstance(block, Image):
            out.append(f"![{block.caption}]({block.path})\n\n*{block.caption}*")
    return "\n\n".join(out) + "\n"


def _inline_html(text: str) -> str:
    escaped = html.escape(str(text))
    escaped = re.sub(r"`([^`]+)`", r"<code>\1</code>", escaped)
    return re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", escaped)


def to_html(doc: Document, folder: str, title: str) -> str:
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title><style>"
             "body{font-family:sans-serif;max-width:1200px;margin:2em auto;line-height:1.45}"
             "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;"
             "text-align:right}th{background:#eee}td:first-child{text-align:left}"
             "img{max-width:100%}figcaption{font-style:italic;margin-bottom:1.5em}"
             "code{background:#f3f3f3}</style></head><body>"]
    for block in doc.blocks:
        if isinstance(block, Heading):
            parts.append(f"<h{block.level}>{_inline_html(block.text)}</h{block.level}>")
        elif isinstance(block, Paragraph):
            for paragraph in block.text.split("\n\n"):
                if paragraph.lstrip().startswith("- "):
                    items = [item[2:] for item in paragraph.strip().split("\n") if item.startswith("- ")]
                    parts.append("<ul>" + "".join(f"<li>{_inline_html(i)}</li>" for i in items) + "</ul>")
                else:
                    parts.append(f"<p>{_inline_html(paragraph)}</p>")
        elif isinstance(block, Table):
            if block.caption:
                parts.append(f"<p>{_inline_html(block.caption)}</p>")
            head = "".join(f"<th>{_inline_html(h)}</th>" for h in block.header)
            body = "".join("<tr>" + "".join(f"<td>{_inline_html(c)}</td>" for c in row) + "</tr>"
                           for row in block.rows)
            parts.append(f"<table><tr>{head}</tr>{body}</table>")
        elif isinstance(block, Image):
            full = os.path.join(folder, block.path)
            if os.path.exists(full):
                mime = "image/svg+xml" if full.endswith(".svg") else "image/png"
                with open(full, "rb") as f:
                    data = base64.b64encode(f.read()).decode("ascii")
                parts.append(f"<figure><img src='data:{mime};base64,{data}' alt='{html.escape(block.caption)}'>"
                             f"<figcaption>{_inline_html(block.caption)}</figcaption></figure>")
            else:
                parts.append(f"<p><b>missing picture {html.escape(block.path)}</b></p>")
    parts.append("</body></html>")
    return "\n".join(parts)
