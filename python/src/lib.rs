//! `motif._motif`: the native half of the Python package. Each function takes numpy arrays and a
//! job description as JSON (built by `motif/__init__.py` from keyword arguments named as the CLI's
//! flags), converts the arrays into engine inputs, releases the GIL, runs the job through
//! `motif-jobs` (the layer the CLI uses too, so the same seed gives the same bytes) and returns
//! numpy arrays and the report as JSON text.
//!
//! Errors: a bad description or parameter is a `ValueError` naming the option (`OptionError`,
//! `InputError`); a run past a memory, point or work limit is a `LimitError`, both a `ValueError`
//! and a `MemoryError`; a file that cannot be read or written is an `OSError`; nothing reaches the
//! interpreter as a crash.

#![allow(unreachable_pub, reason = "a cdylib: its pub items are what it exports, reachable from outside Rust")]

use motif_core::{NoProgress, Point, Polyline, RgbaImage};
use motif_jobs::columns::Column;
use motif_jobs::{Job, JobError};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyMemoryError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyType};

type Image<'py> = Bound<'py, numpy::PyArray3<u8>>;
type PyColumns<'py> = Vec<(String, bool, PyReadonlyArray1<'py, f64>)>;
type OutColumns<'py> = Vec<(String, bool, Bound<'py, PyArray1<f64>>)>;

fn value_error(error: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(error.to_string())
}

pyo3::create_exception!(_motif, MotifError, PyValueError, "A run refused by motif (a ValueError).");
pyo3::create_exception!(_motif, OptionError, MotifError, "An option out of its range or inconsistent with another.");
pyo3::create_exception!(
    _motif,
    InputError,
    MotifError,
    "An input (image, points, curve, strokes) that cannot be used."
);

/// `LimitError`: a run that would pass a memory, point or work limit. It is a `MotifError` (so a
/// `ValueError`, like every refusal) and a `MemoryError`, so `except MemoryError` catches it too.
/// `create_exception!` takes one base, so the class is made once by Python's `type`.
static LIMIT_ERROR: pyo3::sync::PyOnceLock<Py<PyType>> = pyo3::sync::PyOnceLock::new();

fn limit_error_type(py: Python<'_>) -> PyResult<&Bound<'_, PyType>> {
    let made = LIMIT_ERROR.get_or_try_init(py, || -> PyResult<Py<PyType>> {
        let namespace = PyDict::new(py);
        namespace.set_item("__doc__", "A run that would pass a memory, point or work limit.")?;
        namespace.set_item("__module__", "motif._motif")?;
        let bases = (py.get_type::<MotifError>(), py.get_type::<PyMemoryError>());
        let class = py.get_type::<PyType>().call1(("LimitError", bases, namespace))?;
        Ok(class.cast_into::<PyType>()?.unbind())
    })?;
    Ok(made.bind(py))
}

fn limit_error(message: String) -> PyErr {
    Python::attach(|py| match limit_error_type(py) {
        Ok(class) => PyErr::from_type(class.clone(), message),
        Err(error) => error,
    })
}

/// The job's error as the exception of its kind.
fn job_error(error: JobError) -> PyErr {
    let message = error.to_string();
    match error.kind() {
        motif_jobs::ErrorKind::Option => OptionError::new_err(message),
        motif_jobs::ErrorKind::Input => InputError::new_err(message),
        motif_jobs::ErrorKind::Limit => limit_error(message),
        _ => MotifError::new_err(message),
    }
}

fn io_error(error: motif_io::IoError) -> PyErr {
    PyOSError::new_err(error.to_string())
}

fn description<T: serde::de::DeserializeOwned>(job: &str) -> PyResult<T> {
    serde_json::from_str(job).map_err(|error| OptionError::new_err(format!("bad options: {error}")))
}

/// An H×W (grey), H×W×1, H×W×3 or H×W×4 uint8 array as an RGBA image. `what` names it in errors.
fn image_of(array: &PyReadonlyArrayDyn<'_, u8>, what: &str) -> PyResult<RgbaImage> {
    let shape = array.shape();
    let (height, width, channels) = match *shape {
        [h, w] => (h, w, 1),
        [h, w, c] if [1, 3, 4].contains(&c) => (h, w, c),
        _ => {
            return Err(value_error(format!(
                "{what}: an image must be a uint8 array of shape H×W or H×W×C with C = 1, 3 or 4, not {shape:?}"
            )));
        }
    };
    if width == 0 || height == 0 {
        return Err(value_error(format!("{what}: the image is empty ({height}×{width})")));
    }
    if (width as u64) * (height as u64) > motif_core::limits::MAX_IMAGE_PIXELS {
        let side = motif_core::limits::MAX_IMAGE_SIDE;
        return Err(value_error(format!("{what}: {height}×{width} is larger than {side}×{side} pixels")));
    }
    // Contiguous arrays are read in place; others (slices, transposes) through numpy's view.
    let view = array.as_array();
    let pixel = |y: usize, x: usize| -> [u8; 4] {
        let at = |c: usize| if shape.len() == 2 { view[[y, x]] } else { view[[y, x, c]] };
        match channels {
            1 => [at(0), at(0), at(0), 255],
            3 => [at(0), at(1), at(2), 255],
            _ => [at(0), at(1), at(2), at(3)],
        }
    };
    let pixels = match array.as_slice() {
        Ok(data) => data
            .chunks_exact(channels)
            .map(|p| match channels {
                1 => [p[0], p[0], p[0], 255],
                3 => [p[0], p[1], p[2], 255],
                _ => [p[0], p[1], p[2], p[3]],
            })
            .collect(),
        Err(_) => (0..height).flat_map(|y| (0..width).map(move |x| (y, x))).map(|(y, x)| pixel(y, x)).collect(),
    };
    RgbaImage::from_pixels(width, height, pixels).map_err(value_error)
}

/// An RGBA image as an H×W×4 uint8 array.
fn array_of<'py>(py: Python<'py>, image: &RgbaImage) -> PyResult<Image<'py>> {
    let data = image.as_bytes().to_vec();
    PyArray1::from_vec(py, data).reshape([image.height(), image.width(), 4])
}

