"""Tests the built playground (web/dist) in a real browser: headless Chromium through Selenium.

Usage: python3 web/test_page.py [--screenshots DIR] [--json FIGURES.json]

Serves web/dist on a free local port, loads the page, and with real input events drags a curve
handle, brushes a stroke on the points canvas, moves the strokes scale slider and synthesizes,
and paints on the stylize guide. Checks that each canvas changed and is not blank, that no panel
shows an error, and that the browser console has no errors; saves a screenshot per step. Prints
the speed figures the page measured (single thread, in the Web Worker). Checks that brush strokes
give the same bits in the page's WebAssembly as natively (`cargo run --example brush`). Exits
non-zero on any failure. Needs Debian's `chromium` and `chromium-driver` and `pip install selenium`.
"""

import argparse
import functools
import http.server
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import threading
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

DIST = pathlib.Path(__file__).resolve().parent / "dist"


def png(width, height, rgb):
    """A fully opaque RGB PNG (no alpha channel)."""
    import struct
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    rows = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


OPAQUE_PNG = png(64, 24, (200, 160, 40))


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *arguments):
        pass


def serve(folder):
    handler = functools.partial(QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = os.environ.get("CHROMIUM", "/usr/bin/chromium")
    for flag in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1400,1800"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver"))
    return webdriver.Chrome(service=service, options=options)


def wait_for(driver, script, timeout, what):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = driver.execute_script(script)
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"timed out after {timeout} s waiting for {what}")


CANVAS_STATE = """
const canvas = document.getElementById(arguments[0]);
const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
let inked = 0, hash = 0;
for (let i = 0; i < data.length; i += 4) {
  if (data[i] < 245 || data[i + 1] < 245 || data[i + 2] < 245) inked++;
  hash = (hash * 31 + data[i] + 7 * data[i + 1] + 13 * data[i + 2]) | 0;
}
return [inked / (data.length / 4), hash];
"""


def canvas_state(driver, canvas):
    return driver.execute_script(CANVAS_STATE, canvas)


def timings(driver, panel):
    return driver.execute_script(f"return window.motifTimings.{panel}.slice()")


def drag(driver, element, start, moves, pause=0.03):
    """Presses at `start` (canvas pixels from its top-left corner) and moves through `moves`."""
    box = driver.execute_script("const b = arguments[0].getBoundingClientRect(); return [b.width, b.height];", element)
    size = driver.execute_script("return [arguments[0].width, arguments[0].height];", element)
    to_offset = lambda p: (p[0] * box[0] / size[0] - box[0] / 2, p[1] * box[1] / size[1] - box[1] / 2)
    chain = ActionChains(driver, duration=10)
    x, y = to_offset(start)
    chain.move_to_element_with_offset(element, int(x), int(y)).click_and_hold()
    for point in moves:
        x, y = to_offset(point)
        chain.move_to_element_with_offset(element, int(x), int(y)).pause(pause)
    chain.release().perform()


def check_panel_ok(driver, panel):
    element = driver.find_element(By.ID, f"{panel}-info")
    assert "error" not in element.get_attribute("class"), f"{panel} shows an error: {element.text}"


