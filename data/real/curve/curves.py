"""Writes the curves of the curve corpus (SVG paths and a CSV polyline), in canvas pixels.

    python curves.py OUT_DIR FLOURISH.svg HEART.svg FONT.ttf RHINE_LONLAT.csv

Sources (build.sh fetches them) and outputs:
  FLOURISH.svg      openclipart "Flourish One, Horizontal" (Nathan Eady): one hand-drawn stroked
                    path of 9 cubic Béziers -> flourish.svg (segments 1-5, x 1.2) and
                    flourish_sweep.svg (segment 3, x 0.8).
  HEART.svg         openclipart "Heart" (Jon Phillips): one closed path with a cusp at the top
                    -> heart.svg (x 1).
  FONT.ttf          DejaVu Sans Bold (fonts-dejavu-core) -> letter_s.svg, the outline of S.
  RHINE_LONLAT.csv  the Rhine of mapdata's `rivers` database, lon,lat (written by rhine.R)
                    -> rhine.csv, Basel to the delta, projected, smoothed and thinned.

Every output is scaled uniformly (never distorted) and translated so that the curve's bounding
box starts at MARGIN pixels from the origin; y points down as on screen. Numbers are written with
two decimals (SVG) or three (CSV), so the files are the same on every platform.
"""

import csv
import math
import re
import sys
from pathlib import Path

MARGIN = 40.0

# ---------------------------------------------------------------------------------------------
# A tiny SVG path reader: absolute and relative M, L, H, V, C, S, Q, T, Z (no arcs).
# A path is a list of subpaths; a subpath is (start point, [segments], closed), a segment is
# ("L", p) or ("C", c1, c2, p) or ("Q", c, p).


def parse_path(d: str):
    tokens = re.findall(r"[MmLlHhVvCcSsQqTtZz]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", d)
    subpaths = []
    i = 0
    cmd = None
    cur = (0.0, 0.0)
    start = cur
    last_ctrl = None
    segs = None

    def num():
        nonlocal i
        v = float(tokens[i])
        i += 1
        return v

    while i < len(tokens):
        t = tokens[i]
        if re.fullmatch(r"[A-Za-z]", t):
            cmd = t
            i += 1
            if cmd in "Zz":
                if segs is not None:
                    subpaths[-1] = (subpaths[-1][0], segs, True)
                cur = start
                segs = None
                continue
        rel = cmd.islower()
        c = cmd.upper()
        ox, oy = cur if rel else (0.0, 0.0)
        if c == "M":
            cur = (ox + num(), oy + num())
            start = cur
            segs = []
            subpaths.append((cur, segs, False))
            cmd = "l" if rel else "L"
            last_ctrl = None
            continue
        if segs is None:  # drawing after Z without M starts at the previous start
            segs = []
            subpaths.append((cur, segs, False))
        if c == "L":
            p = (ox + num(), oy + num())
            segs.append(("L", p))
            last_ctrl = None
        elif c == "H":
            p = ((ox if rel else 0.0) + num(), cur[1])
            segs.append(("L", p))
            last_ctrl = None
        elif c == "V":
            p = (cur[0], (oy if rel else 0.0) + num())
            segs.append(("L", p))
            last_ctrl = None
        elif c == "C":
            c1 = (ox + num(), oy + num())
            c2 = (ox + num(), oy + num())
            p = (ox + num(), oy + num())
            segs.append(("C", c1, c2, p))
            last_ctrl = c2
        elif c == "S":
            c1 = (2 * cur[0] - last_ctrl[0], 2 * cur[1] - last_ctrl[1]) if last_ctrl else cur
            c2 = (ox + num(), oy + num())
            p = (ox + num(), oy + num())
            segs.append(("C", c1, c2, p))
            last_ctrl = c2
        elif c == "Q":
            q = (ox + num(), oy + num())
            p = (ox + num(), oy + num())
            segs.append(("Q", q, p))
            last_ctrl = q
        elif c == "T":
            q = (2 * cur[0] - last_ctrl[0], 2 * cur[1] - last_ctrl[1]) if last_ctrl else cur
            p = (ox + num(), oy + num())
            segs.append(("Q", q, p))
            last_ctrl = q
        else:
            raise ValueError(f"unsupported path command {cmd}")
        cur = p
    return subpaths


def first_path_d(svg_file: Path) -> str:
    text = svg_file.read_text(encoding="utf-8")
    m = re.search(r"<path\b[^>]*?\sd=\"([^\"]*)\"", text, re.S)
    if not m:
        raise ValueError(f"{svg_file}: no <path d=...>")
    return m.group(1)