/// Runs `work` without the GIL, in a pool of `threads` workers when given.
fn detached<T: Send>(py: Python<'_>, threads: Option<usize>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    match threads {
        None => Ok(py.detach(work)),
        Some(0) => Err(value_error("threads must be at least 1")),
        Some(count) => {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(count).build().map_err(value_error)?;
            Ok(py.detach(|| pool.install(work)))
        }
    }
}

fn report_json(figures: &serde_json::Map<String, serde_json::Value>) -> String {
    serde_json::Value::Object(figures.clone()).to_string()
}

/// Reads a PNG, JPEG or WebP as an H×W×4 uint8 array.
#[pyfunction]
fn read_image<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<Image<'py>> {
    let image = py.detach(|| motif_io::read_image(&path)).map_err(io_error)?;
    array_of(py, &image)
}

/// Writes an image array as an 8-bit RGBA PNG, atomically.
#[pyfunction]
fn write_png(py: Python<'_>, path: std::path::PathBuf, image: PyReadonlyArrayDyn<'_, u8>) -> PyResult<()> {
    let image = image_of(&image, "image")?;
    py.detach(|| motif_io::write_png(&path, &image)).map_err(io_error)
}

/// Reads a PLY or CSV point file as `[(name, integer, values)]`.
#[pyfunction]
fn read_points<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<OutColumns<'py>> {
    let table = py.detach(|| motif_io::read_points(&path)).map_err(io_error)?;
    Ok(table
        .columns
        .iter()
        .enumerate()
        .map(|(c, column)| {
            let values: Vec<f64> = (0..table.rows).map(|row| table.row(row)[c]).collect();
            (column.name.clone(), column.kind == motif_io::ColumnKind::Int, PyArray1::from_vec(py, values))
        })
        .collect())
}

/// `motif texture`: (image, report JSON).
#[pyfunction]
#[pyo3(signature = (exemplar, job, threads=None))]
fn texture<'py>(
    py: Python<'py>,
    exemplar: PyReadonlyArrayDyn<'py, u8>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Image<'py>, String)> {
    let job: motif_jobs::stylize::TextureJob = description(job)?;
    let exemplar = motif_jobs::stylize::style_image_channels(&image_of(&exemplar, "exemplar")?);
    let inputs = motif_jobs::stylize::TextureInputs { exemplar, mask: None };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    Ok((array_of(py, &RgbaImage::from_float(&run.output.image))?, report_json(&run.figures)))
}

/// `motif inpaint`: (image, report JSON). `hole` is an H×W bool array (true = fill).
#[pyfunction]
#[pyo3(signature = (image, hole, job, threads=None))]
fn inpaint<'py>(
    py: Python<'py>,
    image: PyReadonlyArrayDyn<'py, u8>,
    hole: PyReadonlyArrayDyn<'py, bool>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Image<'py>, String)> {
    let job: motif_jobs::stylize::InpaintJob = description(job)?;
    let image = image_of(&image, "image")?;
    let shape = hole.shape().to_vec();
    if shape != [image.height(), image.width()] {
        return Err(value_error(format!(
            "hole must be an H×W bool array of the image's size {}×{}, got shape {shape:?}",
            image.height(),
            image.width()
        )));
    }
    let hole: Vec<bool> = hole.as_array().iter().copied().collect();
    let image = motif_jobs::stylize::style_image_channels(&image);
    let inputs = motif_jobs::stylize::InpaintInputs { image, hole };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    Ok((array_of(py, &RgbaImage::from_float(&run.output.image))?, report_json(&run.figures)))
}

