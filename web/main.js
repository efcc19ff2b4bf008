// The playground page: canvases, input events and drawing. All synthesis runs in worker.js.

const worker = new Worker("./worker.js", { type: "module" });
let nextId = 1;
const waiting = new Map();
worker.onmessage = (event) => {
  const { id, ok, value, error } = event.data;
  const pending = waiting.get(id);
  waiting.delete(id);
  if (ok) pending.resolve(value);
  else pending.reject(new Error(error));
};
worker.onerror = (event) => setStatus(`worker error: ${event.message}`, true);

function request(method, args = {}, transfer = []) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    waiting.set(id, { resolve, reject });
    worker.postMessage({ id, method, args }, transfer);
  });
}

// Runs at most one request of a kind at a time; while one runs, only the latest call waits.
function latestOnly(run) {
  let busy = false;
  let queued = null;
  return async function schedule(...args) {
    if (busy) {
      queued = args;
      return;
    }
    busy = true;
    try {
      await run(...args);
    } finally {
      busy = false;
      if (queued) {
        const again = queued;
        queued = null;
        schedule(...again);
      }
    }
  };
}

const $ = (id) => document.getElementById(id);
function setStatus(text, isError = false) {
  $("status").textContent = text;
  $("status").className = isError ? "error" : "";
}
function info(panel, text, isError = false) {
  const element = $(`${panel}-info`);
  element.textContent = text;
  element.className = isError ? "info error" : "info";
}
// The page's own log of figures, read by the browser test (web/test_page.py).
window.motifTimings = { curve: [], points: [], strokes: [], stylize: [] };

function putImage(canvas, rgba, width, height, background = "#fff") {
  const context = canvas.getContext("2d");
  context.fillStyle = background;
  context.fillRect(0, 0, canvas.width, canvas.height);
  const image = new ImageData(new Uint8ClampedArray(rgba), width, height);
  const bitmapCanvas = new OffscreenCanvas(width, height);
  bitmapCanvas.getContext("2d").putImageData(image, 0, 0);
  const scale = Math.min(canvas.width / width, canvas.height / height, 1);
  context.drawImage(bitmapCanvas, 0, 0, width * scale, height * scale);
}

async function decodePng(blob) {
  if (blob.size > 20 * 1024 * 1024) throw new Error(`the file is ${(blob.size / 1048576).toFixed(0)} MB; give an image under 20 MB`);
  let bitmap;
  try {
    bitmap = await createImageBitmap(blob);
  } catch {
    throw new Error("the file is not an image the browser can decode (give a PNG)");
  }
  const { maxImageSide } = await request("limits");
  if (bitmap.width > maxImageSide || bitmap.height > maxImageSide) throw new Error(`the image is ${bitmap.width}×${bitmap.height}; give at most ${maxImageSide} pixels a side`);
  const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
  const context = canvas.getContext("2d");
  context.drawImage(bitmap, 0, 0);
  const data = context.getImageData(0, 0, bitmap.width, bitmap.height).data;
  return { rgba: data.buffer, width: bitmap.width, height: bitmap.height };
}

// ---------------------------------------------------------------- curve
const curve = {
  canvas: $("curve-canvas"),
  handles: [[60, 250], [190, 110], [320, 250], [450, 110], [580, 240]],
  dragging: -1,
  image: null,
};

function catmullRom(points, closed, perSegment = 12) {
  const list = closed ? [...points, points[0]] : points;
  const at = (i) => (closed ? points[(i + points.length) % points.length] : list[Math.max(0, Math.min(list.length - 1, i))]);
  const out = [];
  for (let i = 0; i < list.length - 1; i++) {
    const [p0, p1, p2, p3] = [at(i - 1), at(i), at(i + 1), at(i + 2)];
    for (let s = 0; s < perSegment; s++) {
      const t = s / perSegment;
      const t2 = t * t, t3 = t2 * t;
      out.push(
        0.5 * (2 * p1[0] + (-p0[0] + p2[0]) * t + (2 * p0[0] - 5 * p1[0] + 4 * p2[0] - p3[0]) * t2 + (-p0[0] + 3 * p1[0] - 3 * p2[0] + p3[0]) * t3),
        0.5 * (2 * p1[1] + (-p0[1] + p2[1]) * t + (2 * p0[1] - 5 * p1[1] + 4 * p2[1] - p3[1]) * t2 + (-p0[1] + 3 * p1[1] - 3 * p2[1] + p3[1]) * t3),
      );
    }
  }
  const last = closed ? list[0] : list[list.length - 1];
  out.push(last[0], last[1]);
  return out;
}

