//! `motif strokes`: vector stroke pattern analysis and synthesis along a path or in a region
//! (Barla et al. 2006), wired to SVG files.

mod bench;
mod corpus;
mod demo;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use kurbo::BezPath;
use motif_core::{Point, Polyline};
use motif_io::SvgWriter;
use motif_jobs::Job;
use motif_jobs::options::{Declared as _, SvgOptions};
use motif_jobs::strokes::{
    Analysis, RunScale, Stroke, StrokesInputs, StrokesJob, StrokesOptions, StrokesRun, Target, TargetSpec, ToneMap,
    draw_stroke, reference_from_svg, strokes_svg,
};

use crate::context::Context;
use crate::gallery::Demo;
use crate::job_args::JobArgs;

/// Options of `motif strokes`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("target").required(true).args(["along", "region", "rect"])))]
pub struct StrokesArgs {
    /// Reference drawing (SVG): every stroked or filled path is a stroke, with its width and colour,
    /// in drawing order.
    #[arg(long, value_name = "REF.svg")]
    pub reference: PathBuf,
    /// ε, the pattern's scale in drawing units: strokes closer than this (or continuing each other
    /// within it) form one element. Must be > 0. Default: inferred from the reference, in the
    /// widest gap between the distances at which its strokes join (the summary and the report
    /// give it); check it with --analysis and give it to override.
    #[arg(long = "scale", value_name = "EPS", allow_negative_numbers = true)]
    pub scale: Option<f64>,
    /// Synthesize a 1D pattern along the first path of this SVG (its first subpath).
    #[arg(long, value_name = "PATH.svg")]
    pub along: Option<PathBuf>,
    /// Synthesize a 2D pattern inside the first closed path of this SVG (a simple polygon).
    #[arg(long, value_name = "SHAPE.svg")]
    pub region: Option<PathBuf>,
    /// Synthesize a 2D pattern inside the rectangle (0, 0)–(W, H), in drawing units.
    #[arg(long, value_name = "W,H", value_parser = parse_rect)]
    pub rect: Option<(f64, f64)>,
    /// Every option of the synthesis, declared in `motif_jobs::strokes::StrokesOptions`.
    #[command(flatten)]
    pub options: JobArgs<StrokesOptions>,
    /// Density map (an image stretched over the target region's bounding box, with its aspect
    /// ratio): darkness sets the element density relative to the reference's (black: the
    /// reference's density, mid-grey: half, white: none), so a hatching or stippling can shade a
    /// photo. Grey is the pixel's luma over white.
    #[arg(long, value_name = "MAP.png")]
    pub density_map: Option<PathBuf>,
    /// Scale map (an image over the target region's bounding box): element scale 2^(2·grey − 1),
    /// black 0.5, mid-grey 1, white 2, stroke widths included; larger elements are spaced further
    /// apart.
    #[arg(long, value_name = "MAP.png")]
    pub scale_map: Option<PathBuf>,
    /// How SVG curves are flattened ([`SvgOptions`], declared in `motif_jobs::options`).
    #[command(flatten)]
    pub svg: JobArgs<SvgOptions>,
    /// Also draw the analysed reference here (SVG): each element's strokes in its cluster colour,
    /// its box, and the neighbourhood graph between element centres.
    #[arg(long, value_name = "ANALYSIS.svg")]
    pub analysis: Option<PathBuf>,
    /// The synthesized pattern (SVG).
    #[arg(long, value_name = "OUT.svg")]
    pub out: PathBuf,
    /// Also render the output to PNG (with resvg).
    #[arg(long, value_name = "OUT.png")]
    pub png: Option<PathBuf>,
    /// Pixels per drawing unit of the PNG, > 0.
    #[arg(long, value_name = "S", default_value_t = 1.0)]
    pub png_scale: f64,
}