# Runs the three strokes of `crates/motif-jobs/examples/brush.rs` on the built-in hex exemplar in
# the page's WebAssembly module (on the main thread, a fresh panel) and returns the FNV-1a digest
# of the result's bits, as the example prints it.
BRUSH_DIGEST_SCRIPT = """
const done = arguments[arguments.length - 1];
(async () => {
  const wasm = await import('./pkg/motif_web.js');
  await wasm.default();
  const panel = new wasm.PointsPanel('hex');
  const ex = panel.exemplar();
  const lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (let i = 0; i < ex.length / 3; i++) for (let a = 0; a < 2; a++) {
    lo[a] = Math.min(lo[a], ex[3 * i + a]); hi[a] = Math.max(hi[a], ex[3 * i + a]);
  }
  const spacing = Math.sqrt((hi[0] - lo[0]) * (hi[1] - lo[1]) / (ex.length / 3));
  const scale = 14.0 / spacing;
  const wave = (x0, y0) => [[x0, y0], ...Array.from({ length: 16 }, (_, j) => [x0 + 25 * (j + 1), y0 + 10 * (-1) ** (j + 1)])];
  const strokes = [wave(60, 90), wave(60, 220), [[120, 40], ...Array.from({ length: 16 }, (_, j) => [120 + 20 * (j + 1), 40 + 15 * (j + 1)])]];
  let result;
  for (const stroke of strokes) {
    const job = { neighbourhood: 2.0 * spacing, domain: { box: [1, 1] }, "max-points": 20000, shrink: 0.6, "patch-candidates": 16, "keep-margin": 2.0 * spacing, "merge-iterations": 6, "window-cutoff": 1.5 };
    result = panel.brush(new Float64Array(stroke.flatMap(([x, y]) => [x / scale, y / scale])), 3.0 * spacing, JSON.stringify(job));
  }
  const bits = new BigUint64Array(new Float64Array(result.points).buffer);
  let digest = 0xcbf29ce484222325n;
  for (const b of bits) digest = ((digest ^ b) * 0x100000001b3n) & 0xffffffffffffffffn;
  done(digest.toString(16).padStart(16, '0'));
})().catch((e) => done('error: ' + e));
"""


# Runs the curve job of `crates/motif-jobs/examples/curve_digest.rs` in the page's WebAssembly
# module on the exemplar bytes the example printed, and returns the FNV-1a digest of the result's
# RGBA bytes, as the example prints it.
CURVE_DIGEST_SCRIPT = """
const [hex, width, height, points, job, done] = arguments;
(async () => {
  const wasm = await import('./pkg/motif_web.js');
  await wasm.default();
  const bytes = new Uint8Array(hex.length / 2);
  for (let i = 0; i < bytes.length; i++) bytes[i] = parseInt(hex.substr(2 * i, 2), 16);
  const panel = new wasm.CurvePanel(bytes, width, height);
  const result = panel.synthesize(new Float64Array(points), job);
  let digest = 0xcbf29ce484222325n;
  for (const b of result.rgba) digest = ((digest ^ BigInt(b)) * 0x100000001b3n) & 0xffffffffffffffffn;
  done(digest.toString(16).padStart(16, '0'));
})().catch((e) => done('error: ' + e));
"""


# Runs the strokes job of `crates/motif-jobs/examples/strokes_digest.rs` in the page's WebAssembly
# module (the built-in `figures` reference into a 300 × 300 square) and returns the FNV-1a digest of
# the output's coordinates and widths, as the example prints it.
STROKES_DIGEST_SCRIPT = """
const [job, done] = arguments;
(async () => {
  const wasm = await import('./pkg/motif_web.js');
  await wasm.default();
  const panel = new wasm.StrokesPanel('figures');
  const result = JSON.parse(panel.synthesize(300, 300, job));
  const values = [];
  for (const stroke of result.strokes) {
    for (const [x, y] of stroke.points) values.push(x, y);
    values.push(stroke.width);
  }
  let digest = 0xcbf29ce484222325n;
  for (const b of new BigUint64Array(new Float64Array(values).buffer)) digest = ((digest ^ b) * 0x100000001b3n) & 0xffffffffffffffffn;
  done(digest.toString(16).padStart(16, '0'));
})().catch((e) => done('error: ' + e));
"""


# Runs the stylize job of `crates/motif-jobs/examples/stylize_digest.rs` in the page's WebAssembly
# module (the built-in map, a rectangle painted with a palette colour, band mode) and returns the
# FNV-1a digest of the result's RGBA bytes, as the example prints it.
STYLIZE_DIGEST_SCRIPT = """
const [side, rectangle, colour, done] = arguments;
(async () => {
  const wasm = await import('./pkg/motif_web.js');
  await wasm.default();
  const panel = new wasm.StylizePanel(side);
  const target = panel.guide();
  const paint = panel.palette().slice(4 * colour, 4 * colour + 4);
  for (let y = rectangle[2]; y < rectangle[3]; y++) for (let x = rectangle[0]; x < rectangle[1]; x++) target.set(paint, 4 * (y * side + x));
  const result = panel.stylize(target, side, side, JSON.stringify({ band: 4 }));
  let digest = 0xcbf29ce484222325n;
  for (const b of result.rgba) digest = ((digest ^ BigInt(b)) * 0x100000001b3n) & 0xffffffffffffffffn;
  done(digest.toString(16).padStart(16, '0'));
})().catch((e) => done('error: ' + e));
"""


