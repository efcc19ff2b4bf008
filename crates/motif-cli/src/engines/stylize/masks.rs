//! Masks on `motif stylize` and `motif texture` (`--mask` with `--keep`), `motif inpaint`, and
//! `motif zoom`.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use clap::Args;
use motif_core::{ByteImage, RgbaImage};
use motif_jobs::Job;
use motif_jobs::stylize::Mask;
use motif_jobs::stylize::{
    InpaintInputs, InpaintJob, SynthesisOptions, ZoomJob, ZoomJobOptions, hole_of, kept_image, style_image_channels,
};

use super::{load, write_debug};
use crate::context::Context;
use crate::job_args::JobArgs;

/// Synthesize only part of the output (ebsynth's masks).
#[derive(Args, Debug, Clone)]
pub struct MaskOptions {
    /// Synthesize only where this image (the output's size) is white, at least half white and
    /// half opaque; every other pixel is kept exactly from --keep. At every pyramid level only
    /// the patches touching the mask are optimized, against the kept pixels around them, so the
    /// border is seamless.
    #[arg(long, value_name = "MASK.png", requires = "keep")]
    pub mask: Option<PathBuf>,
    /// The image (the output's size) whose pixels outside --mask the output keeps.
    #[arg(long, value_name = "KEEP.png", requires = "mask")]
    pub keep: Option<PathBuf>,
}

impl MaskOptions {
    /// The files to protect from being overwritten.
    pub fn inputs(&self) -> impl Iterator<Item = &Path> {
        self.mask.iter().chain(&self.keep).map(PathBuf::as_path)
    }

    /// The mask for a style of `channels` channels, when one is given, read within `max_memory`.
    pub fn read(&self, channels: usize, max_memory: u64) -> anyhow::Result<Option<Mask<ByteImage>>> {
        let (Some(mask_path), Some(keep_path)) = (&self.mask, &self.keep) else { return Ok(None) };
        let (mask, keep) = (load(mask_path, max_memory)?, load(keep_path, max_memory)?);
        same_size(&mask, mask_path, &keep, keep_path)?;
        Ok(Some(Mask { keep: kept_image(&keep, channels), hole: hole_of(&mask), exclude_hole_from_style: false }))
    }

    /// Names the files in an error of the masked run.
    pub fn describe(&self) -> String {
        match (&self.mask, &self.keep) {
            (Some(mask), Some(keep)) => format!(" with --mask {} and --keep {}", mask.display(), keep.display()),
            _ => String::new(),
        }
    }
}

/// A mask must have the size of the image it masks.
fn same_size(mask: &RgbaImage, mask_path: &Path, image: &RgbaImage, image_path: &Path) -> anyhow::Result<()> {
    if (mask.width(), mask.height()) != (image.width(), image.height()) {
        anyhow::bail!(
            "the mask {} is {}×{} but {} is {}×{}: they must have the same size",
            mask_path.display(),
            mask.width(),
            mask.height(),
            image_path.display(),
            image.width(),
            image.height()
        );
    }
    Ok(())
}

/// Options of `motif inpaint`.
#[derive(Args, Debug)]
pub struct InpaintArgs {
    /// The image with a hole to fill (PNG/JPEG/WebP).
    #[arg(long, value_name = "IMAGE.png")]
    pub image: PathBuf,
    /// The hole: white (at least half white and half opaque) where the image is filled, black
    /// where it is kept; the image's size.
    #[arg(long, value_name = "HOLE.png")]
    pub mask: PathBuf,
    /// Every option of the synthesis, declared in `motif_jobs::stylize::SynthesisOptions`.
    #[command(flatten)]
    pub options: JobArgs<SynthesisOptions>,
    /// Also write nnf.png and error.png into this directory (see `motif stylize --help`).
    #[arg(long, value_name = "DIR")]
    pub debug_dir: Option<PathBuf>,
    /// The filled image (PNG).
    #[arg(long, value_name = "OUT.png")]
    pub out: PathBuf,
}

