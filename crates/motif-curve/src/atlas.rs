//! Several exemplars mixed in one synthesis (the paper's future work, §4: "matches across
//! exemplars").

use motif_core::RgbaImage;

use crate::piece::Position;

/// Several exemplars side by side in one image, two transparent columns apart (pieces stay inside
/// one source's pattern extent, see `Exemplar::with_sources`), top-aligned.
pub(crate) struct Atlas {
    pub image: RgbaImage,
    /// Column range `[x0, x1)` of each source.
    pub sources: Vec<(usize, usize)>,
}

/// Transparent columns between two exemplars of an atlas.
const ATLAS_GAP: usize = 2;

impl Atlas {
    pub(crate) fn new(first: &RgbaImage, more: &[RgbaImage]) -> Self {
        if more.is_empty() {
            return Self { image: first.clone(), sources: vec![(0, first.width())] };
        }
        let all: Vec<&RgbaImage> = std::iter::once(first).chain(more).collect();
        let mut sources = Vec::with_capacity(all.len());
        let mut x = 0;
        for image in &all {
            sources.push((x, x + image.width()));
            x += image.width() + ATLAS_GAP;
        }
        let width = x - ATLAS_GAP;
        let height = all.iter().map(|image| image.height()).max().unwrap_or(0);
        let image = RgbaImage::from_fn(width, height, |x, y| {
            let source = sources.iter().position(|&(x0, x1)| (x0..x1).contains(&x));
            match source {
                Some(k) if y < all[k].height() => all[k].get(x - sources[k].0, y),
                _ => [0; 4],
            }
        });
        Self { image, sources }
    }

    /// The source of atlas position `u` and the position in that source's coordinates.
    pub(crate) fn local(&self, u: Position) -> (usize, Position) {
        let k = self.sources.iter().rposition(|&(x0, _)| u[0] >= x0 as i32).unwrap_or(0);
        (k, [u[0] - self.sources[k].0 as i32, u[1]])
    }
}
