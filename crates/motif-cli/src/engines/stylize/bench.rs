//! `motif bench --engine stylize`: CPU-seconds per megapixel on the two ebsynth-like workloads,
//! the paper's Table 1 (pre-synthesized textures, band sizes) and PatchMatch against the exact
//! search.

use std::path::Path;

use motif_core::{ByteImage, FloatImage, NoProgress};
use motif_stylize::{
    Guide, Input, NnfMethod, Output, Params, PresynthInput, Segmentation, presynthesize, samples, synthesize,
};
use serde_json::{Map, Value, json};

use crate::suite::Bench;

/// Process CPU time (user + system) in seconds, from `/proc/self/stat` (Linux); `None` elsewhere.
fn cpu_seconds() -> Option<f64> {
    let text = motif_io::read_text(Path::new("/proc/self/stat")).ok()?;
    // Fields after the parenthesized command name; utime and stime are fields 14 and 15.
    let rest = &text[text.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// A seeded guide/style pair of `size`² with `guide_channels` (3 or 10) guide channels.
fn bench_pair(size: usize, guide_channels: usize, seed: u64) -> Input {
    let source = samples::map_guide(size, size, 5, seed);
    let target = samples::map_guide(size, size, 5, seed + 1);
    let style = samples::crayon_style(&source, seed + 2);
    let mut guides = vec![Guide { source, target, weight: None }];
    if guide_channels == 10 {
        for (channels, offset) in [(4, 3), (3, 5)] {
            guides.push(Guide {
                source: samples::smooth_field(size, size, channels, seed + offset),
                target: samples::smooth_field(size, size, channels, seed + offset + 1),
                weight: None,
            });
        }
    }
    Input::guided(style, guides)
}

/// One synthesis, its wall-clock seconds and the process's CPU-seconds (where known).
pub(super) fn timed<I: motif_core::ChannelImage>(
    input: &Input<I>,
    params: &Params,
) -> anyhow::Result<(Output, f64, Option<f64>)> {
    let cpu_start = cpu_seconds();
    let start = std::time::Instant::now();
    let output = synthesize(input, params, &mut NoProgress)?;
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu_start.and_then(|s| cpu_seconds().map(|e| e - s));
    Ok((output, wall, cpu))
}

/// Figures for `motif bench`: CPU-seconds per megapixel on the two ebsynth-like workloads,
/// Table 1 (band 0/2/4/8/full on a 360×360 5-segment map, one thread), PatchMatch/exact energy.
pub(super) fn bench(bench: &Bench) -> anyhow::Result<Value> {
    // `--case 0.15mp`, `1mp`, `table1`, `exact` or `memory` runs only those parts (default: all).
    let selected = |key: &str| bench.selects(key, "generated");
    let mut figures = Map::new();
    let cases: [(&str, &str, usize, usize, usize); 2] = if bench.quick {
        [("0.15mp", "rgb_guide_patch3", 64, 3, 3), ("1mp", "ten_guide_channels_patch5", 64, 10, 5)]
    } else {
        [("0.15mp", "rgb_guide_patch3_0.15mp", 388, 3, 3), ("1mp", "ten_guide_channels_patch5_1mp", 1000, 10, 5)]
    };
    for (key, name, size, guide_channels, patch) in cases {
        if !selected(key) {
            continue;
        }
        let input = bench_pair(size, guide_channels, bench.seed);
        let mut params = Params::default();
        params.patch_size = patch;
        params.seed = bench.seed;
        let (output, wall, cpu) = timed(&input, &params)?;
        let megapixels = (size * size) as f64 / 1e6;
        figures.insert(
            name.to_string(),
            json!({
                "size": [size, size],
                "channels": { "style": 3, "guide": guide_channels },
                "patch_size": patch,
                "wall_s": wall,
                "cpu_s": cpu,
                "cpu_s_per_megapixel": cpu.map(|c| c / megapixels),
                "wall_s_per_megapixel": wall / megapixels,
                "energy": output.report.energy,
                "source_coverage": output.report.source_coverage,
                "ebsynth_cpu_s_per_megapixel": if guide_channels == 3 { "about 36" } else { "150-210" },
            }),
        );
    }

    if selected("table1") {
        figures.insert("table_1".into(), table_1(bench)?);
    }
    if selected("exact") {
        figures.insert("patchmatch_vs_exact".into(), patchmatch_vs_exact(bench)?);
    }
    if selected("memory") {
        figures.insert("memory_0.8mp_three_guides".into(), memory(bench)?);
    }
    if bench.names("video") {
        figures.insert("video".into(), super::video_bench::video(bench)?);
    }
    if bench.names("structure") {
        figures.insert("structure".into(), structure(bench)?);
    }
    if bench.names("tiles") {
        figures.insert("tiles".into(), super::tiles_bench::tiles(bench)?);
    }
    if bench.names("texture-native") {
        figures.insert("texture_native".into(), super::native_bench::texture_native(bench)?);
    }
    Ok(Value::Object(figures))
}

/// Peak memory on ebsynth's `facestyle` shape (issue 16): a 900 × 900 style (0.81 MP) with three
/// guides, two grey and one RGB, to a 900 × 900 target. The peak is the process's resident memory
/// while the inputs are held and the synthesis runs (Linux; the bench's own baseline included);
/// ebsynth peaks at about 91 MB on that example.
fn memory(bench: &Bench) -> anyhow::Result<Value> {
    let size = if bench.quick { 200 } else { 900 };
    // 8-bit, as the front ends decode PNGs; each float sample is dropped once converted.
    let bytes = |image: FloatImage| ByteImage::from_float(&image);
    let grey = |seed: u64| bytes(samples::smooth_field(size, size, 1, seed));
    let source = samples::map_guide(size, size, 5, bench.seed);
    let target = bytes(samples::map_guide(size, size, 5, bench.seed + 1));
    let style = bytes(samples::crayon_style(&source, bench.seed + 2));
    let source = bytes(source);
    let guides = vec![
        Guide { source: grey(bench.seed + 3), target: grey(bench.seed + 4), weight: None },
        Guide { source: grey(bench.seed + 5), target: grey(bench.seed + 6), weight: None },
        Guide { source, target, weight: None },
    ];
    let input = Input::guided(style, guides);
    let params = Params::default().with_seed(bench.seed);
    let before = motif_io::peak_memory();
    let reset = motif_io::reset_peak_memory();
    let (output, wall, _) = timed(&input, &params)?;
    let peak = if reset { motif_io::peak_memory() } else { None };
    Ok(json!({
        "size": [size, size],
        "channels": { "style": 3, "guide": 5 },
        "peak_resident_bytes": peak,
        "peak_before_the_case_bytes": before,
        "estimated_memory_bytes": output.report.estimated_memory_bytes,
        "wall_s": wall,
        "ebsynth_peak_bytes": "about 91 MB (facestyle)",
    }))
}

/// Structure on the real textures of `data/real/stylize` (run with `--case structure`): each grown
/// to twice its size with 5 × 5 patches (the default), with 9 × 9 and 15 × 15 ones, and with
/// patches from 11 × 11 or 15 × 15 at the coarsest level down to 5 × 5 (`coarse_patch_size`), and the
/// nearest-patch distance at 15 × 15 (`motif_stylize::nearest_patch_distance`, 8-bit units
/// squared, 100 output patches) of each, its sharpness over the exemplar's (below 1: washed out;
/// the distance alone rewards blur) and seconds.
fn structure(bench: &Bench) -> anyhow::Result<Value> {
    let folder = crate::suite::corpus_folder("stylize");
    let mut figures = Map::new();
    for (name, kind) in [
        ("brick", "regular"),
        ("burlap", "regular"),
        ("parque1", "regular"),
        ("parque2", "regular"),
        ("walnut", "directional"),
        ("bark", "irregular"),
        ("stone33", "irregular"),
        ("leaves", "irregular"),
    ] {
        let image = motif_io::read_image(&folder.join(format!("{name}.png")))?;
        // 8-bit, as `motif texture` hands it to the engine; the figures read it as floats.
        let bytes = motif_jobs::stylize::style_image_channels(&image);
        let exemplar = bytes.to_float();
        let (width, height) = (2 * exemplar.width(), 2 * exemplar.height());
        let mut runs = Map::new();
        let side = exemplar.width().min(exemplar.height());
        // Columns: name, patch side, coarsest patch side, structure weight, quilt block.
        for (name, patch, coarse, structure, quilt) in [
            ("patch_5", 5, 0, 0.0, 0),
            ("patch_9", 9, 0, 0.0, 0),
            ("patch_15", 15, 0, 0.0, 0),
            ("coarse_11", 5, 11, 0.0, 0),
            ("coarse_15", 5, 15, 0.0, 0),
            ("structure_3", 5, 0, 3.0, 0),
            ("coarse_11_structure_1", 5, 11, 1.0, 0),
            ("coarse_11_structure_3", 5, 11, 3.0, 0),
            ("coarse_11_structure_10", 5, 11, 10.0, 0),
            ("quilt_third", 5, 0, 0.0, (side / 3).max(8)),
            ("quilt_half", 5, 0, 0.0, (side / 2).max(8)),
        ] {
            let params = Params::default()
                .with_seed(bench.seed)
                .with_patch_size(patch)
                .with_coarse_patch_size(coarse)
                .with_structure_weight(structure)
                .with_quilt_block(quilt);
            let input = Input::texture(bytes.clone(), width, height);
            let (output, wall, _) = timed(&input, &params)?;
            let distance = motif_stylize::nearest_patch_distance(&output.image, &exemplar, 15, 100);
            let sharpness = motif_stylize::sharpness(&output.image) / motif_stylize::sharpness(&exemplar).max(1e-9);
            let elements = motif_stylize::mean_feature_distance(&output.image)
                / motif_stylize::mean_feature_distance(&exemplar).max(1e-9);
            let (lines, exemplar_lines) =
                (motif_stylize::line_contrast(&output.image), motif_stylize::line_contrast(&exemplar));
            let line_ratios = [lines[0] / exemplar_lines[0].max(1e-9), lines[1] / exemplar_lines[1].max(1e-9)];
            runs.insert(
                name.to_string(),
                json!({
                    "nearest_patch_distance_15": distance,
                    "sharpness_ratio": sharpness,
                    "feature_distance_ratio": elements,
                    "line_contrast_ratio_rows_columns": line_ratios,
                    "wall_s": wall,
                }),
            );
        }
        runs.insert("kind".into(), json!(kind));
        runs.insert("size".into(), json!([width, height]));
        figures.insert(name.into(), Value::Object(runs));
    }
    Ok(Value::Object(figures))
}

/// Table 1: pre-synthesized textures, band sizes, on one thread.
fn table_1(bench: &Bench) -> anyhow::Result<Value> {
    let size = if bench.quick { 96 } else { 360 };
    let source_guide = samples::map_guide(size, size, 5, bench.seed + 10);
    let target_guide = samples::map_guide(size, size, 5, bench.seed + 11);
    let style = samples::crayon_style(&source_guide, bench.seed + 12);
    let mut params = Params::default();
    params.seed = bench.seed;
    params.segments = Some(Segmentation::Palette);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let table = pool.install(|| -> anyhow::Result<Value> {
        let presynth_start = std::time::Instant::now();
        let texture_size = if bench.quick { 48 } else { 128 };
        let textures = presynthesize(
            &PresynthInput { style: style.clone(), guide: source_guide.clone(), size: (texture_size, texture_size) },
            &params,
            &mut NoProgress,
        )?;
        let presynth_ms = presynth_start.elapsed().as_secs_f64() * 1000.0;
        let guided = Input::guided(
            style.clone(),
            vec![Guide { source: source_guide.clone(), target: target_guide.clone(), weight: None }],
        );
        let mut rows = Map::new();
        for band in [0, 2, 4, 8] {
            let mut input = guided.clone();
            input.textures = Some(textures.clone().into());
            let mut banded = params.clone();
            banded.band = band;
            let start = std::time::Instant::now();
            let output = synthesize(&input, &banded, &mut NoProgress)?;
            rows.insert(
                format!("band_{band}"),
                json!({ "ms": start.elapsed().as_secs_f64() * 1000.0, "optimized_pixels": output.report.searched_pixels }),
            );
        }
        let start = std::time::Instant::now();
        let output = synthesize(&guided, &params, &mut NoProgress)?;
        rows.insert(
            "full".into(),
            json!({ "ms": start.elapsed().as_secs_f64() * 1000.0, "optimized_pixels": output.report.searched_pixels }),
        );
        Ok(json!({
            "size": [size, size],
            "segments": 5,
            "threads": 1,
            "presynth_ms": presynth_ms,
            "texture_size": [texture_size, texture_size],
            "rows": rows,
            "paper_single_core_ms": { "band_0": 2, "band_2": 2376, "band_4": 9342, "band_8": 20859, "full": 600000 },
        }))
    })?;
    Ok(table)
}

/// PatchMatch against the exact search on a small case, with the occurrence penalty (the
/// default) and without it (where the exact search is a true per-iteration optimum).
fn patchmatch_vs_exact(bench: &Bench) -> anyhow::Result<Value> {
    let small = if bench.quick { 40 } else { 64 };
    let input = bench_pair(small, 3, bench.seed + 20);
    let mut comparison = Map::new();
    for (name, uniformity) in [("uniformity_3500", 3500.0), ("uniformity_0", 0.0)] {
        let mut params = Params::default();
        params.patch_size = 5;
        params.seed = bench.seed;
        params.uniformity = uniformity;
        let (patchmatch, patchmatch_s, _) = timed(&input, &params)?;
        params.nnf = NnfMethod::Exact;
        let (exact, exact_s, _) = timed(&input, &params)?;
        comparison.insert(
            name.into(),
            json!({
                "patchmatch_energy": patchmatch.report.energy.total,
                "exact_energy": exact.report.energy.total,
                "energy_ratio": patchmatch.report.energy.total / exact.report.energy.total.max(f64::MIN_POSITIVE),
                "patchmatch_s": patchmatch_s,
                "exact_s": exact_s,
                "speed_up": exact_s / patchmatch_s.max(1e-9),
            }),
        );
    }
    comparison.insert("size".into(), json!([small, small]));
    Ok(Value::Object(comparison))
}