def native_example(name, *arguments):
    """The lines a motif-jobs example prints, built and run natively (release)."""
    command = ["cargo", "run", "--release", "--quiet", "-p", "motif-jobs", "--example", name, "--", *arguments]
    return subprocess.run(command, cwd=DIST.parent.parent, check=True, capture_output=True, text=True).stdout.strip().splitlines()


def native_stylize_run():
    """The stylize example's map side, painted rectangle, colour and result digest, run natively."""
    output = native_example("stylize_digest")
    words = output[0].replace("[", "").replace("]", "").replace(",", "").split()
    return {
        "side": int(words[1]), "rectangle": [int(v) for v in words[3:7]], "colour": int(words[8]),
        "digest": output[-1].split("digest ")[1],
    }


def native_strokes_run():
    """The strokes example's job and result digest, built and run natively."""
    output = native_example("strokes_digest")
    return {"job": output[0].split(" ", 1)[1], "digest": output[-1].split("digest ")[1]}


def native_curve_run():
    """The curve example's exemplar, polyline, job and result digest, built and run natively."""
    output = native_example("curve_digest")
    lines = dict(line.split(" ", 1) for line in output[:3])
    width, height, hex_bytes = lines["exemplar"].split(" ")
    return {
        "hex": hex_bytes, "width": int(width), "height": int(height),
        "points": json.loads(lines["points"]), "job": lines["job"],
        "digest": output[-1].split("digest ")[1],
    }


