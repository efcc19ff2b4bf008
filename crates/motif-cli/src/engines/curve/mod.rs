//! `motif curve`: structured patterns along curves (Zhou, Lasram, Lefebvre 2013), wired to PNG,
//! SVG and JSON files.

mod bench;
mod demo;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use motif_core::{Point, Polyline};
use motif_curve::{AlphaMode, ClosedMode, Method, PieceShape, Solver};
use motif_jobs::curve::{CurveInputs, CurveJob};
use serde_json::json;

use crate::context::Context;
use crate::gallery::Demo;

/// Options of `motif curve`.
#[derive(Args, Debug)]
pub struct CurveArgs {
    /// Exemplar image (PNG/JPEG) with alpha: opaque pixels are the pattern, on a transparent
    /// background. Repeat to mix several exemplars (up to 16): pieces may come from any of them.
    #[arg(long, value_name = "EX.png", required = true)]
    pub exemplar: Vec<PathBuf>,
    /// The curve: an SVG file (its first path's first subpath; closed if it ends with Z), or a CSV
    /// or PLY point list with x and y columns (closed if its last point repeats the first).
    #[arg(long, value_name = "CURVE.svg")]
    pub path: PathBuf,
    /// Ribbon width b in canvas pixels, > 0. Width × scale is the number of samples per piece
    /// edge (C) and should exceed the pattern's height in the exemplar. Default: inferred from
    /// the first exemplar, the pattern's height (rows with alpha above --cut-alpha) plus the
    /// clear row above and below, 15% wider, divided by the scale.
    #[arg(long, value_name = "B", allow_negative_numbers = true)]
    pub width: Option<f64>,
    /// Piece length δ along the curve in canvas pixels, > 0 and at most the curve's length.
    /// Default: inferred from the first exemplar, 0.55 of the pattern's period along x (the first
    /// strong peak of the autocorrelation of its columns), kept between a quarter and 0.6 of the
    /// pattern's height, divided by the scale; 0.3 of the pattern's height when it has no
    /// period.
    #[arg(long, value_name = "D", allow_negative_numbers = true)]
    pub piece_length: Option<f64>,
    /// Scale s: exemplar pixels per canvas pixel, 0.05–20 (2 draws the pattern at half size).
    #[arg(long, value_name = "S", default_value_t = 1.0, allow_negative_numbers = true)]
    pub scale: f64,
    /// Closed-curve handling.
    #[arg(long, value_enum, default_value = "auto")]
    pub closed: ClosedMode,
    /// Avoidance map over the canvas (PNG): opaque white pixels are forbidden to the pattern. It
    /// sets the canvas size (canvas origin = document origin).
    #[arg(long, value_name = "MASK.png")]
    pub avoid: Option<PathBuf>,
    /// Do not detect fold-overs and overlaps of the ribbon (by default the pattern avoids them).
    #[arg(long)]
    pub no_foldover_avoidance: bool,
    /// Stitch piece boundaries (edge alignment with penalty P, propagated inside the pieces).
    #[arg(long)]
    pub stitch: bool,
    /// Stitching penalty P for moving opaque samples, 0–100000.
    #[arg(long, value_name = "P", default_value_t = 32.0)]
    pub stitch_penalty: f64,
    /// Pattern generator.
    #[arg(long, value_enum, default_value = "synth")]
    pub method: Method,
    /// Dynamic-programming solver.
    #[arg(long, value_enum, default_value = "exact")]
    pub solver: Solver,
    /// Alpha in the matching cost.
    #[arg(long, value_enum, default_value = "continuous")]
    pub alpha: AlphaMode,
    /// γ, the matching cost of an opaque against a transparent pixel, 1–100000.
    #[arg(long, value_name = "GAMMA", default_value_t = 1024.0)]
    pub gamma: f64,
    /// Pin the first piece's exemplar position (top-left corner, pixels; must be a valid position).
    #[arg(long, value_name = "X,Y", value_parser = parse_pin, allow_hyphen_values = true)]
    pub pin_first: Option<[i32; 2]>,
    /// Canvas size in pixels (document origin at the top-left); default: fitted to the ribbon.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub canvas: Option<[usize; 2]>,
    /// Margin around the ribbon when the canvas is fitted, pixels, 0–4096.
    #[arg(long, value_name = "PX", default_value_t = 4.0)]
    pub margin: f64,
    /// Anti-aliasing: render samples per pixel along each axis, 1–8.
    #[arg(long, value_name = "N", default_value_t = 3)]
    pub samples: usize,
    /// Alpha (0–254) at or below which a pixel counts as transparent when checking that a piece
    /// slices the pattern completely.
    #[arg(long, value_name = "A", default_value_t = 8)]
    pub cut_alpha: u8,
    /// Minimum coverage, 0–1: a piece position is valid only if it holds at least this share of
    /// the pattern pixels a typical piece holds (the median over exemplar windows spanning the
    /// pattern's height). Keeps the optimum from repeating a thin sliver; 0 = the paper's rule.
    #[arg(long, value_name = "F", default_value_t = 0.5)]
    pub min_coverage: f64,
    /// Repetition penalty W (not in the paper), in seam-cost units, 0–10^6: each pair of pieces at
    /// most --variety-radius pieces apart that copy the same exemplar window costs W. 0 = the
    /// paper's energy, which may alternate two windows along a straight line.
    #[arg(long, value_name = "W", default_value_t = 0.0, allow_hyphen_values = true)]
    pub variety: f64,
    /// How many pieces apart a repeated window is penalised by --variety, 1–1000.
    #[arg(long, value_name = "R", default_value_t = 8)]
    pub variety_radius: usize,
    /// Piece shape: bent pieces follow the ribbon (seams compare vertical columns, so the
    /// exemplar continues across them; stretched outside bends); rigid pieces are the paper's
    /// undistorted, rotated copies.
    #[arg(long, value_enum, default_value = "bent")]
    pub pieces_shape: PieceShape,
    /// Width profile: comma-separated T:F pairs, T the fraction of the curve's length (0–1,
    /// ascending) and F the factor (0.1–10) multiplying --width there, interpolated in between;
    /// the pattern scales with the width (e.g. 0:0.5,0.5:1.5,1:0.5 swells in the middle). Needs
    /// bent pieces.
    #[arg(long, value_name = "T:F,...", value_parser = parse_profile)]
    pub width_profile: Option<WidthProfile>,
    /// Round bends of the curve tighter than F × width to that radius, so that the ribbon does
    /// not fold at cusps and corners (where the paper leaves pieces empty), 0–8; 0 keeps the
    /// curve as given.
    #[arg(long, value_name = "F", default_value_t = 0.6, allow_hyphen_values = true)]
    pub round_bends: f64,
    /// Measure the result against the exemplar (patches read back along the curve, nearest
    /// exemplar patch) and add the figures to the report and the summary.
    #[arg(long)]
    pub fidelity: bool,
    /// Exact closed mode: start positions tried at most before giving up the certificate.
    #[arg(long, value_name = "N", default_value_t = 64)]
    pub closed_max_starts: usize,
    /// Curve flattening tolerance for SVG paths, pixels, 0.001–100.
    #[arg(long, value_name = "T", default_value_t = 0.1)]
    pub tolerance: f64,
    /// Also write the result with the ribbon, piece borders, forbidden areas and per-seam cost
    /// (heat colour, green = cheap, red = expensive) drawn on top (PNG).
    #[arg(long, value_name = "OUT.png")]
    pub debug_overlay: Option<PathBuf>,
    /// Rendered pattern (PNG, transparent background).
    #[arg(long, value_name = "OUT.png")]
    pub out: PathBuf,
    /// Piece list (JSON): per piece its canvas quad, exemplar position u, rotation, seam cost and
    /// stitch remapping T.
    #[arg(long, value_name = "OUT.json")]
    pub pieces: Option<PathBuf>,
}

