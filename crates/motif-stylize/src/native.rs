//! Texture synthesis from exemplars much larger than the output ([`Params::local_search_above`]):
//! which levels search the whole (reduced) exemplar and which refine the matches upsampled from
//! the coarser level, so that the time grows with the output, not the exemplar.

use motif_core::ChannelImage;

use crate::Params;
use crate::synthesis::{Problem, level_size};

/// A level that refines upsampled matches ([`Params::local_search_above`]) has more than this many
/// times its output's pixels in its exemplar: below it, a search of the whole exemplar costs
/// about what the output does.
pub const LOCAL_SEARCH_RATIO: usize = 4;

/// The largest offset of the random search, in the level's pixels, on a level that refines
/// upsampled matches: the coarser level placed each match within a pixel or two, propagation
/// carries coherent runs, and a few pixels of slack let a patch settle on its best alignment.
pub const LOCAL_SEARCH_RADIUS: usize = 8;

/// In a native-size run ([`is_native`]), the occurrence penalty's ω_best counts at most this many
/// exemplar pixels per searched target patch: uniform use as if the exemplar had the output's size.
pub(crate) const OCCURRENCE_SOURCE_SHARE: usize = 1;

/// Whether pyramid level `level` (0 = finest) of `levels` refines the matches upsampled from the
/// coarser level instead of searching the whole exemplar ([`Params::local_search_above`]): in a
/// native-size run (see [`is_native`]), a level but the coarsest whose exemplar has more than
/// `local_search_above` pixels and [`LOCAL_SEARCH_RATIO`] times its output's.
pub(crate) fn is_local<I: ChannelImage>(
    problem: &Problem<'_, I>,
    params: &Params,
    levels: usize,
    level: usize,
) -> bool {
    level + 1 < levels && is_native(problem, params) && large_exemplar(problem, params, level)
}

/// Whether the run is plain texture synthesis (no guides, mask, band or seeded start) from an
/// exemplar of more than [`Params::local_search_above`] pixels and [`LOCAL_SEARCH_RATIO`] times
/// the output's. Then at every level the occurrence penalty counts uniform use as if the
/// exemplar had only the output's pixels (uncapped, ω_best falls with the exemplar's size, the
/// penalty of a coherent copy grows with it and breaks up every coherent run: the output blurs;
/// a cap of 4 still blurred patches of a tiled stone wall at 4 096²), and the levels of
/// [`is_local`] refine upsampled matches.
pub(crate) fn is_native<I: ChannelImage>(problem: &Problem<'_, I>, params: &Params) -> bool {
    let texture_only = problem.source_guides.is_empty()
        && problem.mask.is_none()
        && problem.composition.is_none()
        && problem.seeds.is_none();
    texture_only && large_exemplar(problem, params, 0)
}

/// Whether pyramid level `level`'s exemplar has more than [`Params::local_search_above`] pixels
/// and [`LOCAL_SEARCH_RATIO`] times its output's.
fn large_exemplar<I: ChannelImage>(problem: &Problem<'_, I>, params: &Params, level: usize) -> bool {
    let (source, target) =
        (level_size((problem.style.width(), problem.style.height()), level), level_size(problem.target_size, level));
    let (source, target) = (source.0 * source.1, target.0 * target.1);
    source > params.local_search_above && source > LOCAL_SEARCH_RATIO * target
}
