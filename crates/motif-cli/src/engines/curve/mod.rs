//! `motif curve`: structured patterns along curves (Zhou, Lasram, Lefebvre 2013), wired to PNG,
//! SVG and JSON files.

mod bench;
mod demo;

use std::ffi::{OsStr, OsString};
use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use motif_core::{Point, Polyline};
use motif_jobs::Job;
use motif_jobs::curve::{CurveInputs, CurveJob, CurveOptions};
use motif_jobs::options::{Declared as _, SvgOptions};
use serde_json::json;

use crate::context::Context;
use crate::gallery::Demo;
use crate::job_args::JobArgs;

/// Options of `motif curve`: its files, the flattening tolerance of an SVG curve, and the job's
/// options ([`CurveOptions`], declared in `motif_jobs::curve`).
#[derive(Args, Debug)]
pub struct CurveArgs {
    /// Exemplar image (PNG/JPEG/WebP) with alpha: opaque pixels are the pattern, on a transparent
    /// background. Repeat to mix several exemplars (up to 16): pieces may come from any of them.
    #[arg(long, value_name = "EX.png", required = true)]
    pub exemplar: Vec<PathBuf>,
    /// The curve: an SVG file (its first path's first subpath; closed if it ends with Z), or a CSV
    /// or PLY point list with x and y columns (closed if its last point repeats the first).
    #[arg(long, value_name = "CURVE.svg")]
    pub path: PathBuf,
    /// Avoidance map over the canvas (PNG): opaque white pixels are forbidden to the pattern. It
    /// sets the canvas size (canvas origin = document origin).
    #[arg(long, value_name = "MASK.png")]
    pub avoid: Option<PathBuf>,
    /// A start tile from an image of its own (PNG with alpha; its whole pattern), in place of
    /// --start-tile's columns of the exemplar: an end cap or a clasp drawn as the first piece.
    #[arg(long, value_name = "TILE.png")]
    pub start_tile_image: Option<PathBuf>,
    /// An end tile from an image of its own, drawn whole as the last piece.
    #[arg(long, value_name = "TILE.png")]
    pub end_tile_image: Option<PathBuf>,
    /// A corner tile from an image of its own, drawn whole at every corner sharper than
    /// --corner-angle.
    #[arg(long, value_name = "TILE.png")]
    pub corner_tile_image: Option<PathBuf>,
    /// Every option of the job.
    #[command(flatten)]
    pub options: JobArgs<CurveOptions>,
    /// How SVG curves are flattened ([`SvgOptions`], declared in `motif_jobs::options`).
    #[command(flatten)]
    pub svg: JobArgs<SvgOptions>,
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

/// The tile flags: `--start-tile`, `--end-tile` and `--corner-tile` take columns X0,X1 of the
/// exemplar (the declared option) or, on the command line, a PNG file of the tile, which is the
/// matching `--…-tile-image` flag's.
const TILE_FLAGS: [&str; 3] = ["--start-tile", "--end-tile", "--corner-tile"];

/// The command line with every tile flag whose value is a PNG file turned into the tile image
/// flag (`--corner-tile link.png` is `--corner-tile-image link.png`); everything else as given.
pub(crate) fn tile_files_as_image_flags(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    let is_png = |value: &OsStr| Path::new(value).extension().is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let mut out = Vec::new();
    let mut args = args.into_iter().peekable();
    while let Some(arg) = args.next() {
        let text = arg.to_string_lossy().into_owned();
        let image_flag = |flag: &str| format!("{flag}-image");
        if TILE_FLAGS.contains(&text.as_str()) && args.peek().is_some_and(|value| is_png(value)) {
            out.push(image_flag(&text).into());
            continue;
        }
        if let Some((flag, value)) = text.split_once('=')
            && TILE_FLAGS.contains(&flag)
            && is_png(OsStr::new(value))
        {
            out.push(format!("{}={value}", image_flag(flag)).into());
            continue;
        }
        out.push(arg);
    }
    out
}

/// Reads the curve: an SVG path or a point list.
pub(crate) fn read_curve(path: &Path, tolerance: f64) -> anyhow::Result<Polyline> {
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

/// Runs `motif curve`.
pub(crate) fn run(args: &CurveArgs, context: &mut Context) -> anyhow::Result<()> {
    let mut inputs: Vec<&Path> = args.exemplar.iter().map(PathBuf::as_path).collect();
    inputs.push(&args.path);
    inputs.extend(args.avoid.as_deref());
    let tile_paths = [&args.start_tile_image, &args.end_tile_image, &args.corner_tile_image];
    inputs.extend(tile_paths.iter().filter_map(|path| path.as_deref()));
    for output in std::iter::once(&args.out).chain(&args.pieces).chain(&args.debug_overlay) {
        context.check_output(output, &inputs)?;
    }
    let budget = motif_io::ImageBudget::max_memory(context.max_memory);
    let exemplar = motif_io::read_image_within(&args.exemplar[0], budget)?;
    let more_exemplars = args.exemplar[1..]
        .iter()
        .map(|path| motif_io::read_image_within(path, budget))
        .collect::<Result<Vec<_>, _>>()?;
    args.svg.options.check_ranges()?;
    let curve = read_curve(&args.path, args.svg.options.tolerance)?;
    let avoidance = args.avoid.as_deref().map(|path| motif_io::read_image_within(path, budget)).transpose()?;
    let tiles: Vec<Option<_>> = tile_paths
        .iter()
        .map(|path| path.as_deref().map(|path| motif_io::read_image_within(path, budget)).transpose())
        .collect::<Result<_, _>>()?;
    let inputs = CurveInputs {
        exemplar: &exemplar,
        more_exemplars: &more_exemplars,
        curve: &curve,
        avoidance: avoidance.as_ref(),
        tile_images: [tiles[0].as_ref(), tiles[1].as_ref(), tiles[2].as_ref()],
    };
    // `motif_jobs::curve` turns the job into engine parameters, as it does for every front end.
    let job = CurveJob { max_memory: Some(context.max_memory), options: args.options.options.clone() };
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
        motif_io::write_png(path, &motif_jobs::curve::debug_overlay(&output))?;
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
    let dimension =
        |d: motif_jobs::curve::Dimension| format!("{}{}", d.value, if d.inferred { " (inferred)" } else { "" });
    let report = &output.report;
    let fit = match report.fit {
        motif_jobs::curve::Fit::None => String::new(),
        motif_jobs::curve::Fit::Stretch => format!(" (stretched to {:.1})", report.fitted_piece_length),
        _ => format!(" (spaced by {:.1})", report.fit_gap),
    };
    let corners = if args.options.corner_tile.is_some() || args.corner_tile_image.is_some() {
        format!(", {} corner tile{}", report.corner_tiles, if report.corner_tiles == 1 { "" } else { "s" })
    } else {
        String::new()
    };
    let closed = match (report.closed_certified, report.closed_gap) {
        (Some(true), _) => ", closed cycle certified optimal".to_string(),
        (Some(false), Some(gap)) => format!(
            ", closed cycle within {:.2}% of the optimum (not certified after {} starts)",
            100.0 * gap,
            report.closed_starts_tried
        ),
        _ => String::new(),
    };
    let trials = match run.size_trials.len() {
        0 | 1 => String::new(),
        n => format!(", best of {n} size trials"),
    };
    context.summary(&format!(
        "curve: width {}, piece length {}{fit}{trials}, {} pieces{corners}, total seam cost {:.1} (mean {:.1}){closed}, {:.1}% valid positions, {} distinct windows, DP {:.1} ms/row (median){} -> {}",
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
pub(crate) struct Curve;

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

#[cfg(test)]
mod tests {
    use std::ffi::OsString;

    use super::tile_files_as_image_flags;

    fn rewritten(args: &[&str]) -> Vec<String> {
        let args = args.iter().map(OsString::from);
        tile_files_as_image_flags(args).into_iter().map(|a| a.into_string().unwrap()).collect()
    }

    #[test]
    fn a_png_given_to_a_tile_flag_is_the_tile_image() {
        assert_eq!(
            rewritten(&["motif", "curve", "--corner-tile", "link.PNG", "--start-tile", "0,64", "--end-tile=cap.png"]),
            ["motif", "curve", "--corner-tile-image", "link.PNG", "--start-tile", "0,64", "--end-tile-image=cap.png"]
        );
        // Columns, other flags and a PNG given to another flag stay as they are.
        let kept = ["motif", "curve", "--exemplar", "e.png", "--end-tile", "3,9", "--out", "out.png"];
        assert_eq!(rewritten(&kept), kept);
    }
}
