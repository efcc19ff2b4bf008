//! The style side of band mode (§3.7) made once for many targets: a slippy map's tiles share
//! their style, source guides and textures, and only their target guides differ.
//!
//! [`prepare`] stacks the style and source guides into the patch distance's 8-bit layout (what
//! `Level::new` does for every run), labels the source by the textures' colours and lists each
//! segment's valid patch centres. A run given the result ([`Input::prepared`]) checks that it was
//! made from the same style, source guides, texture colours, weights and patch size (refused
//! otherwise), and stacks and labels only its target: the same bytes as without it.

use std::borrow::Cow;

use motif_core::{ChannelImage, FloatImage};

use crate::centres::{SegmentCentres, segment_centres};
use crate::level::{channel_scales, stack_source};
use crate::{Error, Input, InputError, Params};

/// A level's stacked source and its segments' patch centres, borrowed or the level's own.
pub(crate) type SourceSide<'a> = (Cow<'a, [u8]>, Cow<'a, [SegmentCentres]>);

/// The style side of band mode prepared once ([`prepare`]) for every input that shares it (see
/// [`Input::prepared`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedStyle<I = FloatImage> {
    /// What it was made from, checked against each input.
    style: I,
    source_guides: Vec<I>,
    colours: Vec<Vec<f32>>,
    scales: Vec<f32>,
    patch: usize,
    /// The style and source guides stacked, 8-bit (`Level::source`).
    source: Vec<u8>,
    /// The source's segment labels, from the textures' colours.
    labels: Vec<u16>,
    /// Per label, its valid source patch centres (`Level::segment_centres`).
    segment_centres: Vec<SegmentCentres>,
}

/// Prepares the style side of `input` (style, guides, textures; see [`PreparedStyle`]) for
/// `params`: validated as [`crate::synthesize`] validates it.
pub fn prepare<I: ChannelImage>(input: &Input<I>, params: &Params) -> Result<PreparedStyle<I>, Error> {
    params.validate()?;
    crate::check_images(input, params.patch_size)?;
    let Some(textures) = &input.textures else {
        return Err(Error::Input(InputError::NoTextures));
    };
    let colours: Vec<Vec<f32>> = textures.iter().map(|t| t.colour.clone()).collect();
    let guide = crate::segments::segment_guide(input, params)?;
    // Only the source is labelled here: each run labels (and checks) its own target.
    crate::segments::check_colours(&colours, guide.source.channels())?;
    let labels = crate::segments::label_image(&guide.source.to_float_image(), &colours);
    let (style_weights, guide_weights) = crate::weights(input, params);
    let (_, scales) = channel_scales(&style_weights, &guide_weights);
    let source_guides: Vec<&I> = input.guides.iter().map(|g| &g.source).collect();
    let source = stack_source(&input.style, &source_guides, &scales);
    let size = (input.style.width(), input.style.height());
    let segment_centres = segment_centres(&labels, size, params.patch_size / 2, colours.len());
    Ok(PreparedStyle {
        style: input.style.clone(),
        source_guides: source_guides.into_iter().cloned().collect(),
        colours,
        scales,
        patch: params.patch_size,
        source,
        labels,
        segment_centres,
    })
}

impl<I: ChannelImage> PreparedStyle<I> {
    /// The source's segment labels.
    pub(crate) fn labels(&self) -> &[u16] {
        &self.labels
    }

