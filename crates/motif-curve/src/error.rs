//! The engine's one error type.

use motif_core::InvalidParameter;

/// Everything that can go wrong, grouped as image-rs groups its errors: a parameter out of its
/// range, an input the engine cannot use, or a run that would pass a limit. Messages are
/// lower-case and say what to change.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its range.
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// An input exemplar, curve or pin cannot be used as given.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The run would pass the memory limit.
    #[error(transparent)]
    Limit(#[from] LimitError),
}

impl From<motif_core::TooMuchMemory> for Error {
    fn from(error: motif_core::TooMuchMemory) -> Self {
        Self::Limit(LimitError::Memory(error))
    }
}

/// An input exemplar, curve or pin cannot be used as given ([`Error::Input`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// A piece has no position that slices the pattern completely.
    #[error(
        "no valid exemplar position for piece {piece}: the ribbon is {samples} exemplar pixels wide (width × scale) \
         but the pattern is {pattern_height} pixels tall; use a wider ribbon, a larger scale or shorter pieces"
    )]
    NoValidPosition {
        /// The piece.
        piece: usize,
        /// `C`.
        samples: usize,
        /// Height of the exemplar's non-transparent rows.
        pattern_height: usize,
    },
    /// The pinned first position is not valid.
    #[error("pin-first position ({x}, {y}) is not a valid position of the first piece ({count} valid positions exist)")]
    InvalidPin {
        /// x.
        x: i32,
        /// y.
        y: i32,
        /// Number of valid positions of the first piece.
        count: usize,
    },
}

/// The run would pass the memory limit ([`Error::Limit`]).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// The run's estimated memory passes [`Params::max_memory`](crate::Params::max_memory).
    #[error(transparent)]
    Memory(#[from] motif_core::TooMuchMemory),
}
