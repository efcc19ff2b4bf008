//! `motif stylize` (guided stylization, `presynth` for §3.7 textures) and `motif texture`
//! (non-guided texture synthesis), wired to PNG files. Options mirror ebsynth's so its users can
//! switch: `-style` → `--style`, `-guide A B -weight W` → `--guide A B --weight W`, and so on.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::{Args, Subcommand, ValueEnum};
use motif_core::{FloatImage, NoProgress, RgbaImage};
use motif_stylize::{
    Guide, NearestNeighbourField, NnfMethod, Output, PresynthInput, SegmentTexture, Segmentation, StylizeInput,
    StylizeParams, apply_field, presynthesize, samples, synthesize,
};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::bench::Bench;
use crate::context::Context;
use crate::demo::{Demo, DemoCase};

/// Nearest-neighbour search method.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum NnfArg {
    /// Randomized PatchMatch (propagation + random search), deterministic on any thread count.
    Patchmatch,
    /// Brute force over every source patch: exact, slow; for small images.
    Exact,
}

/// Synthesis options shared by `stylize`, `stylize presynth` and `texture` (ebsynth's names and
/// defaults).
#[derive(Args, Debug, Clone)]
pub struct SynthesisOptions {
    /// α: weight of the style term (A' against B' patches), 0–1000.
    #[arg(long, value_name = "W", default_value_t = 1.0, allow_negative_numbers = true)]
    pub style_weight: f32,
    /// λ: weight of the occurrence penalty that spreads the use of source patches evenly and
    /// prevents wash-out (ebsynth's units: squared 8-bit differences), 0–1000000; 0 = off.
    #[arg(long, value_name = "U", default_value_t = 3500.0, allow_negative_numbers = true)]
    pub uniformity: f32,
    /// Patch side in pixels: odd, 3–31. Larger keeps bigger structures of the style.
    #[arg(long, value_name = "P", default_value_t = 5, allow_negative_numbers = true)]
    pub patch_size: usize,
    /// Pyramid levels, 0–32; 0 = as many as fit (the coarsest at least 2·P+1 pixels a side).
    #[arg(long, value_name = "L", default_value_t = 0)]
    pub pyramid_levels: usize,
    /// Search-then-vote iterations per pyramid level (N of Algorithm 1), 1–100.
    #[arg(long = "search-vote-iters", value_name = "N", default_value_t = 6)]
    pub search_vote_iterations: usize,
    /// PatchMatch iterations per search, 1–100.
    #[arg(long = "patchmatch-iters", value_name = "K", default_value_t = 4)]
    pub patchmatch_iterations: usize,
    /// Stop improving a pixel once a vote changes it by less than this (largest channel change,
    /// 8-bit units), 0–1020; 0 = search every pixel every time.
    #[arg(long, value_name = "T", default_value_t = 5.0, allow_negative_numbers = true)]
    pub stop_threshold: f32,
    /// Nearest-neighbour search: patchmatch (fast) or exact (brute force, small images only).
    #[arg(long, value_enum, default_value = "patchmatch")]
    pub nnf: NnfArg,
    /// After the finest level, one more search-and-vote with 3×3 patches and no uniformity
    /// (ebsynth's extrapass3x3): crisper fine detail.
    #[arg(long = "extra-pass-3x3")]
    pub extra_pass_3x3: bool,
}

impl SynthesisOptions {
    fn params(&self, seed: u64) -> StylizeParams {
        let mut params = StylizeParams::default();
        params.style_weight = self.style_weight;
        params.uniformity = self.uniformity;
        params.patch_size = self.patch_size;
        params.pyramid_levels = self.pyramid_levels;
        params.search_vote_iterations = self.search_vote_iterations;
        params.patchmatch_iterations = self.patchmatch_iterations;
        params.stop_threshold = self.stop_threshold;
        params.nnf = match self.nnf {
            NnfArg::Patchmatch => NnfMethod::PatchMatch,
            NnfArg::Exact => NnfMethod::Exact,
        };
        params.extra_pass_3x3 = self.extra_pass_3x3;
        params.seed = seed;
        params
    }
}

