//! `motif stylize` (guided stylization), `motif presynth` (its §3.7 textures) and `motif texture`
//! (non-guided texture synthesis), wired to PNG files. Options mirror ebsynth's so its users can
//! switch: `-style` → `--style`, `-guide A B -weight W` → `--guide A B --weight W`, and so on.

mod bench;
mod cache;
mod demo;
mod masks;
mod native_bench;
mod tiles_bench;
mod video;
mod video_bench;

pub(crate) use masks::{InpaintArgs, ZoomArgs, run_inpaint, run_zoom};
pub(crate) use video::{VideoArgs, run_video};

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use motif_core::RgbaImage;
use motif_jobs::Job;
use motif_jobs::stylize::{NearestNeighbourField, Output, apply_field};
use motif_jobs::stylize::{
    PresynthInputs, PresynthJob, PresynthJobOptions, StylizeInputs, StylizeJob, StylizeJobOptions, TextureInputs,
    TextureJob, TextureJobOptions, guide_image_channels, guide_pair, style_image_channels,
};

use crate::context::Context;
use crate::gallery::Demo;
use crate::job_args::JobArgs;

/// Options of `motif stylize`.
#[derive(Args, Debug)]
pub struct StylizeArgs {
    /// The style exemplar A' (PNG/JPEG/WebP; RGB, or RGBA when it has transparency).
    #[arg(long, value_name = "A1.png")]
    pub style: PathBuf,
    /// A guide pair: the source guide A (the style's size) and the target guide B (the output's
    /// size). Repeat for several guides. Each is used as grey (1 channel), RGB (3) or RGBA (4, when
    /// it has transparency); grey next to RGB is read as RGB; transparency in only one file of a
    /// pair is an error. At least one pair is required.
    #[arg(long, num_args = 2, value_names = ["A.png", "B.png"], action = clap::ArgAction::Append)]
    pub guide: Vec<PathBuf>,
    /// Every option of the synthesis, declared in `motif_jobs::stylize` (`SynthesisOptions`,
    /// `StylizeOptions`).
    #[command(flatten)]
    pub options: JobArgs<StylizeJobOptions>,
    /// Masks.
    #[command(flatten)]
    pub masking: masks::MaskOptions,
    /// Directory written by `motif presynth`: fill every pixel at least --band pixels
    /// from a segment edge of the target guide with its segment's texture and optimize only the
    /// band (§3.7). Implies --segments. The textures' colours are the segments: every guide pixel
    /// takes the nearest, and a target colour far from all of them and their blends is refused.
    #[arg(long, value_name = "DIR")]
    pub presynth: Option<PathBuf>,
    /// Also write nnf.png (the final nearest-neighbour field as a 16-bit PNG: red/green = source
    /// x/y, blue = the pixel's weight in the final vote × 65535; alpha 0 where not searched) and
    /// error.png (per-pixel energy, white = highest) into this directory.
    #[arg(long, value_name = "DIR")]
    pub debug_dir: Option<PathBuf>,
    /// Skip synthesis: re-apply a field saved by --debug-dir (nnf.png) to --style (which must
    /// have the size of the style the field was made with), with the final vote's weights: the
    /// style the field was made with gives back B' exactly (outside band mode). The patch size is
    /// --patch-size (or 3 if the field came from --extra-pass-3x3). 8-bit fields of earlier
    /// versions are re-applied as a plain mean.
    #[arg(long, value_name = "NNF.png", conflicts_with_all = ["guide", "presynth"])]
    pub apply_nnf: Option<PathBuf>,
    /// The stylized output B' (PNG).
    #[arg(long, value_name = "B1.png")]
    pub out: PathBuf,
}

/// Options of `motif presynth`.
#[derive(Args, Debug)]
pub struct PresynthArgs {
    /// The style exemplar A'.
    #[arg(long, value_name = "A1.png")]
    pub style: PathBuf,
    /// The source segment guide A (the style's size): each colour is a segment; with
    /// --segment-count, each of K k-means colours, every pixel taking the nearest.
    #[arg(long, value_name = "A.png")]
    pub guide: PathBuf,
    /// Texture size in pixels; the textures tile, so it need not match the target.
    #[arg(long, value_name = "WxH", default_value = "256x256", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Every option of the synthesis (use the same --patch-size as the later stylize run),
    /// declared in `motif_jobs::stylize` (`SynthesisOptions`, `PresynthOptions`).
    #[command(flatten)]
    pub options: JobArgs<PresynthJobOptions>,
    /// Output directory (created if missing): segment-N.png and presynth.json.
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
}