fn parse_rect(text: &str) -> Result<(f64, f64), String> {
    let parts: Vec<&str> = text.split(',').collect();
    let [w, h] = parts.as_slice() else { return Err(format!("expected W,H (two numbers), got `{text}`")) };
    let number = |s: &str| s.trim().parse::<f64>().map_err(|_| format!("`{s}` is not a number"));
    Ok((number(w)?, number(h)?))
}

/// The job the arguments describe, for `target` (`motif_jobs::strokes` turns it into engine
/// parameters, as it does for every front end).
fn job_of(args: &StrokesArgs, seed: u64, target: TargetSpec) -> StrokesJob {
    StrokesJob { seed, options: args.options.options.clone(), ..StrokesJob::new(args.scale, target) }
}

fn first_subpath(path: &BezPath, tolerance: f64) -> anyhow::Result<Option<Polyline>> {
    Ok(Polyline::from_bez_path(path, tolerance)?.into_iter().next())
}

fn read_target(args: &StrokesArgs) -> anyhow::Result<(TargetSpec, f64, f64)> {
    let listed = |polyline: &Polyline| -> Vec<[f64; 2]> {
        let mut points: Vec<[f64; 2]> = polyline.points().iter().map(|p| [p.x, p.y]).collect();
        // A closed path is listed with its first point repeated at the end.
        if polyline.is_closed()
            && let Some(&first) = points.first()
        {
            points.push(first);
        }
        points
    };
    if let Some(file) = &args.along {
        let document = motif_io::read_svg(file)?;
        for path in &document.paths {
            if let Some(polyline) = first_subpath(&path.path, args.svg.options.tolerance)? {
                return Ok((TargetSpec::Along(listed(&polyline)), document.width, document.height));
            }
        }
        bail!("{}: no path with a length > 0 to synthesize along", file.display());
    }
    if let Some(file) = &args.region {
        let document = motif_io::read_svg(file)?;
        for path in &document.paths {
            let Some(outline) = first_subpath(&path.path, args.svg.options.tolerance)? else { continue };
            if !outline.is_closed() {
                continue;
            }
            // Checked here too, so that the error names the file and the path.
            motif_jobs::strokes::region_from_outline(outline.points().to_vec())
                .with_context(|| format!("{}: the region (path `{}`) cannot be used", file.display(), path.id))?;
            let points = outline.points().iter().map(|p| [p.x, p.y]).collect();
            return Ok((TargetSpec::Region(points), document.width, document.height));
        }
        bail!("{}: no closed path (one ending with Z, or a rect, circle, ellipse or polygon) to fill", file.display());
    }
    let (width, height) = args.rect.expect("clap requires one target");
    if !(width.is_finite() && height.is_finite() && width > 0.0 && height > 0.0) {
        bail!("invalid rect = {width},{height}: the target region needs a width and a height > 0");
    }
    Ok((TargetSpec::Rect([width, height]), width, height))
}

/// A density or scale map read from `file` within `max_memory`, checked against the job's target.
fn read_map(file: Option<&Path>, flag: &str, job: &StrokesJob, max_memory: u64) -> anyhow::Result<Option<ToneMap>> {
    let Some(file) = file else { return Ok(None) };
    let map = ToneMap::from_image(&motif_io::read_image_within(file, motif_io::ImageBudget::map(max_memory))?);
    match job.engine_target()? {
        Target::Region(region) => {
            map.check_fits(&region.bounds(), &format!("{flag} {}", file.display())).map_err(anyhow::Error::from)?
        }
        Target::Path(_) => {
            bail!("{flag} {}: maps need a region target (--region or --rect), not --along", file.display())
        }
    }
    Ok(Some(map))
}

/// A distinct colour per cluster (golden-angle hues).
fn cluster_colour(index: usize) -> [u8; 4] {
    let hue = (index as f64 * 137.507_764).rem_euclid(360.0) / 60.0;
    let x = 1.0 - (hue.rem_euclid(2.0) - 1.0).abs();
    let (r, g, b) = match hue as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    let channel = |v: f64| (40.0 + 170.0 * v).round() as u8;
    [channel(r), channel(g), channel(b), 255]
}