/// A parsed `--width-profile` (a newtype, so that clap takes it as one value).
#[derive(Debug, Clone)]
pub struct WidthProfile(pub Vec<(f64, f64)>);

fn parse_profile(text: &str) -> Result<WidthProfile, String> {
    text.split(',')
        .map(|pair| {
            let (t, f) = pair.split_once(':').ok_or_else(|| format!("{pair:?} is not T:F (e.g. 0.5:2)"))?;
            let number = |v: &str| v.trim().parse::<f64>().map_err(|_| format!("{v:?} in {pair:?} is not a number"));
            Ok((number(t)?, number(f)?))
        })
        .collect::<Result<_, _>>()
        .map(WidthProfile)
}

fn parse_pin(text: &str) -> Result<[i32; 2], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    match parts.as_slice() {
        [x, y] => Ok([
            x.parse().map_err(|_| format!("`{x}` is not an integer"))?,
            y.parse().map_err(|_| format!("`{y}` is not an integer"))?,
        ]),
        _ => Err("expected X,Y (two integers)".into()),
    }
}

fn parse_size(text: &str) -> Result<[usize; 2], String> {
    let (w, h) = text.split_once(['x', 'X']).ok_or("expected WxH, for example 800x600")?;
    let parse = |v: &str| v.trim().parse::<usize>().map_err(|_| format!("`{v}` is not a positive integer"));
    Ok([parse(w)?, parse(h)?])
}

