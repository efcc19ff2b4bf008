//! Job descriptions of every engine: refused, or parameters the engine accepts.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motif_jobs::curve::CurveJob;
use motif_jobs::points::PointsJob;
use motif_jobs::strokes::StrokesJob;
use motif_jobs::stylize::{PresynthJob, StylizeJob, TextureJob};

fuzz_target!(|data: &[u8]| {
    let Ok(value) = serde_json::from_slice::<serde_json::Value>(data) else { return };
    if let Ok(job) = serde_json::from_value::<CurveJob>(value.clone()) {
        let _ = job.params();
    }
    if let Ok(job) = serde_json::from_value::<PointsJob>(value.clone()) {
        let _ = job.engine_domain();
        let _ = job.params(2, &[]);
        let _ = job.params(3, &[]);
    }
    if let Ok(job) = serde_json::from_value::<StrokesJob>(value.clone()) {
        let _ = job.engine_target();
        let _ = job.params();
    }
    if let Ok(job) = serde_json::from_value::<StylizeJob>(value.clone()) {
        let _ = job.params(false);
    }
    if let Ok(job) = serde_json::from_value::<TextureJob>(value.clone()) {
        let _ = job.params();
    }
    if let Ok(job) = serde_json::from_value::<PresynthJob>(value) {
        let _ = job.params();
    }
});
