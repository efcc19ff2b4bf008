//! `motif bench --engine stylize --case texture-native`: a texture of a fixed size from exemplars
//! of growing size (issue 34, item 5), whose time should grow with the output, not the exemplar.

use motif_core::ByteImage;
use motif_stylize::{Input, Params};
use serde_json::{Map, Value, json};

use crate::suite::Bench;

/// `exemplar` repeated to `side × side` pixels. GIMP's patterns tile seamlessly, so the result has
/// the pattern's own patches and no seams: a large exemplar for speed whose figures stay
/// comparable across sizes (it is periodic, so it is not a fidelity case of a large photo).
fn tiled(exemplar: &ByteImage, side: usize) -> anyhow::Result<ByteImage> {
    let (width, height, channels) = (exemplar.width(), exemplar.height(), exemplar.channels());
    let mut data = Vec::with_capacity(side * side * channels);
    for y in 0..side {
        for x in 0..side {
            data.extend_from_slice(exemplar.pixel(x % width, y % height));
        }
    }
    Ok(ByteImage::from_data(side, side, channels, data)?)
}

/// `params` with the coarse patch `motif texture` infers for `exemplar` (no quilt here: the output
/// is never larger than the exemplar).
fn as_texture_job(params: &Params, exemplar: &ByteImage) -> Params {
    let size = (exemplar.width(), exemplar.height());
    params.clone().with_coarse_patch_size(motif_stylize::inferred_coarse_patch_size(size, params.patch_size, 0))
}

/// The centre `side × side` of `image`.
fn centre(image: &ByteImage, side: usize) -> anyhow::Result<ByteImage> {
    let (left, top, channels) = ((image.width() - side) / 2, (image.height() - side) / 2, image.channels());
    let mut data = Vec::with_capacity(side * side * channels);
    for y in top..top + side {
        for x in left..left + side {
            data.extend_from_slice(image.pixel(x, y));
        }
    }
    Ok(ByteImage::from_data(side, side, channels, data)?)
}

/// The hard case at its native size: GNOME's 4096 × 4096 wood wallpaper
/// (`data/real/stylize/wood-4096.webp`) against its own centre 1024 × 1024 (512 × 512 when quick),
/// a `size²` texture from each, `rounds` alternating rounds: seconds (min and max), their ratio,
/// and the fidelity of the first round against the whole exemplar: sharpness over the
/// exemplar's, and the nearest-patch distance at 15 × 15 (16 samples) with output and exemplar
/// both reduced 4× (patches of 60 pixels: the slats' layout; exhaustive at full size would take
/// minutes).
fn real_wood(bench: &Bench, params: &Params, size: usize, rounds: usize) -> anyhow::Result<Value> {
    let path = crate::suite::corpus_folder("stylize").join("wood-4096.webp");
    let image = motif_io::read_image(&path)?;
    let native = motif_jobs::stylize::style_image_channels(&image);
    let small = centre(&native, if bench.quick { 512 } else { 1024 })?;
    let native_float = native.to_float();
    let reference = native_float.downsample().downsample();
    let native_sharpness = motif_stylize::sharpness(&native_float).max(1e-9);
    let figures = |output: &motif_stylize::Output| {
        let reduced = output.image.downsample().downsample();
        let distance = motif_stylize::nearest_patch_distance(&reduced, &reference, 15, 16);
        (distance, motif_stylize::sharpness(&output.image) / native_sharpness)
    };
    let exemplars = [("crop", &small), ("native", &native)];
    let mut seconds = [Vec::new(), Vec::new()];
    let mut fidelity = [None, None];
    for _ in 0..rounds {
        for (index, (_, exemplar)) in exemplars.iter().enumerate() {
            let params = as_texture_job(params, exemplar);
            let (output, wall, _) = super::bench::timed(&Input::texture((*exemplar).clone(), size, size), &params)?;
            seconds[index].push(wall);
            fidelity[index].get_or_insert_with(|| figures(&output));
        }
    }
    let range = |times: &[f64]| times.iter().fold((f64::INFINITY, 0.0_f64), |(l, h), &t| (l.min(t), h.max(t)));
    let mut rows = Map::new();
    for (index, (name, exemplar)) in exemplars.iter().enumerate() {
        let (low, high) = range(&seconds[index]);
        let (distance, sharpness) = fidelity[index].expect("one round at least");
        rows.insert(
            (*name).into(),
            json!({
                "exemplar": [exemplar.width(), exemplar.height()],
                "wall_s_min": low, "wall_s_max": high,
                "nearest_patch_distance_15": distance, "sharpness_ratio": sharpness,
            }),
        );
    }
    let (crop_low, crop_high) = range(&seconds[0]);
    let (native_low, native_high) = range(&seconds[1]);
    rows.insert("time_over_crop".into(), json!([native_low / crop_high.max(1e-9), native_high / crop_low.max(1e-9)]));
    rows.insert("output".into(), json!([size, size]));
    rows.insert("source".into(), json!("GNOME's wood-l.webp (gnome-backgrounds 43.1), 4096 x 4096, a real texture"));
    Ok(Value::Object(rows))
}