/// `motif zoom`: (levels, report JSONs), outermost level first.
#[pyfunction]
#[pyo3(signature = (exemplar, job, threads=None))]
fn zoom<'py>(
    py: Python<'py>,
    exemplar: PyReadonlyArrayDyn<'py, u8>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Vec<Image<'py>>, Vec<String>)> {
    let job: motif_jobs::stylize::ZoomJob = description(job)?;
    let exemplar = motif_jobs::stylize::style_image_channels(&image_of(&exemplar, "exemplar")?).to_float();
    let run = detached(py, threads, || job.run(exemplar, &mut NoProgress))?.map_err(job_error)?;
    let mut images = Vec::with_capacity(run.levels.len());
    for level in &run.levels {
        images.push(array_of(py, &RgbaImage::from_float(&level.output.image))?);
    }
    Ok((images, run.levels.iter().map(|level| report_json(&level.figures)).collect()))
}

/// A mask array (H×W bool, true = synthesize) as a hole of `size`.
fn hole_array(mask: &PyReadonlyArrayDyn<'_, bool>, (width, height): (usize, usize), what: &str) -> PyResult<Vec<bool>> {
    let shape = mask.shape().to_vec();
    if shape != [height, width] {
        return Err(value_error(format!(
            "{what} must be an H×W bool array of the frames' size {height}×{width}, got shape {shape:?}"
        )));
    }
    Ok(mask.as_array().iter().copied().collect())
}

/// Frames and keyframe styles decoded as `motif video` decodes them.
fn video_inputs(
    frames: &[PyReadonlyArrayDyn<'_, u8>],
    styles: &[PyReadonlyArrayDyn<'_, u8>],
) -> PyResult<(Vec<motif_core::FloatImage>, Vec<motif_core::FloatImage>)> {
    let frames = frames
        .iter()
        .enumerate()
        .map(|(i, f)| image_of(f, &format!("frame {i}")).map(|image| motif_jobs::stylize::video_frame(&image)))
        .collect::<PyResult<Vec<_>>>()?;
    let styles = styles.iter().map(|s| image_of(s, "keyframe")).collect::<PyResult<Vec<_>>>()?;
    Ok((frames, motif_jobs::stylize::video_styles(&styles)))
}

/// `motif video`: (frames, report JSON). `keys` are (frame index, stylized frame) pairs.
#[pyfunction]
#[pyo3(signature = (frames, keys, mask, job, threads=None))]
fn video<'py>(
    py: Python<'py>,
    frames: Vec<PyReadonlyArrayDyn<'py, u8>>,
    keys: Vec<(usize, PyReadonlyArrayDyn<'py, u8>)>,
    mask: Option<PyReadonlyArrayDyn<'py, bool>>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Vec<Image<'py>>, String)> {
    let job: motif_jobs::stylize::VideoJob = description(job)?;
    let styles: Vec<PyReadonlyArrayDyn<'py, u8>> = keys.iter().map(|(_, s)| s.clone()).collect();
    let (frames, styles) = video_inputs(&frames, &styles)?;
    let size = frames.first().map_or((0, 0), |f| (f.width(), f.height()));
    let mask = mask.map(|m| hole_array(&m, size, "mask")).transpose()?;
    let keys = keys
        .iter()
        .zip(styles)
        .map(|((frame, _), style)| motif_jobs::stylize::Keyframe { frame: *frame, style })
        .collect();
    let input = motif_jobs::stylize::VideoInput { frames, keys, mask };
    let run = detached(py, threads, || job.run(input, &mut NoProgress))?.map_err(job_error)?;
    let (output, figures) = (run.output, run.figures);
    let images = output.frames.iter().map(|f| array_of(py, &RgbaImage::from_float(f))).collect::<PyResult<Vec<_>>>()?;
    Ok((images, report_json(&figures)))
}

/// The independent keyframe intervals: (first, last, starts at a keyframe, ends at one).
#[pyfunction]
fn video_intervals(frame_count: usize, key_frames: Vec<usize>) -> Vec<(usize, usize, bool, bool)> {
    motif_jobs::stylize::VideoJob::intervals(frame_count, &key_frames)
        .into_iter()
        .map(|i| (i.first, i.last, i.starts_at_key, i.ends_at_key))
        .collect()
}

/// One interval of `motif video` (see `video_intervals`): (frames, report JSON).
#[pyfunction]
#[pyo3(signature = (frames, interval, first_style, last_style, mask, job, threads=None))]
#[allow(clippy::too_many_arguments, reason = "a Python function's keyword arguments")]
fn video_interval<'py>(
    py: Python<'py>,
    frames: Vec<PyReadonlyArrayDyn<'py, u8>>,
    interval: (usize, usize, bool, bool),
    first_style: Option<PyReadonlyArrayDyn<'py, u8>>,
    last_style: Option<PyReadonlyArrayDyn<'py, u8>>,
    mask: Option<PyReadonlyArrayDyn<'py, bool>>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Vec<Image<'py>>, String)> {
    let job: motif_jobs::stylize::VideoJob = description(job)?;
    let (first, last, starts_at_key, ends_at_key) = interval;
    if last < first || last - first + 1 != frames.len() {
        return Err(value_error(format!("interval {first}–{last} does not hold the {} frames given", frames.len())));
    }
    let styles: Vec<PyReadonlyArrayDyn<'py, u8>> = first_style.iter().chain(&last_style).cloned().collect();
    let (frames, mut styles) = video_inputs(&frames, &styles)?;
    let last_decoded = if last_style.is_some() { styles.pop() } else { None };
    let first_decoded = if first_style.is_some() { styles.pop() } else { None };
    let size = frames.first().map_or((0, 0), |f| (f.width(), f.height()));
    let mask = mask.map(|m| hole_array(&m, size, "mask")).transpose()?;
    let interval = motif_jobs::stylize::Interval { first, last, starts_at_key, ends_at_key };
    let output = detached(py, threads, || {
        job.run_interval(
            &frames,
            interval,
            first_decoded.as_ref(),
            last_decoded.as_ref(),
            mask.as_deref(),
            &mut NoProgress,
        )
    })?
    .map_err(job_error)?;
    let images = output.frames.iter().map(|f| array_of(py, &RgbaImage::from_float(f))).collect::<PyResult<Vec<_>>>()?;
    let report = serde_json::to_value(&output.report).map_err(value_error)?;
    Ok((images, report.to_string()))
}

/// The pre-synthesized textures of `motif presynth`, one per segment colour of a style's guide,
/// kept whole (with the fields that start the band mode) for `stylize(textures=...)`.
#[pyclass(frozen, module = "motif._motif")]
struct Textures(Vec<motif_jobs::stylize::SegmentTexture>);

#[pymethods]
impl Textures {
    /// The segment colours, 0–255 per channel of the guide.
    fn colours(&self) -> Vec<Vec<u8>> {
        let byte = |v: &f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        self.0.iter().map(|texture| texture.colour.iter().map(byte).collect()).collect()
    }

    /// The textures as H×W×4 uint8 arrays, in the order of `colours()`.
    fn images<'py>(&self, py: Python<'py>) -> PyResult<Vec<Image<'py>>> {
        self.0.iter().map(|texture| array_of(py, &RgbaImage::from_float(&texture.image))).collect()
    }

    fn __len__(&self) -> usize {
        self.0.len()
    }
}

