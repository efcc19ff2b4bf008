//! The engine's one error type.

use motif_core::InvalidParameter;

/// Everything that can go wrong, grouped as image-rs groups its errors: a parameter out of its
/// range, an input the engine cannot use, or a run that would pass a limit. Messages are
/// lower-case and say what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter (or a piece of input geometry checked like one) is outside its range.
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// An input reference, target or density map cannot be used as given.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The run would pass a limit on elements, matching work or memory.
    #[error(transparent)]
    Limit(#[from] LimitError),
}

impl From<motif_core::TooMuchMemory> for Error {
    fn from(error: motif_core::TooMuchMemory) -> Self {
        Self::Limit(LimitError::Memory(error))
    }
}

/// An input reference, target or density map cannot be used as given ([`Error::Input`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// The reference drawing holds no visible stroke.
    #[error("the reference has no strokes: it needs at least one stroked or filled path with a length > 0")]
    NoStrokes,
    /// The target region's boundary crosses itself.
    #[error(
        "the target region is self-intersecting: its boundary crosses itself, so inside and outside are ambiguous; \
         draw it as one simple closed path"
    )]
    SelfIntersectingRegion,
    /// The density map leaves the whole target blank.
    #[error(
        "the density map is white (or nearly) over the whole target, so no element would be drawn: \
         darker pixels draw denser elements (black: the reference's density)"
    )]
    BlankDensityMap,
}

/// The run would pass a limit on elements, matching work or memory ([`Error::Limit`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// The target would need more elements than the limit allows.
    #[error(
        "the target needs {count} elements, more than the limit of {limit}: use a smaller target or a larger scale"
    )]
    TooManyElements {
        /// Elements the target would need (N_tar).
        count: usize,
        /// The limit ([`crate::Params::max_elements`]).
        limit: usize,
    },
    /// Matching would compare too many neighbourhoods ([`crate::MAX_COMPARISONS`]).
    #[error(
        "matching {outputs} output elements against {references} reference elements would take about {minutes:.0} \
         minutes (its time grows with their product; at most about {limit_minutes:.0} minutes are allowed): use a \
         smaller target, a larger scale or a smaller reference"
    )]
    TooMuchMatching {
        /// Elements to synthesize.
        outputs: usize,
        /// Elements found in the reference.
        references: usize,
        /// The estimated matching time, minutes.
        minutes: f64,
        /// The time [`crate::MAX_COMPARISONS`] stands for, minutes.
        limit_minutes: f64,
    },
    /// The run's estimated memory passes [`crate::Params::max_memory`].
    #[error(transparent)]
    Memory(#[from] motif_core::TooMuchMemory),
}