/// The analysed reference as SVG: strokes in cluster colours, element boxes, neighbour graph.
/// `scale` is ε as the label shows it.
pub(crate) fn analysis_svg(analysis: &Analysis, strokes: &[Stroke], width: f64, height: f64, scale: &str) -> String {
    let mut writer = SvgWriter::new(width, height);
    let thin = (0.01 * width.max(height)).clamp(0.3, 1.0);
    writer.begin_group("graph");
    let grey = motif_io::StrokePaint { width: thin, colour: [120, 120, 120, 200] };
    for (a, b) in analysis.graph.edges() {
        let (p, q) = (analysis.elements[a].frame.centre, analysis.elements[b].frame.centre);
        writer.polyline(&[p, q], false, Some(grey), None);
    }
    writer.end_group();
    for (index, element) in analysis.elements.iter().enumerate() {
        let colour = cluster_colour(index);
        writer.begin_group(&format!("element-{index}"));
        for &s in &element.strokes {
            let mut stroke = strokes[s].clone();
            stroke.colour = colour;
            stroke.fill = stroke.fill.map(|_| [colour[0], colour[1], colour[2], 90]);
            draw_stroke(&mut writer, &stroke);
        }
        let mut frame = element.frame;
        // Degenerate boxes (single straight strokes) still show as a thin rectangle.
        frame.thickness = frame.thickness.max(thin);
        frame.length = frame.length.max(thin);
        writer.polyline(&frame.corners(), true, Some(motif_io::StrokePaint { width: 0.5 * thin, colour }), None);
        writer.circle(element.frame.centre, 1.5 * thin, None, Some(colour));
        writer.end_group();
    }
    let label = format!(
        "ε = {scale}: {} strokes → {} elements, {} neighbour edges",
        strokes.len(),
        analysis.elements.len(),
        analysis.graph.edges().count()
    );
    writer.text(Point::new(4.0, 4.0 + 3.0 * thin.max(3.0)), 3.0 * thin.max(3.0), [40, 40, 40, 255], &label);
    writer.finish()
}

