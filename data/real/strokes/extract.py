#!/usr/bin/env python3
"""Cuts the reference drawings of the stroke-pattern corpus out of openclipart drawings, and the
greyscale photograph out of scikit-image's astronaut picture.

    python3 extract.py --list                  # prints "NAME PACKAGE PATH" for every source
    python3 extract.py NAME SOURCE OUT_DIR     # writes OUT_DIR/<NAME>.svg (or the photo's PNG)

Every SVG case below (a) reads the source drawing with the `svgelements` package (styles
resolved and inherited, transforms applied, every shape as path segments; `drawing()` turns arcs
and quadratics into cubics and multiplies group opacities; clip paths, masks, filters and text
are dropped; gradient paint is no plain colour, so it fails every colour test, and a kept path
may not have one), (b) splits compound paths into one path per outer subpath (holes stay with
their outline), (c) keeps the paths that pass the case's selection and lie inside its window
(or, for the one `clip` case, cuts them at the window's edge), and (d) writes them in drawing
order, translated so that the window's corner is the origin, with coordinates rounded to 0.01.
Nothing is drawn, moved or recoloured.

SVG cases need the `svgelements` package; the photo needs Pillow.
"""

import io
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

sys.dont_write_bytecode = True  # no __pycache__ in the corpus folder
import svgelements as se  # noqa: E402

OC = "usr/share/openclipart/svg/"


def star_like(sub):
    """A closed polygon of 8–24 corners alternating between two radii (a star)."""
    pts = [sub["start"]] + [s[-1] for s in sub["segs"]]
    if len(pts) > 2 and math.dist(pts[0], pts[-1]) < 1e-6:
        pts = pts[:-1]
    n = len(pts)
    if n not in (8, 10, 12, 14, 16, 18, 20, 24) or any(s[0] != "L" for s in sub["segs"]):
        return False
    cx = sum(p[0] for p in pts) / n
    cy = sum(p[1] for p in pts) / n
    r = [math.hypot(p[0] - cx, p[1] - cy) for p in pts]
    a, b = r[0::2], r[1::2]
    ma, mb = sum(a) / len(a), sum(b) / len(b)
    if min(ma, mb) <= 0:
        return False
    return (min(ma, mb) / max(ma, mb) < 0.75 and all(abs(x - ma) < 0.25 * ma for x in a)
            and all(abs(x - mb) < 0.25 * mb for x in b))


def size_below(limit):
    return lambda s, b: max(b[2] - b[0], b[3] - b[1]) < limit


def fill_in(*colours):
    return lambda s, b: s.style["fill"] in colours


def outside(x0, y0, x1, y1):
    """The box's centre is not in this rectangle."""
    return lambda s, b: not (x0 <= (b[0] + b[2]) / 2 <= x1 and y0 <= (b[1] + b[3]) / 2 <= y1)


