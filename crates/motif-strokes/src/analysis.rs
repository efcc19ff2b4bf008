//! Reference analysis (§2): fit an element to every stroke, cluster, then relate the elements
//! (chain or unskewed Delaunay graph, shift vectors, neighbourhood sizes, density).

use kurbo::{Affine, Vec2};
use motif_core::Point;
use motif_core::{math, vector};

use crate::Error;
use crate::InputError;
use crate::border::flag_border;
use crate::cluster::{Element, cluster};
use crate::distribution::{Graph, neighbourhood_size, shift_from_offsets, unskewed_delaunay};
use crate::element::{FitSet, OrientedBox};
use crate::params::Params;
use crate::stroke::Stroke;

/// The analysed reference pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// The elements, in document coordinates. Along a path they are sorted in chain order.
    pub elements: Vec<Element>,
    /// True when analysed as a 1D pattern (for a path target), false for a 2D one.
    pub along_path: bool,
    /// Angle θ of the pattern's main direction (1D; 0 in 2D). The pattern frame is the document
    /// rotated by −θ, so that a 1D pattern runs along +x.
    pub frame_angle: f64,
    /// Neighbour graph: the chain (1D) or the edges of unskewed Delaunay triangles (2D).
    pub graph: Graph,
    /// Shift vector S_ref of each element in the pattern frame (position minus its neighbours'
    /// barycentre), for elements with at least k neighbours (2 in 1D, 4 in 2D); `None` otherwise.
    pub shifts: Vec<Option<Vec2>>,
    /// Size A_E of each element's neighbourhood (1D: length spanned by its neighbours; 2D: area of
    /// the polygon through them).
    pub neighbourhood_sizes: Vec<f64>,
    /// A_ref / N_ref: drawing length (1D) or area (2D) per element. 1D: the mean spacing of the
    /// chain along the main direction; 2D: twice the mean area of the unskewed triangles (a
    /// triangulation has about two triangles per point). With too few elements to measure it:
    /// (L + ε) or (L + ε)².
    pub area_per_element: f64,
    /// L: the mean principal-axis length of the elements.
    pub mean_length: f64,
    /// Delaunay triangles dropped by the unskewed filter (2D).
    pub skewed_triangles: usize,
    /// Elements whose ink touches the reference's bounding box.
    pub border: Vec<bool>,
    /// Border elements that are not copied (they may be pieces cut by the reference's frame):
    /// kept as neighbours only. See the `border` module.
    pub fragments: Vec<bool>,
}

impl Analysis {
    /// The rotation from document to pattern frame.
    pub fn to_pattern(&self) -> Affine {
        vector::rotation(-self.frame_angle)
    }

    /// Element `i`'s centre in the pattern frame.
    pub fn pattern_position(&self, i: usize) -> Point {
        self.to_pattern() * self.elements[i].frame.centre
    }

    /// Element `i`'s box in the pattern frame.
    pub fn pattern_frame(&self, i: usize) -> OrientedBox {
        let frame = self.elements[i].frame.rotated(-self.frame_angle);
        OrientedBox { centre: self.pattern_position(i), axis: crate::element::canonical_axis(frame.axis), ..frame }
    }

    /// A_ref: the reference's length (1D) or area (2D), N_ref × [`Analysis::area_per_element`].
    pub fn reference_area(&self) -> f64 {
        self.area_per_element * self.elements.len() as f64
    }

    /// True when element `i` may be copied to the output (it is not a fragment).
    pub fn is_usable(&self, i: usize) -> bool {
        !self.fragments[i]
    }

    /// Minimum neighbour count for position variation: k = 2 in 1D, 4 in 2D (§3.3).
    pub fn shift_neighbours(along_path: bool) -> usize {
        if along_path { 2 } else { 4 }
    }
}

/// Fit sets of every stroke (§2.1).
pub(crate) fn fit_sets(strokes: &[Stroke], params: &Params) -> Vec<FitSet> {
    strokes.iter().map(|stroke| FitSet::of_stroke(stroke, params.fit)).collect()
}