/// A `size²` texture from GIMP's stone wall (`data/real/stylize/stone33.png`, 156 × 156) tiled to
/// each exemplar side, two alternating rounds: seconds (min and max), and the nearest-patch
/// distance at 15 × 15 to the pattern (`motif_stylize::nearest_patch_distance`) and sharpness over
/// the pattern's (below 1: washed out) of the first round. The middle exemplar also runs with
/// every level searching the whole exemplar (`local_search_above` = max), the reference for the
/// fidelity of the local refinement.
pub(super) fn texture_native(bench: &Bench) -> anyhow::Result<Value> {
    let folder = crate::suite::corpus_folder("stylize");
    let image = motif_io::read_image(&folder.join("stone33.png"))?;
    let pattern = motif_jobs::stylize::style_image_channels(&image);
    let pattern_float = pattern.to_float();
    let (size, sides) = if bench.quick { (128, [128, 512, 1024]) } else { (1024, [1024, 4096, 8192]) };
    let rounds = if bench.quick { 1 } else { 2 };
    let params = Params::default().with_seed(bench.seed);
    let mut seconds = vec![Vec::new(); sides.len()];
    let mut fidelity = vec![None; sides.len()];
    let figures = |output: &motif_stylize::Output| {
        let distance = motif_stylize::nearest_patch_distance(&output.image, &pattern_float, 15, 100);
        let sharpness = motif_stylize::sharpness(&output.image) / motif_stylize::sharpness(&pattern_float).max(1e-9);
        (distance, sharpness)
    };
    for _ in 0..rounds {
        for (index, &side) in sides.iter().enumerate() {
            let exemplar = tiled(&pattern, side)?;
            let params = as_texture_job(&params, &exemplar);
            let (output, wall, _) = super::bench::timed(&Input::texture(exemplar, size, size), &params)?;
            seconds[index].push(wall);
            fidelity[index].get_or_insert_with(|| (figures(&output), output.report.estimated_memory_bytes));
        }
    }
    let mut rows = Map::new();
    let first = seconds[0].iter().copied().fold(f64::INFINITY, f64::min);
    for ((side, times), fidelity) in sides.iter().zip(&seconds).zip(&fidelity) {
        let ((distance, sharpness), memory) = fidelity.expect("one round at least");
        let (low, high) = times.iter().fold((f64::INFINITY, 0.0_f64), |(l, h), &t| (l.min(t), h.max(t)));
        rows.insert(
            format!("exemplar_{side}"),
            json!({
                "exemplar": [side, side],
                "wall_s_min": low,
                "wall_s_max": high,
                "time_over_smallest_exemplar": low / first.max(1e-9),
                "nearest_patch_distance_15": distance,
                "sharpness_ratio": sharpness,
                "estimated_memory_bytes": memory,
            }),
        );
    }
    let side = sides[1];
    let exemplar = tiled(&pattern, side)?;
    let whole = as_texture_job(&params, &exemplar).with_local_search_above(usize::MAX);
    let (output, wall, _) = super::bench::timed(&Input::texture(exemplar, size, size), &whole)?;
    let (distance, sharpness) = figures(&output);
    rows.insert(
        format!("exemplar_{side}_whole_search"),
        json!({
            "exemplar": [side, side],
            "wall_s": wall,
            "nearest_patch_distance_15": distance,
            "sharpness_ratio": sharpness,
            "estimated_memory_bytes": output.report.estimated_memory_bytes,
        }),
    );
    rows.insert("real_wood".into(), real_wood(bench, &params, size, rounds)?);
    rows.insert("output".into(), json!([size, size]));
    rows.insert("rounds".into(), json!(rounds));
    rows.insert("exemplar_source".into(), json!("GIMP's stone33 pattern (156 x 156) tiled: a speed case"));
    Ok(Value::Object(rows))
}