/// `value` to three significant figures (an inferred ε in the summary: 6.24, 0.512, 112).
fn three_figures(value: f64) -> String {
    let decimals = (2 - value.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{value:.decimals$}")
}

/// The run's ε as the summary and the analysis drawing show it: `6 (given)`, `6.99 (inferred)`.
fn shown_scale(scale: &RunScale) -> String {
    match scale.inferred {
        Some(_) => format!("{} (inferred)", three_figures(scale.value)),
        None => format!("{} (given)", motif_core::error::number(scale.value)),
    }
}

/// The one-line summary of a run written to `out`.
fn summary(run: &StrokesRun, out: &Path) -> String {
    let report = &run.output.report;
    format!(
        "motif strokes: ε {}; {} reference strokes → {} elements ({} cut by the frame, not copied); {} output elements ({} matched within thresholds, {} fell back, {} removed to avoid overlaps) → {}",
        shown_scale(&run.scale),
        report.reference_strokes,
        report.reference_elements,
        report.fragment_elements,
        report.output_elements,
        report.matched_elements,
        report.fallback_elements,
        report.overlap.removed,
        out.display()
    )
}

/// Runs `motif strokes`.
pub(crate) fn run(args: &StrokesArgs, context: &mut Context) -> anyhow::Result<()> {
    let mut inputs: Vec<&Path> = vec![&args.reference];
    inputs.extend(args.along.as_deref());
    inputs.extend(args.region.as_deref());
    inputs.extend(args.density_map.as_deref());
    inputs.extend(args.scale_map.as_deref());
    context.check_output(&args.out, &inputs)?;
    for extra in args.png.iter().chain(&args.analysis) {
        context.check_output(extra, &inputs)?;
    }
    if !(args.png_scale.is_finite() && args.png_scale > 0.0) {
        bail!("invalid png-scale = {}: must be a finite number > 0", args.png_scale);
    }
    args.svg.options.check_ranges()?;
    // The options are checked before any file is read (the target is not needed for that).
    job_of(args, context.seed, TargetSpec::Rect([1.0, 1.0])).params()?;
    let reference = motif_io::read_svg(&args.reference)?;
    let strokes = reference_from_svg(&reference, args.svg.options.tolerance)
        .with_context(|| format!("cannot read the reference {}", args.reference.display()))?;
    let (target, width, height) = read_target(args)?;
    let job = StrokesJob { max_memory: Some(context.max_memory), ..job_of(args, context.seed, target) };
    let density_map = read_map(args.density_map.as_deref(), "--density-map", &job, context.max_memory)?;
    let scale_map = read_map(args.scale_map.as_deref(), "--scale-map", &job, context.max_memory)?;
    let shown_strokes = args.analysis.as_ref().map(|_| strokes.clone());
    let run = job
        .run(StrokesInputs { reference: strokes, density_map, scale_map }, context.progress())
        .with_context(|| format!("cannot synthesize from {}", args.reference.display()))?;
    let output = &run.output;
    let svg = strokes_svg(&output.strokes, width, height, Some("strokes"));
    motif_io::write_text(&args.out, &svg)?;
    if let Some(png) = &args.png {
        context.check_render(output.report.estimated_memory_bytes, &svg, args.png_scale)?;
        let image = motif_io::render_svg(&svg, args.png_scale, &args.out)?;
        motif_io::write_png(png, &image)?;
    }
    if let (Some(path), Some(strokes)) = (&args.analysis, &shown_strokes) {
        let scale = shown_scale(&run.scale);
        let text = analysis_svg(&output.analysis, strokes, reference.width, reference.height, &scale);
        motif_io::write_text(path, &text)?;
    }
    context.summary(&summary(&run, &args.out));
    context.job_figures(run.figures);
    Ok(())
}

fn write_strokes_svg(path: &Path, strokes: &[Stroke], width: f64, height: f64) -> anyhow::Result<()> {
    motif_io::write_text(path, &strokes_svg(strokes, width, height, None))?;
    Ok(())
}

/// A gently waving curve from `(x0, y)` to `(x1, y)` as a cubic Bézier path.
fn wave(x0: f64, x1: f64, y: f64, amplitude: f64, waves: usize) -> BezPath {
    let mut path = BezPath::new();
    path.move_to((x0, y));
    let step = (x1 - x0) / waves as f64;
    for i in 0..waves {
        let a = x0 + i as f64 * step;
        let sign = if i % 2 == 0 { -1.0 } else { 1.0 };
        path.curve_to((a + 0.35 * step, y + sign * amplitude), (a + 0.65 * step, y + sign * amplitude), (a + step, y));
    }
    path
}

/// A five-lobed blob region (a closed polygon of 120 points) centred at `(cx, cy)`.
fn blob(cx: f64, cy: f64, radius: f64) -> BezPath {
    let mut path = BezPath::new();
    for i in 0..120 {
        let angle = std::f64::consts::TAU * i as f64 / 120.0;
        let r = radius * (1.0 + 0.15 * (5.0 * angle).cos());
        let point = Point::new(cx + r * angle.cos(), cy + r * angle.sin());
        if i == 0 { path.move_to(point) } else { path.line_to(point) }
    }
    path.close_path();
    path
}

/// The strokes engine in the registry.
pub(crate) struct Strokes;

impl crate::registry::Engine for Strokes {
    fn name(&self) -> &'static str {
        "strokes"
    }

    fn demo(&self, gallery: &mut Demo<'_>) -> anyhow::Result<()> {
        demo::demo(gallery)
    }

    fn bench(&self, bench: &crate::suite::Bench) -> anyhow::Result<serde_json::Value> {
        bench::bench(bench)
    }
}