/// Runs `motif inpaint`.
pub(crate) fn run_inpaint(args: &InpaintArgs, context: &mut Context) -> anyhow::Result<()> {
    context.check_output(&args.out, &[&args.image, &args.mask])?;
    super::check_debug(args.debug_dir.as_deref(), &[&args.image, &args.mask], context)?;
    let (image, mask) = (load(&args.image, context.max_memory)?, load(&args.mask, context.max_memory)?);
    same_size(&mask, &args.mask, &image, &args.image)?;
    let image = style_image_channels(&image);
    let hole = hole_of(&mask);
    let holes = hole.iter().filter(|&&h| h).count();
    let job =
        InpaintJob { seed: context.seed, max_memory: Some(context.max_memory), options: args.options.options.clone() };
    let run = job
        .run(InpaintInputs { image, hole }, context.progress())
        .with_context(|| format!("cannot fill {} with the hole {}", args.image.display(), args.mask.display()))?;
    let output = &run.output;
    motif_io::write_png(&args.out, &RgbaImage::from_float(&output.image))?;
    if let Some(dir) = &args.debug_dir {
        write_debug(dir, output)?;
    }
    context.figure("hole_pixels", holes);
    context.job_figures(run.figures);
    context.summary(&format!(
        "motif inpaint: {holes} pixels filled in {:.0} ms, energy {:.0} → {}",
        output.report.total_ms,
        output.report.energy.total,
        args.out.display()
    ));
    Ok(())
}

/// Options of `motif zoom`.
#[derive(Args, Debug)]
pub struct ZoomArgs {
    /// The texture exemplar (PNG/JPEG/WebP).
    #[arg(long, value_name = "EX.png")]
    pub exemplar: PathBuf,
    /// Size of every zoom level in pixels.
    #[arg(long, value_name = "WxH", value_parser = super::parse_size)]
    pub size: (usize, usize),
    /// Every option of the synthesis, declared in `motif_jobs::stylize` (`SynthesisOptions`,
    /// `ZoomOptions`).
    #[command(flatten)]
    pub options: JobArgs<ZoomJobOptions>,
    /// Output folder (created if missing): zoom-01.png (unzoomed), zoom-02.png, …
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
}

/// Runs `motif zoom`.
pub(crate) fn run_zoom(args: &ZoomArgs, context: &mut Context) -> anyhow::Result<()> {
    let names: Vec<PathBuf> =
        (1..=args.options.own.levels.min(64)).map(|level| args.out_dir.join(format!("zoom-{level:02}.png"))).collect();
    // The folder is made after the run, if missing.
    context.check_outputs_in(&args.out_dir, &names, &[&args.exemplar])?;
    let exemplar = style_image_channels(&load(&args.exemplar, context.max_memory)?).to_float();
    let job = ZoomJob {
        size: [args.size.0, args.size.1],
        seed: context.seed,
        max_memory: Some(context.max_memory),
        options: args.options.options.clone(),
    };
    let factor = job.options.own.factor;
    let run = job
        .run(exemplar, context.progress())
        .with_context(|| format!("cannot zoom into {}", args.exemplar.display()))?;
    motif_io::create_folder(&args.out_dir)?;
    for (level, name) in run.levels.iter().zip(&names) {
        motif_io::write_png(name, &RgbaImage::from_float(&level.output.image))?;
    }
    let total_ms: f64 = run.levels.iter().map(|level| level.output.report.total_ms).sum();
    let levels = run.levels.len();
    context.job_figures(run.figures);
    context.summary(&format!(
        "motif zoom: {} levels of {}×{}, each {}× closer, in {:.0} ms → {}",
        levels,
        args.size.0,
        args.size.1,
        factor,
        total_ms,
        args.out_dir.display()
    ));
    Ok(())
}