/// `motif presynth`: (textures, report JSON) for `style` and its segment guide.
#[pyfunction]
#[pyo3(signature = (style, guide, job, threads=None))]
fn presynth<'py>(
    py: Python<'py>,
    style: PyReadonlyArrayDyn<'py, u8>,
    guide: PyReadonlyArrayDyn<'py, u8>,
    job: &str,
    threads: Option<usize>,
) -> PyResult<(Textures, String)> {
    let job: motif_jobs::stylize::PresynthJob = description(job)?;
    let style = motif_jobs::stylize::style_image_channels(&image_of(&style, "style")?).to_float();
    let guide = motif_jobs::stylize::guide_image_channels(&image_of(&guide, "guide")?).to_float();
    let inputs = motif_jobs::stylize::PresynthInputs { style, guide };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    Ok((Textures(run.textures), report_json(&run.figures)))
}

/// `motif stylize`: (image, report JSON). `guides` are (source, target) pairs; `textures` the
/// result of `presynth` for the band mode.
#[pyfunction]
#[pyo3(signature = (style, guides, job, textures=None, threads=None))]
fn stylize<'py>(
    py: Python<'py>,
    style: PyReadonlyArrayDyn<'py, u8>,
    guides: Vec<(PyReadonlyArrayDyn<'py, u8>, PyReadonlyArrayDyn<'py, u8>)>,
    job: &str,
    textures: Option<PyRef<'py, Textures>>,
    threads: Option<usize>,
) -> PyResult<(Image<'py>, String)> {
    let job: motif_jobs::stylize::StylizeJob = description(job)?;
    let style = motif_jobs::stylize::style_image_channels(&image_of(&style, "style")?);
    let mut pairs = Vec::with_capacity(guides.len());
    for (index, (source, target)) in guides.iter().enumerate() {
        let source = image_of(source, &format!("source guide {}", index + 1))?;
        let target = image_of(target, &format!("target guide {}", index + 1))?;
        pairs.push(motif_jobs::stylize::guide_pair(&source, &target));
    }
    let textures = textures.map(|textures| textures.0.clone());
    let inputs =
        motif_jobs::stylize::StylizeInputs { textures, ..motif_jobs::stylize::StylizeInputs::new(style, pairs) };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    Ok((array_of(py, &RgbaImage::from_float(&run.output.image))?, report_json(&run.figures)))
}