/// Options of `motif texture`.
#[derive(Args, Debug)]
pub struct TextureArgs {
    /// The texture exemplar (PNG/JPEG/WebP).
    #[arg(long, value_name = "EX.png")]
    pub exemplar: PathBuf,
    /// Output size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Every option of the synthesis, declared in `motif_jobs::stylize` (`SynthesisOptions`,
    /// `TextureOptions`).
    #[command(flatten)]
    pub options: JobArgs<TextureJobOptions>,
    /// Masks.
    #[command(flatten)]
    pub masking: masks::MaskOptions,
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

/// Reads an image within `max_memory` (bytes): a larger declared size is refused from its header.
fn load(path: &Path, max_memory: u64) -> anyhow::Result<RgbaImage> {
    let image = motif_io::read_image_within(path, motif_io::ImageBudget::max_memory(max_memory))?;
    if image.is_empty() {
        bail!("{}: the image is empty", path.display());
    }
    Ok(image)
}

/// The files `--debug-dir` writes: the field, then the error map.
fn debug_files(dir: &Path) -> Vec<PathBuf> {
    vec![dir.join("nnf.png"), dir.join("error.png")]
}

/// Plans `--debug-dir`'s files as outputs, when it is given.
fn check_debug(dir: Option<&Path>, inputs: &[&Path], context: &Context) -> anyhow::Result<()> {
    dir.map_or(Ok(()), |dir| context.check_outputs_in(dir, &debug_files(dir), inputs))
}

fn write_debug(dir: &Path, output: &Output) -> anyhow::Result<()> {
    let [nnf_path, error_path] = <[PathBuf; 2]>::try_from(debug_files(dir)).expect("two files");
    motif_io::create_folder(dir)?;
    let field = &output.field;
    let nnf = motif_io::Rgba16 { width: field.width, height: field.height, pixels: field.to_rgba16() };
    motif_io::write_png16(&nnf_path, &nnf)?;
    let max = output.error_map.data().iter().copied().fold(0.0_f32, f32::max).max(f32::MIN_POSITIVE);
    let mut error = output.error_map.clone();
    error.data_mut().iter_mut().for_each(|v| *v /= max);
    motif_io::write_png(&error_path, &RgbaImage::from_float(&error))?;
    Ok(())
}

/// Runs `motif stylize`.
pub(crate) fn run_stylize(args: &StylizeArgs, context: &mut Context) -> anyhow::Result<()> {
    let (style_path, out) = (&args.style, &args.out);
    let pairs: Vec<(&PathBuf, &PathBuf)> = args.guide.chunks_exact(2).map(|pair| (&pair[0], &pair[1])).collect();
    let mut inputs: Vec<&Path> = vec![style_path.as_path()];
    inputs.extend(args.guide.iter().map(PathBuf::as_path));
    inputs.extend(args.apply_nnf.iter().map(PathBuf::as_path));
    inputs.extend(args.masking.inputs());
    // The cache's folder: its files are inputs.
    inputs.extend(args.presynth.as_deref());
    context.check_output(out, &inputs)?;
    check_debug(args.debug_dir.as_deref(), &inputs, context)?;
    // Only the 8-bit channels the engine takes are kept (not the decoded RGBA).
    let style = style_image_channels(&load(style_path, context.max_memory)?);
    let job =
        StylizeJob { seed: context.seed, max_memory: Some(context.max_memory), options: args.options.options.clone() };
    // The options are checked before the guides are read.
    let params = job.params(args.presynth.is_some())?;
    if let Some(field_path) = &args.apply_nnf {
        let (width, height, patch) = (style.width(), style.height(), params.patch_size);
        let field =
            match motif_io::read_png16_within(field_path, motif_io::ImageBudget::max_memory(context.max_memory))? {
                Some(nnf) => {
                    NearestNeighbourField::from_rgba16(nnf.width, nnf.height, &nnf.pixels, width, height, patch)?
                }
                None => NearestNeighbourField::from_rgba(&load(field_path, context.max_memory)?, width, height, patch)?,
            };
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
    let weight = &args.options.own.weight;
    if !weight.is_empty() && weight.len() != pairs.len() {
        bail!(
            "{} --weight values for {} --guide pairs: give none or exactly one per guide, in order",
            weight.len(),
            pairs.len()
        );
    }
    let mut guides = Vec::with_capacity(pairs.len());
    for (source_path, target_path) in &pairs {
        let source = load(source_path, context.max_memory)?;
        let target = load(target_path, context.max_memory)?;
        guides.push(guide_pair(&source, &target));
    }
    let mut textures = None;
    if let Some(dir) = &args.presynth {
        let (loaded, generation) = cache::read(dir, &style, params.patch_size)?;
        if let Some(generation) = generation {
            context.figure("presynth_generation", generation);
        }
        textures = Some(loaded);
    }
    let mask = args.masking.read(style.channels(), context.max_memory)?;
    let run = job.run(StylizeInputs { style, guides, textures, mask }, context.progress()).with_context(|| {
        let guides: Vec<String> = pairs.iter().map(|(a, b)| format!("{} → {}", a.display(), b.display())).collect();
        format!("cannot stylize {} with guides {}{}", style_path.display(), guides.join(", "), args.masking.describe())
    })?;
    let output = &run.output;
    motif_io::write_png(out, &RgbaImage::from_float(&output.image))?;
    if let Some(dir) = &args.debug_dir {
        write_debug(dir, output)?;
    }
    context.job_figures(run.figures);
    context.summary(&format!(
        "motif stylize: {}×{} in {:.0} ms, energy {:.0}, source coverage {:.1} % → {}",
        output.image.width(),
        output.image.height(),
        output.report.total_ms,
        output.report.energy.total,
        100.0 * output.report.source_coverage,
        out.display()
    ));
    Ok(())
}

/// Runs `motif presynth`.
pub(crate) fn run_presynth(args: &PresynthArgs, context: &mut Context) -> anyhow::Result<()> {
    // The folder's files are replaced: no input may live there, and it must be a folder.
    context.check_output_folder("--out-dir", &args.out_dir, &[&args.style, &args.guide])?;
    let style_image = load(&args.style, context.max_memory)?;
    let guide_image = load(&args.guide, context.max_memory)?;
    let job = PresynthJob {
        size: Some([args.size.0, args.size.1]),
        seed: context.seed,
        max_memory: Some(context.max_memory),
        options: args.options.options.clone(),
    };
    let params = job.params()?;
    let style = style_image_channels(&style_image).to_float();
    let guide = guide_image_channels(&guide_image).to_float();
    let run = job.run(PresynthInputs { style, guide }, context.progress())?;
    let textures = &run.textures;
    motif_io::create_folder(&args.out_dir)?;
    let generation = cache::write(&args.out_dir, params.patch_size, textures)?;
    context.job_figures(run.figures.clone());
    context.figure("generation", generation);
    context.summary(&format!(
        "motif presynth: {} segment textures of {}×{} → {}",
        textures.len(),
        args.size.0,
        args.size.1,
        args.out_dir.display()
    ));
    Ok(())
}

/// Runs `motif texture`.
pub(crate) fn run_texture(args: &TextureArgs, context: &mut Context) -> anyhow::Result<()> {
    let mut inputs = vec![args.exemplar.as_path()];
    inputs.extend(args.masking.inputs());
    context.check_output(&args.out, &inputs)?;
    check_debug(args.debug_dir.as_deref(), &inputs, context)?;
    let exemplar = style_image_channels(&load(&args.exemplar, context.max_memory)?);
    let mask = args.masking.read(exemplar.channels(), context.max_memory)?;
    let job = TextureJob {
        size: [args.size.0, args.size.1],
        seed: context.seed,
        max_memory: Some(context.max_memory),
        options: args.options.options.clone(),
    };
    let run = job
        .run(TextureInputs { exemplar, mask }, context.progress())
        .with_context(|| format!("cannot synthesize from {}{}", args.exemplar.display(), args.masking.describe()))?;
    let output = &run.output;
    motif_io::write_png(&args.out, &RgbaImage::from_float(&output.image))?;
    if let Some(dir) = &args.debug_dir {
        write_debug(dir, output)?;
    }
    let quilt = match (run.figures["quilt_block"].as_u64(), run.figures["quilt_block_inferred"].as_bool()) {
        (Some(0) | None, _) => String::new(),
        (Some(block), inferred) => {
            format!(", quilt block {block}{}", if inferred == Some(true) { " (inferred)" } else { "" })
        }
    };
    let coarse = match (run.figures["coarse_patch_size"].as_u64(), run.figures["coarse_patch_size_inferred"].as_bool())
    {
        (Some(0) | None, _) => String::new(),
        (Some(side), inferred) => {
            format!(", coarse patch {side}{}", if inferred == Some(true) { " (inferred)" } else { "" })
        }
    };
    context.job_figures(run.figures);
    context.summary(&format!(
        "motif texture: {}×{}{}{quilt}{coarse} in {:.0} ms, energy {:.0} → {}",
        args.size.0,
        args.size.1,
        if args.options.own.tileable { " (tileable)" } else { "" },
        output.report.total_ms,
        output.report.energy.total,
        args.out.display()
    ));
    Ok(())
}

/// The stylize engine in the registry.
pub(crate) struct Stylize;

impl crate::registry::Engine for Stylize {
    fn name(&self) -> &'static str {
        "stylize"
    }

    fn demo(&self, gallery: &mut Demo<'_>) -> anyhow::Result<()> {
        demo::demo(gallery)
    }

    fn bench(&self, bench: &crate::suite::Bench) -> anyhow::Result<serde_json::Value> {
        bench::bench(bench)
    }
}