/// Segment guidance options (§3.6).
#[derive(Args, Debug, Clone)]
pub struct SegmentOptions {
    /// Treat the colours of the segment guide as segment labels: ω_best per segment (Eq. 6) and
    /// no match across segments. Exact palette (at most 64 colours) unless --segment-count.
    #[arg(long)]
    pub segments: bool,
    /// Quantize the segment guide into K colours by k-means (for anti-aliased guides), 2–64;
    /// implies --segments.
    #[arg(long, value_name = "K")]
    pub segment_count: Option<usize>,
    /// Which --guide pair defines the segments, counted from 1.
    #[arg(long, value_name = "I", default_value_t = 1)]
    pub segment_guide: usize,
}

impl SegmentOptions {
    fn apply(&self, params: &mut StylizeParams) -> anyhow::Result<()> {
        params.segments = match (self.segments, self.segment_count) {
            (_, Some(k)) => Some(Segmentation::KMeans(k)),
            (true, None) => Some(Segmentation::Palette),
            (false, None) => None,
        };
        if self.segment_guide == 0 {
            bail!("invalid segment-guide = 0: guides are counted from 1");
        }
        params.segment_guide = self.segment_guide - 1;
        Ok(())
    }
}

/// Options of `motif stylize`.
#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true)]
pub struct StylizeArgs {
    /// `presynth`: make the per-segment textures for --presynth.
    #[command(subcommand)]
    pub action: Option<StylizeAction>,
    /// The style exemplar A' (PNG/JPEG; RGB, or RGBA when it has transparency). Required.
    #[arg(long, value_name = "A1.png")]
    pub style: Option<PathBuf>,
    /// A guide pair: the source guide A (the style's size) and the target guide B (the output's
    /// size). Repeat for several guides. Each is used as grey (1 channel), RGB (3) or RGBA (4, when
    /// it has transparency); grey next to RGB is read as RGB; transparency in only one file of a
    /// pair is an error. At least one pair is required.
    #[arg(long, num_args = 2, value_names = ["A.png", "B.png"], action = clap::ArgAction::Append)]
    pub guide: Vec<PathBuf>,
    /// β: weight of a guide, 0–1000. Give none (each guide then weighs 1/number of guides, as in
    /// ebsynth) or one per --guide, in the same order.
    #[arg(long, value_name = "W", action = clap::ArgAction::Append, allow_negative_numbers = true)]
    pub weight: Vec<f32>,
    /// Synthesis options.
    #[command(flatten)]
    pub synthesis: SynthesisOptions,
    /// Segment guidance.
    #[command(flatten)]
    pub segment: SegmentOptions,
    /// Directory written by `motif stylize presynth`: fill every pixel at least --band pixels
    /// from a segment edge of the target guide with its segment's texture and optimize only the
    /// band (§3.7). Implies --segments.
    #[arg(long, value_name = "DIR")]
    pub presynth: Option<PathBuf>,
    /// Band half-width T in pixels for --presynth, 0–4096; 0 = pure bitmap composition.
    #[arg(long, value_name = "T", default_value_t = 4)]
    pub band: usize,
    /// Search-vote iterations for the band when the textures carry their fields (caches made
    /// by this version): the band starts at the textures' own matches, so fewer are needed,
    /// 1–100. Older caches (no fields) use --search-vote-iters.
    #[arg(long = "band-iters", value_name = "N", default_value_t = 3)]
    pub band_iterations: usize,
    /// PatchMatch iterations per search for such a band, 1–100 (else --patchmatch-iters).
    #[arg(long = "band-patchmatch-iters", value_name = "K", default_value_t = 2)]
    pub band_patchmatch_iterations: usize,
    /// Also write nnf.png (the final nearest-neighbour field: red/green = source x/y mod 256,
    /// blue = their high bits; alpha 0 where not searched) and error.png (per-pixel energy,
    /// white = highest) into this directory.
    #[arg(long, value_name = "DIR")]
    pub debug_dir: Option<PathBuf>,
    /// Skip synthesis: re-apply a field saved by --debug-dir (nnf.png) to --style (which must
    /// have the size of the style the field was made with). The patch size is --patch-size (or 3
    /// if the field came from --extra-pass-3x3).
    #[arg(long, value_name = "NNF.png", conflicts_with_all = ["guide", "presynth"])]
    pub apply_nnf: Option<PathBuf>,
    /// The stylized output B' (PNG). Required.
    #[arg(long, value_name = "B1.png")]
    pub out: Option<PathBuf>,
}

/// Sub-actions of `motif stylize`.
#[derive(Subcommand, Debug)]
pub enum StylizeAction {
    /// Synthesize one seamless texture per segment of the source guide from the style (§3.7) and
    /// cache them in a directory for `motif stylize --presynth DIR`.
    Presynth(PresynthArgs),
}