/// Analyses `strokes` as a 1D (`along_path`) or 2D pattern at scale `params.scale`.
pub fn analyse(strokes: &[Stroke], params: &Params, along_path: bool) -> Result<Analysis, Error> {
    params.validate()?;
    if strokes.is_empty() {
        return Err(Error::Input(InputError::NoStrokes));
    }
    let sets = fit_sets(strokes, params);
    let elements = cluster(strokes, &sets, params.scale);
    Ok(relate(elements, strokes, params, along_path))
}

/// The distribution step (§2.3) on elements clustered from `strokes`, and the border flags.
pub(crate) fn relate(elements: Vec<Element>, strokes: &[Stroke], params: &Params, along_path: bool) -> Analysis {
    let mut analysis = distribute(elements, params.scale, along_path);
    let flags = flag_border(&analysis, strokes);
    analysis.border = flags.border;
    analysis.fragments = flags.fragment;
    analysis
}

/// The distribution step (§2.3) on clustered elements.
fn distribute(mut elements: Vec<Element>, scale: f64, along_path: bool) -> Analysis {
    let count = elements.len();
    let mean_length = elements.iter().map(|e| e.frame.length).sum::<f64>() / count.max(1) as f64;
    let mut frame_angle = 0.0;
    let mut skewed_triangles = 0;
    let (graph, area_per_element);
    if along_path {
        // Main direction: principal axis of the element centres as equal point masses.
        let mean = elements.iter().fold(Vec2::ZERO, |s, e| s + e.frame.centre.to_vec2()) / count.max(1) as f64;
        let (mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0);
        for e in &elements {
            let d = e.frame.centre.to_vec2() - mean;
            xx += d.x * d.x;
            xy += d.x * d.y;
            yy += d.y * d.y;
        }
        let axis = if count >= 2 && (xx + yy) > 0.0 {
            let angle = 0.5 * math::atan2(2.0 * xy, xx - yy);
            Vec2::new(math::cos(angle), math::sin(angle))
        } else {
            Vec2::new(1.0, 0.0)
        };
        let axis = if axis.x < 0.0 || (axis.x == 0.0 && axis.y < 0.0) { -axis } else { axis };
        frame_angle = math::atan2(axis.y, axis.x);
        let project = |e: &Element| e.frame.centre.to_vec2().dot(axis);
        elements.sort_by(|a, b| project(a).total_cmp(&project(b)));
        graph = Graph::chain(count, false);
        area_per_element = if count >= 2 {
            (project(&elements[count - 1]) - project(&elements[0])) / (count - 1) as f64
        } else {
            mean_length + scale
        };
    } else {
        let centres: Vec<Point> = elements.iter().map(|e| e.frame.centre).collect();
        let delaunay = unskewed_delaunay(&centres);
        skewed_triangles = delaunay.skewed_triangles;
        graph = delaunay.graph;
        area_per_element = if delaunay.unskewed_triangles > 0 {
            2.0 * delaunay.mean_triangle_area
        } else {
            (mean_length + scale).powi(2)
        };
    }
    let mut analysis = Analysis {
        elements,
        along_path,
        frame_angle,
        graph,
        shifts: Vec::new(),
        neighbourhood_sizes: Vec::new(),
        // Coincident centres measure no spacing: fall back to the element size.
        area_per_element: if area_per_element > 1e-9 * (mean_length + scale) {
            area_per_element
        } else if along_path {
            mean_length + scale
        } else {
            (mean_length + scale).powi(2)
        },
        mean_length,
        skewed_triangles,
        border: vec![false; count],
        fragments: vec![false; count],
    };
    let minimum = Analysis::shift_neighbours(along_path);
    let mut offsets = Vec::new();
    for i in 0..count {
        offsets.clear();
        let here = analysis.pattern_position(i);
        offsets.extend(analysis.graph.neighbours(i).iter().map(|&j| analysis.pattern_position(j as usize) - here));
        analysis.shifts.push((offsets.len() >= minimum).then(|| shift_from_offsets(&offsets)));
        analysis.neighbourhood_sizes.push(neighbourhood_size(&offsets, along_path));
    }
    analysis
}