/// Reads the curve: an SVG path or a point list.
pub fn read_curve(path: &Path, tolerance: f64) -> anyhow::Result<Polyline> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if extension == "svg" {
        let document = motif_io::read_svg(path)?;
        for svg_path in &document.paths {
            let polylines = Polyline::from_bez_path(&svg_path.path, tolerance)
                .with_context(|| format!("{}: bad curve", path.display()))?;
            if let Some(first) = polylines.into_iter().next() {
                return Ok(first);
            }
        }
        bail!("{}: the path has zero length (every subpath collapses to a point)", path.display());
    }
    let table = motif_io::read_points(path)?;
    let (Some(x), Some(y)) = (table.column("x"), table.column("y")) else {
        bail!("{}: a point list needs columns named x and y", path.display());
    };
    let mut points: Vec<Point> = (0..table.rows).map(|r| Point::new(table.row(r)[x], table.row(r)[y])).collect();
    let closed = points.len() > 2 && points.first() == points.last();
    if closed {
        points.pop();
    }
    Polyline::new(points, closed).with_context(|| format!("{}: bad curve", path.display()))
}

/// The job the arguments describe (`motif_jobs::curve` turns it into engine parameters, as it
/// does for every front end).
fn job_of(args: &CurveArgs) -> CurveJob {
    CurveJob {
        scale: Some(args.scale),
        closed: Some(args.closed),
        method: Some(args.method),
        solver: Some(args.solver),
        alpha: Some(args.alpha),
        gamma: Some(args.gamma),
        stitch: args.stitch,
        stitch_penalty: Some(args.stitch_penalty),
        no_foldover_avoidance: args.no_foldover_avoidance,
        pin_first: args.pin_first,
        canvas: args.canvas,
        margin: Some(args.margin),
        samples: Some(args.samples),
        cut_alpha: Some(args.cut_alpha),
        min_coverage: Some(args.min_coverage),
        variety: Some(args.variety),
        variety_radius: Some(args.variety_radius),
        pieces_shape: Some(args.pieces_shape),
        width_profile: args
            .width_profile
            .as_ref()
            .map_or_else(Vec::new, |p| p.0.iter().map(|&(t, f)| [t, f]).collect()),
        round_bends: Some(args.round_bends),
        closed_max_starts: Some(args.closed_max_starts),
        fidelity: args.fidelity,
        width: args.width,
        piece_length: args.piece_length,
        max_memory: None,
    }
}

