//! Example-based repetitive structure synthesis from point samples, in 2D and 3D, after Roveri,
//! Öztireli, Martin, Solenthaler and Gross, "Example Based Repetitive Structure Synthesis" (2015).
//!
//! The exemplar and the output are point sets with attributes (§4.1); both become sums of Gaussians
//! (§4.3) and the output is optimized so that every neighbourhood of it matches some neighbourhood
//! of the exemplar under the similarity error T of Eq. 5–6. Modules, by section of the paper:
//!
//! - `points` (§4.1, Eq. 1): [`PointSet`], points with float attributes and element ids.
//! - `model` (§4.3, Eq. 4–5): features, the kernel of the discrete error density for the box and
//!   Gaussian windows truncated at `window_cutoff` δ (2δ by default), exemplar/output state, rigid elements (§6.1).
//! - `energy` (Eq. 6): T and the analytic gradients ∂T/∂x_i, ∂T/∂a_i, point-centric and
//!   parallel; `match_objective`: `S_k` as a function of `m_k` and ∂S/∂m_k (the local step's); `pairs`: its output–output term summed once per pair over the nodes around the
//!   pair's midpoint; `exemplar_pairs`: the exemplar's own term `C_k` over listed exemplar pairs;
//!   `reference`: the plain per-quadrature-point version used by tests and the speed-up figure.
//! - `quadratic` (§4.4, Eq. 5): T as the quadratic form in the attributes that it is at fixed
//!   positions, minimized by conjugate gradients in the attribute half of the merging step.
//! - `surface` (§6.1, Figure 5): continuous structures with normals reconstructed as meshes for
//!   display (implicit MLS, surface nets).
//! - `domain` (§6.2): boxes, polygon regions, brush strokes, mesh volumes (`volume`: the inside
//!   of a closed triangle mesh, Figure 1's chair), mesh surfaces (`mesh_surface`: a 2D exemplar
//!   laid on the tangent planes, its x axis along the direction of least curvature from
//!   `curvature`, Figure 6 middle; `triangles`: closest points); `quadrature`: the regular grid;
//!   rotation and scale fields stored at the quadrature points (Eq. 8).
//! - `matching` (§5.1, local step): per quadrature point, gradient descent from random starts and
//!   from the grid neighbours' last matches (propagation, as in PatchMatch).
//! - `merging` (§5.1, global step): descent on positions (quasi-Newton for free points, the
//!   paper's gradient steps with rigid motions for elements), then attributes, discrete attributes
//!   snapped (§4.4).
//! - `sampling` (§5.1, Eq. 7): sampling control by the signed density difference P, within count
//!   bounds around the exemplar's density.
//! - `pair_statistics` (after Algorithm 1; not in the paper): the points near the seams between
//!   copies move so that the output's ring counts and nearest-neighbour distances follow the
//!   exemplar's (pair-correlation synthesis, Öztireli and Gross 2012), then are relocated one at
//!   a time where that brings the statistics closer (its `relocation`: Tscheschel and Stoyan
//!   2006, which forms a clustered exemplar's clusters from random points), and a surplus over the
//!   exemplar's density is thinned where that helps them most (its `thinning`).
//! - `init` (§5.2): patch initialization (default; each quadrature point starts matched to its
//!   copy's source); `placement`: random points, and placing exemplar points or elements.
//! - `setup`: the exemplar as features (attributes normalized, labels detected), the domain and
//!   its quadrature, the initial output; the output set, sampling control's count bounds and the
//!   fidelity figures read off the final state.
//! - `solver` (Algorithm 1): the multi-scale loop, progressive synthesis (§6.2), the report.
//! - `fidelity`: nearest-neighbour and g(r) distances to the exemplar in units of its spacing,
//!   the mean cluster size and (3D) the local thickness of `thickness`, with a random set, a
//!   tiled copy and the exemplar's halves as baselines.
//! - [`samples`]: generated exemplars (demo, benchmarks); [`EnergyCase`]: single evaluations of T
//!   for benchmarks.
//! - `quilting` (§5.2 with image quilting): each initial patch's source chosen by how well its
//!   surroundings agree with the points already placed.
//! - `cut` (§5.2 with image quilting's minimum error boundary cut): in 2D, neighbouring copies
//!   overlap by a band and are joined along the path where they agree best.
//! - `grid`, `raster`, `linear`: uniform-grid and per-cell-list neighbour queries and compressed neighbour lists, multilinear
//!   rasters, small vectors.
//!
//! The entry point is [`synthesize`]; [`Params::validate`] checks the parameters alone. The crate
//! does no I/O and builds for `wasm32`.
//!
//! ```
//! use motif_core::NoProgress;
//! use motif_points::samples::hex_exemplar;
//! use motif_points::{Domain, Input, Params, synthesize};
//!
//! // A jittered hexagonal exemplar (8 × 8 points, spacing 1) grown into a 10 × 8 box.
//! let exemplar = hex_exemplar(8, 8, 0.05, 1);
//! let domain = Domain::Box { min: vec![0.0, 0.0], max: vec![10.0, 8.0] };
//! let params = Params::default().with_neighbourhood(Some(1.5)).with_seed(7);
//! params.validate().unwrap();
//! let output = synthesize(&Input::new(exemplar, domain), &params, &mut NoProgress).unwrap();
//! let (count, expected) = (output.points.len() as f64, output.report.expected_points);
//! assert!((count - expected).abs() <= 0.1 * expected, "{count} points for {expected}");
//! // Nearest-neighbour distances stay close to the exemplar's (a random set would be 0.2–0.3).
//! assert!(output.report.fidelity.output.nearest_neighbour < 0.15);
//! ```

