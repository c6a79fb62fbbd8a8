#!/usr/bin/env python3
"""plot_labels.py: a figure's text as a reader sees it, measured by other
programs.

    python3 tests/plot_labels.py [--names FILE] FIGURE.pdf FIGURE.svg [...]

Each FIGURE.pdf and FIGURE.svg is one figure drawn as PDF and as SVG;
--names FILE the whole names (records, arches) the figures may shorten,
one a line.
Each word's box comes from poppler's pdftotext -bbox: of the PDF, and of
the SVG as librsvg lays it out (rsvg-convert -f pdf).  Checked:
  - every word of the PDF within the page's 10 mm margins, every word of
    the SVG within its page;
  - no two words of either overlap (their glyph bands: each box less a
    quarter of its height above and a fifth below, less a point at each
    side), a data point drawn as a glyph (●, ○, ◆: a word of symbols)
    counting as a word, except with another point;
  - no label of the SVG (a word not of symbols) lies on a mark of the figure: the SVG is drawn
    again without its <text> elements (rsvg-convert, then pdftoppm at
    2 pixels per point) and the pixels inside each word's glyph band must
    be of one colour, the background the
    word is written on: a line, a point or an edge of a fill crossing a
    label fails;
  - with --names, a shortened label (one with an ellipsis, or two) stands
    for one whole name only: its start, its end and any part between
    two ellipses found in one name and no other.
Prints one line per fault and a summary; exits 1 if any.  Used by
tests/test_plot_labels.c.
"""
import os
import re
import subprocess
import sys
import tempfile

import unicodedata

import numpy as np

MARGIN_PT = 28.35 - 1  # 10 mm, less a point
SCALE = 2  # raster pixels per point
TOL = 40  # a colour step that marks a mark (0-255 per channel)


def words_of(pdf):
    out = subprocess.run(["pdftotext", "-f", "1", "-l", "1", "-bbox", pdf, "-"],
                         capture_output=True, text=True, check=True).stdout
    page = re.search(r'<page width="([\d.]+)" height="([\d.]+)"', out)
    w = []
    for m in re.finditer(r'<word xMin="([-\d.]+)" yMin="([-\d.]+)" xMax="([-\d.]+)" '
                         r'yMax="([-\d.]+)">(.*?)</word>', out):
        x0, y0, x1, y1 = (float(m.group(k)) for k in range(1, 5))
        text = m.group(5).replace("&amp;", "&").replace("&lt;", "<").replace("&gt;", ">")
        w.append((x0, y0, x1, y1, text))
    return float(page.group(1)), float(page.group(2)), w


def band(w):
    """A word's glyph band: its box (the font's ascent to descent) less a
    quarter of its height above and a fifth below, less a point at each
    side: where its letters' ink is."""
    h = w[3] - w[1]
    return (w[0] + 1, w[1] + 0.25 * h, w[2] - 1, w[3] - 0.2 * h)


def overlap(a, b):
    a, b = band(a), band(b)
    return min(a[2], b[2]) > max(a[0], b[0]) and min(a[3], b[3]) > max(a[1], b[1])


def is_symbol(w):
    """A data mark drawn as a glyph (a point: ●, ○, ◆): not a label."""
    return all(unicodedata.category(c) == "So" for c in w[4])


def raster_without_text(svg, tmp):
    text = open(svg, encoding="utf-8").read()
    bare = re.sub(r"<text\b.*?</text>", "", text, flags=re.S)
    path = os.path.join(tmp, "bare.svg")
    open(path, "w", encoding="utf-8").write(bare)
    pdf = os.path.join(tmp, "bare.pdf")
    subprocess.run(["rsvg-convert", "-f", "pdf", "-o", pdf, path], check=True)
    subprocess.run(["pdftoppm", "-r", str(72 * SCALE), "-singlefile", pdf,
                    os.path.join(tmp, "bare")], check=True)
    raw = open(os.path.join(tmp, "bare.ppm"), "rb").read()
    m = re.match(rb"P6\s+(\d+)\s+(\d+)\s+(\d+)\s", raw)
    w, h = int(m.group(1)), int(m.group(2))
    return np.frombuffer(raw[m.end():], dtype=np.uint8).reshape(h, w, 3)