# Each case: source (path in the Debian package openclipart-svg), window (x0, y0, x1, y1) in the
# source's user units, mode ("inside": keep paths entirely inside the window; "groups": keep the
# groups of paths that lie entirely inside the window, a group being a path and the smaller
# paths centred in its box (a bubble and its highlight, a honeycomb cell and its shading); "clip": cut paths at the window's edge) and the tests
# every kept path passes.
CASES = {
    "lamp_hatching": dict(
        source=OC + "tools/hurricane_lamp_ganson.svg",
        window=(50, 78, 116, 202),
        mode="inside",
        tests=[fill_in("#000000"), size_below(30)],
        note="the black hatching of the lamp's glass chimney, without the lamp"),
    "elephant_hatching": dict(
        source=OC + "unsorted/elefantone.svg",
        window=(180, 20, 360, 200),
        mode="inside",
        tests=[fill_in("#000000"), size_below(60)],
        note="the black hatching strokes of the elephant's ear, shoulder, back and flank; "
             "the grey body, its outline and everything outside the window removed"),
    "juice_bubbles": dict(
        source=OC + "food/juice_glass_andremarcel._01.svg",
        window=(270, 170, 360, 236),
        mode="groups",
        tests=[fill_in("#c48906", "#ffffff"), size_below(30)],
        note="the bubbles on the juice (brown discs with a light rim, white highlights); "
             "glass, juice, straw removed"),
    "arkansas_stars": dict(
        source=OC + "signs_and_symbols/flags/america/united_states/usa_arkansas.svg",
        window=(40, 17, 702, 462),
        mode="inside",
        tests=[lambda s, b: any(star_like(u) for u in s.subs)],
        note="the 29 stars (white and blue, black outline) of the flag; the field, the "
             "diamond band and the lettering removed"),
    "honeycomb_cells": dict(
        source=OC + "unsorted/ape_miele.svg",
        window=(0, 196, 262, 383),
        mode="groups",
        tests=[size_below(35), outside(220, 140, 300, 200)],
        note="the cells of the lower left part of the comb (each a disc with shading "
             "crescents and highlights; a few empty black cells); the comb's background removed"),
    "melon_seeds": dict(
        source=OC + "food/fruit/melon_goneri_le_bouder_01.svg",
        window=(165, 348, 320, 420),
        mode="inside",
        tests=[fill_in("#d98b00"), size_below(20)],
        note="the upper half of the translucent seed cluster (fill and stroke opacity "
             "0.13–0.45, two stroke widths); the melon removed"),
    "tangram_colours": dict(
        source=OC + "shapes/tangram_erwan_02.svg",
        window=(100, 500, 2100, 2460),
        mode="inside",
        tests=[fill_in("#ea6f00", "#68bce7", "#009a00", "#eae500", "#e500ce", "#0040e5",
                       "#00e5a5")],
        note="the 36 coloured tangram figures of the left sheet (each the seven pieces, one "
             "colour per piece); the frames and the black silhouettes of the right sheet removed"),
    "cactus_spines_cropped": dict(
        source=OC + "plants/cacuts_01.svg",
        window=(210, 180, 440, 410),
        mode="clip",
        tests=[lambda s, b: s.style["stroke"] in ("#000000", "#8c6500"), size_below(60)],
        note="the spines (each a brown stroke over a black shadow stroke) in a square window "
             "of the big arm, cut at the window's edge; the arm, the sky and the sun removed"),
    "birds_flock": dict(
        source=OC + "animals/birds/stormo_di_uccelli_archit_01.svg",
        window=(0, 0, 415, 256),
        mode="inside",
        tests=[],
        note="the whole drawing: a flock of birds, each one or two filled brush marks"),
}

PHOTOS = {
    # name: Debian package, path in it, crop box (left, top, right, bottom) in pixels
    "photo_astronaut": dict(
        package="python3-skimage",
        source="usr/lib/python3/dist-packages/skimage/data/astronaut.png",
        box=(130, 10, 330, 210),
        note="Eileen Collins' face and hair, 200 × 200 px at the original resolution"),
}


# ---------------------------------------------------------------------------------------------
# Reading a drawing with svgelements. A mark is one rendered shape (or, after split_compound, one
# outer subpath of it with its holes): absolute subpaths {"start": p, "segs": [("L", p) or
# ("C", c1, c2, p), ...], "closed": bool} in the root's user units, and its resolved paint.

class Mark:
    def __init__(self, subs, style):
        self.subs = subs
        self.style = style

    def points(self, steps=8):
        """A polyline approximation of every subpath (for boxes and clipping)."""
        out = []
        for s in self.subs:
            pts = [s["start"]]
            p = s["start"]
            for seg in s["segs"]:
                if seg[0] == "L":
                    pts.append(seg[1])
                else:
                    c1, c2, q = seg[1], seg[2], seg[3]
                    for i in range(1, steps + 1):
                        t = i / steps
                        u = 1 - t
                        pts.append((u ** 3 * p[0] + 3 * u * u * t * c1[0] + 3 * u * t * t * c2[0] + t ** 3 * q[0],
                                    u ** 3 * p[1] + 3 * u * u * t * c1[1] + 3 * u * t * t * c2[1] + t ** 3 * q[1]))
                p = seg[-1]
            out.append(pts)
        return out

    def bbox(self):
        pts = [p for sub in self.points() for p in sub]
        if not pts:
            return None
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        return (min(xs), min(ys), max(xs), max(ys))


def xy(p):
    return (float(p[0]), float(p[1]))


def segments(shape):
    """The shape's segments in the root's user units. Arcs become cubics (one per quarter turn or
    part of one) before the transform is applied, so that a skewed or stretched ellipse becomes
    the exact image of its circle's cubics."""
    m = shape.transform
    for seg in shape.segments(transformed=False):
        if isinstance(seg, se.Arc):
            if seg.start == seg.end:
                continue
            n = max(1, math.ceil(abs(seg.sweep) / (math.pi / 2) - 1e-9))
            pieces = list(seg.as_cubic_curves(n))
        else:
            pieces = [seg]
        for piece in pieces:
            yield piece * m


