//! The crate's one error type.

use motif_core::InvalidParameter;

/// What can go wrong making tiles, grouped as the engines group theirs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is outside its range.
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// The stylization (presynthesis or a tile's band) failed.
    #[error(transparent)]
    Stylize(#[from] motif_stylize::Error),
}