function drawCurve() {
  const context = curve.canvas.getContext("2d");
  context.fillStyle = "#fff";
  context.fillRect(0, 0, curve.canvas.width, curve.canvas.height);
  if (curve.image) context.drawImage(curve.image, -curve.origin[0], -curve.origin[1]);
  context.fillStyle = "rgba(30, 90, 200, 0.7)";
  for (const [x, y] of curve.handles) {
    context.beginPath();
    context.arc(x, y, 7, 0, 2 * Math.PI);
    context.fill();
  }
}

const synthesizeCurve = latestOnly(async () => {
  const width = Number($("curve-width").value);
  const job = { width, "piece-length": Number($("curve-piece").value), canvas: [curve.canvas.width, curve.canvas.height], samples: 1 };
  const points = catmullRom(curve.handles, $("curve-closed").checked);
  const start = performance.now();
  try {
    const result = await request("curveSynthesize", { points, job });
    const bitmap = new OffscreenCanvas(result.width, result.height);
    bitmap.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(result.rgba), result.width, result.height), 0, 0);
    curve.image = bitmap;
    curve.origin = [0, 0];
    drawCurve();
    const total = performance.now() - start;
    window.motifTimings.curve.push({ engine_ms: result.ms, total_ms: total, pieces: result.report.pieces });
    const warnings = (result.report.warnings || []).join("; ");
    info("curve", `${result.report.pieces} pieces in ${result.ms.toFixed(0)} ms (redraw ${total.toFixed(0)} ms)${warnings ? " — " + warnings : ""}`);
  } catch (error) {
    info("curve", error.message, true);
    drawCurve();
  }
});

async function loadCurveExemplar(blobPromise) {
  try {
    const decoded = await decodePng(await blobPromise);
    await request("curveExemplar", decoded, [decoded.rgba]);
    synthesizeCurve();
  } catch (error) {
    info("curve", error.message, true);
  }
}

function canvasPoint(canvas, event) {
  const box = canvas.getBoundingClientRect();
  return [((event.clientX - box.left) * canvas.width) / box.width, ((event.clientY - box.top) * canvas.height) / box.height];
}

curve.canvas.addEventListener("pointerdown", (event) => {
  const [x, y] = canvasPoint(curve.canvas, event);
  curve.dragging = curve.handles.findIndex(([hx, hy]) => Math.hypot(hx - x, hy - y) < 14);
  if (curve.dragging >= 0) curve.canvas.setPointerCapture(event.pointerId);
});
curve.canvas.addEventListener("pointermove", (event) => {
  if (curve.dragging < 0) return;
  curve.handles[curve.dragging] = canvasPoint(curve.canvas, event);
  drawCurve();
  synthesizeCurve();
});
curve.canvas.addEventListener("pointerup", () => (curve.dragging = -1));
for (const id of ["curve-width", "curve-piece"]) {
  $(id).addEventListener("input", () => {
    $(`${id}-value`).textContent = $(id).value;
    synthesizeCurve();
  });
}
$("curve-closed").addEventListener("change", () => synthesizeCurve());
$("curve-exemplar").addEventListener("change", () => loadCurveExemplar(fetch($("curve-exemplar").value).then((r) => r.blob())));
$("curve-file").addEventListener("change", () => {
  const file = $("curve-file").files[0];
  if (file) loadCurveExemplar(Promise.resolve(file));
});

