"""What the HTML report's tests require of a page (test_html_report.py, test_html_report_browser.py):
strict UTF-8, parsed by html.parser into the few elements the generator writes, no script, no
event handler, no link or image that leaves the file, and every image a PNG data: URI that PIL
decodes whole at the size its tag states."""

import base64
import io
import os
import sys
from html.parser import HTMLParser

# html_report.py and plot.py, from the build tree (as `vgroove report` runs them).
PLOT = os.environ.get("VGROOVE_PLOT") or os.path.join(os.path.dirname(__file__), "..", "..", "python", "vgroove",
                                                      "plot.py")
sys.path.insert(0, os.path.dirname(os.path.abspath(PLOT)))
import html_report  # noqa: E402

ALLOWED_TAGS = {"html", "head", "meta", "title", "style", "body", "h1", "h2", "p", "span", "table", "caption", "thead",
                "tbody", "tr", "th", "td", "a", "code", "figure", "img", "figcaption", "section"}
VOID = {"meta", "img"}
DATA_PNG = "data:image/png;base64,"


class Page(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags, self.images, self.hrefs, self.data = [], [], [], []
        self.open, self.errors = [], []
        self.tables, self._table, self._cell = [], None, None  # tables: {"caption": str, "rows": [[cell text]]}

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        a = dict(attrs)
        for k, v in attrs:
            if k.startswith("on"):
                self.errors.append(f"<{tag}> has an event handler {k}")
            if v is not None and "javascript:" in v.lower():
                self.errors.append(f"<{tag} {k}> holds javascript:")
        if tag == "img":
            self.images.append(a)
        if tag == "a":
            self.hrefs.append(a.get("href", ""))
        if tag == "table":
            self._table = {"caption": "", "rows": []}
        elif tag == "tr" and self._table is not None:
            self._table["rows"].append([])
        elif tag in ("td", "th", "caption"):
            self._cell = []
        if tag not in VOID:
            self.open.append(tag)

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in VOID:
            self.open.pop()

    def handle_endtag(self, tag):
        if not self.open or self.open[-1] != tag:
            self.errors.append(f"</{tag}> closes <{self.open[-1] if self.open else 'nothing'}>")
        else:
            self.open.pop()
        if tag in ("td", "th") and self._table is not None and self._table["rows"] and self._cell is not None:
            self._table["rows"][-1].append("".join(self._cell))
        elif tag == "caption" and self._table is not None and self._cell is not None:
            self._table["caption"] = "".join(self._cell)
        elif tag == "table" and self._table is not None:
            self.tables.append(self._table)
            self._table = None
        if tag in ("td", "th", "caption"):
            self._cell = None

    def handle_data(self, d):
        self.data.append(d)
        if self._cell is not None:
            self._cell.append(d)

    def table(self, caption_start: str) -> dict:
        """The first table whose caption starts so."""
        for t in self.tables:
            if t["caption"].startswith(caption_start):
                return t
        raise AssertionError(f"no table captioned {caption_start!r}: {[t['caption'] for t in self.tables]}")

    def text(self) -> str:
        return "".join(self.data)


def decode_png(data: bytes, width: int, height: int) -> None:
    """PIL decodes the image whole, at the stated size, with pixels that are not all one colour."""
    from PIL import Image
    with Image.open(io.BytesIO(data)) as im:
        assert im.format == "PNG"
        im.load()
        assert im.size == (width, height), (im.size, width, height)
        lo_hi = im.convert("L").getextrema()
        assert lo_hi[0] < lo_hi[1], "an image of one colour"


def check_page(path: str) -> Page:
    """The page at `path` parsed and checked (see the module's docstring); returns the parse."""
    raw = open(path, "rb").read()
    page_text = raw.decode("utf-8")  # strict: the page is UTF-8
    assert page_text.startswith("<!DOCTYPE html>")
    p = Page()
    p.feed(page_text)
    p.close()
    assert not p.errors, p.errors[:5]
    assert not p.open, p.open
    assert set(p.tags) <= ALLOWED_TAGS, set(p.tags) - ALLOWED_TAGS
    assert "script" not in p.tags
    for h in p.hrefs:
        assert h.startswith("#r") or h == "#top", h
    for img in p.images:
        src = img.get("src", "")
        assert src.startswith(DATA_PNG), src[:80]
        decode_png(base64.b64decode(src[len(DATA_PNG):], validate=True), int(img["width"]), int(img["height"]))
    return p