def subpaths(shape):
    """The shape's outline as subpaths of lines and cubics (quadratics become their exact
    cubics)."""
    subs = []
    cur = None
    for seg in segments(shape):
        if isinstance(seg, se.Move):
            cur = {"start": xy(seg.end), "segs": [], "closed": False}
            subs.append(cur)
            continue
        if isinstance(seg, se.Close):
            if cur is not None:
                cur["closed"] = True
            continue
        if cur is None or cur["closed"]:  # drawing on after a close starts a new subpath
            cur = {"start": xy(seg.start), "segs": [], "closed": False}
            subs.append(cur)
        if isinstance(seg, se.Line):
            cur["segs"].append(("L", xy(seg.end)))
        elif isinstance(seg, se.CubicBezier):
            cur["segs"].append(("C", xy(seg.control1), xy(seg.control2), xy(seg.end)))
        elif isinstance(seg, se.QuadraticBezier):
            p0, q, p = xy(seg.start), xy(seg.control), xy(seg.end)
            cur["segs"].append(("C", (p0[0] + 2 / 3 * (q[0] - p0[0]), p0[1] + 2 / 3 * (q[1] - p0[1])),
                                (p[0] + 2 / 3 * (q[0] - p[0]), p[1] + 2 / 3 * (q[1] - p[1])), p))
        else:
            raise ValueError("unexpected path segment %r" % seg)
    return [s for s in subs if s["segs"] or s["closed"]]


def number(value):
    return se.Length(value).value() if value not in (None, "", "none") else 0.0


def paint(shape, opacity):
    """The shape's paint: colours as '#rrggbb' or 'none', opacities (group opacity included),
    widths and dashes scaled by the shape's transform."""
    v = shape.values
    scale = math.sqrt(abs(shape.transform.determinant))
    st = {}
    for key, colour in (("fill", shape.fill), ("stroke", shape.stroke)):
        raw = str(v.get(key, "")).strip()
        if raw.startswith("url("):
            st[key] = raw  # a gradient or pattern: no plain colour (fails every colour test)
        else:
            st[key] = colour.hexrgb if colour is not None and colour.value is not None else "none"
        st[key + "-opacity"] = float(v.get(key + "-opacity", 1)) * opacity
    st["stroke-width"] = shape.implicit_stroke_width or 0.0
    # Paint that draws nothing is no paint.
    if st["stroke-width"] <= 0 or st["stroke-opacity"] <= 0:
        st["stroke"] = "none"
    if st["fill-opacity"] <= 0:
        st["fill"] = "none"
    dash = str(v.get("stroke-dasharray", "none")).strip()
    dashes = [number(x) * scale for x in re.split(r"[\s,]+", dash) if x] if dash != "none" else []
    st["stroke-dasharray"] = dashes if any(dashes) else None
    st["stroke-dashoffset"] = number(v.get("stroke-dashoffset")) * scale
    for key, default in (("fill-rule", "nonzero"), ("stroke-linecap", "butt"),
                         ("stroke-linejoin", "miter")):
        st[key] = str(v.get(key, default)).strip()
    return st


def drawing(tree):
    """The rendered shapes of an SVG document (an ElementTree) in drawing order, as marks."""
    marks = []

    def walk(node, opacity):
        for child in node:
            if not isinstance(child, (se.Group, se.Use, se.Shape)):
                continue  # text, images, unknown elements
            own = child.values.get(se.SVG_STRUCT_ATTRIB, {}).get("opacity", 1)
            op = opacity * float(own)
            if isinstance(child, se.Shape):
                if child.values.get("visibility") in ("hidden", "collapse"):
                    continue
                subs = subpaths(child)
                if subs:
                    marks.append(Mark(subs, paint(child, op)))
            else:
                walk(child, op)

    # svgelements keeps the document's namespace declarations among the attributes it inherits,
    # so Adobe Illustrator's xmlns:x="http://ns.adobe.com/Extensibility/1.0/" reads as x="1" on
    # the root and shifts the whole drawing by one unit; ElementTree's rewrite names every
    # prefix ns0, ns1, … (or rdf, dc, …), which no SVG attribute is called.
    buf = io.BytesIO()
    tree.write(buf, encoding="utf-8")
    buf.seek(0)
    svg = se.SVG.parse(buf, reify=False)
    walk(svg, float(svg.values.get(se.SVG_STRUCT_ATTRIB, {}).get("opacity", 1)))
    return marks