// ---------------------------------------------------------------- points
const points = { canvas: $("points-canvas"), stroke: null, shown: [], exemplar: [], scale: 16 };

function drawPoints() {
  const context = points.canvas.getContext("2d");
  context.fillStyle = "#fff";
  context.fillRect(0, 0, points.canvas.width, points.canvas.height);
  const colour = (a) => `hsl(${(a * 67) % 360}, 65%, 40%)`;
  for (let i = 0; i < points.shown.length; i += 3) {
    context.fillStyle = colour(points.shown[i + 2]);
    context.beginPath();
    context.arc(points.shown[i] * points.scale, points.shown[i + 1] * points.scale, 3, 0, 2 * Math.PI);
    context.fill();
  }
  if (points.stroke) {
    context.strokeStyle = "rgba(200, 60, 30, 0.5)";
    context.lineWidth = Number($("points-width").value) * points.scale;
    context.lineCap = "round";
    context.beginPath();
    points.stroke.forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
    context.stroke();
  }
}

async function startPoints() {
  const { exemplar } = await request("pointsStart", { exemplar: $("points-exemplar").value });
  points.exemplar = exemplar;
  // About 14 pixels between neighbours, whatever the exemplar's units.
  let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
  for (let i = 0; i < exemplar.length; i += 3) {
    minX = Math.min(minX, exemplar[i]); maxX = Math.max(maxX, exemplar[i]);
    minY = Math.min(minY, exemplar[i + 1]); maxY = Math.max(maxY, exemplar[i + 1]);
  }
  points.spacing = Math.sqrt(((maxX - minX) * (maxY - minY)) / (exemplar.length / 3));
  points.scale = 14 / points.spacing;
  points.shown = [];
  drawPoints();
  info("points", `exemplar: ${exemplar.length / 3} points; brush to grow it`);
}

async function brushPoints(stroke) {
  const unit = (p) => [p[0] / points.scale, p[1] / points.scale];
  const list = stroke.map(unit).flat();
  if (list.length < 4) return;
  const width = Number($("points-width").value) * points.spacing;
  // Interactive settings: two window sizes (shrink 0.6), 16 quilting candidates, at most 6
  // merging steps per window size and the window truncated at 1.5 δ instead of 2 δ: a fraction
  // of the CLI defaults' work with nearly the same fidelity on the hex exemplar
  // (docs/performance.md).
  const job = { neighbourhood: 2 * points.spacing, domain: { box: [1, 1] }, "max-points": 20000, shrink: 0.6, "patch-candidates": 16, "merge-iterations": 6, "window-cutoff": 1.5, "keep-margin": points.spacing * 2 };
  const start = performance.now();
  try {
    const result = await request("pointsBrush", { points: list, width, job });
    const before = points.shown.length / 3;
    points.shown = result.points;
    points.stroke = null;
    drawPoints();
    const total = performance.now() - start;
    const added = points.shown.length / 3 - before;
    window.motifTimings.points.push({ engine_ms: result.ms, total_ms: total, added, points: points.shown.length / 3 });
    info("points", `${points.shown.length / 3} points (${added >= 0 ? "+" : ""}${added}) in ${result.ms.toFixed(0)} ms`);
  } catch (error) {
    points.stroke = null;
    drawPoints();
    info("points", error.message, true);
  }
}

points.canvas.addEventListener("pointerdown", (event) => {
  points.canvas.setPointerCapture(event.pointerId);
  points.stroke = [canvasPoint(points.canvas, event)];
});
points.canvas.addEventListener("pointermove", (event) => {
  if (!points.stroke) return;
  const p = canvasPoint(points.canvas, event);
  const last = points.stroke[points.stroke.length - 1];
  if (Math.hypot(p[0] - last[0], p[1] - last[1]) > 4) points.stroke.push(p);
  drawPoints();
});
points.canvas.addEventListener("pointerup", () => {
  if (points.stroke) brushPoints(points.stroke);
});
$("points-width").addEventListener("input", () => ($("points-width-value").textContent = $("points-width").value));
$("points-clear").addEventListener("click", async () => {
  await request("pointsClear");
  points.shown = [];
  drawPoints();
});
$("points-exemplar").addEventListener("change", () => startPoints().catch((e) => info("points", e.message, true)));

