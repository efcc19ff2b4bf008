//! Running the stylize-family jobs: their typed inputs, their runs and the figures of their
//! reports.

use motif_core::{ByteImage, ChannelImage, FloatImage, InvalidParameter, Progress, RgbaImage};
use motif_stylize::{Guide, Input, Mask, Output, PresynthInput, SegmentTexture};
use serde_json::{Map, Value, json};

use super::{GuidePair, InpaintJob, PresynthJob, StylizeJob, TextureJob, ZoomJob};
use super::{PresynthJobOptions, StylizeJobOptions, SynthesisOptions, TextureJobOptions, ZoomJobOptions};
use crate::{Finished, Job, JobError};

/// A finished stylize, texture or inpaint job.
#[derive(Debug, Clone)]
pub struct StylizeRun {
    /// The engine's output (image, field, error map and its `Report`).
    pub output: Output,
    /// The report's figures as one JSON object, the keys every front end writes.
    pub figures: Map<String, Value>,
}

impl StylizeRun {
    fn of(output: Output) -> Self {
        Self { figures: figures(&output), output }
    }
}

/// The decoded inputs of a stylize job: the style A', the guide pairs (A, B) and, for the band
/// mode of §3.7, the pre-synthesized textures; 8-bit images by default, floats work too.
#[derive(Debug, Clone)]
pub struct StylizeInputs<I = ByteImage> {
    /// The style exemplar A'.
    pub style: I,
    /// The guide pairs (A, B), in order.
    pub guides: Vec<GuidePair<I>>,
    /// Pre-synthesized textures, one per segment (`--presynth`).
    pub textures: Option<Vec<SegmentTexture>>,
    /// Synthesize only the mask's hole and keep the rest.
    pub mask: Option<Mask<I>>,
}

impl<I> StylizeInputs<I> {
    /// The style and its guide pairs, without textures or mask.
    pub fn new(style: I, guides: Vec<GuidePair<I>>) -> Self {
        Self { style, guides, textures: None, mask: None }
    }
}

impl StylizeJob {
    /// [`Job::run`] on images of any channel type (floats as well as bytes).
    pub fn run_on<I: ChannelImage>(
        &self,
        inputs: StylizeInputs<I>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        let StylizeInputs { style, guides, textures, mask } = inputs;
        let weight = &self.options.own.weight;
        if !weight.is_empty() && weight.len() != guides.len() {
            let allowed = format!("none or exactly one per guide ({} guides), in order", guides.len());
            return Err(InvalidParameter::new("weight", format!("{} values", weight.len()), allowed).into());
        }
        let params = self.params(textures.is_some())?;
        let guides = guides
            .into_iter()
            .enumerate()
            .map(|(index, (source, target))| Guide { source, target, weight: weight.get(index).copied() })
            .collect();
        let mut input = Input::guided(style, guides);
        input.textures = textures.map(Into::into);
        input.mask = mask;
        Ok(StylizeRun::of(motif_stylize::synthesize(&input, &params, progress)?))
    }
}

impl Job for StylizeJob {
    const NAME: &'static str = "stylize";
    const FIELDS: &'static [&'static str] = &["seed", "max-memory"];
    const SUMMARY: &'static str = "Paint a target guide in the style of an exemplar (A : A' :: B : B')";
    const DETAILS: &'static str = "Guided patch-based synthesis with occurrence penalty, segments and \
        pre-synthesized textures (Texler et al.); options mirror ebsynth's.";
    type Options = StylizeJobOptions;
    type Inputs<'a> = StylizeInputs;
    type Run = StylizeRun;

    fn run(&self, inputs: StylizeInputs, progress: &mut dyn Progress) -> Result<StylizeRun, JobError> {
        self.run_on(inputs, progress)
    }
}

/// The decoded inputs of a texture job: the exemplar, and a mask to synthesize only part of the
/// output.
#[derive(Debug, Clone)]
pub struct TextureInputs<I = ByteImage> {
    /// The texture exemplar.
    pub exemplar: I,
    /// Synthesize only the mask's hole and keep the rest.
    pub mask: Option<Mask<I>>,
}