def metadata(tree):
    """Title and creator of the drawing's RDF metadata (cc:Work)."""
    md = {}
    for work in tree.getroot().iter():
        if work.tag.split("}")[-1] != "Work":
            continue
        for ch in work:
            n = ch.tag.split("}")[-1]
            if n == "title" and (ch.text or "").strip():
                md["title"] = ch.text.strip()
            if n in ("creator", "publisher"):
                for t in ch.iter():
                    if t.tag.split("}")[-1] == "title" and (t.text or "").strip():
                        md.setdefault(n, t.text.strip())
    return md


def split_compound(shape):
    """Splits a path of several subpaths into one mark per outer subpath, each keeping the
    subpaths that lie inside its box (the holes of a filled shape, the inner lines of a glyph)."""
    if len(shape.subs) < 2:
        return [shape]
    boxes = []
    for pts in shape.points():
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        boxes.append((min(xs), min(ys), max(xs), max(ys)))
    parent = list(range(len(shape.subs)))
    area = [(b[2] - b[0]) * (b[3] - b[1]) for b in boxes]
    for i, b in enumerate(boxes):
        best = None
        for j, c in enumerate(boxes):
            if j != i and area[j] > area[i] and c[0] <= b[0] and c[1] <= b[1] and c[2] >= b[2] and c[3] >= b[3]:
                if best is None or area[j] < area[best]:
                    best = j
        if best is not None:
            parent[i] = best

    def root(i):
        seen = 0
        while parent[i] != i and seen < len(parent):
            i = parent[i]
            seen += 1
        return i
    groups = {}
    for i in range(len(shape.subs)):
        groups.setdefault(root(i), []).append(i)
    return [Mark([shape.subs[i] for i in sorted(g)], shape.style) for _, g in sorted(groups.items())]


# ---------------------------------------------------------------------------------------------
# Writing: plain <path> elements with explicit paint.

def fmt(x, digits=2):
    s = "%.*f" % (digits, x)
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def path_data(subs, dx=0.0, dy=0.0):
    parts = []
    for s in subs:
        p = lambda q: fmt(q[0] - dx) + "," + fmt(q[1] - dy)
        parts.append("M" + p(s["start"]))
        last = None
        for seg in s["segs"]:
            if seg[0] == "L":
                parts.append(("" if last == "L" else "L") + p(seg[1]))
            else:
                parts.append(("" if last == "C" else "C") + " ".join(p(q) for q in seg[1:]))
            last = seg[0]
        if s["closed"]:
            parts.append("Z")
    return " ".join(parts)


def path_element(shape, dx, dy, subs):
    st = shape.style
    for key in ("fill", "stroke"):
        if st[key].startswith("url("):
            raise ValueError("a kept path is painted with %s, not a plain colour" % st[key])
    attrs = ['d="%s"' % path_data(subs, dx, dy), 'fill="%s"' % st["fill"]]
    if st["fill"] != "none":
        if st["fill-opacity"] < 0.999:
            attrs.append('fill-opacity="%s"' % fmt(st["fill-opacity"]))
        if st["fill-rule"] == "evenodd":
            attrs.append('fill-rule="evenodd"')
    attrs.append('stroke="%s"' % st["stroke"])
    if st["stroke"] != "none":
        attrs.append('stroke-width="%s"' % fmt(st["stroke-width"]))
        if st["stroke-opacity"] < 0.999:
            attrs.append('stroke-opacity="%s"' % fmt(st["stroke-opacity"]))
        if st["stroke-dasharray"]:
            attrs.append('stroke-dasharray="%s"' % ",".join(fmt(v) for v in st["stroke-dasharray"]))
            if st["stroke-dashoffset"]:
                attrs.append('stroke-dashoffset="%s"' % fmt(st["stroke-dashoffset"]))
        if st["stroke-linecap"] != "butt":
            attrs.append('stroke-linecap="%s"' % st["stroke-linecap"])
        if st["stroke-linejoin"] != "miter":
            attrs.append('stroke-linejoin="%s"' % st["stroke-linejoin"])
    return "<path " + " ".join(attrs) + "/>"


