"""Flattens an SVG drawing into a list of plain paths (Python 3 standard library only).

Every rendered shape (path, rect, circle, ellipse, line, polyline, polygon, and <use> copies of
them) becomes one `Shape`: its outline as absolute subpaths of line and cubic segments in the
root's user units (every transform applied, arcs and quadratics turned into cubics), with its
resolved, inherited paint (fill, stroke, widths, opacities, dashes). Gradients are replaced by
the colour of their middle stop; clip paths, masks, filters, markers and text are dropped.

Used by extract.py; nothing here depends on a particular drawing.
"""

import math
import re
import xml.etree.ElementTree as ET

SVG_NS = "{http://www.w3.org/2000/svg}"
XLINK_HREF = "{http://www.w3.org/1999/xlink}href"
SHAPES = {"path", "rect", "circle", "ellipse", "line", "polyline", "polygon"}
NOT_RENDERED = {"defs", "clipPath", "mask", "pattern", "symbol", "marker", "metadata",
                "linearGradient", "radialGradient", "filter", "text", "title", "desc",
                "style", "script", "foreignObject", "namedview", "switch"}
# Inherited presentation properties we keep.
INHERITED = ["fill", "fill-opacity", "fill-rule", "stroke", "stroke-width", "stroke-opacity",
             "stroke-dasharray", "stroke-dashoffset", "stroke-linecap", "stroke-linejoin",
             "stroke-miterlimit", "visibility", "color"]
DEFAULTS = {"fill": "#000000", "fill-opacity": "1", "fill-rule": "nonzero", "stroke": "none",
            "stroke-width": "1", "stroke-opacity": "1", "stroke-dasharray": "none",
            "stroke-dashoffset": "0", "stroke-linecap": "butt", "stroke-linejoin": "miter",
            "stroke-miterlimit": "4", "visibility": "visible", "color": "#000000"}

NAMED_COLOURS = {
    "black": "#000000", "white": "#ffffff", "red": "#ff0000", "green": "#008000",
    "blue": "#0000ff", "yellow": "#ffff00", "gray": "#808080", "grey": "#808080",
    "orange": "#ffa500", "brown": "#a52a2a", "navy": "#000080", "purple": "#800080",
    "silver": "#c0c0c0", "maroon": "#800000", "lime": "#00ff00", "olive": "#808000",
    "teal": "#008080", "aqua": "#00ffff", "cyan": "#00ffff", "fuchsia": "#ff00ff",
    "magenta": "#ff00ff", "pink": "#ffc0cb", "gold": "#ffd700", "darkgreen": "#006400",
    "darkred": "#8b0000", "darkblue": "#00008b", "lightgray": "#d3d3d3",
    "lightgrey": "#d3d3d3", "darkgray": "#a9a9a9", "darkgrey": "#a9a9a9",
}


def local(tag):
    return tag.split("}")[-1] if isinstance(tag, str) else ""


# ---------------------------------------------------------------------------------------------
# Affine matrices (a, b, c, d, e, f): x' = a x + c y + e, y' = b x + d y + f.

IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)


def mul(m, n):
    """m · n (n applied first)."""
    a, b, c, d, e, f = m
    a2, b2, c2, d2, e2, f2 = n
    return (a * a2 + c * b2, b * a2 + d * b2, a * c2 + c * d2, b * c2 + d * d2,
            a * e2 + c * f2 + e, b * e2 + d * f2 + f)


def apply(m, p):
    a, b, c, d, e, f = m
    return (a * p[0] + c * p[1] + e, b * p[0] + d * p[1] + f)


NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def parse_transform(text):
    m = IDENTITY
    if not text:
        return m
    for name, args in re.findall(r"(\w+)\s*\(([^)]*)\)", text):
        v = [float(x) for x in re.findall(NUMBER, args)]
        if name == "matrix":
            t = tuple(v)
        elif name == "translate":
            t = (1, 0, 0, 1, v[0], v[1] if len(v) > 1 else 0)
        elif name == "scale":
            t = (v[0], 0, 0, v[1] if len(v) > 1 else v[0], 0, 0)
        elif name == "rotate":
            r = math.radians(v[0])
            t = (math.cos(r), math.sin(r), -math.sin(r), math.cos(r), 0, 0)
            if len(v) == 3:
                t = mul(mul((1, 0, 0, 1, v[1], v[2]), t), (1, 0, 0, 1, -v[1], -v[2]))
        elif name == "skewX":
            t = (1, 0, math.tan(math.radians(v[0])), 1, 0, 0)
        elif name == "skewY":
            t = (1, math.tan(math.radians(v[0])), 0, 1, 0, 0)
        else:
            raise ValueError("unknown transform " + name)
        m = mul(m, t)
    return m