// ---------------------------------------------------------------- strokes
const strokes = { reference: [], elements: [] };

function bounds(list) {
  let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const stroke of list) for (const [x, y] of stroke.points) {
    minX = Math.min(minX, x); maxX = Math.max(maxX, x); minY = Math.min(minY, y); maxY = Math.max(maxY, y);
  }
  return [minX, minY, maxX, maxY];
}

function drawStrokes(canvas, list, frame, boxes = []) {
  const context = canvas.getContext("2d");
  context.fillStyle = "#fff";
  context.fillRect(0, 0, canvas.width, canvas.height);
  const [minX, minY, maxX, maxY] = frame;
  const scale = Math.min((canvas.width - 20) / (maxX - minX || 1), (canvas.height - 20) / (maxY - minY || 1));
  const map = ([x, y]) => [10 + (x - minX) * scale, 10 + (y - minY) * scale];
  boxes.forEach((box, index) => {
    context.strokeStyle = `hsl(${(index * 137.5) % 360}, 70%, 45%)`;
    context.lineWidth = 1;
    context.beginPath();
    box.corners.map(map).forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
    context.closePath();
    context.stroke();
  });
  for (const stroke of list) {
    const [r, g, b, a] = stroke.colour;
    context.strokeStyle = `rgba(${r}, ${g}, ${b}, ${a / 255})`;
    context.lineWidth = Math.max(0.5, stroke.width * scale);
    context.beginPath();
    stroke.points.map(map).forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
    if (stroke.closed) context.closePath();
    if (stroke.fill) {
      const [fr, fg, fb, fa] = stroke.fill;
      context.fillStyle = `rgba(${fr}, ${fg}, ${fb}, ${fa / 255})`;
      context.fill();
    }
    if (stroke.width > 0) context.stroke();
  }
}

// The scale ε the strokes panel asks for: null (inferred from the reference) while "inferred" is
// ticked, else the slider's.
function strokesScale() {
  return $("strokes-scale-auto").checked ? null : Number($("strokes-scale").value);
}

const analyseStrokes = latestOnly(async () => {
  try {
    const start = performance.now();
    const analysis = await request("strokesAnalyse", { scale: strokesScale() });
    const scale = Number(analysis.scale.toPrecision(3));
    if (analysis.scale_inferred) {
      $("strokes-scale").value = scale;
      $("strokes-scale-value").textContent = `${scale} (inferred)`;
    }
    strokes.elements = analysis.elements;
    drawStrokes($("strokes-reference"), strokes.reference, bounds(strokes.reference), analysis.elements);
    const total = performance.now() - start;
    window.motifTimings.strokes.push({ kind: "analysis", engine_ms: analysis.milliseconds, total_ms: total });
    info("strokes", `${analysis.elements.length} elements at ε = ${scale}${analysis.scale_inferred ? " (inferred)" : ""} (analysis ${analysis.milliseconds.toFixed(1)} ms)`);
  } catch (error) {
    info("strokes", error.message, true);
  }
});

async function startStrokes() {
  const { reference } = await request("strokesStart", { reference: $("strokes-choice").value });
  strokes.reference = reference;
  await analyseStrokes();
}