    /// The stacked source and the segment centres, for a level of `patch`-sided patches with
    /// channel `scales`: `None` when they were prepared for others.
    pub(crate) fn source_side(&self, patch: usize, scales: &[f32]) -> Option<SourceSide<'_>> {
        (patch == self.patch && scales == self.scales)
            .then(|| (Cow::Borrowed(&self.source[..]), Cow::Borrowed(&self.segment_centres[..])))
    }

    /// Refuses an input this was not prepared from (see [`Input::prepared`]).
    pub(crate) fn check(&self, input: &Input<I>, params: &Params) -> Result<(), Error> {
        let mismatch = |what: &str| Err(Error::Input(InputError::PreparedMismatch { what: what.to_string() }));
        if params.patch_size != self.patch {
            return mismatch("patch size");
        }
        if input.style != self.style {
            return mismatch("style");
        }
        if input.guides.len() != self.source_guides.len()
            || input.guides.iter().zip(&self.source_guides).any(|(guide, source)| &guide.source != source)
        {
            return mismatch("source guides");
        }
        let colours_match = input.textures.as_ref().is_some_and(|textures| {
            textures.len() == self.colours.len() && textures.iter().zip(&self.colours).all(|(t, c)| &t.colour == c)
        });
        if !colours_match {
            return mismatch("textures' colours");
        }
        let (style_weights, guide_weights) = crate::weights(input, params);
        if channel_scales(&style_weights, &guide_weights).1 != self.scales {
            return mismatch("weights");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use motif_core::{ByteImage, NoProgress};

    use super::*;
    use crate::{Guide, PresynthInput, Segmentation, presynthesize, synthesize};

    /// The input of `two_segment_case` with its textures, as float or 8-bit images.
    fn banded(params: &Params) -> (Input, Input<ByteImage>) {
        let input = crate::tests_synthesis::two_segment_case();
        let guide = &input.guides[0];
        let presynth = PresynthInput { style: input.style.clone(), guide: guide.source.clone(), size: (32, 32) };
        let textures: Arc<[_]> = presynthesize(&presynth, params, &mut NoProgress).unwrap().into();
        let bytes = |image: &FloatImage| ByteImage::from_float(image);
        let byte_guide = Guide { source: bytes(&guide.source), target: bytes(&guide.target), weight: None };
        let mut byte_input = Input::guided(bytes(&input.style), vec![byte_guide]);
        byte_input.textures = Some(textures.clone());
        byte_input.texture_origin = (5, -3);
        let float_input = Input { textures: Some(textures), texture_origin: (5, -3), ..input };
        (float_input, byte_input)
    }

    /// The output with the input's prepared style, after checking that it is the output without.
    fn same_with_prepared<I: ChannelImage>(input: &Input<I>, params: &Params) -> Arc<PreparedStyle<I>> {
        let plain = synthesize(input, params, &mut NoProgress).unwrap();
        let prepared = Arc::new(prepare(input, params).unwrap());
        let fast = Input { prepared: Some(prepared.clone()), ..input.clone() };
        let output = synthesize(&fast, params, &mut NoProgress).unwrap();
        assert!(output.report.searched_pixels > 0);
        assert_eq!(output.image, plain.image);
        prepared
    }

    #[test]
    fn a_prepared_style_gives_the_same_bytes_and_refuses_another_input() {
        let params = Params { segments: Some(Segmentation::Palette), band_local_search: true, ..Default::default() };
        let (float_input, byte_input) = banded(&params);
        same_with_prepared(&byte_input, &params);
        let prepared = same_with_prepared(&float_input, &params);
        let refused = |input: &Input, params: &Params| {
            let input = Input { prepared: Some(prepared.clone()), ..input.clone() };
            match synthesize(&input, params, &mut NoProgress) {
                Err(Error::Input(InputError::PreparedMismatch { what })) => what,
                other => panic!("{other:?}"),
            }
        };
        let mut style = float_input.clone();
        style.style.data_mut()[7] = 0.5;
        assert_eq!(refused(&style, &params), "style");
        let mut guide = float_input.clone();
        guide.guides[0].source.data_mut()[0] = 0.25;
        assert_eq!(refused(&guide, &params), "source guides");
        let mut weight = float_input.clone();
        weight.guides[0].weight = Some(0.5);
        assert_eq!(refused(&weight, &params), "weights");
        let mut colours = float_input.clone();
        let mut textures = colours.textures.as_deref().unwrap().to_vec();
        textures[0].colour[0] = 0.5;
        colours.textures = Some(textures.into());
        assert_eq!(refused(&colours, &params), "textures' colours");
        assert_eq!(refused(&float_input, &Params { patch_size: 7, ..params.clone() }), "patch size");
    }
}