/// A map's tile set (`motif tiles`): the textures pre-synthesized once, any tile on demand.
#[pyclass(frozen, module = "motif._motif")]
struct Tiles {
    run: motif_jobs::tiles::TilesRun,
    job: motif_jobs::tiles::TilesJob,
    /// The map file, the job's JSON and the legend file or folder: what `tiles` was called with,
    /// so that a pickled tile set (a Dask task's) is made again from them.
    map: std::path::PathBuf,
    description: String,
    legend: Option<std::path::PathBuf>,
}

fn layer_of(layer: &str) -> PyResult<motif_jobs::tiles::Layer> {
    match layer {
        "stylized" => Ok(motif_jobs::tiles::Layer::Stylized),
        "plain" => Ok(motif_jobs::tiles::Layer::Plain),
        other => Err(OptionError::new_err(format!("layer must be \"stylized\" or \"plain\", not {other:?}"))),
    }
}

fn tile_of(z: u8, x: u32, y: u32) -> PyResult<motif_jobs::tiles::TileId> {
    motif_jobs::tiles::TileId::new(z, x, y).map_err(|error| OptionError::new_err(error.to_string()))
}

impl Tiles {
    /// Tile `(z, x, y)` of the layer named `layer`, rendered without the GIL.
    fn image(
        &self,
        py: Python<'_>,
        (z, x, y): (u8, u32, u32),
        layer: &str,
        threads: Option<usize>,
    ) -> PyResult<RgbaImage> {
        let (layer, tile) = (layer_of(layer)?, tile_of(z, x, y)?);
        detached(py, threads, || self.run.render(tile, layer))?.map_err(job_error)
    }
}

#[pymethods]
impl Tiles {
    /// Tile `(z, x, y)` of layer `layer` ("stylized" or "plain") as an H×W×4 uint8 array.
    #[pyo3(signature = (z, x, y, layer="stylized", threads=None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        z: u8,
        x: u32,
        y: u32,
        layer: &str,
        threads: Option<usize>,
    ) -> PyResult<Image<'py>> {
        array_of(py, &self.image(py, (z, x, y), layer, threads)?)
    }

    /// Tile `(z, x, y)` as the PNG bytes `motif tiles` serves and packs.
    #[pyo3(signature = (z, x, y, layer="stylized", threads=None))]
    fn render_png<'py>(
        &self,
        py: Python<'py>,
        z: u8,
        x: u32,
        y: u32,
        layer: &str,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        Ok(PyBytes::new(py, &motif_io::encode_png(&self.image(py, (z, x, y), layer, threads)?)))
    }

    /// Writes `tiles` ((z, x, y), PNG bytes) of layer `layer` as one PMTiles archive at `path`,
    /// with the header `motif tiles render` writes for the same job.
    #[pyo3(signature = (path, tiles, layer="stylized"))]
    fn write_archive(
        &self,
        py: Python<'_>,
        path: std::path::PathBuf,
        tiles: Vec<((u8, u32, u32), Vec<u8>)>,
        layer: &str,
    ) -> PyResult<()> {
        let layer = layer_of(layer)?;
        let mut packed = Vec::with_capacity(tiles.len());
        for ((z, x, y), png) in tiles {
            packed.push((tile_of(z, x, y)?, png));
        }
        let name = self.map.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let header = self.job.archive_header(&self.run, &name, layer);
        let info = motif_io::PyramidInfo {
            zooms: (header.zooms[0], header.zooms[1]),
            bounds: header.bounds,
            metadata: header.metadata,
        };
        py.detach(|| motif_io::write_pmtiles(&path, &info, &packed)).map_err(io_error)
    }

    /// Pickled as the call that made it and its pre-synthesized textures (numpy arrays): where it
    /// is unpickled the map and legend are read again, the presynthesis is not run.
    #[allow(clippy::type_complexity, reason = "pickle's (callable, arguments) pair")]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (std::path::PathBuf, String, Option<std::path::PathBuf>, Vec<TextureOut<'py>>))>
    {
        let function = py.import("motif._motif")?.getattr("tiles_with_textures")?;
        let textures = self.run.tiles.textures().iter().map(|texture| texture_out(py, texture)).collect();
        Ok((function, (self.map.clone(), self.description.clone(), self.legend.clone(), textures)))
    }

    /// The tiles of the job's zoom levels that meet the map, as (z, x, y), by zoom, row, column.
    fn pyramid(&self) -> PyResult<Vec<(u8, u32, u32)>> {
        Ok(self.run.pyramid().map_err(job_error)?.into_iter().map(|tile| (tile.z, tile.x, tile.y)).collect())
    }

    /// The figures of the run, as JSON.
    fn report(&self) -> String {
        report_json(&self.run.figures)
    }
}

/// A pre-synthesized texture as plain values and flat arrays: its colour, (width, height,
/// channels), its pixels, and its field ((width, height, source width, source height, patch),
/// two u32 per pixel with `u32::MAX` for none, the vote weights).
type TextureOut<'py> = (Vec<f32>, (usize, usize, usize), Bound<'py, PyArray1<f32>>, Option<FieldOut<'py>>);
type FieldOut<'py> =
    ((usize, usize, usize, usize, usize), Bound<'py, PyArray1<u32>>, Option<Bound<'py, PyArray1<u16>>>);