# ---------------------------------------------------------------------------------------------
# Path data → subpaths of segments ("L", p) / ("C", c1, c2, p), each subpath
# {"start": p, "segs": [...], "closed": bool}.

def tokenize(d):
    for cmd, args in re.findall(r"([MmLlHhVvCcSsQqTtAaZz])([^MmLlHhVvCcSsQqTtAaZz]*)", d):
        if cmd in "Aa":
            # Arc flags may be written without separators ("a1 1 0 011 1").
            nums = []
            rest = args
            while True:
                rest = rest.lstrip(" \t\r\n,")
                if not rest:
                    break
                k = len(nums) % 7
                if k in (3, 4):
                    nums.append(float(rest[0]))
                    rest = rest[1:]
                else:
                    mt = re.match(NUMBER, rest)
                    if not mt:
                        raise ValueError("bad arc data: " + args)
                    nums.append(float(mt.group(0)))
                    rest = rest[mt.end():]
        else:
            nums = [float(x) for x in re.findall(NUMBER, args)]
        yield cmd, nums


def arc_to_cubics(p0, rx, ry, phi, large, sweep, p1):
    """SVG endpoint arc → list of cubic segments (SVG 1.1 implementation notes F.6.5)."""
    if p0 == p1:
        return []
    if rx == 0 or ry == 0:
        return [("L", p1)]
    rx, ry = abs(rx), abs(ry)
    cphi, sphi = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    dx, dy = (p0[0] - p1[0]) / 2, (p0[1] - p1[1]) / 2
    x1p, y1p = cphi * dx + sphi * dy, -sphi * dx + cphi * dy
    lam = (x1p / rx) ** 2 + (y1p / ry) ** 2
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    num = rx * rx * ry * ry - rx * rx * y1p * y1p - ry * ry * x1p * x1p
    den = rx * rx * y1p * y1p + ry * ry * x1p * x1p
    coef = math.sqrt(max(0.0, num / den)) if den else 0.0
    if large == sweep:
        coef = -coef
    cxp, cyp = coef * rx * y1p / ry, -coef * ry * x1p / rx
    cx = cphi * cxp - sphi * cyp + (p0[0] + p1[0]) / 2
    cy = sphi * cxp + cphi * cyp + (p0[1] + p1[1]) / 2

    def angle(ux, uy, vx, vy):
        a = math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)
        return a

    t1 = angle(1, 0, (x1p - cxp) / rx, (y1p - cyp) / ry)
    dt = angle((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx, (-y1p - cyp) / ry)
    if not sweep and dt > 0:
        dt -= 2 * math.pi
    elif sweep and dt < 0:
        dt += 2 * math.pi
    n = max(1, int(math.ceil(abs(dt) / (math.pi / 2) - 1e-9)))
    h = dt / n
    k = 4 / 3 * math.tan(h / 4)
    segs = []

    def pt(t):
        x, y = rx * math.cos(t), ry * math.sin(t)
        return (cphi * x - sphi * y + cx, sphi * x + cphi * y + cy)

    def dv(t):
        x, y = -rx * math.sin(t), ry * math.cos(t)
        return (cphi * x - sphi * y, sphi * x + cphi * y)

    t = t1
    for i in range(n):
        a, b = pt(t), pt(t + h)
        da, db = dv(t), dv(t + h)
        end = p1 if i == n - 1 else b
        segs.append(("C", (a[0] + k * da[0], a[1] + k * da[1]),
                     (b[0] - k * db[0], b[1] - k * db[1]), end))
        t += h
    return segs


def parse_path(d):
    subs = []
    cur = None
    pos = (0.0, 0.0)
    start = (0.0, 0.0)
    last_ctrl = None   # for S/s
    last_qctrl = None  # for T/t
    prev = ""

    def new_sub(p):
        nonlocal cur
        cur = {"start": p, "segs": [], "closed": False}
        subs.append(cur)

    def ensure():
        if cur is None or cur["closed"]:
            new_sub(pos)

    for cmd, nums in tokenize(d):
        rel = cmd.islower()
        C = cmd.upper()
        if C == "Z":
            if cur is not None and not cur["closed"]:
                cur["closed"] = True
            pos = start
            last_ctrl = last_qctrl = None
            prev = "Z"
            continue
        arity = {"M": 2, "L": 2, "H": 1, "V": 1, "C": 6, "S": 4, "Q": 4, "T": 2, "A": 7}[C]
        if len(nums) % arity:
            nums = nums[: len(nums) - len(nums) % arity]
        groups = [nums[i:i + arity] for i in range(0, len(nums), arity)]
        for gi, g in enumerate(groups):
            ox, oy = pos if rel else (0.0, 0.0)
            if C == "M" and gi == 0:
                pos = (g[0] + ox, g[1] + oy)
                start = pos
                new_sub(pos)
                last_ctrl = last_qctrl = None
                continue
            ensure()
            if C in "ML":
                p = (g[0] + ox, g[1] + oy)
                cur["segs"].append(("L", p))
                last_ctrl = last_qctrl = None
            elif C == "H":
                p = (g[0] + ox, pos[1])
                cur["segs"].append(("L", p))
                last_ctrl = last_qctrl = None
            elif C == "V":
                p = (pos[0], g[0] + (pos[1] if rel else 0.0))
                cur["segs"].append(("L", p))
                last_ctrl = last_qctrl = None
            elif C == "C":
                c1 = (g[0] + ox, g[1] + oy)
                c2 = (g[2] + ox, g[3] + oy)
                p = (g[4] + ox, g[5] + oy)
                cur["segs"].append(("C", c1, c2, p))
                last_ctrl, last_qctrl = c2, None
            elif C == "S":
                c1 = (2 * pos[0] - last_ctrl[0], 2 * pos[1] - last_ctrl[1]) if last_ctrl else pos
                c2 = (g[0] + ox, g[1] + oy)
                p = (g[2] + ox, g[3] + oy)
                cur["segs"].append(("C", c1, c2, p))
                last_ctrl, last_qctrl = c2, None
            elif C in "QT":
                if C == "Q":
                    q = (g[0] + ox, g[1] + oy)
                    p = (g[2] + ox, g[3] + oy)
                else:
                    q = (2 * pos[0] - last_qctrl[0], 2 * pos[1] - last_qctrl[1]) if last_qctrl else pos
                    p = (g[0] + ox, g[1] + oy)
                c1 = (pos[0] + 2 / 3 * (q[0] - pos[0]), pos[1] + 2 / 3 * (q[1] - pos[1]))
                c2 = (p[0] + 2 / 3 * (q[0] - p[0]), p[1] + 2 / 3 * (q[1] - p[1]))
                cur["segs"].append(("C", c1, c2, p))
                last_ctrl, last_qctrl = None, q
            elif C == "A":
                p = (g[5] + ox, g[6] + oy)
                cur["segs"].extend(arc_to_cubics(pos, g[0], g[1], g[2], int(g[3]), int(g[4]), p))
                last_ctrl = last_qctrl = None
            pos = p
        prev = C
    return [s for s in subs if s["segs"] or s["closed"]]


def transform_subs(subs, m):
    out = []
    for s in subs:
        segs = []
        for seg in s["segs"]:
            segs.append((seg[0],) + tuple(apply(m, p) for p in seg[1:]))
        out.append({"start": apply(m, s["start"]), "segs": segs, "closed": s["closed"]})
    return out


def length(v):
    return float(re.match(NUMBER, v.strip()).group(0)) if v and re.match(NUMBER, v.strip()) else 0.0


def shape_subs(el):
    tag = local(el.tag)
    g = lambda k: length(el.get(k, "0"))
    if tag == "path":
        return parse_path(el.get("d", ""))
    if tag == "rect":
        x, y, w, h = g("x"), g("y"), g("width"), g("height")
        if w <= 0 or h <= 0:
            return []
        rx, ry = el.get("rx"), el.get("ry")
        rx = length(rx) if rx else None
        ry = length(ry) if ry else None
        if rx is None:
            rx = ry
        if ry is None:
            ry = rx
        if not rx:
            return parse_path("M%r,%r H%r V%r H%r Z" % (x, y, x + w, y + h, x))
        rx, ry = min(rx, w / 2), min(ry, h / 2)
        return parse_path(
            "M%r,%r H%r A%r,%r 0 0 1 %r,%r V%r A%r,%r 0 0 1 %r,%r H%r A%r,%r 0 0 1 %r,%r "
            "V%r A%r,%r 0 0 1 %r,%r Z" % (
                x + rx, y, x + w - rx, rx, ry, x + w, y + ry, y + h - ry, rx, ry, x + w - rx,
                y + h, x + rx, rx, ry, x, y + h - ry, y + ry, rx, ry, x + rx, y))
    if tag in ("circle", "ellipse"):
        cx, cy = g("cx"), g("cy")
        if tag == "circle":
            rx = ry = g("r")
        else:
            rx, ry = g("rx"), g("ry")
        if rx <= 0 or ry <= 0:
            return []
        return parse_path("M%r,%r A%r,%r 0 0 1 %r,%r A%r,%r 0 0 1 %r,%r Z" % (
            cx + rx, cy, rx, ry, cx - rx, cy, rx, ry, cx + rx, cy))
    if tag == "line":
        return parse_path("M%r,%r L%r,%r" % (g("x1"), g("y1"), g("x2"), g("y2")))
    if tag in ("polyline", "polygon"):
        v = [float(x) for x in re.findall(NUMBER, el.get("points", ""))]
        if len(v) < 4:
            return []
        d = "M" + " L".join("%r,%r" % (v[i], v[i + 1]) for i in range(0, len(v) - 1, 2))
        return parse_path(d + (" Z" if tag == "polygon" else ""))
    return []


# ---------------------------------------------------------------------------------------------
# Styles.

def own_style(el):
    st = {}
    for k in INHERITED + ["opacity", "display"]:
        if el.get(k) is not None:
            st[k] = el.get(k).strip()
    for decl in (el.get("style") or "").split(";"):
        if ":" in decl:
            k, v = decl.split(":", 1)
            k, v = k.strip(), v.strip()
            if k in INHERITED or k in ("opacity", "display"):
                st[k] = v
    return st


def parse_colour(v, current="#000000"):
    """A paint value → '#rrggbb', 'none', or ('url', id)."""
    v = v.strip()
    if v.startswith("url("):
        ref = re.match(r"url\(\s*#([^)\s]+)\s*\)", v)
        return ("url", ref.group(1)) if ref else "none"
    if v in ("none", ""):
        return "none"
    if v == "currentColor":
        return parse_colour(current)
    if v.startswith("#"):
        h = v[1:]
        if len(h) == 3:
            h = "".join(c * 2 for c in h)
        return "#" + h[:6].lower()
    m = re.match(r"rgb\(\s*([\d.]+)(%?)\s*,\s*([\d.]+)(%?)\s*,\s*([\d.]+)(%?)\s*\)", v)
    if m:
        out = []
        for i in (1, 3, 5):
            x = float(m.group(i))
            if m.group(i + 1):
                x = x * 2.55
            out.append(max(0, min(255, int(round(x)))))
        return "#%02x%02x%02x" % tuple(out)
    if v.lower() in NAMED_COLOURS:
        return NAMED_COLOURS[v.lower()]
    raise ValueError("unknown colour " + v)


class Shape:
    def __init__(self, subs, style, source_id, group_path):
        self.subs = subs
        self.style = style
        self.id = source_id
        self.groups = group_path  # ids of the enclosing groups, outermost first

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
        xs, ys = [], []
        for pts in self.points():
            for x, y in pts:
                xs.append(x)
                ys.append(y)
        if not xs:
            return None
        return (min(xs), min(ys), max(xs), max(ys))


class Drawing:
    def __init__(self, path):
        self.tree = ET.parse(path)
        self.root = self.tree.getroot()
        self.ids = {el.get("id"): el for el in self.root.iter() if el.get("id")}
        self.shapes = []
        self.metadata = self._metadata()
        self._walk(self.root, IDENTITY, dict(DEFAULTS), 1.0, [])

    def _metadata(self):
        md = {}
        for el in self.root.iter():
            t = local(el.tag)
            if t == "Work":
                for ch in el:
                    n = local(ch.tag)
                    if n == "title" and (ch.text or "").strip():
                        md["title"] = ch.text.strip()
                    if n in ("creator", "publisher"):
                        for t2 in ch.iter():
                            if local(t2.tag) == "title" and (t2.text or "").strip():
                                md.setdefault(n, t2.text.strip())
                    if n == "license":
                        md["license"] = ch.get("{http://www.w3.org/1999/02/22-rdf-syntax-ns#}resource", "")
        return md

    def gradient_colour(self, gid, depth=0):
        el = self.ids.get(gid)
        if el is None or depth > 8:
            return "none", 1.0
        stops = [s for s in el if local(s.tag) == "stop"]
        if not stops:
            href = el.get(XLINK_HREF) or el.get("href")
            if href and href.startswith("#"):
                return self.gradient_colour(href[1:], depth + 1)
            return "none", 1.0
        s = stops[len(stops) // 2]
        st = own_style(s)
        for decl in (s.get("style") or "").split(";"):
            if ":" in decl:
                k, v = decl.split(":", 1)
                st[k.strip()] = v.strip()
        col = st.get("stop-color", s.get("stop-color", "#000000"))
        op = float(st.get("stop-opacity", s.get("stop-opacity", "1")))
        return parse_colour(col), op

    def _walk(self, el, m, style, opacity, groups):
        tag = local(el.tag)
        if tag in NOT_RENDERED:
            return
        own = own_style(el)
        if own.get("display") == "none":
            return
        st = dict(style)
        for k in INHERITED:
            if k in own:
                st[k] = own[k]
        op = opacity * float(own.get("opacity", "1"))
        m2 = mul(m, parse_transform(el.get("transform")))
        if tag in ("svg", "g", "a") or el is self.root:
            gp = groups + ([el.get("id")] if el.get("id") and el is not self.root else [])
            for ch in el:
                self._walk(ch, m2, st, op, gp)
        elif tag == "use":
            href = el.get(XLINK_HREF) or el.get("href")
            ref = self.ids.get(href[1:]) if href and href.startswith("#") else None
            if ref is not None:
                m3 = mul(m2, (1, 0, 0, 1, length(el.get("x", "0")), length(el.get("y", "0"))))
                self._walk(ref, m3, st, op, groups)
        elif tag in SHAPES:
            if st.get("visibility") in ("hidden", "collapse"):
                return
            subs = shape_subs(el)
            if not subs:
                return
            self.shapes.append(Shape(transform_subs(subs, m2), self._resolve(st, op, m2),
                                     el.get("id"), groups))

    def _resolve(self, st, op, m):
        out = {}
        cur = st.get("color", "#000000")
        for key in ("fill", "stroke"):
            c = parse_colour(st[key], cur)
            o = float(st[key + "-opacity"]) * op
            if isinstance(c, tuple):
                c, go = self.gradient_colour(c[1])
                o *= go
            out[key] = c
            out[key + "-opacity"] = o
        scale = math.sqrt(abs(m[0] * m[3] - m[1] * m[2]))
        out["stroke-width"] = length(st["stroke-width"]) * scale
        # Paint that draws nothing is no paint.
        if out["stroke-width"] <= 0 or out["stroke-opacity"] <= 0:
            out["stroke"] = "none"
        if out["fill-opacity"] <= 0:
            out["fill"] = "none"
        dash = st["stroke-dasharray"]
        if dash and dash != "none":
            v = [length(x) * scale for x in re.split(r"[\s,]+", dash.strip()) if x]
            out["stroke-dasharray"] = v if any(v) else None
        else:
            out["stroke-dasharray"] = None
        out["stroke-dashoffset"] = length(st["stroke-dashoffset"]) * scale
        for k in ("fill-rule", "stroke-linecap", "stroke-linejoin", "stroke-miterlimit"):
            out[k] = st[k]
        return out


# ---------------------------------------------------------------------------------------------
# Output.

def fmt(x, digits=2):
    s = "%.*f" % (digits, x)
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def path_data(subs, dx=0.0, dy=0.0, digits=2):
    parts = []
    for s in subs:
        p = lambda q: fmt(q[0] - dx, digits) + "," + fmt(q[1] - dy, digits)
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


def path_element(shape, dx=0.0, dy=0.0, subs=None, style_override=None, digits=2):
    st = dict(shape.style)
    if style_override:
        st.update(style_override)
    attrs = ['d="%s"' % path_data(shape.subs if subs is None else subs, dx, dy, digits)]
    attrs.append('fill="%s"' % st["fill"])
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


def split_compound(shape):
    """Splits a path of several subpaths into one Shape per outer subpath, each keeping the
    subpaths that lie inside its box (the holes of a filled shape, the inner lines of a glyph)."""
    if len(shape.subs) < 2:
        return [shape]
    boxes = []
    for s, pts in zip(shape.subs, shape.points()):
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
    return [Shape([shape.subs[i] for i in sorted(g)], shape.style, shape.id, shape.groups)
            for _, g in sorted(groups.items())]