/// Options of `motif stylize presynth`.
#[derive(Args, Debug)]
pub struct PresynthArgs {
    /// The style exemplar A'.
    #[arg(long, value_name = "A1.png")]
    pub style: PathBuf,
    /// The source segment guide A (the style's size): each colour is a segment.
    #[arg(long, value_name = "A.png")]
    pub guide: PathBuf,
    /// Texture size in pixels; the textures tile, so it need not match the target.
    #[arg(long, value_name = "WxH", default_value = "256x256", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Synthesis options (use the same --patch-size as the later stylize run).
    #[command(flatten)]
    pub synthesis: SynthesisOptions,
    /// Quantize the guide into K colours by k-means instead of an exact palette, 2–64.
    #[arg(long, value_name = "K")]
    pub segment_count: Option<usize>,
    /// Output directory (created if missing): segment-N.png and presynth.json.
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
}

/// Options of `motif texture`.
#[derive(Args, Debug)]
pub struct TextureArgs {
    /// The texture exemplar (PNG/JPEG).
    #[arg(long, value_name = "EX.png")]
    pub exemplar: PathBuf,
    /// Output size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Wrap patches around the borders so the output tiles seamlessly.
    #[arg(long)]
    pub tileable: bool,
    /// Synthesis options.
    #[command(flatten)]
    pub synthesis: SynthesisOptions,
    /// Also write nnf.png and error.png into this directory (see `motif stylize --help`).
    #[arg(long, value_name = "DIR")]
    pub debug_dir: Option<PathBuf>,
    /// The synthesized texture (PNG).
    #[arg(long, value_name = "OUT.png")]
    pub out: PathBuf,
}

fn parse_size(text: &str) -> Result<(usize, usize), String> {
    let (w, h) = text.split_once(['x', 'X', ',']).ok_or_else(|| format!("`{text}` is not WxH (e.g. 512x512)"))?;
    let parse = |v: &str| v.trim().parse::<usize>().map_err(|_| format!("`{text}` is not WxH (e.g. 512x512)"));
    let (w, h) = (parse(w)?, parse(h)?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("size {w}x{h} must be between 1 and 16384 a side"));
    }
    Ok((w, h))
}

/// The manifest of a presynth directory.
#[derive(Serialize, Deserialize, Debug)]
struct Manifest {
    patch_size: usize,
    segments: Vec<ManifestEntry>,
}

#[derive(Serialize, Deserialize, Debug)]
struct ManifestEntry {
    /// Guide colour as `#rrggbb` (or `#rrggbbaa`, `#gg` for grey guides).
    colour: String,
    file: String,
    /// Where each texture pixel came from (the presynthesis field as written by `--debug-dir`'s
    /// `nnf.png`): seeds the band's field. Absent in older caches (random start then).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    field: Option<String>,
}

fn load(path: &Path) -> anyhow::Result<RgbaImage> {
    let image = motif_io::read_image(path)?;
    if image.is_empty() {
        bail!("{}: the image is empty", path.display());
    }
    Ok(image)
}

/// Channels of a decoded file: 4 with any transparency, else 1 when grey, else 3.
fn file_channels(image: &RgbaImage) -> usize {
    if !image.is_fully_opaque() {
        4
    } else if image.pixels().iter().all(|p| p[0] == p[1] && p[1] == p[2]) {
        1
    } else {
        3
    }
}

/// Channel lists for a guide pair: equal counts stay; a grey file next to an RGB one is read as
/// RGB (grey is a special RGB); transparency on one side only is a mismatch the engine reports.
fn pair_channels(source: &RgbaImage, target: &RgbaImage) -> (Vec<usize>, Vec<usize>) {
    let list = |channels: usize| match channels {
        1 => vec![0],
        3 => vec![0, 1, 2],
        _ => vec![0, 1, 2, 3],
    };
    match (file_channels(source), file_channels(target)) {
        (1, 3) | (3, 1) => (list(3), list(3)),
        (a, b) => (list(a), list(b)),
    }
}

fn style_float(image: &RgbaImage) -> FloatImage {
    if image.is_fully_opaque() { image.to_float_channels(&[0, 1, 2]) } else { image.to_float() }
}