type TextureIn<'py> = (Vec<f32>, (usize, usize, usize), PyReadonlyArray1<'py, f32>, Option<FieldIn<'py>>);
type FieldIn<'py> =
    ((usize, usize, usize, usize, usize), PyReadonlyArray1<'py, u32>, Option<PyReadonlyArray1<'py, u16>>);

/// No match, in a [`FieldOut`]'s coordinates.
const NO_MATCH: u32 = u32::MAX;

fn texture_out<'py>(py: Python<'py>, texture: &motif_jobs::stylize::SegmentTexture) -> TextureOut<'py> {
    let image = &texture.image;
    let field = texture.field.as_ref().map(|field| {
        let matches = field.matches.iter().flat_map(|m| m.unwrap_or([NO_MATCH; 2])).collect();
        let shape = (field.width, field.height, field.source_width, field.source_height, field.patch_size);
        let weights = field.weights.as_ref().map(|w| PyArray1::from_slice(py, w));
        (shape, PyArray1::from_vec(py, matches), weights)
    });
    let shape = (image.width(), image.height(), image.channels());
    (texture.colour.clone(), shape, PyArray1::from_slice(py, image.data()), field)
}

fn texture_in(
    index: usize,
    (colour, (width, height, channels), pixels, field): TextureIn<'_>,
) -> PyResult<motif_jobs::stylize::SegmentTexture> {
    let bad = |what: &str| InputError::new_err(format!("pickled tile set: texture {}: {what}", index + 1));
    let image = motif_core::FloatImage::from_data(width, height, channels, pixels.as_slice()?.to_vec())
        .map_err(|error| bad(&error.to_string()))?;
    let field = match field {
        None => None,
        Some(((width, height, source_width, source_height, patch_size), matches, weights)) => {
            let matches = matches.as_slice()?;
            let weights = weights.map(|w| w.as_slice().map(<[u16]>::to_vec)).transpose()?;
            let pixels = width.checked_mul(height).ok_or_else(|| bad("field too large"))?;
            if matches.len() != 2 * pixels || weights.as_ref().is_some_and(|w| w.len() != pixels) {
                return Err(bad("field arrays do not match its size"));
            }
            let matches = matches.chunks_exact(2).map(|m| (m[0] != NO_MATCH).then_some([m[0], m[1]])).collect();
            Some(motif_jobs::stylize::NearestNeighbourField {
                width,
                height,
                source_width,
                source_height,
                patch_size,
                matches,
                weights,
            })
        }
    };
    Ok(motif_jobs::stylize::SegmentTexture { colour, image, field })
}

/// Reads the map and the legend, and checks the job: what [`tiles`] and [`tiles_with_textures`]
/// start from.
fn tiles_inputs(
    py: Python<'_>,
    map: &std::path::Path,
    job: &str,
    legend: Option<&std::path::Path>,
) -> PyResult<(motif_jobs::tiles::TilesJob, motif_jobs::tiles::TilesInputs)> {
    let job: motif_jobs::tiles::TilesJob = description(job)?;
    let limit = motif_core::DEFAULT_MAX_MEMORY;
    let (map_data, _) = py.detach(|| motif_io::read_osm(map, limit)).map_err(io_error)?;
    let legend_data = py.detach(|| motif_io::read_legend(legend, limit)).map_err(io_error)?;
    Ok((job, motif_jobs::tiles::TilesInputs { map: map_data, legend: legend_data }))
}

/// A tile set unpickled: [`tiles`] with the textures it pre-synthesized (no presynthesis here).
#[pyfunction]
#[pyo3(signature = (map, job, legend, textures, threads=None))]
fn tiles_with_textures(
    py: Python<'_>,
    map: std::path::PathBuf,
    job: &str,
    legend: Option<std::path::PathBuf>,
    textures: Vec<TextureIn<'_>>,
    threads: Option<usize>,
) -> PyResult<Tiles> {
    let (parsed, inputs) = tiles_inputs(py, &map, job, legend.as_deref())?;
    let textures = textures.into_iter().enumerate().map(|(index, t)| texture_in(index, t)).collect::<PyResult<_>>()?;
    let run = detached(py, threads, || parsed.run_with_textures(inputs, textures))?.map_err(job_error)?;
    Ok(Tiles { run, job: parsed, map, description: job.to_string(), legend })
}

