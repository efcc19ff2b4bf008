//! One pyramid level laid out for fast patch distances (Eq. 4).
//!
//! Every channel of the style and of all guides is stacked into one interleaved buffer per side,
//! stored as 8 bits like ebsynth's images (4× less memory than floats). Each channel `c` is stored
//! as `round(v · 255 · sqrt(w_c / w_max))`, so the weighted patch distance of Eq. 4 is
//! `w_max · Σ (a − b)²` over plain integer differences: one integer sum of squares per patch row,
//! which the compiler vectorizes (multiply-add of 16-bit pairs), with one float multiply per row
//! for the early exit. Channels of the largest weight (all of them when the weights are equal, the
//! common case) keep full 8-bit precision; a channel of weight `w` keeps `sqrt(w / w_max)` of it.
//! The target buffer is padded by the patch radius (border clamped, or wrapped when tileable) so
//! every target patch is in bounds too.

use std::borrow::Cow;

use motif_core::{ChannelImage, FloatImage, Samples};
use rayon::prelude::*;

use crate::centres::{SegmentCentres, segment_centres};

/// The largest patch side whose distances are summed whole, without early exit.
pub(crate) const WHOLE_PATCH_SIDE: usize = 5;

/// Marks a target pixel whose segment has no source pixels: it may match anywhere.
pub(crate) const UNRESTRICTED: u16 = u16::MAX;

/// A pyramid level of the source (style + guides) and target (output style + guides).
pub(crate) struct Level<'a> {
    /// Patch side.
    pub patch: usize,
    /// Patch radius, `patch / 2`.
    pub radius: usize,
    /// Channels per stacked pixel: style channels first, then guide channels.
    pub channels: usize,
    /// Style channels (the first `style_channels` of each stacked pixel).
    pub style_channels: usize,
    /// Source size.
    pub source_width: usize,
    /// Source size.
    pub source_height: usize,
    /// Stacked source, 8-bit: `source_width × source_height × channels` (borrowed from a
    /// [`crate::PreparedStyle`] when the run has one).
    pub source: Cow<'a, [u8]>,
    /// The style at this level, unweighted (voting averages these values), borrowed from the
    /// pyramid: no copy of the largest level.
    pub style: Samples<'a>,
    /// Per stacked channel: `255 · sqrt(w_c / w_max)`, the 8-bit scale of its values.
    pub channel_scales: Vec<f32>,
    /// `w_max`: the largest channel weight, the factor of every integer sum of squares.
    pub weight: f32,
    /// Target size.
    pub target_width: usize,
    /// Target size.
    pub target_height: usize,
    /// Padded target row length in pixels: `target_width + 2 · radius`.
    pub padded_width: usize,
    /// Stacked, padded target, 8-bit: `padded_width × (target_height + 2·radius) × channels`.
    /// Its guide channels are written once, when the level is built; votes rewrite the style's.
    pub target: Vec<u8>,
    /// Whether target patches wrap around the borders.
    pub tileable: bool,
    /// Segment label of every source pixel (when segments are on).
    pub source_labels: Option<Cow<'a, [u16]>>,
    /// Per target pixel: the only source label its patch may match, or [`UNRESTRICTED`].
    pub target_restrict: Option<Vec<u16>>,
    /// Per label: the valid source patch centres with that label (for random candidates).
    pub segment_centres: Cow<'a, [SegmentCentres]>,
    /// Which target patch centres are searched (all when `None`; the band in §3.7 mode).
    pub active: Option<Vec<bool>>,
    /// Which target pixels voting writes (all when `None`).
    pub domain: Option<Vec<bool>>,
    /// The largest offset of PatchMatch's random search around a match: the source's larger
    /// side (the whole source) unless the level only refines upsampled matches
    /// ([`crate::Params::local_search_above`]).
    pub search_radius: usize,
    /// Texture synthesis from a large exemplar: ω_best of the occurrence penalty counts at most
    /// this many source pixels per searched target patch (`crate::occurrence`); `None`: all.
    pub source_share_cap: Option<usize>,
}