def points_of(subpath):
    start, segs, _ = subpath
    pts = [start]
    for s in segs:
        pts.extend(s[1:])
    return pts


def transform(subpath, f):
    start, segs, closed = subpath
    return (f(start), [(s[0],) + tuple(f(p) for p in s[1:]) for s in segs], closed)


def fit(subpath, scale: float):
    """Scales by `scale` and moves the bounding box of all points (control points included) to MARGIN."""
    pts = points_of(subpath)
    x0 = min(p[0] for p in pts)
    y0 = min(p[1] for p in pts)
    moved = transform(subpath, lambda p: ((p[0] - x0) * scale + MARGIN, (p[1] - y0) * scale + MARGIN))
    pts = points_of(moved)
    return moved, max(p[0] for p in pts) + MARGIN, max(p[1] for p in pts) + MARGIN


def fmt(v: float) -> str:
    s = f"{v:.2f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def path_d(subpath) -> str:
    start, segs, closed = subpath
    out = [f"M {fmt(start[0])},{fmt(start[1])}"]
    for s in segs:
        out.append(s[0] + " " + " ".join(f"{fmt(p[0])},{fmt(p[1])}" for p in s[1:]))
    if closed:
        out.append("Z")
    return " ".join(out)


def write_svg(path: Path, subpath, width: float, height: float, title: str) -> None:
    w, h = math.ceil(width), math.ceil(height)
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">\n'
        f"  <title>{title}</title>\n"
        f'  <path d="{path_d(subpath)}" fill="none" stroke="black" stroke-width="2"/>\n'
        "</svg>\n",
        encoding="utf-8",
    )


# ---------------------------------------------------------------------------------------------


def flourish(src: Path, out: Path, name: str, first: int, last: int, scale: float) -> None:
    """Cubic segments first..last (1-based, inclusive) of the 9 of the hand-drawn flourish."""
    sub = parse_path(first_path_d(src))[0]
    segs = sub[1]
    start = sub[0] if first == 1 else segs[first - 2][-1]
    sub = (start, segs[first - 1 : last], False)
    sub, w, h = fit(sub, scale)
    write_svg(
        out / f"{name}.svg", sub, w, h,
        f"openclipart Flourish One, Horizontal (Nathan Eady), cubic segments {first}-{last} of 9",
    )


def heart(src: Path, out: Path, name: str, scale: float) -> None:
    sub = parse_path(first_path_d(src))[0]
    sub, w, h = fit(sub, scale)
    write_svg(out / f"{name}.svg", sub, w, h, "openclipart Heart (Jon Phillips)")


def glyph(font: Path, char: str, out: Path, name: str, height_px: float) -> None:
    from fontTools.pens.recordingPen import RecordingPen
    from fontTools.ttLib import TTFont

    f = TTFont(str(font))
    gs = f.getGlyphSet()
    gname = f.getBestCmap()[ord(char)]
    pen = RecordingPen()
    gs[gname].draw(pen)
    # First contour only; quadratic splines (qCurveTo with implied on-curve points) become Q.
    start = None
    segs = []
    closed = False
    cur = None
    for op, args in pen.value:
        if op == "moveTo":
            if start is not None:
                break
            start = args[0]
            cur = start
        elif op == "lineTo":
            segs.append(("L", args[0]))
            cur = args[0]
        elif op == "qCurveTo":
            offs = list(args[:-1])
            on = args[-1]
            for k, q in enumerate(offs):
                p = on if k == len(offs) - 1 else ((q[0] + offs[k + 1][0]) / 2, (q[1] + offs[k + 1][1]) / 2)
                segs.append(("Q", q, p))
            cur = on
        elif op == "curveTo":
            segs.append(("C",) + tuple(args))
            cur = args[-1]
        elif op in ("closePath", "endPath"):
            closed = op == "closePath"
            break
    # Drop a closing line back to the start (Z draws it).
    if closed and segs and segs[-1][0] == "L" and segs[-1][1] == start:
        segs.pop()
    sub = (start, segs, closed)
    ascent = max(p[1] for p in points_of(sub)) - min(p[1] for p in points_of(sub))
    sub = transform(sub, lambda p: (p[0], -p[1]))  # font y up -> screen y down
    sub, w, h = fit(sub, height_px / ascent)
    write_svg(out / f"{name}.svg", sub, w, h, f"DejaVu Sans Bold, glyph {char!r}, first contour")


