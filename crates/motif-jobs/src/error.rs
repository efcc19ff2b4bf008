//! The error of a job: a description that does not make sense, or the engine's own error.

use motif_core::InvalidParameter;

/// Everything that can stop a job.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JobError {
    /// A value of the description is out of range or inconsistent (named as the flag is).
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// The curve engine refused the run.
    #[error(transparent)]
    Curve(#[from] motif_curve::Error),
    /// The points engine refused the run.
    #[error(transparent)]
    Points(#[from] motif_points::Error),
    /// The strokes engine refused the run.
    #[error(transparent)]
    Strokes(#[from] motif_strokes::Error),
    /// The stylize engine refused the run.
    #[error(transparent)]
    Stylize(#[from] motif_stylize::Error),
}

impl JobError {
    /// The engine's memory refusal, when this is one (a front end restates it with what it
    /// holds itself).
    pub fn too_much_memory(&self) -> Option<&motif_core::TooMuchMemory> {
        match self {
            Self::Curve(motif_curve::Error::TooMuchMemory(error))
            | Self::Points(motif_points::Error::TooMuchMemory(error))
            | Self::Strokes(motif_strokes::Error::TooMuchMemory(error))
            | Self::Stylize(motif_stylize::Error::TooMuchMemory(error)) => Some(error),
            _ => None,
        }
    }
}