/// What a level is built from.
/// `'a`: the style, which the level keeps borrowing; `'s`: the rest, read while building it.
pub(crate) struct LevelSpec<'s, 'a, I> {
    pub patch: usize,
    pub style: &'a I,
    /// Per style channel: α / style channels.
    pub style_weights: &'s [f32],
    /// The source guides (style's size) and target guides (target size), one image each.
    pub source_guides: Vec<&'s I>,
    pub target_guides: Vec<&'s I>,
    /// Per stacked guide channel: β_i / channels of guide i.
    pub guide_weights: &'s [f32],
    pub target_size: (usize, usize),
    pub tileable: bool,
    pub source_labels: Option<Cow<'a, [u16]>>,
    pub target_labels: Option<Cow<'s, [u16]>>,
    pub label_count: usize,
    /// The style side made once for many runs, used when it fits this level's patch and weights.
    pub prepared: Option<&'a crate::PreparedStyle<I>>,
}

impl<'a> Level<'a> {
    /// Stacks and weights the images of one level.
    pub(crate) fn new<I: ChannelImage>(spec: LevelSpec<'_, 'a, I>) -> Level<'a> {
        let patch = spec.patch;
        let radius = patch / 2;
        let style_channels = spec.style.channels();
        let guide_channels = spec.guide_weights.len();
        let channels = style_channels + guide_channels;
        let (source_width, source_height) = (spec.style.width(), spec.style.height());
        let (weight, scales) = channel_scales(spec.style_weights, spec.guide_weights);
        let prepared = spec.prepared.and_then(|prepared| prepared.source_side(patch, &scales));
        let (source, segment_centres) = prepared.unwrap_or_else(|| {
            let source = stack_source(spec.style, &spec.source_guides, &scales);
            let centres = spec.source_labels.as_deref().map_or_else(
                || vec![SegmentCentres::EMPTY; spec.label_count],
                |labels| segment_centres(labels, (source_width, source_height), radius, spec.label_count),
            );
            (Cow::Owned(source), Cow::Owned(centres))
        });
        let (target_width, target_height) = spec.target_size;
        let padded_width = target_width + 2 * radius;
        let padded_height = target_height + 2 * radius;
        let mut target = vec![0_u8; padded_width * padded_height * channels];
        if guide_channels > 0 {
            let target_images = spec.target_guides.iter().map(|g| (g.samples(), g.channels()));
            let guides = Quantizer::consecutive(target_images, &scales[style_channels..]);
            let columns: Vec<usize> =
                (0..padded_width).map(|px| unpadded(px, target_width, radius, spec.tileable)).collect();
            target.par_chunks_mut(padded_width * channels).enumerate().for_each(|(py, row)| {
                let first = unpadded(py, target_height, radius, spec.tileable) * target_width;
                stack_row(&guides, (first, &columns), row, (channels, style_channels));
            });
        }
        let target_restrict = spec.target_labels.map(|labels| {
            labels
                .iter()
                .map(|&label| if segment_centres[usize::from(label)].is_empty() { UNRESTRICTED } else { label })
                .collect()
        });
        Level {
            patch,
            radius,
            channels,
            style_channels,
            source_width,
            source_height,
            source,
            channel_scales: scales,
            weight,
            target_width,
            target_height,
            padded_width,
            target,
            tileable: spec.tileable,
            source_labels: spec.source_labels,
            target_restrict,
            segment_centres,
            active: None,
            domain: None,
            search_radius: source_width.max(source_height),
            source_share_cap: None,
            style: spec.style.samples(),
        }
    }

    /// Number of target pixels.
    pub(crate) fn target_len(&self) -> usize {
        self.target_width * self.target_height
    }

    /// Whether target patch centre `index` is searched.
    #[inline]
    pub(crate) fn is_active(&self, index: usize) -> bool {
        self.active.as_ref().is_none_or(|active| active[index])
    }

    /// Whether target pixel `index` is written by voting.
    #[inline]
    pub(crate) fn in_domain(&self, index: usize) -> bool {
        self.domain.as_ref().is_none_or(|domain| domain[index])
    }

    /// Source centre `s` as `(x, y)`, divided in 32 bits (centres are `u32`, so the width fits;
    /// a 32-bit division is several times cheaper than a 64-bit one on most x86 processors).
    #[inline]
    pub(crate) fn source_xy(&self, s: u32) -> (usize, usize) {
        let width = self.source_width as u32;
        ((s % width) as usize, (s / width) as usize)
    }

    /// The column of source centre `s` ([`Self::source_xy`]'s first half, where only it is needed).
    #[inline]
    pub(crate) fn source_x(&self, s: u32) -> usize {
        (s % self.source_width as u32) as usize
    }

    /// The centres that target pixel `t` may match when its segment restricts it (§3.6).
    #[inline]
    pub(crate) fn segment_of(&self, t: usize) -> Option<&SegmentCentres> {
        let label = self.target_restrict.as_ref()?[t];
        (label != UNRESTRICTED).then(|| &self.segment_centres[usize::from(label)])
    }

    /// Whether source centre `s` may serve target pixel `t` (segment restriction, §3.6).
    #[inline]
    pub(crate) fn allowed(&self, t: usize, s: u32) -> bool {
        match (&self.target_restrict, &self.source_labels) {
            (Some(restrict), Some(labels)) => {
                let wanted = restrict[t];
                wanted == UNRESTRICTED || labels[s as usize] == wanted
            }
            _ => true,
        }
    }

    /// The first and one-past-last valid source centre coordinate on each axis.
    #[inline]
    pub(crate) fn valid_x(&self) -> (usize, usize) {
        (self.radius, self.source_width - self.radius)
    }

    /// See [`valid_x`](Self::valid_x).
    #[inline]
    pub(crate) fn valid_y(&self) -> (usize, usize) {
        (self.radius, self.source_height - self.radius)
    }

    /// Weighted squared distance between source patch centred at `s` and the target patch
    /// centred at `(x, y)`; stops early (returning a value ≥ `limit`) once a partial sum
    /// reaches `limit`. `ROW` is the patch row length (`patch × channels` bytes) when fixed at
    /// compile time, else 0 (see [`row_distance_n`]).
    #[inline(always)]
    pub(crate) fn distance<const ROW: usize>(&self, s: u32, x: usize, y: usize, limit: f32) -> f32 {
        self.distance_from::<ROW>(s, x, y, 0, 0.0, limit)
    }

    /// The first patch row's share of [`distance`](Self::distance). Computing it for a batch of
    /// candidates before any branch on the results lets the processor overlap their cache
    /// misses (random source patches rarely sit in L2). `ROW` is the patch row length in bytes
    /// (`patch × channels`) when known at compile time, else 0 (see [`row_distance_n`]).
    #[inline(always)]
    pub(crate) fn first_row<const ROW: usize>(&self, s: u32, x: usize, y: usize) -> f32 {
        let channels = self.channels;
        let row_len = self.patch * channels;
        let source_offset = (s as usize - self.radius * (self.source_width + 1)) * channels;
        let target_offset = (y * self.padded_width + x) * channels;
        self.weight
            * row_distance_n::<ROW>(
                &self.source[source_offset..source_offset + row_len],
                &self.target[target_offset..target_offset + row_len],
            ) as f32
    }

    /// Reads one byte of every row of source patch `s`: issued for a whole batch of candidates
    /// before their distances, these independent loads overlap their cache misses (a software
    /// prefetch without `unsafe`).
    #[inline(always)]
    pub(crate) fn touch(&self, s: u32) -> u32 {
        let stride = self.source_width * self.channels;
        let start = (s as usize - self.radius * (self.source_width + 1)) * self.channels;
        (0..self.patch).map(|row| u32::from(self.source[start + row * stride])).sum()
    }

    /// Where the rows of the source patch centred on `s` and of the target patch at `(x, y)` lie.
    #[inline(always)]
    fn patch_rows(&self, s: u32, x: usize, y: usize) -> PatchRows {
        let channels = self.channels;
        PatchRows {
            row_len: self.patch * channels,
            source_stride: self.source_width * channels,
            target_stride: self.padded_width * channels,
            // Top-left of the source patch: `s − radius · (width + 1)` (no division needed).
            source: (s as usize - self.radius * (self.source_width + 1)) * channels,
            target: (y * self.padded_width + x) * channels,
        }
    }

    /// [`distance`](Self::distance) continued from patch row `first_row`, with `partial` the sum
    /// of the rows before it; `ROW` as in [`first_row`](Self::first_row).
    #[inline(always)]
    pub(crate) fn distance_from<const ROW: usize>(
        &self,
        s: u32,
        x: usize,
        y: usize,
        first_row: usize,
        partial: f32,
        limit: f32,
    ) -> f32 {
        let PatchRows { row_len, source_stride, target_stride, source, target } = self.patch_rows(s, x, y);
        let mut source_offset = source + first_row * source_stride;
        let mut target_offset = target + first_row * target_stride;
        let mut total = partial;
        for _ in first_row..self.patch {
            total += self.weight
                * row_distance_n::<ROW>(
                    &self.source[source_offset..source_offset + row_len],
                    &self.target[target_offset..target_offset + row_len],
                ) as f32;
            if total >= limit {
                return total;
            }
            source_offset += source_stride;
            target_offset += target_stride;
        }
        total
    }

    /// [`distance_from`](Self::distance_from), but for patches of at most [`WHOLE_PATCH_SIDE`]
    /// without early exit: their rows are loaded together and up to four unpredictable branches
    /// fewer are taken, which costs less than the rows saved (a 5×5 map tile's band computed
    /// 34 of the 41 rows with early exit). The callers compare the result with `limit`, and a sum
    /// that stopped early is ≥ `limit` as the full one is (the terms are not negative), so the
    /// decisions are the same; a full sum adds the same terms in the same order, so it is the
    /// same value.
    #[inline(always)]
    pub(crate) fn distance_small<const ROW: usize>(
        &self,
        s: u32,
        x: usize,
        y: usize,
        first_row: usize,
        partial: f32,
        limit: f32,
    ) -> f32 {
        if self.patch > WHOLE_PATCH_SIDE {
            return self.distance_from::<ROW>(s, x, y, first_row, partial, limit);
        }
        let PatchRows { row_len, source_stride, target_stride, source: source_offset, target: target_offset } =
            self.patch_rows(s, x, y);
        let mut total = partial;
        for row in first_row..self.patch {
            let (source, target) = (source_offset + row * source_stride, target_offset + row * target_stride);
            total += self.weight
                * row_distance_n::<ROW>(&self.source[source..source + row_len], &self.target[target..target + row_len])
                    as f32;
        }
        total
    }

    /// Like [`distance`](Self::distance) without early exit, split into the style part and the
    /// guide part (for the report), with the distance itself, summed row by row as
    /// [`distance_from`](Self::distance_from) sums it (the same value).
    pub(crate) fn distance_parts(&self, s: u32, x: usize, y: usize) -> (f32, f32, f32) {
        let (channels, style_channels) = (self.channels, self.style_channels);
        let row_len = self.patch * channels;
        let mut source_offset = (s as usize - self.radius * (self.source_width + 1)) * channels;
        let mut target_offset = (y * self.padded_width + x) * channels;
        let (mut style, mut guide, mut total) = (0_u32, 0_u32, 0.0_f32);
        for _ in 0..self.patch {
            let source = &self.source[source_offset..source_offset + row_len];
            let target = &self.target[target_offset..target_offset + row_len];
            let (mut row_style, mut row_guide) = (0_u32, 0_u32);
            for (a, b) in source.chunks_exact(channels).zip(target.chunks_exact(channels)) {
                for (channel, (&p, &q)) in a.iter().zip(b).enumerate() {
                    let d = i32::from(p) - i32::from(q);
                    if channel < style_channels { row_style += (d * d) as u32 } else { row_guide += (d * d) as u32 }
                }
            }
            style += row_style;
            guide += row_guide;
            total += self.weight * (row_style + row_guide) as f32;
            source_offset += self.source_width * channels;
            target_offset += self.padded_width * channels;
        }
        (self.weight * style as f32, self.weight * guide as f32, total)
    }

    /// Replaces the target's style channels by `image` (target size, values in `[0, 1]`) and
    /// refreshes the padding. With `only_domain`, only pixels of the voting domain are rewritten
    /// (after a vote, the only ones that can have changed; the band in §3.7 mode).
    pub(crate) fn set_target_style(&mut self, image: &FloatImage, only_domain: bool) {
        let domain = if only_domain { self.domain.as_deref() } else { None };
        let (channels, style_channels, radius) = (self.channels, self.style_channels, self.radius);
        let (width, height, padded_width) = (self.target_width, self.target_height, self.padded_width);
        let (tileable, scales) = (self.tileable, &self.channel_scales[..style_channels]);
        self.target.par_chunks_mut(padded_width * channels).enumerate().for_each(|(py, row)| {
            let y = unpadded(py, height, radius, tileable);
            for px in 0..padded_width {
                let x = unpadded(px, width, radius, tileable);
                if domain.is_some_and(|domain| !domain[y * width + x]) {
                    continue;
                }
                let out = &mut row[px * channels..px * channels + style_channels];
                for ((slot, value), scale) in out.iter_mut().zip(image.pixel(x, y)).zip(scales) {
                    *slot = quantize(*value, *scale);
                }
            }
        });
    }
}