def matches(label, names):
    """The names a shortened label can stand for (a word of a title may end
    in a colon or a comma)."""
    parts = label.rstrip(":,;").split("…")
    out = []
    for n in names:
        if not n.startswith(parts[0]) or not n.endswith(parts[-1]):
            continue
        at, ok = len(parts[0]), True
        for mid in parts[1:-1]:
            k = n.find(mid, at)
            ok = ok and k >= 0
            at = k + len(mid) if k >= 0 else at
        if ok and len(n) > len(parts[0]) + len(parts[-1]):
            out.append(n)
    return out


def check(pdf, svg, names, tmp):
    faults = []
    pw, ph, pwords = words_of(pdf)
    for x0, y0, x1, y1, t in pwords:
        if x0 < MARGIN_PT or y0 < MARGIN_PT or x1 > pw - MARGIN_PT or y1 > ph - MARGIN_PT:
            faults.append("PDF: \"%s\" at x %.1f-%.1f, y %.1f-%.1f is outside the %.0f x %.0f "
                          "page's 10 mm margins" % (t, x0, x1, y0, y1, pw, ph))
    svgpdf = os.path.join(tmp, "svg.pdf")
    subprocess.run(["rsvg-convert", "-f", "pdf", "-o", svgpdf, svg], check=True)
    sw, sh, swords = words_of(svgpdf)
    for x0, y0, x1, y1, t in swords:
        if x0 < 0 or y0 < 0 or x1 > sw or y1 > sh:
            faults.append("SVG: \"%s\" at x %.1f-%.1f, y %.1f-%.1f is outside the %.0f x %.0f "
                          "page" % (t, x0, x1, y0, y1, sw, sh))
    for what, ws in (("PDF", pwords), ("SVG", swords)):
        for i in range(len(ws)):
            for j in range(i + 1, len(ws)):
                if overlap(ws[i], ws[j]) and not (is_symbol(ws[i]) and is_symbol(ws[j])):
                    faults.append("%s: \"%s\" and \"%s\" overlap" % (what, ws[i][4], ws[j][4]))
    img = raster_without_text(svg, tmp)
    for w in swords:
        if is_symbol(w):
            continue
        x0, y0, x1, y1, t = w
        bx = band(w)
        a, b = int(bx[0] * SCALE), int(bx[2] * SCALE)
        c, d = int(bx[1] * SCALE), int(bx[3] * SCALE)
        if b <= a or d <= c:
            continue
        box = img[max(c, 0):d, max(a, 0):b].reshape(-1, 3).astype(int)
        if box.size == 0:
            continue
        spread = (box.max(axis=0) - box.min(axis=0)).max()
        if spread > TOL:
            faults.append("SVG: \"%s\" at x %.1f-%.1f, y %.1f-%.1f lies on a mark of the figure "
                          "(colours %s to %s under it)" % (t, x0, x1, y0, y1,
                                                           tuple(box.min(axis=0)),
                                                           tuple(box.max(axis=0))))
    nshort = 0
    for what, ws in (("PDF", pwords), ("SVG", swords)):
        for s in sorted(set(w[4] for w in ws if "…" in w[4])):
            nshort += what == "PDF"
            if names:
                m = matches(s, names)
                if len(m) != 1:
                    faults.append("%s: the shortened label \"%s\" stands for %d names (%s)" %
                                  (what, s, len(m), ", ".join(m[:4])))
    return faults, len(pwords), len(swords), nshort


def main():
    args = sys.argv[1:]
    names = []
    if args[:1] == ["--names"]:
        names = [l.rstrip("\n") for l in open(args[1], encoding="utf-8") if l.strip()]
        args = args[2:]
    tmp = tempfile.mkdtemp()
    bad = 0
    for pdf, svg in zip(args[::2], args[1::2]):
        faults, npw, nsw, nshort = check(pdf, svg, names, tmp)
        name = os.path.basename(pdf).rsplit(".", 1)[0]
        for f in faults[:20]:
            print("%s: %s" % (name, f))
        print("%s: %d words (PDF), %d words (SVG), %d shortened, %d faults"
              % (name, npw, nsw, nshort, len(faults)))
        bad += len(faults) + (npw == 0) + (nsw == 0)
    sys.exit(1 if bad or not args else 0)


if __name__ == "__main__":
    main()