def simplify(pts, tol: float):
    """Ramer-Douglas-Peucker: keeps the end points and every point farther than `tol` from the chord."""
    keep = [False] * len(pts)
    keep[0] = keep[-1] = True
    stack = [(0, len(pts) - 1)]
    while stack:
        a, b = stack.pop()
        (ax, ay), (bx, by) = pts[a], pts[b]
        dx, dy = bx - ax, by - ay
        n = math.hypot(dx, dy)
        best, far = -1.0, -1
        for i in range(a + 1, b):
            px, py = pts[i]
            d = abs(dx * (py - ay) - dy * (px - ax)) / n if n > 0 else math.hypot(px - ax, py - ay)
            if d > best:
                best, far = d, i
        if far >= 0 and best > tol:
            keep[far] = True
            stack.extend([(a, far), (far, b)])
    return [p for p, k in zip(pts, keep) if k]


def smooth(pts, spacing: float, sigma: float):
    """Resamples the polyline every `spacing` px of arc length and convolves x and y with a Gaussian
    of standard deviation `sigma` px of arc length; near the ends the polyline is extended by point
    reflection through the end point, so the end points stay where they are."""
    cum = [0.0]
    for a, b in zip(pts, pts[1:]):
        cum.append(cum[-1] + math.dist(a, b))
    n = max(2, int(round(cum[-1] / spacing)) + 1)
    res = []
    j = 0
    for i in range(n):
        t = cum[-1] * i / (n - 1)
        while j < len(pts) - 2 and cum[j + 1] < t:
            j += 1
        seg = cum[j + 1] - cum[j]
        f = (t - cum[j]) / seg if seg > 0 else 0.0
        res.append((pts[j][0] + f * (pts[j + 1][0] - pts[j][0]), pts[j][1] + f * (pts[j + 1][1] - pts[j][1])))
    r = int(math.ceil(3 * sigma / (cum[-1] / (n - 1))))
    w = [math.exp(-0.5 * (k * (cum[-1] / (n - 1)) / sigma) ** 2) for k in range(-r, r + 1)]
    ws = sum(w)

    def at(i):
        if i < 0:
            return (2 * res[0][0] - res[-i][0], 2 * res[0][1] - res[-i][1])
        if i >= n:
            k = 2 * (n - 1) - i
            return (2 * res[-1][0] - res[k][0], 2 * res[-1][1] - res[k][1])
        return res[i]

    out = []
    for i in range(n):
        x = sum(w[k + r] * at(i + k)[0] for k in range(-r, r + 1)) / ws
        y = sum(w[k + r] * at(i + k)[1] for k in range(-r, r + 1)) / ws
        out.append((x, y))
    return out


def rhine(src: Path, out: Path, name: str, first: int, extent: float, sigma: float, tol: float) -> None:
    """Points from index `first` on, in an equirectangular projection about their mean latitude
    (x = lon cos(lat0), y = -lat: north up), scaled to `extent` px along the longer side, smoothed
    along the arc length by a Gaussian of `sigma` px (see smooth) and thinned by
    Ramer-Douglas-Peucker with tolerance `tol` px."""
    rows = [(float(r["lon"]), float(r["lat"])) for r in csv.DictReader(src.open())][first:]
    lat0 = sum(p[1] for p in rows) / len(rows)
    k = math.cos(math.radians(lat0))
    xs = [p[0] * k for p in rows]
    ys = [-p[1] for p in rows]
    s = extent / max(max(xs) - min(xs), max(ys) - min(ys))
    pts = [(x * s, y * s) for x, y in zip(xs, ys)]
    if sigma > 0:
        pts = smooth(pts, 1.0, sigma)
    if tol > 0:
        pts = simplify(pts, tol)
    x0 = min(p[0] for p in pts)
    y0 = min(p[1] for p in pts)
    kept = [(x - x0 + MARGIN, y - y0 + MARGIN) for x, y in pts]
    with (out / f"{name}.csv").open("w", newline="") as fh:
        fh.write("x,y\n")
        for x, y in kept:
            fh.write(f"{x:.3f},{y:.3f}\n")
    print(f"{name}.csv: {len(kept)} points, 1 px = {111.32 / s:.3f} km")


RHINE_FIRST = 38  # Basel (7.583 E, 47.567 N): the Rhine from Basel to the delta
RHINE_SIGMA = 12.0
RHINE_TOLERANCE = 0.25


def main() -> None:
    out = Path(sys.argv[1])
    flourish(Path(sys.argv[2]), out, "flourish", 1, 5, 1.2)
    flourish(Path(sys.argv[2]), out, "flourish_sweep", 3, 3, 0.8)
    heart(Path(sys.argv[3]), out, "heart", 1.0)
    glyph(Path(sys.argv[4]), "S", out, "letter_s", 360.0)
    rhine(Path(sys.argv[5]), out, "rhine", RHINE_FIRST, 860.0, RHINE_SIGMA, RHINE_TOLERANCE)


if __name__ == "__main__":
    main()