// Coordinates are indexed `0..D` throughout: index loops over fixed-size arrays read like the
// formulas they implement.
#![allow(
    clippy::needless_range_loop,
    reason = "fixed-size vector and matrix code indexes by axis, as the paper's formulas do"
)]

mod curvature;
mod cut;
mod cut_copy;
mod domain;
mod energy;
mod error;
mod exemplar_pairs;
mod fidelity;
mod grid;
mod init;
mod linear;
mod local_global;
mod match_objective;
mod matching;
mod merging;
mod mesh_surface;
mod model;
mod output_pairs;
mod pair_statistics;
mod params;
mod placement;
mod points;
mod prepare;
mod quadratic;
mod quadrature;
mod quilting;
mod raster;
mod reference;
pub mod samples;
mod sampling;
mod setup;
mod solver;
mod surface;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_attributes;
#[cfg(test)]
mod tests_surface;
#[cfg(test)]
mod tests_synthesis;
mod thickness;
mod triangles;
mod volume;

pub use domain::MAX_STROKE_SCALE;
pub use error::{AttributeRole, DomainProblem, Error, InputError, LimitError, PointSetProblem};
pub use fidelity::{Distances, Fidelity, Statistics};
pub use pair_statistics::StatisticsRefinement;
pub use params::{
    BrushStroke, Domain, Evaluator, Field, FieldFunction, Initialization, Input, Params, Refinement, SurfaceDirections,
    Window,
};
pub use points::{MAX_COORDINATE, PointSet};
pub use solver::{
    EnergyCase, EvaluatorComparison, IterationEnergy, Output, Report, SurfaceFigures, compare_evaluators, synthesize,
};
pub use surface::reconstruct_surface;

/// Checks a mesh and its direction field for a surface domain (triangles, finite vertices, valid
/// indices, no degenerate triangle, one finite nonzero direction or one per vertex), so that a
/// front end can name the file before any work. Open meshes are fine on a surface.
pub fn check_surface_mesh(mesh: &motif_core::TriangleMesh, directions: &SurfaceDirections) -> Result<(), Error> {
    mesh_surface::MeshSurface::new(mesh, directions)
        .map(|_| ())
        .map_err(|problem| Error::Input(InputError::EmptyDomain(problem)))
}

/// Checks a mesh for a volume domain (triangles, finite vertices, valid indices, no degenerate
/// triangle, closed), so that a front end can name the file before any work.
pub fn check_volume_mesh(mesh: &motif_core::TriangleMesh) -> Result<(), Error> {
    volume::MeshVolume::new(mesh).map(|_| ()).map_err(|problem| Error::Input(InputError::EmptyDomain(problem)))
}
