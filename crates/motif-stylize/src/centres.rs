//! The valid source patch centres of each segment (§3.6's restriction), where the random search
//! draws its candidate "anywhere in the pixel's own segment", and the box that holds them, which
//! rejects a far candidate by its coordinates before any of its memory is read.
//!
//! A segment that is one rectangle of the source (each block of a map legend's atlas) needs no
//! list at all: its `i`-th centre is arithmetic, so the draw costs no cache miss either.

/// The valid centres of one segment, in row order, and their bounding box.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SegmentCentres {
    /// Every centre, as `y · width + x`, in row order (empty when `rectangle`).
    list: Vec<u32>,
    /// How many centres there are.
    len: usize,
    /// The centres' bounding box, `x0..x1` × `y0..y1` (empty when there are none).
    x: (usize, usize),
    y: (usize, usize),
    /// The source's width, to turn a box position into an index.
    width: usize,
    /// The centres fill their box: the `i`-th is computed, not read from `list`.
    rectangle: bool,
}

impl SegmentCentres {
    /// A segment with no centre.
    pub(crate) const EMPTY: Self = Self { list: Vec::new(), len: 0, x: (0, 0), y: (0, 0), width: 1, rectangle: false };

    fn new(list: Vec<u32>, width: usize) -> Self {
        let len = list.len();
        if len == 0 {
            return Self::EMPTY;
        }
        let (mut x, mut y) = ((usize::MAX, 0), (usize::MAX, 0));
        for &index in &list {
            let (px, py) = (index as usize % width, index as usize / width);
            x = (x.0.min(px), x.1.max(px + 1));
            y = (y.0.min(py), y.1.max(py + 1));
        }
        // Distinct centres inside the box, as many as its area: they are all of it.
        let rectangle = len == (x.1 - x.0) * (y.1 - y.0);
        let list = if rectangle { Vec::new() } else { list };
        Self { list, len, x, y, width, rectangle }
    }

    /// How many centres the segment has.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Whether the segment has no valid centre.
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The `i`-th centre in row order (`i < len`).
    #[inline]
    pub(crate) fn get(&self, i: usize) -> u32 {
        if self.rectangle {
            let side = self.x.1 - self.x.0;
            ((self.y.0 + i / side) * self.width + self.x.0 + i % side) as u32
        } else {
            self.list[i]
        }
    }

    /// Whether the centres are every position of their box ([`Self::may_hold`] is then exact).
    #[inline]
    pub(crate) fn fills_box(&self) -> bool {
        self.rectangle
    }

    /// Whether source position `(x, y)` may be one of the centres (it lies in their box).
    #[inline]
    pub(crate) fn may_hold(&self, x: usize, y: usize) -> bool {
        (self.x.0..self.x.1).contains(&x) && (self.y.0..self.y.1).contains(&y)
    }
}

/// Per label, the valid patch centres (a `radius` from every border) of a `size` source with
/// these pixel `labels`.
pub(crate) fn segment_centres(
    labels: &[u16],
    (width, height): (usize, usize),
    radius: usize,
    count: usize,
) -> Vec<SegmentCentres> {
    let mut centres = vec![Vec::new(); count];
    for y in radius..height - radius {
        for x in radius..width - radius {
            let index = y * width + x;
            centres[usize::from(labels[index])].push(index as u32);
        }
    }
    centres.into_iter().map(|list| SegmentCentres::new(list, width)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every segment's `get` and `may_hold` against its plain list, for labels that make
    /// rectangles (blocks side by side), ragged shapes and empty segments.
    #[test]
    fn centres_read_as_their_list() {
        let (width, height, radius) = (23, 11, 2);
        let shapes: [&dyn Fn(usize, usize) -> u16; 3] =
            [&|x, _| (x / 8) as u16, &|x, y| ((x * 7 + y * y) % 3) as u16, &|x, y| u16::from(x + y > 20)];
        for shape in shapes {
            let labels: Vec<u16> = (0..width * height).map(|i| shape(i % width, i / width)).collect();
            let centres = segment_centres(&labels, (width, height), radius, 4);
            assert!(centres[3].is_empty(), "label 3 is never used");
            let mut rectangles = 0;
            for (label, segment) in centres.iter().enumerate() {
                rectangles += usize::from(segment.rectangle);
                let list: Vec<u32> = (radius..height - radius)
                    .flat_map(|y| (radius..width - radius).map(move |x| (y * width + x) as u32))
                    .filter(|&i| usize::from(labels[i as usize]) == label)
                    .collect();
                assert_eq!(segment.len(), list.len());
                assert_eq!((0..segment.len()).map(|i| segment.get(i)).collect::<Vec<_>>(), list);
                for y in 0..height {
                    for x in 0..width {
                        let centre = list.contains(&((y * width + x) as u32));
                        let valid = (radius..width - radius).contains(&x) && (radius..height - radius).contains(&y);
                        assert!(!centre || segment.may_hold(x, y), "label {label}: ({x}, {y}) outside the box");
                        if segment.fills_box() && valid {
                            assert_eq!(centre, segment.may_hold(x, y), "label {label}: ({x}, {y})");
                        }
                    }
                }
            }
            if labels[0] == 0 && labels[8] == 1 {
                assert_eq!(rectangles, 3, "the three blocks are rectangles");
            }
        }
    }
}