impl TextureJob {
    /// [`Job::run`] on images of any channel type (floats as well as bytes).
    pub fn run_on<I: ChannelImage>(
        &self,
        inputs: TextureInputs<I>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        let exemplar_size = (inputs.exemplar.width(), inputs.exemplar.height());
        let (quilt_block, inferred) = self.quilt_block(exemplar_size, inputs.mask.is_some());
        let (coarse_patch_size, coarse_inferred) = self.coarse_patch_size(exemplar_size, quilt_block);
        let params = self.params()?.with_quilt_block(quilt_block).with_coarse_patch_size(coarse_patch_size);
        let mut input = Input::texture(inputs.exemplar, self.size[0], self.size[1]);
        input.mask = inputs.mask;
        let mut run = StylizeRun::of(motif_stylize::synthesize(&input, &params, progress)?);
        run.figures.insert("quilt_block".into(), json!(quilt_block));
        run.figures.insert("quilt_block_inferred".into(), json!(inferred));
        run.figures.insert("coarse_patch_size".into(), json!(coarse_patch_size));
        run.figures.insert("coarse_patch_size_inferred".into(), json!(coarse_inferred));
        Ok(run)
    }
}

impl Job for TextureJob {
    const NAME: &'static str = "texture";
    const FIELDS: &'static [&'static str] = &["size", "seed", "max-memory"];
    const SUMMARY: &'static str = "Grow a texture of any size from an exemplar image, optionally tileable";
    const DETAILS: &'static str = "Patch-based texture synthesis (the stylize engine without guides), started \
        from an image quilt with minimum-error cuts when the output grows the exemplar (--quilt-block, inferred \
        unless given); exemplars much larger than the output are searched whole only at the coarse levels.";
    type Options = TextureJobOptions;
    type Inputs<'a> = TextureInputs;
    type Run = StylizeRun;

    fn run(&self, inputs: TextureInputs, progress: &mut dyn Progress) -> Result<StylizeRun, JobError> {
        self.run_on(inputs, progress)
    }
}

/// The decoded inputs of an inpaint job: the image and its hole.
#[derive(Debug, Clone)]
pub struct InpaintInputs<I = ByteImage> {
    /// The image to fill.
    pub image: I,
    /// Per pixel, row by row: `true` where the image is filled.
    pub hole: Vec<bool>,
}

impl InpaintJob {
    /// [`Job::run`] on images of any channel type (floats as well as bytes).
    pub fn run_on<I: ChannelImage>(
        &self,
        inputs: InpaintInputs<I>,
        progress: &mut dyn Progress,
    ) -> Result<StylizeRun, JobError> {
        let params = self.params()?;
        let input = Input::inpaint(inputs.image, inputs.hole);
        Ok(StylizeRun::of(motif_stylize::synthesize(&input, &params, progress)?))
    }
}

impl Job for InpaintJob {
    const NAME: &'static str = "inpaint";
    const FIELDS: &'static [&'static str] = &["seed", "max-memory"];
    const SUMMARY: &'static str = "Fill a hole in an image from the rest of it";
    const DETAILS: &'static str = "Patch-based synthesis whose kept pixels are the image outside the hole and \
        whose sources are its patches wholly outside it, with the occurrence penalty so the fill does not clone \
        one patch.";
    type Options = SynthesisOptions;
    type Inputs<'a> = InpaintInputs;
    type Run = StylizeRun;

    fn run(&self, inputs: InpaintInputs, progress: &mut dyn Progress) -> Result<StylizeRun, JobError> {
        self.run_on(inputs, progress)
    }
}

/// A finished zoom job: one run per level, outermost first.
#[derive(Debug, Clone)]
pub struct ZoomRun {
    /// The levels, outermost first.
    pub levels: Vec<StylizeRun>,
    /// The whole run's figures: `estimated_memory_bytes`, `levels`, `factor`, `level_ms`.
    pub figures: Map<String, Value>,
}