def write_svg(path, width, height, elements, comment):
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<svg xmlns="http://www.w3.org/2000/svg" width="%s" height="%s" viewBox="0 0 %s %s">'
             % (fmt(width), fmt(height), fmt(width), fmt(height)),
             "<!-- %s -->" % comment.replace("--", "-")]
    lines += elements
    lines.append("</svg>")
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# Clipping (the "clip" mode): curves crossing the window are flattened, then cut.

def flatten_sub(sub, tol=0.05):
    pts = [sub["start"]]
    p = sub["start"]
    for seg in sub["segs"]:
        if seg[0] == "L":
            pts.append(seg[1])
        else:
            c1, c2, q = seg[1], seg[2], seg[3]
            est = math.dist(p, c1) + math.dist(c1, c2) + math.dist(c2, q)
            n = max(1, int(math.ceil(math.sqrt(est / tol) / 2)))
            for i in range(1, n + 1):
                t = i / n
                u = 1 - t
                pts.append((u ** 3 * p[0] + 3 * u * u * t * c1[0] + 3 * u * t * t * c2[0] + t ** 3 * q[0],
                            u ** 3 * p[1] + 3 * u * u * t * c1[1] + 3 * u * t * t * c2[1] + t ** 3 * q[1]))
        p = seg[-1]
    if sub["closed"] and math.dist(pts[0], pts[-1]) > 1e-9:
        pts.append(pts[0])
    return pts


def clip_segment(p, q, w):
    """Liang–Barsky: the part of segment pq inside the window, or None."""
    x0, y0, x1, y1 = w
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for pk, qk in ((-dx, p[0] - x0), (dx, x1 - p[0]), (-dy, p[1] - y0), (dy, y1 - p[1])):
        if pk == 0:
            if qk < 0:
                return None
        else:
            t = qk / pk
            if pk < 0:
                t0 = max(t0, t)
            else:
                t1 = min(t1, t)
    if t0 > t1:
        return None
    return (p[0] + t0 * dx, p[1] + t0 * dy), (p[0] + t1 * dx, p[1] + t1 * dy)


def clip_polyline(pts, w):
    pieces = []
    cur = None
    for p, q in zip(pts, pts[1:]):
        c = clip_segment(p, q, w)
        if c is None:
            cur = None
            continue
        a, b = c
        if cur is not None and math.dist(cur[-1], a) < 1e-9:
            cur.append(b)
        else:
            cur = [a, b]
            pieces.append(cur)
        if math.dist(b, q) > 1e-9:  # left the window
            cur = None
    return [pc for pc in pieces if len(pc) >= 2 and any(math.dist(pc[0], x) > 1e-6 for x in pc)]


def clip_polygon(pts, w):
    """Sutherland–Hodgman against the window."""
    x0, y0, x1, y1 = w
    poly = pts[:-1] if math.dist(pts[0], pts[-1]) < 1e-9 else pts
    for inside, cut in (
            (lambda p: p[0] >= x0, lambda p, q: (x0, p[1] + (q[1] - p[1]) * (x0 - p[0]) / (q[0] - p[0]))),
            (lambda p: p[0] <= x1, lambda p, q: (x1, p[1] + (q[1] - p[1]) * (x1 - p[0]) / (q[0] - p[0]))),
            (lambda p: p[1] >= y0, lambda p, q: (p[0] + (q[0] - p[0]) * (y0 - p[1]) / (q[1] - p[1]), y0)),
            (lambda p: p[1] <= y1, lambda p, q: (p[0] + (q[0] - p[0]) * (y1 - p[1]) / (q[1] - p[1]), y1))):
        out = []
        for i, q in enumerate(poly):
            p = poly[i - 1]
            if inside(q):
                if not inside(p):
                    out.append(cut(p, q))
                out.append(q)
            elif inside(p):
                out.append(cut(p, q))
        poly = out
        if not poly:
            return None
    return poly if len(poly) >= 3 else None


def inside_box(b, w):
    return b[0] >= w[0] and b[1] >= w[1] and b[2] <= w[2] and b[3] <= w[3]