/// The image coordinate of padded coordinate `p` (padding `radius`) on an axis of `size` pixels:
/// wrapped when tileable, else clamped to the border.
#[inline]
fn unpadded(p: usize, size: usize, radius: usize, tileable: bool) -> usize {
    let v = p as isize - radius as isize;
    if tileable { v.rem_euclid(size as isize) as usize } else { v.clamp(0, size as isize - 1) as usize }
}

/// The style and source guides stacked pixel by pixel, channel `c` quantized with `scales[c]`.
pub(crate) fn stack_source<I: ChannelImage>(style: &I, source_guides: &[&I], scales: &[f32]) -> Vec<u8> {
    let channels = scales.len();
    let width = style.width();
    let images = std::iter::once((style.samples(), style.channels()))
        .chain(source_guides.iter().map(|g| (g.samples(), g.channels())));
    let quantizers = Quantizer::consecutive(images, scales);
    let mut source = vec![0_u8; width * style.height() * channels];
    let columns: Vec<usize> = (0..width).collect();
    source.par_chunks_mut(width * channels).enumerate().for_each(|(y, row)| {
        stack_row(&quantizers, (y * width, &columns), row, (channels, 0));
    });
    source
}

/// One stacked row: pixel `i` of `row` (`stride` bytes each) takes, from byte `offset` on, the
/// quantized samples of pixel `first + columns[i]` of every image of `quantizers` in turn.
fn stack_row(
    quantizers: &[Quantizer<'_>],
    (first, columns): (usize, &[usize]),
    row: &mut [u8],
    (stride, offset): (usize, usize),
) {
    let mut offset = offset;
    for image in quantizers {
        image.stack_row((first, columns), row, (stride, offset));
        offset += image.channels();
    }
}

/// The largest channel weight `w_max` and each channel's 8-bit scale `255 · sqrt(w_c / w_max)`,
/// style channels first, then the guides'.
pub(crate) fn channel_scales(style_weights: &[f32], guide_weights: &[f32]) -> (f32, Vec<f32>) {
    let weights: Vec<f32> = style_weights.iter().chain(guide_weights).copied().collect();
    let weight = weights.iter().copied().fold(0.0_f32, f32::max);
    let scales = weights.iter().map(|&w| if weight > 0.0 { 255.0 * (w / weight).sqrt() } else { 0.0 }).collect();
    (weight, scales)
}

/// The samples of one image stacked into a level, channel `k` quantized with `scales[k]`
/// ([`quantize`]); 8-bit samples through a table per channel made by [`quantize`] itself (the
/// same bytes, without float work per sample).
struct Quantizer<'s> {
    samples: Samples<'s>,
    scales: &'s [f32],
    tables: Vec<[u8; 256]>,
}