/// `motif tiles`: the tile set of the OpenStreetMap extract at `map` with the legend at `legend`
/// (a folder, a JSON file, or the built-in one when `None`).
#[pyfunction]
#[pyo3(signature = (map, job, legend=None, threads=None))]
fn tiles(
    py: Python<'_>,
    map: std::path::PathBuf,
    job: &str,
    legend: Option<std::path::PathBuf>,
    threads: Option<usize>,
) -> PyResult<Tiles> {
    let (parsed, inputs) = tiles_inputs(py, &map, job, legend.as_deref())?;
    let run = detached(py, threads, || parsed.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    Ok(Tiles { run, job: parsed, map, description: job.to_string(), legend })
}

/// `motif curve` along a polyline of (N, 2) points (closed when the last repeats the first):
/// (image, pieces JSON, report JSON).
#[pyfunction]
#[pyo3(signature = (exemplar, points, job, more_exemplars=Vec::new(), avoid=None, threads=None, tile_images=Vec::new()))]
#[allow(clippy::too_many_arguments, reason = "a Python function's keyword arguments")]
fn curve<'py>(
    py: Python<'py>,
    exemplar: PyReadonlyArrayDyn<'py, u8>,
    points: PyReadonlyArray2<'py, f64>,
    job: &str,
    more_exemplars: Vec<PyReadonlyArrayDyn<'py, u8>>,
    avoid: Option<PyReadonlyArrayDyn<'py, u8>>,
    threads: Option<usize>,
    tile_images: Vec<Option<PyReadonlyArrayDyn<'py, u8>>>,
) -> PyResult<(Image<'py>, String, String)> {
    let job: motif_jobs::curve::CurveJob = description(job)?;
    let exemplar = image_of(&exemplar, "exemplar")?;
    let more: Vec<RgbaImage> = more_exemplars
        .iter()
        .enumerate()
        .map(|(index, image)| image_of(image, &format!("exemplar {}", index + 2)))
        .collect::<PyResult<_>>()?;
    let avoidance = avoid.as_ref().map(|image| image_of(image, "avoid")).transpose()?;
    if tile_images.len() > 3 {
        return Err(value_error("tile images: at most three (start, end, corner)".to_string()));
    }
    let names = ["start_tile_image", "end_tile_image", "corner_tile_image"];
    let tiles: Vec<Option<RgbaImage>> = tile_images
        .iter()
        .zip(names)
        .map(|(image, name)| image.as_ref().map(|image| image_of(image, name)).transpose())
        .collect::<PyResult<_>>()?;
    let tile = |k: usize| tiles.get(k).and_then(Option::as_ref);
    let shape = points.shape();
    if shape[1] != 2 || shape[0] < 2 {
        return Err(value_error(format!("path: the curve must be an (N, 2) array of N ≥ 2 points, not {shape:?}")));
    }
    let view = points.as_array();
    let mut list: Vec<Point> = (0..shape[0]).map(|i| Point::new(view[[i, 0]], view[[i, 1]])).collect();
    let closed = list.len() > 2 && list.first() == list.last();
    if closed {
        list.pop();
    }
    let curve = Polyline::new(list, closed).map_err(|error| value_error(format!("path: {error}")))?;
    let inputs = motif_jobs::curve::CurveInputs {
        exemplar: &exemplar,
        more_exemplars: &more,
        curve: &curve,
        avoidance: avoidance.as_ref(),
        tile_images: [tile(0), tile(1), tile(2)],
    };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    let pieces = serde_json::to_string(&run.output.pieces).map_err(value_error)?;
    Ok((array_of(py, &run.output.image)?, pieces, report_json(&run.figures)))
}

fn columns_of(columns: &PyColumns<'_>) -> Vec<Column> {
    columns
        .iter()
        .map(|(name, integer, values)| Column {
            name: name.clone(),
            integer: *integer,
            values: values.as_array().to_vec(),
        })
        .collect()
}

/// An optional uint8 image array as a grey map (`what` names it in errors).
fn tone_map(array: Option<PyReadonlyArrayDyn<'_, u8>>, what: &str) -> PyResult<Option<motif_core::ToneMap>> {
    array.map(|array| image_of(&array, what).map(|image| motif_core::ToneMap::from_image(&image))).transpose()
}

/// `motif points`: (columns `[(name, integer, values)]`, report JSON).
#[pyfunction]
#[pyo3(signature = (exemplar, job, existing=None, threads=None, rotation_map=None, scale_map=None))]
fn points<'py>(
    py: Python<'py>,
    exemplar: PyColumns<'py>,
    job: &str,
    existing: Option<PyColumns<'py>>,
    threads: Option<usize>,
    rotation_map: Option<PyReadonlyArrayDyn<'_, u8>>,
    scale_map: Option<PyReadonlyArrayDyn<'_, u8>>,
) -> PyResult<(OutColumns<'py>, String)> {
    let maps = motif_jobs::points::FieldMaps {
        rotation: tone_map(rotation_map, "rotation_map")?,
        scale: tone_map(scale_map, "scale_map")?,
    };
    let job: motif_jobs::points::PointsJob = description(job)?;
    let (exemplar, integer) = motif_jobs::columns::point_set(&columns_of(&exemplar), "exemplar").map_err(job_error)?;
    let existing = match &existing {
        Some(columns) => {
            Some(motif_jobs::columns::point_set(&columns_of(columns), "existing points").map_err(job_error)?.0)
        }
        None => None,
    };
    let inputs = motif_jobs::points::PointsInputs { exemplar, existing, integer_columns: &integer, maps };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    let columns = motif_jobs::columns::columns(&run.output.points, &integer)
        .into_iter()
        .map(|column| (column.name, column.integer, PyArray1::from_vec(py, column.values)))
        .collect();
    Ok((columns, report_json(&run.figures)))
}

