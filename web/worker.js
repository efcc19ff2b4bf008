// The playground's Web Worker: owns the WebAssembly sessions so the page never freezes.
// Messages: {id, panel, method, args}; replies: {id, ok, value} or {id, ok: false, error}.
import init, { CurvePanel, PointsPanel, StrokesPanel, StylizePanel, job_options, max_image_side } from "./pkg/motif_web.js";

const ready = init();
const sessions = {};

function respond(id, value, transfer = []) {
  self.postMessage({ id, ok: true, value }, transfer);
}

const handlers = {
  async limits() {
    return { maxImageSide: max_image_side() };
  },
  async options({ job }) {
    return JSON.parse(job_options(job));
  },
  async curveExemplar({ rgba, width, height }) {
    sessions.curve = new CurvePanel(new Uint8Array(rgba), width, height);
    return {};
  },
  async curveSynthesize({ points, job }) {
    const result = sessions.curve.synthesize(new Float64Array(points), JSON.stringify(job));
    const rgba = result.rgba;
    return { value: { width: result.width, height: result.height, rgba: rgba.buffer, report: JSON.parse(result.report), ms: result.milliseconds }, transfer: [rgba.buffer] };
  },
  async pointsStart({ exemplar }) {
    sessions.points = new PointsPanel(exemplar);
    return { exemplar: Array.from(sessions.points.exemplar()) };
  },
  async pointsBrush({ points, width, job }) {
    const result = sessions.points.brush(new Float64Array(points), width, JSON.stringify(job));
    return { points: Array.from(result.points), report: JSON.parse(result.report), ms: result.milliseconds };
  },
  async pointsClear() {
    sessions.points.clear();
    return {};
  },
  async strokesStart({ reference, strokes }) {
    sessions.strokes = strokes ? StrokesPanel.from_strokes(JSON.stringify(strokes)) : new StrokesPanel(reference);
    return { reference: JSON.parse(sessions.strokes.reference()) };
  },
  async strokesAnalyse({ scale }) {
    return JSON.parse(sessions.strokes.analyse(scale));
  },
  async strokesSynthesize({ width, height, job }) {
    return JSON.parse(sessions.strokes.synthesize(width, height, JSON.stringify(job)));
  },
  async stylizeStart({ size }) {
    const start = performance.now();
    sessions.stylize = new StylizePanel(size);
    const panel = sessions.stylize;
    return {
      guide: Array.from(panel.guide()),
      style: Array.from(panel.style()),
      palette: Array.from(panel.palette()),
      ms: performance.now() - start,
    };
  },
  async stylizeRun({ rgba, width, height, job }) {
    const result = sessions.stylize.stylize(new Uint8Array(rgba), width, height, JSON.stringify(job));
    const out = result.rgba;
    return { value: { width: result.width, height: result.height, rgba: out.buffer, report: JSON.parse(result.report), ms: result.milliseconds }, transfer: [out.buffer] };
  },
};

self.onmessage = async (event) => {
  const { id, method, args } = event.data;
  try {
    await ready;
    const handler = handlers[method];
    if (!handler) throw new Error(`unknown request ${method}`);
    const answer = await handler(args || {});
    if (answer && answer.transfer) respond(id, answer.value, answer.transfer);
    else respond(id, answer);
  } catch (error) {
    // Engine errors arrive as JsError with the engine's message; the worker stays alive.
    self.postMessage({ id, ok: false, error: String(error && error.message ? error.message : error) });
  }
};