/// Runs `motif curve`.
pub fn run(args: &CurveArgs, context: &mut Context) -> anyhow::Result<()> {
    let mut inputs: Vec<&Path> = args.exemplar.iter().map(PathBuf::as_path).collect();
    inputs.push(&args.path);
    inputs.extend(args.avoid.as_deref());
    for output in std::iter::once(&args.out).chain(&args.pieces).chain(&args.debug_overlay) {
        context.check_output(output, &inputs)?;
    }
    let budget = motif_io::ImageBudget::max_memory(context.max_memory);
    let exemplar = motif_io::read_image_within(&args.exemplar[0], budget)?;
    let more_exemplars = args.exemplar[1..]
        .iter()
        .map(|path| motif_io::read_image_within(path, budget))
        .collect::<Result<Vec<_>, _>>()?;
    if !(args.tolerance.is_finite() && (0.001..=100.0).contains(&args.tolerance)) {
        bail!(
            "invalid tolerance = {}: must be between 0.001 and 100 pixels",
            motif_core::error::number(args.tolerance)
        );
    }
    let curve = read_curve(&args.path, args.tolerance)?;
    let avoidance = args.avoid.as_deref().map(|path| motif_io::read_image_within(path, budget)).transpose()?;
    let inputs = CurveInputs {
        exemplar: &exemplar,
        more_exemplars: &more_exemplars,
        curve: &curve,
        avoidance: avoidance.as_ref(),
    };
    let job = CurveJob { max_memory: Some(context.max_memory), ..job_of(args) };
    let run = job.run(inputs, context.progress())?;
    let output = run.output;
    motif_io::write_png(&args.out, &output.image)?;
    if let Some(path) = &args.pieces {
        let document = json!({
            "canvas": output.report.canvas,
            "canvas_origin": output.report.canvas_origin,
            "exemplar": [exemplar.width(), exemplar.height()],
            "samples_per_edge": output.report.samples_per_edge,
            "closed": output.report.closed,
            "total_cost": output.report.total_cost,
            "pieces": output.pieces,
        });
        motif_io::write_json(path, &document)?;
    }
    if let Some(path) = &args.debug_overlay {
        motif_io::write_png(path, &motif_curve::debug_overlay(&output))?;
    }
    context.job_figures(run.figures);
    for warning in &output.report.warnings {
        context.summary(&format!("warning: {warning}"));
    }
    let fidelity = run.fidelity.map(|figures| {
        format!(
            ", patch distance {:.4} (exemplar coverage {:.0}%)",
            figures.mean_distance,
            100.0 * figures.exemplar_coverage
        )
    });
    let dimension = |d: motif_curve::Dimension| format!("{}{}", d.value, if d.inferred { " (inferred)" } else { "" });
    context.summary(&format!(
        "curve: width {}, piece length {}, {} pieces, total seam cost {:.1} (mean {:.1}), {:.1}% valid positions, {} distinct windows, DP {:.1} ms/row (median){} -> {}",
        dimension(run.dimensions.width),
        dimension(run.dimensions.piece_length),
        output.report.pieces,
        output.report.total_cost,
        output.report.mean_seam_cost,
        100.0 * output.report.valid_fraction,
        output.report.distinct_windows,
        output.report.dp_row_ms_median,
        fidelity.unwrap_or_default(),
        args.out.display()
    ));
    Ok(())
}

/// A heart as a closed SVG path centred at `(cx, cy)`, about `size` pixels wide: the classic
/// parametric heart, sampled and smoothed (circular moving averages) so that its dip and tip are
/// rounded rather than cusps.
fn heart_svg(cx: f64, cy: f64, size: f64) -> String {
    let count = 480;
    let mut points: Vec<(f64, f64)> = (0..count)
        .map(|i| {
            let t = i as f64 / count as f64 * std::f64::consts::TAU;
            let x = 16.0 * t.sin().powi(3);
            let y = -(13.0 * t.cos() - 5.0 * (2.0 * t).cos() - 2.0 * (3.0 * t).cos() - (4.0 * t).cos());
            (x, y)
        })
        .collect();
    for _ in 0..8 {
        let window = 12_i64;
        points = (0..count as i64)
            .map(|i| {
                let (mut x, mut y) = (0.0, 0.0);
                for k in -window..=window {
                    let p = points[(i + k).rem_euclid(count as i64) as usize];
                    x += p.0;
                    y += p.1;
                }
                let n = (2 * window + 1) as f64;
                (x / n, y / n)
            })
            .collect();
    }
    let scale = size / 32.0;
    let mut d = String::new();
    for (i, (x, y)) in points.iter().enumerate() {
        let command = if i == 0 { "M" } else { "L" };
        d.push_str(&format!("{command} {:.2} {:.2} ", cx + x * scale, cy + y * scale));
    }
    d.push('Z');
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0}\" height=\"{:.0}\">\
         <path d=\"{d}\" fill=\"none\" stroke=\"black\"/></svg>",
        cx * 2.0,
        cy * 2.0
    )
}

/// The curve engine in the registry.
pub struct Curve;

impl crate::registry::Engine for Curve {
    fn name(&self) -> &'static str {
        "curve"
    }

    fn demo(&self, gallery: &mut Demo<'_>) -> anyhow::Result<()> {
        demo::demo(gallery)
    }

    fn bench(&self, bench: &crate::suite::Bench) -> anyhow::Result<serde_json::Value> {
        bench::bench(bench)
    }
}