// An SVG drawing sampled by the browser itself: every path, line, polyline, polygon, rect, circle
// and ellipse as a polyline (its geometry in user units, transforms applied), with its stroke
// width and colours as computed by the browser.
async function strokesFromSvg(file) {
  if (file.size > 5 * 1024 * 1024) throw new Error(`the file is ${(file.size / 1048576).toFixed(1)} MB; give an SVG under 5 MB`);
  const text = await file.text();
  const document_ = new DOMParser().parseFromString(text, "image/svg+xml");
  const root = document_.documentElement;
  if (document_.querySelector("parsererror") || root.nodeName.toLowerCase() !== "svg") throw new Error("the file is not an SVG drawing");
  const host = document.createElement("div");
  host.style.cssText = "position:absolute;left:-10000px;top:0;visibility:hidden";
  host.appendChild(document.importNode(root, true));
  document.body.appendChild(host);
  try {
    const colour = (value) => {
      const match = /rgba?\(([^)]+)\)/.exec(value || "");
      if (!match) return null;
      const parts = match[1].split(",").map(Number);
      return [parts[0], parts[1], parts[2], Math.round(255 * (parts.length > 3 ? parts[3] : 1))];
    };
    const list = [];
    for (const element of host.querySelectorAll("path, line, polyline, polygon, rect, circle, ellipse")) {
      const length = element.getTotalLength();
      if (!(length > 0) || list.length >= 5000) continue;
      const matrix = element.getCTM();
      const count = Math.min(400, Math.max(2, Math.ceil(length / 2)));
      const points = [];
      for (let i = 0; i <= count; i++) {
        const p = element.getPointAtLength((length * i) / count).matrixTransform(matrix);
        points.push([p.x, p.y]);
      }
      const style = getComputedStyle(element);
      const closed = /[zZ]\s*$/.test(element.getAttribute("d") || "") || ["polygon", "rect", "circle", "ellipse"].includes(element.nodeName);
      const stroke = style.stroke !== "none" ? colour(style.stroke) : null;
      const fill = style.fill !== "none" ? colour(style.fill) : null;
      list.push({ points, closed, width: stroke ? parseFloat(style.strokeWidth) || 1 : 0, colour: stroke || fill || [0, 0, 0, 255], fill: closed ? fill : null });
    }
    if (!list.length) throw new Error("the SVG has no path with a length > 0");
    return list;
  } finally {
    host.remove();
  }
}

$("strokes-file").addEventListener("change", async () => {
  const file = $("strokes-file").files[0];
  if (!file) return;
  try {
    const list = await strokesFromSvg(file);
    const { reference } = await request("strokesStart", { strokes: list });
    strokes.reference = reference;
    await analyseStrokes();
  } catch (error) {
    info("strokes", error.message, true);
  }
});

$("strokes-scale").addEventListener("input", () => {
  $("strokes-scale-auto").checked = false;
  $("strokes-scale-value").textContent = $("strokes-scale").value;
  analyseStrokes();
});
$("strokes-scale-auto").addEventListener("change", () => {
  if (!$("strokes-scale-auto").checked) $("strokes-scale-value").textContent = $("strokes-scale").value;
  analyseStrokes();
});
$("strokes-choice").addEventListener("change", () => startStrokes().catch((e) => info("strokes", e.message, true)));
$("strokes-run").addEventListener("click", async () => {
  const [minX, minY, maxX, maxY] = bounds(strokes.reference);
  const side = Math.max(maxX - minX, maxY - minY) * 1.6;
  try {
    const scale = strokesScale();
    const job = scale === null ? { target: { rect: [1, 1] } } : { scale, target: { rect: [1, 1] } };
    const result = await request("strokesSynthesize", { width: side, height: side, job });
    drawStrokes($("strokes-output"), result.strokes, [0, 0, side, side]);
    window.motifTimings.strokes.push({ kind: "synthesis", engine_ms: result.milliseconds });
    info("strokes", `${result.report.output_elements} elements synthesized in ${result.milliseconds.toFixed(0)} ms`);
  } catch (error) {
    info("strokes", error.message, true);
  }
});

// ---------------------------------------------------------------- stylize
const stylize = { size: 192, guide: null, colour: null, painting: false };