impl<'s> Quantizer<'s> {
    fn new(samples: Samples<'s>, scales: &'s [f32]) -> Self {
        let tables = match samples {
            Samples::Byte(_) => scales
                .iter()
                .map(|&scale| std::array::from_fn(|byte| quantize(motif_core::channel_image::BYTE_VALUES[byte], scale)))
                .collect(),
            Samples::Float(_) => Vec::new(),
        };
        Self { samples, scales, tables }
    }

    /// One quantizer per image of `(samples, channels)`, taking their scales from `scales` in turn.
    fn consecutive(images: impl Iterator<Item = (Samples<'s>, usize)>, scales: &'s [f32]) -> Vec<Self> {
        let mut first = 0;
        images
            .map(|(samples, channels)| {
                first += channels;
                Self::new(samples, &scales[first - channels..first])
            })
            .collect()
    }

    fn channels(&self) -> usize {
        self.scales.len()
    }

    /// This image's part of [`stack_row`]: its channels of pixel `first + columns[i]`, quantized,
    /// into bytes `offset..` of pixel `i` of `row` (`stride` bytes a pixel). The sample type is
    /// matched once a row, not once a value.
    fn stack_row(&self, (first, columns): (usize, &[usize]), row: &mut [u8], (stride, offset): (usize, usize)) {
        let n = self.scales.len();
        let pixels =
            row.chunks_exact_mut(stride).zip(columns).map(|(out, &x)| (&mut out[offset..offset + n], first + x));
        match self.samples {
            Samples::Byte(values) => {
                for (out, index) in pixels {
                    for ((slot, &value), table) in
                        out.iter_mut().zip(&values[index * n..(index + 1) * n]).zip(&self.tables)
                    {
                        *slot = table[usize::from(value)];
                    }
                }
            }
            Samples::Float(values) => {
                for (out, index) in pixels {
                    for ((slot, &value), &scale) in
                        out.iter_mut().zip(&values[index * n..(index + 1) * n]).zip(self.scales)
                    {
                        *slot = quantize(value, scale);
                    }
                }
            }
        }
    }
}

/// A value in `[0, 1]` times `scale` (at most 255) as 8 bits, rounded.
#[inline]
pub(crate) fn quantize(value: f32, scale: f32) -> u8 {
    // `+ 0.5` then truncation rounds half up like `round` on these non-negative values, without
    // the libm call (`round` is not an SSE2 instruction), which dominated re-quantizing after votes.
    (value.clamp(0.0, 1.0) * scale + 0.5) as u8
}

/// [`row_distance`] for rows of exactly `ROW` bytes (0 = any length): with the length a constant
/// the loop is fully unrolled into whole vector steps, instead of a vector body plus a scalar
/// tail that, for rows of 18 or 30 bytes, costs as much as the body.
#[inline(always)]
pub(crate) fn row_distance_n<const ROW: usize>(a: &[u8], b: &[u8]) -> u32 {
    if ROW == 0 {
        return row_distance(a, b);
    }
    let (a, b) = (&a[..ROW], &b[..ROW]);
    let mut sum = 0_u32;
    for i in 0..ROW {
        sum += byte_square(a[i], b[i]);
    }
    sum
}

/// `(a − b)²` of two bytes. The square of a byte difference fits 16 bits (at most 255² = 65 025):
/// squaring in 16-bit lanes does twice the pixels per vector step of 32-bit ones, and the
/// compiler widens only the squares for the sum.
#[inline(always)]
fn byte_square(a: u8, b: u8) -> u32 {
    let difference = u16::from(a.abs_diff(b));
    u32::from(difference * difference)
}

/// Integer sum of squared differences of two equal-length 8-bit rows. Integer sums are
/// associative, so the compiler vectorizes freely and the result is exact (no order effects).
/// Fits `u32` for rows up to 66 000 bytes (`patch × channels`, far beyond the 31 × 256 allowed).
#[inline(always)]
pub(crate) fn row_distance(a: &[u8], b: &[u8]) -> u32 {
    a.iter().zip(b).map(|(&x, &y)| byte_square(x, y)).sum()
}

/// The first rows (byte offsets) and row steps of a source and a target patch.
struct PatchRows {
    row_len: usize,
    source_stride: usize,
    target_stride: usize,
    source: usize,
    target: usize,
}
