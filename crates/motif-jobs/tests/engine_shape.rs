//! The four engines have one API shape (ARCHITECTURE.md, "the same shape in all four"): one
//! `synthesize(&Input, &Params, &mut dyn Progress) -> Result<Output, Error>`, `Params` whose
//! defaults validate, and an `Error` grouped by category, image-rs style: `Parameter`, `Input`,
//! `Limit`. An engine that drifts from it stops this file compiling or fails its assertions.

use motif_core::{InvalidParameter, MemoryEstimate, Progress, TooMuchMemory};

/// A memory refusal, as an engine's estimate makes one.
fn too_much_memory() -> TooMuchMemory {
    MemoryEstimate::default().add("a buffer", 1000.0, 8.0).check(1, "use a smaller input").unwrap_err()
}

fn invalid_parameter() -> InvalidParameter {
    InvalidParameter::new("width", 0, "> 0")
}

macro_rules! check_shape {
    ($engine:ident, $synthesize:expr) => {{
        use $engine::{Error, Input, InputError, LimitError, Output, Params};
        let _: fn(&Input, &Params, &mut dyn Progress) -> Result<Output, Error> = $synthesize;
        let defaults = Params::default();
        assert!(defaults.validate().is_ok(), "{}: the default parameters validate", stringify!($engine));
        // Each category is its own variant, and the core's errors land in theirs.
        assert!(matches!(Error::from(invalid_parameter()), Error::Parameter(_)), "{}", stringify!($engine));
        let limit = Error::from(too_much_memory());
        assert!(matches!(limit, Error::Limit(LimitError::Memory(_))), "{}", stringify!($engine));
        assert!(limit.to_string().contains("use a smaller input"), "{}: {limit}", stringify!($engine));
        fn is_error<E: std::error::Error + Send + Sync + 'static>() {}
        is_error::<Error>();
        is_error::<InputError>();
        is_error::<LimitError>();
        let _: fn(InputError) -> Error = Error::Input;
    }};
}

#[test]
fn the_four_engines_have_one_shape() {
    check_shape!(motif_curve, motif_curve::synthesize);
    check_shape!(motif_points, motif_points::synthesize);
    check_shape!(motif_strokes, motif_strokes::synthesize);
    check_shape!(motif_stylize, motif_stylize::synthesize::<motif_core::FloatImage>);
}

/// Front ends raise one error type per category: the job's kind is the engine's category.
#[test]
fn a_jobs_error_kind_is_the_engines_category() {
    use motif_jobs::{ErrorKind, JobError};
    assert_eq!(JobError::from(motif_curve::Error::from(invalid_parameter())).kind(), ErrorKind::Option);
    assert_eq!(JobError::from(motif_points::Error::from(too_much_memory())).kind(), ErrorKind::Limit);
    let input = motif_stylize::Error::Input(motif_stylize::InputError::NoFrames);
    assert_eq!(JobError::from(input).kind(), ErrorKind::Input);
    let limit = motif_strokes::Error::Limit(motif_strokes::LimitError::TooManyElements { count: 9, limit: 1 });
    assert_eq!(JobError::from(limit).kind(), ErrorKind::Limit);
}
