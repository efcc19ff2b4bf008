//! `motif bench --engine strokes`.

use anyhow::bail;
use motif_core::{NoProgress, Point, Polygon, Polyline};
use motif_strokes::samples::{FigureField, HatchRow, figure_field, hatch_row};
use motif_strokes::{FitPoints, Input, Output, Params, Target, compare_clustering};
use serde_json::{Value, json};

use super::wave;
use crate::suite::Bench;

fn time_case(input: &Input, params: &Params, repeats: usize) -> anyhow::Result<(Output, f64, Vec<f64>)> {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeats {
        let start = std::time::Instant::now();
        let output = motif_strokes::synthesize(input, params, &mut NoProgress)?;
        times.push(start.elapsed().as_secs_f64() * 1000.0);
        last = Some(output);
    }
    let output = last.expect("at least one repeat");
    Ok((output, motif_core::timing::median(&times), times))
}

fn case_figures(output: &Output, total_ms: f64, target_ms: f64) -> Value {
    let r = &output.report;
    json!({
        "reference_strokes": r.reference_strokes,
        "reference_elements": r.reference_elements,
        "output_elements": r.output_elements,
        "candidate_fraction": r.candidate_fraction,
        "fallback_elements": r.fallback_elements,
        "fragment_elements": r.fragment_elements,
        "overlap": r.overlap,
        "rings": r.rings,
        "lloyd_iterations": r.lloyd_iterations,
        "total_ms_median": total_ms,
        "target_ms": target_ms,
        "meets_target": total_ms <= target_ms,
        "stages_ms": crate::context::stages_object(&r.stages_ms),
    })
}

/// `motif bench` figures: the real-data corpus (`--case corpus` or case names; see
/// [`super::corpus`]), the ε inferred from each corpus drawing (`--case scale` or case names), and
/// the generated cases (`--case generated`): a 60-element 1D hatching
/// reference along a path 10× its length, a 120-element 2D reference of three-stroke figures in a
/// region 10× its area (all stages, median of several runs), and the clustering speed-up of the
/// R-tree queue over the paper's full scan.
pub(super) fn bench(bench: &Bench) -> anyhow::Result<Value> {
    let mut all = serde_json::Map::new();
    if !bench.quick {
        let corpus = super::corpus::bench(bench.seed, &|name| bench.selects(name, "corpus"))?;
        let scale = super::corpus::scale_bench(&|name| bench.selects(name, "scale"))?;
        for (group, figures) in [("corpus", corpus), ("scale", scale)] {
            if figures.as_object().is_some_and(|cases| !cases.is_empty()) {
                all.insert(group.into(), figures);
            }
        }
    }
    if bench.selects("generated", "generated") {
        all.extend(generated(bench)?.as_object().cloned().unwrap_or_default());
    }
    Ok(Value::Object(all))
}

fn generated(bench: &Bench) -> anyhow::Result<Value> {
    let repeats = if bench.quick { 1 } else { 7 };
    let mut params = Params::default();
    params.seed = bench.seed;

    // 1D.
    let row = HatchRow { count: if bench.quick { 12 } else { 60 }, jitter: 1.5, ..HatchRow::default() };
    let hatches = hatch_row(&row, Point::ORIGIN, |i| 0.3 * (i as f64 * 0.3).sin(), |_| [20, 20, 20, 255], bench.seed);
    let length = 10.0 * row.count as f64 * row.spacing;
    let path = Polyline::from_bez_path(&wave(0.0, length, 0.0, 0.05 * length, 5), 0.05)?.remove(0);
    params.scale = 4.0;
    let input = Input::new(hatches, Target::Path(path));
    let (output, one_d_ms, _) = time_case(&input, &params, repeats)?;
    let one_d = case_figures(&output, one_d_ms, 20.0);

    // 2D.
    let field = if bench.quick {
        FigureField { columns: 4, rows: 3, ..FigureField::default() }
    } else {
        FigureField::default()
    };
    let figures = figure_field(&field, Point::ORIGIN, bench.seed);
    let side = (10.0 * (field.columns * field.rows) as f64).sqrt() * field.spacing;
    let region =
        Polygon::new(vec![Point::new(0.0, 0.0), Point::new(side, 0.0), Point::new(side, side), Point::new(0.0, side)])?;
    params.scale = 8.0;
    let input = Input::new(figures, Target::Region(region));
    let (output, two_d_ms, _) = time_case(&input, &params, repeats)?;
    let two_d = case_figures(&output, two_d_ms, 200.0);

    // Clustering: R-tree queue against the paper's full scan, on a long sketchy hatching.
    let big = HatchRow { count: if bench.quick { 50 } else { 800 }, ..HatchRow::default() };
    let strokes = hatch_row(&big, Point::ORIGIN, |i| 0.2 * (i as f64 * 0.1).sin(), |_| [0, 0, 0, 255], bench.seed);
    let clustering = compare_clustering(&strokes, FitPoints::Skeleton, 4.0);
    if !clustering.agree {
        bail!("the R-tree clustering disagrees with the full scan");
    }
    Ok(json!({
        "path_1d": one_d,
        "region_2d": two_d,
        "clustering": {
            "strokes": clustering.strokes,
            "elements": clustering.elements,
            "rtree_ms": clustering.rtree_ms,
            "full_scan_ms": clustering.full_scan_ms,
            "speedup": clustering.full_scan_ms / clustering.rtree_ms.max(1e-9),
        },
    }))
}
