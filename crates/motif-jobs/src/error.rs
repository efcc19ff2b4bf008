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
    /// Reference strokes (SVG or JSON) could not be read.
    #[error(transparent)]
    Reference(#[from] crate::strokes::ReferenceProblem),
}

/// What kind of problem stopped a job: the categories front ends map errors to (Python raises
/// `motif.OptionError`, `motif.InputError` or `motif.LimitError`, all `ValueError`s).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum ErrorKind {
    /// An option or field of the description is out of its range or inconsistent with another.
    Option,
    /// An input (image, point set, curve, strokes, mesh) cannot be used as given.
    Input,
    /// The run would pass a limit on memory, points, elements or work.
    Limit,
}

impl JobError {
    /// The kind of problem, for front ends that raise one error type per kind: the category the
    /// engine's error already carries (its `Parameter`, `Input` or `Limit` variant).
    pub fn kind(&self) -> ErrorKind {
        use motif_curve::Error as Curve;
        use motif_points::Error as Points;
        use motif_strokes::Error as Strokes;
        use motif_stylize::Error as Stylize;
        match self {
            Self::InvalidParameter(_)
            | Self::Curve(Curve::Parameter(_))
            | Self::Points(Points::Parameter(_))
            | Self::Strokes(Strokes::Parameter(_))
            | Self::Stylize(Stylize::Parameter(_)) => ErrorKind::Option,
            Self::Curve(Curve::Limit(_))
            | Self::Points(Points::Limit(_))
            | Self::Strokes(Strokes::Limit(_))
            | Self::Stylize(Stylize::Limit(_)) => ErrorKind::Limit,
            _ => ErrorKind::Input,
        }
    }

    /// The engine's memory refusal, when this is one (a front end restates it with what it
    /// holds itself).
    pub fn too_much_memory(&self) -> Option<&motif_core::TooMuchMemory> {
        match self {
            Self::Curve(motif_curve::Error::Limit(motif_curve::LimitError::Memory(error)))
            | Self::Points(motif_points::Error::Limit(motif_points::LimitError::Memory(error)))
            | Self::Strokes(motif_strokes::Error::Limit(motif_strokes::LimitError::Memory(error)))
            | Self::Stylize(motif_stylize::Error::Limit(motif_stylize::LimitError::Memory(error))) => Some(error),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use motif_core::NoProgress;
    use motif_points::samples::hex_exemplar;
    use serde_json::json;

    use super::ErrorKind;
    use crate::Job;
    use crate::points::{PointsInputs, PointsJob};

    fn kind_of(description: serde_json::Value, exemplar: motif_points::PointSet) -> ErrorKind {
        let job: PointsJob = serde_json::from_value(description).unwrap();
        job.run(PointsInputs::new(exemplar), &mut NoProgress).unwrap_err().kind()
    }

    #[test]
    fn errors_fall_into_their_kinds() {
        let exemplar = hex_exemplar(8, 8, 0.05, 1);
        let domain = json!({ "box": [10, 8] });
        assert_eq!(kind_of(json!({ "domain": domain, "patch-size": 0 }), exemplar.clone()), ErrorKind::Option);
        let two = motif_points::PointSet::new(2, vec![0.0, 0.0, 1.0, 1.0]);
        assert_eq!(kind_of(json!({ "domain": domain }), two), ErrorKind::Input);
        assert_eq!(
            kind_of(json!({ "domain": { "box": [1000, 1000] }, "max-memory": "1M" }), exemplar),
            ErrorKind::Limit
        );
    }
}