/// `motif strokes`: (SVG text, report JSON). The reference is SVG text; the output document is
/// `size` (width, height) user units; the maps are images over the target region's bounds.
#[pyfunction]
#[pyo3(signature = (reference_svg, job, size, tolerance=None, threads=None, density_map=None, scale_map=None))]
#[allow(clippy::too_many_arguments, reason = "a Python function's keyword arguments")]
fn strokes(
    py: Python<'_>,
    reference_svg: &str,
    job: &str,
    size: (f64, f64),
    tolerance: Option<f64>,
    threads: Option<usize>,
    density_map: Option<PyReadonlyArrayDyn<'_, u8>>,
    scale_map: Option<PyReadonlyArrayDyn<'_, u8>>,
) -> PyResult<(String, String)> {
    use motif_jobs::options::Declared as _;
    let mut svg_options = motif_jobs::options::SvgOptions::default();
    svg_options.tolerance = tolerance.unwrap_or(svg_options.tolerance);
    svg_options.check_ranges().map_err(job_error)?;
    let tolerance = svg_options.tolerance;
    let density_map = tone_map(density_map, "density_map")?;
    let scale_map = tone_map(scale_map, "scale_map")?;
    let job: motif_jobs::strokes::StrokesJob = description(job)?;
    let document = motif_io::parse_svg(reference_svg, std::path::Path::new("reference_svg")).map_err(value_error)?;
    let reference = motif_jobs::strokes::reference_from_svg(&document, tolerance).map_err(job_error)?;
    let inputs = motif_jobs::strokes::StrokesInputs { reference, density_map, scale_map };
    let run = detached(py, threads, || job.run(inputs, &mut NoProgress))?.map_err(job_error)?;
    let svg = motif_jobs::strokes::strokes_svg(&run.output.strokes, size.0, size.1, Some("strokes"));
    Ok((svg, report_json(&run.figures)))
}

/// Every name (flag name) a job's description holds, its fields then its options, from
/// `motif_jobs::JOBS`.
#[pyfunction]
fn options<'py>(py: Python<'py>, engine: &str) -> PyResult<Bound<'py, PyList>> {
    let entry = motif_jobs::JobEntry::named(engine).ok_or_else(|| {
        let names: Vec<&str> = motif_jobs::JOBS.iter().map(|entry| entry.name).collect();
        value_error(format!("no engine named {engine}; engines: {}", names.join(", ")))
    })?;
    PyList::new(py, entry.names())
}

/// Every job as (name, summary), in the order of `motif_jobs::JOBS`.
#[pyfunction]
fn jobs() -> Vec<(&'static str, &'static str)> {
    motif_jobs::JOBS.iter().map(|entry| (entry.name, entry.summary)).collect()
}

#[pymodule]
fn _motif(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_function(wrap_pyfunction!(read_image, module)?)?;
    module.add_function(wrap_pyfunction!(write_png, module)?)?;
    module.add_function(wrap_pyfunction!(read_points, module)?)?;
    module.add_function(wrap_pyfunction!(texture, module)?)?;
    module.add_function(wrap_pyfunction!(inpaint, module)?)?;
    module.add_function(wrap_pyfunction!(zoom, module)?)?;
    module.add_function(wrap_pyfunction!(video, module)?)?;
    module.add_function(wrap_pyfunction!(video_intervals, module)?)?;
    module.add_function(wrap_pyfunction!(video_interval, module)?)?;
    module.add_function(wrap_pyfunction!(presynth, module)?)?;
    module.add_class::<Textures>()?;
    module.add_function(wrap_pyfunction!(stylize, module)?)?;
    module.add_function(wrap_pyfunction!(curve, module)?)?;
    module.add_function(wrap_pyfunction!(points, module)?)?;
    module.add_function(wrap_pyfunction!(strokes, module)?)?;
    module.add_function(wrap_pyfunction!(tiles, module)?)?;
    module.add_function(wrap_pyfunction!(tiles_with_textures, module)?)?;
    module.add_class::<Tiles>()?;
    module.add_function(wrap_pyfunction!(options, module)?)?;
    module.add_function(wrap_pyfunction!(jobs, module)?)?;
    module.add("MotifError", module.py().get_type::<MotifError>())?;
    module.add("OptionError", module.py().get_type::<OptionError>())?;
    module.add("InputError", module.py().get_type::<InputError>())?;
    module.add("LimitError", limit_error_type(module.py())?)?;
    Ok(())
}