def native_brush_digest():
    """The digest the brush example prints for the same strokes, built and run natively."""
    return native_example("brush", "2", '"merge-iterations": 6, "window-cutoff": 1.5')[-1].split("digest ")[1]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--screenshots", default=None)
    parser.add_argument("--json", default=None)
    arguments = parser.parse_args()
    if not (DIST / "index.html").is_file():
        sys.exit("web/dist is not built: run web/build.sh first")
    shots = pathlib.Path(arguments.screenshots or tempfile.mkdtemp(prefix="motif-web-"))
    shots.mkdir(parents=True, exist_ok=True)
    server = serve(DIST)
    driver = browser()
    figures = {}
    try:
        driver.get(f"http://127.0.0.1:{server.server_address[1]}/index.html")
        wait_for(driver, "return document.getElementById('status').textContent === 'ready'", 180, "the page to be ready")
        driver.save_screenshot(str(shots / "1-ready.png"))
        for panel in ("curve", "points", "strokes", "stylize"):
            check_panel_ok(driver, panel)
        # Controls bound to declared options carry the declaration's help, and keep in its range.
        declared = driver.execute_script(
            "return [...document.querySelectorAll('[data-option]')].map(c => [c.dataset.option, c.title, Number(c.min)])"
        )
        assert len(declared) == 3 and all(title for _, title, _ in declared), declared
        band = next(d for d in declared if d[0] == "stylize/band")
        assert "band" in band[1].lower() and band[2] >= 0, band

        # Curve: about 50 pieces (piece length 14 on this curve), then drag the middle handle.
        driver.execute_script("const s = document.getElementById('curve-piece'); s.value = 14; s.dispatchEvent(new Event('input'));")
        wait_for(driver, "return window.motifTimings.curve.some(t => t.pieces >= 45)", 60, "a curve of about 50 pieces")
        before = canvas_state(driver, "curve-canvas")
        count = len(timings(driver, "curve"))
        canvas = driver.find_element(By.ID, "curve-canvas")
        drag(driver, canvas, (320, 250), [(320, 250 - 8 * k) for k in range(1, 16)])
        wait_for(driver, f"return window.motifTimings.curve.length > {count}", 60, "the curve to re-synthesize")
        time.sleep(1.0)
        after = canvas_state(driver, "curve-canvas")
        assert after[0] > 0.03 and after[1] != before[1], f"curve canvas {before} → {after}"
        check_panel_ok(driver, "curve")
        edits = [t for t in timings(driver, "curve")[count:] if t["pieces"] >= 45]
        figures["curve_edit_ms"] = {
            "edits": len(edits),
            "pieces": edits[-1]["pieces"] if edits else None,
            "engine_median": statistics.median(t["engine_ms"] for t in edits),
            "redraw_median": statistics.median(t["total_ms"] for t in edits),
            "redraw_max": max(t["total_ms"] for t in edits),
        }
        driver.save_screenshot(str(shots / "2-curve-dragged.png"))

        # Points: brush strokes across the canvas.
        canvas = driver.find_element(By.ID, "points-canvas")
        before = canvas_state(driver, "points-canvas")
        # Two long strokes (about 100 new points each), then one crossing both.
        strokes = [
            ((60, 90), [(60 + 25 * k, 90 + 10 * ((-1) ** k)) for k in range(1, 17)]),
            ((60, 220), [(60 + 25 * k, 220 + 10 * ((-1) ** k)) for k in range(1, 17)]),
            ((120, 40), [(120 + 20 * k, 40 + 15 * k) for k in range(1, 17)]),
        ]
        for start, moves in strokes:
            count = len(timings(driver, "points"))
            drag(driver, canvas, start, moves, pause=0.01)
            wait_for(driver, f"return window.motifTimings.points.length > {count}", 60, "the brush stroke to grow points")
        after = canvas_state(driver, "points-canvas")
        assert after[0] > 0.01 and after[1] != before[1], f"points canvas {before} → {after}"
        check_panel_ok(driver, "points")
        brushes = timings(driver, "points")
        figures["points_brush"] = [
            {"added": t["added"], "engine_ms": round(t["engine_ms"], 1), "updates_per_second_per_100": round(1000 / max(t["engine_ms"], 1e-3) * t["added"] / 100, 1)}
            for t in brushes
        ]
        driver.save_screenshot(str(shots / "3-points-brushed.png"))

        # Strokes: the first analysis is at the ε inferred from the reference; move the scale
        # slider (the analysis follows), then synthesize.
        wait_for(driver, "return /\\(inferred\\)/.test(document.getElementById('strokes-info').textContent)", 30, "the analysis at the inferred scale")
        before = canvas_state(driver, "strokes-output")
        count = len(timings(driver, "strokes"))
        slider = driver.find_element(By.ID, "strokes-scale")
        ActionChains(driver).click_and_hold(slider).move_by_offset(40, 0).pause(0.2).move_by_offset(-20, 0).release().perform()
        wait_for(driver, f"return window.motifTimings.strokes.length > {count}", 30, "a new analysis")
        driver.find_element(By.ID, "strokes-run").click()
        wait_for(driver, "return window.motifTimings.strokes.some(t => t.kind === 'synthesis')", 60, "the strokes synthesis")
        after = canvas_state(driver, "strokes-output")
        assert after[0] > 0.005 and after[1] != before[1], f"strokes output {before} → {after}"
        check_panel_ok(driver, "strokes")
        analyses = [t for t in timings(driver, "strokes") if t["kind"] == "analysis"]
        figures["strokes_analysis_ms"] = {"count": len(analyses), "median": statistics.median(t["engine_ms"] for t in analyses), "max": max(t["engine_ms"] for t in analyses)}

        # Stylize: paint on the target guide; the band re-synthesis updates the output.
        before = canvas_state(driver, "stylize-output")
        count = len(timings(driver, "stylize"))
        canvas = driver.find_element(By.ID, "stylize-guide")
        drag(driver, canvas, (40, 96), [(40 + 10 * k, 96) for k in range(1, 12)], pause=0.01)
        wait_for(driver, f"return window.motifTimings.stylize.length > {count}", 120, "the band re-stylization")
        after = canvas_state(driver, "stylize-output")
        assert after[0] > 0.2 and after[1] != before[1], f"stylize output {before} → {after}"
        check_panel_ok(driver, "stylize")
        figures["stylize_band_ms"] = [round(t["engine_ms"], 1) for t in timings(driver, "stylize")]
        driver.save_screenshot(str(shots / "4-all-panels.png"))

        # Bad input shows a message in the page and leaves the worker alive.
        files = pathlib.Path(tempfile.mkdtemp(prefix="motif-web-input-"))
        opaque = files / "opaque.png"
        opaque.write_bytes(OPAQUE_PNG)
        (files / "notes.svg").write_text("these are notes, not a drawing")
        with open(files / "huge.png", "wb") as handle:
            handle.truncate(25 * 1024 * 1024)
        for panel, field, path, message in (
            ("curve", "curve-file", opaque, "transparent"),
            ("curve", "curve-file", files / "huge.png", "MB"),
            ("strokes", "strokes-file", files / "notes.svg", "not an SVG"),
        ):
            driver.execute_script(f"document.getElementById('{panel}-info').textContent = ''")
            driver.find_element(By.ID, field).send_keys(str(path))
            text = wait_for(driver, f"const e = document.getElementById('{panel}-info'); return e.className.includes('error') && e.textContent", 30, f"the {panel} panel to refuse {path.name}")
            assert message in text, f"{path.name}: {text}"
        count = len(timings(driver, "curve"))
        driver.execute_script("const s = document.getElementById('curve-exemplar'); s.value = 'exemplars/rope.png'; s.dispatchEvent(new Event('change'));")
        wait_for(driver, f"return window.motifTimings.curve.length > {count}", 60, "the worker to synthesize again after bad input")
        check_panel_ok(driver, "curve")
        driver.save_screenshot(str(shots / "5-after-bad-input.png"))
        # A real SVG drawing (a glyph outline) loads as the strokes reference.
        driver.find_element(By.ID, "strokes-file").send_keys(str(DIST.parent.parent / "data" / "real" / "curve" / "letter_s.svg"))
        wait_for(driver, "return /elements at/.test(document.getElementById('strokes-info').textContent)", 30, "the SVG reference's analysis")
        check_panel_ok(driver, "strokes")

        # The same strokes give the same bits in the browser as natively (the brush example).
        browser_digest = driver.execute_async_script(BRUSH_DIGEST_SCRIPT)
        native_digest = native_brush_digest()
        assert browser_digest == native_digest, f"points brush: browser {browser_digest}, native {native_digest}"
        figures["points_brush_digest"] = browser_digest
        # The same for a curve: a generated chain strip along a bent polyline.
        curve_run = native_curve_run()
        browser_digest = driver.execute_async_script(
            CURVE_DIGEST_SCRIPT, curve_run["hex"], curve_run["width"], curve_run["height"], curve_run["points"], curve_run["job"]
        )
        assert browser_digest == curve_run["digest"], f"curve: browser {browser_digest}, native {curve_run['digest']}"
        figures["curve_digest"] = browser_digest
        # And for strokes: the built-in figures synthesized into a square.
        strokes_run = native_strokes_run()
        browser_digest = driver.execute_async_script(STROKES_DIGEST_SCRIPT, strokes_run["job"])
        assert browser_digest == strokes_run["digest"], f"strokes: browser {browser_digest}, native {strokes_run['digest']}"
        figures["strokes_digest"] = browser_digest
        # And for stylize: a painted target guide re-stylized in band mode.
        stylize_run = native_stylize_run()
        browser_digest = driver.execute_async_script(
            STYLIZE_DIGEST_SCRIPT, stylize_run["side"], stylize_run["rectangle"], stylize_run["colour"]
        )
        assert browser_digest == stylize_run["digest"], f"stylize: browser {browser_digest}, native {stylize_run['digest']}"
        figures["stylize_digest"] = browser_digest

        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        assert not errors, f"browser console errors: {errors}"
    finally:
        driver.quit()
        server.shutdown()
    print(json.dumps(figures, indent=2))
    if arguments.json:
        pathlib.Path(arguments.json).write_text(json.dumps(figures, indent=2))
    print(f"web page test passed; screenshots in {shots}")


if __name__ == "__main__":
    main()