fn hex(colour: &[f32]) -> String {
    colour.iter().map(|v| format!("{:02x}", (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect::<String>()
}

fn parse_hex(text: &str) -> anyhow::Result<Vec<f32>> {
    let digits = text.trim_start_matches('#');
    if digits.is_empty() || digits.len() % 2 != 0 || digits.len() > 8 {
        bail!("`{text}` is not a #rrggbb colour");
    }
    (0..digits.len() / 2)
        .map(|i| {
            u8::from_str_radix(&digits[2 * i..2 * i + 2], 16)
                .map(|v| f32::from(v) / 255.0)
                .map_err(|_| anyhow::anyhow!("`{text}` is not a #rrggbb colour"))
        })
        .collect()
}

fn write_debug(dir: &Path, output: &Output) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    motif_io::write_png(&dir.join("nnf.png"), &output.field.to_rgba()?)?;
    let max = output.error_map.data().iter().copied().fold(0.0_f32, f32::max).max(f32::MIN_POSITIVE);
    let mut error = output.error_map.clone();
    error.data_mut().iter_mut().for_each(|v| *v /= max);
    motif_io::write_png(&dir.join("error.png"), &RgbaImage::from_float(&error))?;
    Ok(())
}

fn record(context: &mut Context, output: &Output) {
    context.figure("energy", output.energy);
    context.figure("source_coverage", output.source_coverage);
    context.stages(&output.stages_ms);
    context.figure("engine_ms", output.total_ms);
    context.figure("levels", &output.levels);
    context.figure("searched_pixels", output.searched_pixels);
    context.figure("output_size", [output.image.width(), output.image.height()]);
}

/// Runs `motif stylize` (or its `presynth` action).
pub fn run_stylize(args: &StylizeArgs, context: &mut Context) -> anyhow::Result<()> {
    if let Some(StylizeAction::Presynth(presynth)) = &args.action {
        return run_presynth(presynth, context);
    }
    let Some(style_path) = &args.style else { bail!("--style A1.png is required") };
    let Some(out) = &args.out else { bail!("--out B1.png is required") };
    let pairs: Vec<(&PathBuf, &PathBuf)> = args.guide.chunks_exact(2).map(|pair| (&pair[0], &pair[1])).collect();
    let mut inputs: Vec<&Path> = vec![style_path.as_path()];
    inputs.extend(args.guide.iter().map(PathBuf::as_path));
    inputs.extend(args.apply_nnf.iter().map(PathBuf::as_path));
    context.check_output(out, &inputs)?;
    let style_image = load(style_path)?;
    let style = style_float(&style_image);
    let mut params = args.synthesis.params(context.seed);
    if let Some(field_path) = &args.apply_nnf {
        let field_image = load(field_path)?;
        let field = NearestNeighbourField::from_rgba(&field_image, style.width(), style.height(), params.patch_size)?;
        let image = apply_field(&field, &style)?;
        motif_io::write_png(out, &RgbaImage::from_float(&image))?;
        context.figure("output_size", [image.width(), image.height()]);
        context.summary(&format!(
            "motif stylize: re-applied {} to the style → {}",
            field_path.display(),
            out.display()
        ));
        return Ok(());
    }
    if pairs.is_empty() {
        bail!("at least one --guide A.png B.png pair is required (for unguided synthesis use `motif texture`)");
    }
    if !args.weight.is_empty() && args.weight.len() != pairs.len() {
        bail!(
            "{} --weight values for {} --guide pairs: give none or exactly one per guide, in order",
            args.weight.len(),
            pairs.len()
        );
    }
    args.segment.apply(&mut params)?;
    params.band = args.band;
    params.band_search_vote_iterations = args.band_iterations;
    params.band_patchmatch_iterations = args.band_patchmatch_iterations;
    let mut guides = Vec::with_capacity(pairs.len());
    for (index, (source_path, target_path)) in pairs.iter().enumerate() {
        let source = load(source_path)?;
        let target = load(target_path)?;
        let (source_channels, target_channels) = pair_channels(&source, &target);
        guides.push(Guide {
            source: source.to_float_channels(&source_channels),
            target: target.to_float_channels(&target_channels),
            weight: args.weight.get(index).copied(),
        });
    }
    let mut input = StylizeInput::guided(style, guides);
    if let Some(dir) = &args.presynth {
        let manifest_path = dir.join("presynth.json");
        let manifest: Manifest = motif_io::read_json(&manifest_path).with_context(|| {
            format!("cannot read {} (make it with `motif stylize presynth`)", manifest_path.display())
        })?;
        if manifest.patch_size != params.patch_size {
            bail!(
                "the textures in {} were made with --patch-size {} but this run uses {}",
                dir.display(),
                manifest.patch_size,
                params.patch_size
            );
        }
        let mut textures = Vec::with_capacity(manifest.segments.len());
        for entry in &manifest.segments {
            let image = load(&dir.join(&entry.file))?;
            let image =
                if input.style.channels() == 4 { image.to_float() } else { image.to_float_channels(&[0, 1, 2]) };
            let field = match &entry.field {
                Some(file) => {
                    let path = dir.join(file);
                    let encoded = load(&path)?;
                    let (width, height) = (input.style.width(), input.style.height());
                    let field = NearestNeighbourField::from_rgba(&encoded, width, height, manifest.patch_size)
                        .with_context(|| {
                            format!("{} does not fit the style {}", path.display(), style_path.display())
                        })?;
                    Some(field)
                }
                None => None,
            };
            textures.push(SegmentTexture { colour: parse_hex(&entry.colour)?, image, field });
        }
        if params.segments.is_none() {
            params.segments = Some(Segmentation::Palette);
        }
        input.textures = Some(textures);
    }
    let output = synthesize(&input, &params, context.progress()).with_context(|| {
        let guides: Vec<String> = pairs.iter().map(|(a, b)| format!("{} → {}", a.display(), b.display())).collect();
        format!("cannot stylize {} with guides {}", style_path.display(), guides.join(", "))
    })?;
    motif_io::write_png(out, &RgbaImage::from_float(&output.image))?;
    if let Some(dir) = &args.debug_dir {
        write_debug(dir, &output)?;
    }
    record(context, &output);
    context.summary(&format!(
        "motif stylize: {}×{} in {:.0} ms, energy {:.0}, source coverage {:.1} % → {}",
        output.image.width(),
        output.image.height(),
        output.total_ms,
        output.energy.total,
        100.0 * output.source_coverage,
        out.display()
    ));
    Ok(())
}

fn run_presynth(args: &PresynthArgs, context: &mut Context) -> anyhow::Result<()> {
    // The folder's files are replaced: no input may live there, and it must be a folder.
    if args.out_dir.is_file() {
        bail!("--out-dir {} is a file; give a folder", args.out_dir.display());
    }
    for input in [&args.style, &args.guide] {
        let folder = match input.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        if motif_io::same_file(folder, &args.out_dir) {
            bail!(
                "input {} lies in the --out-dir folder, whose files presynth replaces; move it out or choose another \
                 folder (motif never overwrites an input)",
                input.display()
            );
        }
    }
    // The manifest stands for the folder's outputs, so that --report is checked against the inputs.
    if args.out_dir.is_dir() {
        context.check_output(&args.out_dir.join("presynth.json"), &[&args.style, &args.guide])?;
    }
    let style_image = load(&args.style)?;
    let guide_image = load(&args.guide)?;
    let channels: Vec<usize> = (0..file_channels(&guide_image)).collect();
    let input = PresynthInput {
        style: style_float(&style_image),
        guide: guide_image.to_float_channels(&channels),
        size: args.size,
    };
    let mut params = args.synthesis.params(context.seed);
    params.segments = Some(args.segment_count.map_or(Segmentation::Palette, Segmentation::KMeans));
    let textures = presynthesize(&input, &params, context.progress())?;
    std::fs::create_dir_all(&args.out_dir).with_context(|| format!("cannot create {}", args.out_dir.display()))?;
    let mut segments = Vec::with_capacity(textures.len());
    for (index, texture) in textures.iter().enumerate() {
        let file = format!("segment-{}.png", index + 1);
        motif_io::write_png(&args.out_dir.join(&file), &RgbaImage::from_float(&texture.image))?;
        // The field seeds the band's search; a source too large for its PNG encoding just goes without.
        let field = match texture.field.as_ref().map(NearestNeighbourField::to_rgba) {
            Some(Ok(encoded)) => {
                let name = format!("segment-{}-nnf.png", index + 1);
                motif_io::write_png(&args.out_dir.join(&name), &encoded)?;
                Some(name)
            }
            _ => None,
        };
        segments.push(ManifestEntry { colour: format!("#{}", hex(&texture.colour)), file, field });
    }
    let manifest = Manifest { patch_size: params.patch_size, segments };
    motif_io::write_json(&args.out_dir.join("presynth.json"), &manifest)?;
    context.figure("segments", textures.len());
    context.figure("texture_size", [args.size.0, args.size.1]);
    context.summary(&format!(
        "motif stylize presynth: {} segment textures of {}×{} → {}",
        textures.len(),
        args.size.0,
        args.size.1,
        args.out_dir.display()
    ));
    Ok(())
}

/// Runs `motif texture`.
pub fn run_texture(args: &TextureArgs, context: &mut Context) -> anyhow::Result<()> {
    context.check_output(&args.out, &[&args.exemplar])?;
    let exemplar = style_float(&load(&args.exemplar)?);
    let mut params = args.synthesis.params(context.seed);
    params.tileable = args.tileable;
    let input = StylizeInput::texture(exemplar, args.size.0, args.size.1);
    let output = synthesize(&input, &params, context.progress())?;
    motif_io::write_png(&args.out, &RgbaImage::from_float(&output.image))?;
    if let Some(dir) = &args.debug_dir {
        write_debug(dir, &output)?;
    }
    record(context, &output);
    context.summary(&format!(
        "motif texture: {}×{}{} in {:.0} ms, energy {:.0} → {}",
        args.size.0,
        args.size.1,
        if args.tileable { " (tileable)" } else { "" },
        output.total_ms,
        output.energy.total,
        args.out.display()
    ));
    Ok(())
}

fn to_png(image: &FloatImage) -> RgbaImage {
    RgbaImage::from_float(image)
}

/// Built-in examples: a map stylized with segments, the pre-synthesized speed-up, a tileable
/// texture.
pub fn demo(demo: &mut Demo) -> anyhow::Result<()> {
    // Directory arguments are given as full paths (Demo resolves only file names).
    let debug_dir = demo.path("stylize-debug").to_string_lossy().into_owned();
    let presynth_dir = demo.path("stylize-presynth").to_string_lossy().into_owned();
    let source_guide = samples::map_guide(160, 160, 5, 11);
    let style = samples::crayon_style(&source_guide, 12);
    let target_guide = samples::map_guide(224, 160, 5, 13);
    motif_io::write_png(&demo.path("stylize-A.png"), &to_png(&source_guide))?;
    motif_io::write_png(&demo.path("stylize-A1.png"), &to_png(&style))?;
    motif_io::write_png(&demo.path("stylize-B.png"), &to_png(&target_guide))?;
    demo.case(DemoCase {
        title: "stylize: a map in crayon".into(),
        description: "Guided patch synthesis (StyLit energy with the occurrence penalty) transfers a crayon \
                      style A' drawn over map A onto a new map B; segments keep water, grass and roads apart."
            .into(),
        inputs: vec![
            ("style A'".into(), "stylize-A1.png".into()),
            ("source guide A".into(), "stylize-A.png".into()),
            ("target guide B".into(), "stylize-B.png".into()),
        ],
        outputs: vec![
            ("output B'".into(), "stylize-B1.png".into()),
            ("field".into(), "stylize-debug/nnf.png".into()),
            ("error".into(), "stylize-debug/error.png".into()),
        ],
        args: [
            "stylize",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "stylize-B.png",
            "--segments",
            "--debug-dir",
            &debug_dir,
            "--out",
            "stylize-B1.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    demo.case(DemoCase {
        title: "stylize presynth: one texture per segment".into(),
        description: "Each map segment's crayon texture is synthesized once (seamless, from that segment's \
                      style patches) and cached (§3.7)."
            .into(),
        inputs: vec![("style A'".into(), "stylize-A1.png".into()), ("source guide A".into(), "stylize-A.png".into())],
        outputs: (1..=5).map(|i| (format!("segment {i}"), format!("stylize-presynth/segment-{i}.png"))).collect(),
        args: [
            "stylize",
            "presynth",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "--size",
            "64x64",
            "--out-dir",
            &presynth_dir,
        ]
        .map(String::from)
        .to_vec(),
    })?;
    demo.case(DemoCase {
        title: "stylize --presynth --band 4: only the edges".into(),
        description: "Pixels at least 4 px from a segment edge are copied from the cached textures; only the \
                      band around the edges is optimized, orders of magnitude faster than a full synthesis."
            .into(),
        inputs: vec![("target guide B".into(), "stylize-B.png".into())],
        outputs: vec![("output B'".into(), "stylize-B1-band4.png".into())],
        args: [
            "stylize",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "stylize-B.png",
            "--presynth",
            &presynth_dir,
            "--band",
            "4",
            "--out",
            "stylize-B1-band4.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    let exemplar = samples::crayon_style(&samples::map_guide(64, 64, 2, 14), 15);
    motif_io::write_png(&demo.path("texture-exemplar.png"), &to_png(&exemplar))?;
    demo.case(DemoCase {
        title: "texture: a seamless tile".into(),
        description: "Non-guided texture optimization grows a 160×160 texture from a 64×64 exemplar; with \
                      --tileable its patches wrap around, so copies of it tile without seams."
            .into(),
        inputs: vec![("exemplar".into(), "texture-exemplar.png".into())],
        outputs: vec![("texture".into(), "texture-tile.png".into())],
        args: [
            "texture",
            "--exemplar",
            "texture-exemplar.png",
            "--size",
            "160x160",
            "--tileable",
            "--out",
            "texture-tile.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}

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
fn bench_pair(size: usize, guide_channels: usize, seed: u64) -> StylizeInput {
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
    StylizeInput::guided(style, guides)
}

fn timed(input: &StylizeInput, params: &StylizeParams) -> anyhow::Result<(Output, f64, Option<f64>)> {
    let cpu_start = cpu_seconds();
    let start = std::time::Instant::now();
    let output = synthesize(input, params, &mut NoProgress)?;
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu_start.and_then(|s| cpu_seconds().map(|e| e - s));
    Ok((output, wall, cpu))
}

/// Figures for `motif bench`: CPU-seconds per megapixel on the two ebsynth-like workloads,
/// Table 1 (band 0/2/4/8/full on a 360×360 5-segment map, one thread), PatchMatch/exact energy.
pub fn bench(bench: &Bench) -> anyhow::Result<Value> {
    // `--case 0.15mp`, `1mp`, `table1` or `exact` times only those parts (default: all four).
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
        let mut params = StylizeParams::default();
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
                "energy": output.energy,
                "source_coverage": output.source_coverage,
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
    Ok(Value::Object(figures))
}

/// Table 1: pre-synthesized textures, band sizes, on one thread.
fn table_1(bench: &Bench) -> anyhow::Result<Value> {
    let size = if bench.quick { 96 } else { 360 };
    let source_guide = samples::map_guide(size, size, 5, bench.seed + 10);
    let target_guide = samples::map_guide(size, size, 5, bench.seed + 11);
    let style = samples::crayon_style(&source_guide, bench.seed + 12);
    let mut params = StylizeParams::default();
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
        let guided = StylizeInput::guided(
            style.clone(),
            vec![Guide { source: source_guide.clone(), target: target_guide.clone(), weight: None }],
        );
        let mut rows = Map::new();
        for band in [0, 2, 4, 8] {
            let mut input = guided.clone();
            input.textures = Some(textures.clone());
            let mut banded = params.clone();
            banded.band = band;
            let start = std::time::Instant::now();
            let output = synthesize(&input, &banded, &mut NoProgress)?;
            rows.insert(
                format!("band_{band}"),
                json!({ "ms": start.elapsed().as_secs_f64() * 1000.0, "optimized_pixels": output.searched_pixels }),
            );
        }
        let start = std::time::Instant::now();
        let output = synthesize(&guided, &params, &mut NoProgress)?;
        rows.insert(
            "full".into(),
            json!({ "ms": start.elapsed().as_secs_f64() * 1000.0, "optimized_pixels": output.searched_pixels }),
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
        let mut params = StylizeParams::default();
        params.patch_size = 5;
        params.seed = bench.seed;
        params.uniformity = uniformity;
        let (patchmatch, patchmatch_s, _) = timed(&input, &params)?;
        params.nnf = NnfMethod::Exact;
        let (exact, exact_s, _) = timed(&input, &params)?;
        comparison.insert(
            name.into(),
            json!({
                "patchmatch_energy": patchmatch.energy.total,
                "exact_energy": exact.energy.total,
                "energy_ratio": patchmatch.energy.total / exact.energy.total.max(f64::MIN_POSITIVE),
                "patchmatch_s": patchmatch_s,
                "exact_s": exact_s,
                "speed_up": exact_s / patchmatch_s.max(1e-9),
            }),
        );
    }
    comparison.insert("size".into(), json!([small, small]));
    Ok(Value::Object(comparison))
}