const runStylize = latestOnly(async () => {
  const canvas = $("stylize-guide");
  const data = canvas.getContext("2d").getImageData(0, 0, stylize.size, stylize.size).data;
  const rgba = new Uint8Array(data).buffer;
  try {
    const result = await request("stylizeRun", { rgba, width: stylize.size, height: stylize.size, job: { band: Number($("stylize-band").value) } }, [rgba]);
    putImage($("stylize-output"), result.rgba, result.width, result.height);
    window.motifTimings.stylize.push({ engine_ms: result.ms });
    info("stylize", `band mode: ${result.report.searched_pixels} pixels optimized in ${result.ms.toFixed(0)} ms`);
  } catch (error) {
    info("stylize", error.message, true);
  }
});

function paintAt(event) {
  // Aliased painting: the segments are the guide's exact colours, so no blended edge pixels.
  const canvas = $("stylize-guide");
  const context = canvas.getContext("2d");
  const [cx, cy] = canvasPoint(canvas, event);
  const radius = Number($("stylize-brush").value);
  const image = context.getImageData(0, 0, stylize.size, stylize.size);
  for (let y = Math.max(0, Math.floor(cy - radius)); y < Math.min(stylize.size, cy + radius); y++) {
    for (let x = Math.max(0, Math.floor(cx - radius)); x < Math.min(stylize.size, cx + radius); x++) {
      if (Math.hypot(x + 0.5 - cx, y + 0.5 - cy) <= radius) image.data.set(stylize.colour, (y * stylize.size + x) * 4);
    }
  }
  context.putImageData(image, 0, 0);
}

async function startStylize() {
  info("stylize", "pre-synthesizing one texture per map colour…");
  const result = await request("stylizeStart", { size: stylize.size });
  putImage($("stylize-guide"), result.guide, stylize.size, stylize.size);
  putImage($("stylize-style"), result.style, stylize.size, stylize.size);
  const palette = $("stylize-palette");
  palette.textContent = "";
  for (let i = 0; i < result.palette.length; i += 4) {
    const colour = result.palette.slice(i, i + 4);
    const swatch = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = `rgb(${colour[0]}, ${colour[1]}, ${colour[2]})`;
    swatch.addEventListener("click", () => {
      stylize.colour = colour;
      for (const s of palette.children) s.classList.remove("chosen");
      swatch.classList.add("chosen");
    });
    palette.appendChild(swatch);
    if (!stylize.colour) swatch.click();
  }
  await runStylize();
}

const guideCanvas = $("stylize-guide");
guideCanvas.addEventListener("pointerdown", (event) => {
  guideCanvas.setPointerCapture(event.pointerId);
  stylize.painting = true;
  paintAt(event);
});
guideCanvas.addEventListener("pointermove", (event) => stylize.painting && paintAt(event));
guideCanvas.addEventListener("pointerup", () => {
  stylize.painting = false;
  runStylize();
});
$("stylize-band").addEventListener("input", () => ($("stylize-band-value").textContent = $("stylize-band").value));
$("stylize-band").addEventListener("change", () => runStylize());

// ---------------------------------------------------------------- declared options
// A control bound to a declared option (data-option="job/option") takes the option's help as its
// tooltip and keeps within its declared range (motif-jobs' declarations, through the worker).
async function applyDeclarations() {
  const controls = [...document.querySelectorAll("[data-option]")];
  for (const job of new Set(controls.map((c) => c.dataset.option.split("/")[0]))) {
    const specs = await request("options", { job });
    for (const control of controls.filter((c) => c.dataset.option.startsWith(`${job}/`))) {
      const name = control.dataset.option.split("/")[1];
      const spec = specs.find((s) => s.name === name);
      if (!spec) throw new Error(`the control ${control.id} names ${job} --${name}, which ${job} does not declare`);
      control.title = spec.help;
      if (spec.range) {
        control.min = Math.max(Number(control.min), spec.range[0]);
        control.max = Math.min(Number(control.max), spec.range[1]);
      }
    }
  }
}

// ---------------------------------------------------------------- start
(async () => {
  try {
    await applyDeclarations();
    await loadCurveExemplar(fetch($("curve-exemplar").value).then((r) => r.blob()));
    await startPoints();
    await startStrokes();
    await startStylize();
    setStatus("ready");
  } catch (error) {
    setStatus(error.message, true);
  }
})();