impl Job for ZoomJob {
    const NAME: &'static str = "zoom";
    const FIELDS: &'static [&'static str] = &["size", "seed", "max-memory"];
    const SUMMARY: &'static str = "Zoom into a texture without end: every level synthesized at full resolution";
    const DETAILS: &'static str = "Each level is guided by the centre of the level above, scaled up, so zooming \
        keeps both the layout and the style's own detail (the map paper's §5.3).";
    type Options = ZoomJobOptions;
    type Inputs<'a> = FloatImage;
    type Run = ZoomRun;

    /// Synthesizes the zoom levels of a texture of the exemplar, outermost first.
    fn run(&self, exemplar: FloatImage, progress: &mut dyn Progress) -> Result<ZoomRun, JobError> {
        let params = self.params()?;
        let estimate = self.memory_bytes(&exemplar);
        let input = Input::texture(exemplar, self.size[0], self.size[1]);
        let (factor, levels) = (self.options.own.factor, self.options.own.levels);
        let outputs = motif_stylize::zoom(&input, factor, levels, &params, progress)?;
        let levels: Vec<StylizeRun> = outputs.into_iter().map(StylizeRun::of).collect();
        let figures = crate::object(json!({
            "estimated_memory_bytes": estimate,
            "levels": levels.len(),
            "factor": factor,
            "level_ms": levels.iter().map(|run| run.output.report.total_ms).collect::<Vec<_>>(),
        }));
        Ok(ZoomRun { levels, figures })
    }
}

/// The decoded inputs of a presynth job: the style and its segment guide (the style's size).
#[derive(Debug, Clone)]
pub struct PresynthInputs {
    /// The style exemplar A'.
    pub style: FloatImage,
    /// Its segment guide A.
    pub guide: FloatImage,
}

/// A finished presynth job: one seamless texture per segment.
#[derive(Debug, Clone)]
pub struct PresynthRun {
    /// The textures, one per segment colour.
    pub textures: Vec<SegmentTexture>,
    /// The run's figures: `estimated_memory_bytes`, `segments`, `texture_size`.
    pub figures: Map<String, Value>,
}

impl Job for PresynthJob {
    const NAME: &'static str = "presynth";
    const FIELDS: &'static [&'static str] = &["size", "seed", "max-memory"];
    const SUMMARY: &'static str =
        "Make one seamless texture per segment of a style's guide, for `motif stylize --presynth`";
    const DETAILS: &'static str = "The pre-synthesized textures of Texler et al. §3.7: the target is then filled \
        from them and only a band along segment edges is optimized.";
    type Options = PresynthJobOptions;
    type Inputs<'a> = PresynthInputs;
    type Run = PresynthRun;

    fn run(&self, inputs: PresynthInputs, progress: &mut dyn Progress) -> Result<PresynthRun, JobError> {
        let params = self.params()?;
        let [width, height] = self.texture_size();
        let style_shape = (inputs.style.width(), inputs.style.height(), inputs.style.channels());
        let input = PresynthInput { style: inputs.style, guide: inputs.guide, size: (width, height) };
        let textures: Vec<SegmentTexture> =
            motif_stylize::presynthesize(&input, &params, progress)?.into_iter().map(as_stored).collect();
        let estimate = motif_stylize::presynth_memory(style_shape, (width, height), textures.len());
        let figures = crate::object(json!({
            "estimated_memory_bytes": estimate.total(),
            "segments": textures.len(),
            "texture_size": [width, height],
        }));
        Ok(PresynthRun { textures, figures })
    }
}

/// A texture as 8-bit files hold it (image and colour in bytes), so that stylizing from textures
/// kept in memory (Python, the page) gives the bytes of a run from `motif presynth`'s folder.
fn as_stored(texture: SegmentTexture) -> SegmentTexture {
    let bytes = RgbaImage::from_float(&texture.image);
    let image = if texture.image.channels() == 4 { bytes.to_float() } else { bytes.to_float_channels(&[0, 1, 2]) };
    let colour = texture.colour.iter().map(|v| f32::from((v.clamp(0.0, 1.0) * 255.0).round() as u8) / 255.0).collect();
    SegmentTexture { colour, image, ..texture }
}

macro_rules! finished {
    ($($run:ty),+) => {$(
        impl Finished for $run {
            fn figures(&self) -> &Map<String, Value> {
                &self.figures
            }
        }
    )+};
}

finished!(StylizeRun, ZoomRun, PresynthRun);

/// The figures of a stylize or texture run under the keys of `--report`.
pub fn figures(output: &Output) -> Map<String, Value> {
    let report = &output.report;
    let value = json!({
        "energy": report.energy,
        "estimated_memory_bytes": report.estimated_memory_bytes,
        "source_coverage": report.source_coverage,
        "stages_ms": crate::stages(&report.stages_ms),
        "engine_ms": report.total_ms,
        "levels": report.levels,
        "searched_pixels": report.searched_pixels,
        "output_size": [output.image.width(), output.image.height()],
    });
    crate::object(value)
}