def clip_shape(shape, w):
    subs = []
    for sub, pts in zip(shape.subs, shape.points()):
        xs = [p[0] for p in pts]
        ys = [p[1] for p in pts]
        if inside_box((min(xs), min(ys), max(xs), max(ys)), w):
            subs.append(sub)
            continue
        flat = flatten_sub(sub)
        if sub["closed"] and shape.style["fill"] != "none":
            poly = clip_polygon(flat, w)
            if poly:
                subs.append({"start": poly[0], "segs": [("L", p) for p in poly[1:]], "closed": True})
        else:
            for pc in clip_polyline(flat, w):
                subs.append({"start": pc[0], "segs": [("L", p) for p in pc[1:]], "closed": False})
    return subs


def intersects(b, w):
    return b[2] >= w[0] and b[0] <= w[2] and b[3] >= w[1] and b[1] <= w[3]


def union(boxes):
    return (min(b[0] for b in boxes), min(b[1] for b in boxes),
            max(b[2] for b in boxes), max(b[3] for b in boxes))


def containment_groups(boxes):
    """Groups of boxes around an anchor: each box joins the largest box that holds its centre
    (a highlight joins its bubble, a shading crescent its cell); a box no larger box holds is
    an anchor."""
    area = [(b[2] - b[0]) * (b[3] - b[1]) for b in boxes]
    order = sorted(range(len(boxes)), key=lambda i: -area[i])
    anchor = list(range(len(boxes)))
    for i, b in enumerate(boxes):
        cx, cy = (b[0] + b[2]) / 2, (b[1] + b[3]) / 2
        for j in order:
            if area[j] <= area[i]:
                break
            c = boxes[j]
            if c[0] <= cx <= c[2] and c[1] <= cy <= c[3]:
                anchor[i] = j
                break
    groups = {}
    for i in range(len(boxes)):
        k = i
        while anchor[k] != k:
            k = anchor[k]
        groups.setdefault(k, []).append(i)
    return list(groups.values())


# ---------------------------------------------------------------------------------------------

def extract_svg(name, source, out_dir):
    case = CASES[name]
    w = case["window"]
    tree = ET.parse(source)
    parts = []
    for shape in drawing(tree):
        if shape.style["fill"] == "none" and shape.style["stroke"] == "none":
            continue
        for part in split_compound(shape):
            b = part.bbox()
            if b is not None and all(t(part, b) for t in case["tests"]):
                parts.append((part, b))
    if case["mode"] == "groups":
        keep = set(i for g in containment_groups([b for _, b in parts])
                   if inside_box(union([parts[i][1] for i in g]), w) for i in g)
    elements = []
    for i, (part, b) in enumerate(parts):
        if case["mode"] == "inside" and not inside_box(b, w):
            continue
        if case["mode"] == "groups" and i not in keep:
            continue
        subs = part.subs
        if case["mode"] == "clip":
            if not intersects(b, w):
                continue
            subs = clip_shape(part, w)
            if not subs:
                continue
        elements.append(path_element(part, w[0], w[1], subs))
    count = len(elements)
    md = metadata(tree)
    comment = "%s: from openclipart-svg %s (%s%s), public domain; %s" % (
        name, case["source"][len(OC):], md.get("title", "untitled"),
        ", " + md["creator"] if md.get("creator") else "", case["note"])
    out = os.path.join(out_dir, name + ".svg")
    write_svg(out, w[2] - w[0], w[3] - w[1], elements, comment)
    print("%s: %d paths, %d bytes" % (out, count, os.path.getsize(out)))


def extract_photo(name, source, out_dir):
    from PIL import Image  # needs Pillow

    case = PHOTOS[name]
    im = Image.open(source).convert("RGB").crop(case["box"]).convert("L")
    out = os.path.join(out_dir, name + ".png")
    im.save(out, format="PNG", optimize=False, compress_level=9)
    print("%s: %d × %d px, %d bytes" % (out, im.size[0], im.size[1], os.path.getsize(out)))


def main(argv):
    if argv[1:] == ["--list"]:
        for name, case in CASES.items():
            print(name, "openclipart-svg", case["source"])
        for name, case in PHOTOS.items():
            print(name, case["package"], case["source"])
        return 0
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    name, source, out_dir = argv[1:]
    if name in CASES:
        extract_svg(name, source, out_dir)
    elif name in PHOTOS:
        extract_photo(name, source, out_dir)
    else:
        print("unknown case " + name, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
