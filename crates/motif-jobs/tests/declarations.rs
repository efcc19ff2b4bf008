//! The declarations of `motif_jobs::JOBS` are the single source of the Python package's typed
//! keywords: `python/motif/_options.py` is rendered from them (`MOTIF_BLESS=1` rewrites it), and
//! every declaration is checked for what front ends rely on.

use std::fmt::Write as _;

use motif_jobs::JOBS;
use motif_jobs::options::{Kind, OptionSpec};

const STUB: &str = "python/motif/_options.py";

/// The Python type of an option's value.
fn python_type(kind: Kind) -> String {
    match kind {
        Kind::Flag => "bool".into(),
        Kind::Integer => "int".into(),
        Kind::Number => "float".into(),
        Kind::Choice(names) => {
            let quoted: Vec<String> = names.iter().map(|name| format!("{name:?}")).collect();
            format!("Literal[{}]", quoted.join(", "))
        }
        Kind::Numbers => "Sequence[float]".into(),
        Kind::Names => "Sequence[str]".into(),
        Kind::Weights => "Mapping[str, float]".into(),
        Kind::Size => "Tuple[int, int]".into(),
        Kind::Position => "Tuple[int, int]".into(),
        Kind::Pairs => "Sequence[Tuple[float, float]]".into(),
        Kind::Colour => "str".into(),
        _ => "Any".into(),
    }
}

/// `points` → `PointsOptions`.
fn class_name(job: &str) -> String {
    let mut chars = job.chars();
    chars.next().map(|first| first.to_uppercase().chain(chars).collect::<String>() + "Options").unwrap_or_default()
}

fn render_option(out: &mut String, spec: &OptionSpec) {
    let mut line = String::from("    #:");
    for word in spec.described().split_whitespace() {
        if line.len() + word.len() > 110 {
            let _ = writeln!(out, "{line}");
            line = String::from("    #:");
        }
        line.push(' ');
        line.push_str(word);
    }
    if let Some(default) = &spec.default {
        line.push_str(&format!(" Default: {default}."));
    }
    let _ = writeln!(out, "{line}");
    let _ = writeln!(out, "    {}: {}", spec.name.replace('-', "_"), python_type(spec.kind));
}

fn render() -> String {
    let mut out = String::from(
        "\"\"\"The keyword options of each engine, rendered from motif-jobs' declarations (do not edit).\n\n\
         Regenerate with `MOTIF_BLESS=1 cargo test --release -p motif-jobs --test declarations`.\n\"\"\"\n\n\
         from typing import Any, Literal, Mapping, Sequence, Tuple, TypedDict\n",
    );
    for job in JOBS {
        let _ = write!(out, "\n\nclass {}(TypedDict, total=False):\n", class_name(job.name));
        let _ = writeln!(out, "    \"\"\"Options of `motif.{}()` and `motif {}`.\"\"\"\n", job.name, job.name);
        for spec in (job.options)() {
            render_option(&mut out, &spec);
        }
    }
    out
}

#[test]
fn python_options_are_rendered_from_the_declarations() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(STUB);
    let rendered = render();
    if std::env::var_os("MOTIF_BLESS").is_some() {
        std::fs::write(&path, &rendered).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == rendered,
        "{STUB} is stale: regenerate it with `MOTIF_BLESS=1 cargo test --release -p motif-jobs --test declarations`"
    );
}

/// Names are unique, kebab-case and documented; ranges are ordered; a default is inside its range.
#[test]
fn every_declaration_is_complete() {
    for job in JOBS {
        let specs = (job.options)();
        let mut names: Vec<&str> = specs.iter().map(|spec| spec.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), specs.len(), "{}: duplicate option names", job.name);
        for spec in &specs {
            let what = format!("{} --{}", job.name, spec.name);
            assert!(spec.name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'), "{what}");
            assert!(spec.help.len() > 20, "{what}: no help");
            if let Some((low, high)) = spec.range {
                assert!(low <= high, "{what}: range {low}..{high}");
                if let Some(default) = spec.default.as_deref().and_then(|d| d.parse::<f64>().ok()) {
                    assert!((low..=high).contains(&default), "{what}: default {default} outside {low}..{high}");
                }
            }
        }
    }
}

/// The stylize family's jobs keep their flat JSON (shared and own options side by side, by flag
/// name), refuse names neither declares, and start from the engine's defaults.
#[test]
fn stylize_jobs_join_shared_and_own_options() {
    use motif_jobs::stylize::{InpaintJob, PresynthJob, StylizeJob, TextureJob, VideoJob, ZoomJob};
    use serde_json::json;

    let job: StylizeJob = serde_json::from_value(json!({
        "patch-size": 7, "weight": [0.5], "segment-count": 3, "search-vote-iters": 2, "seed": 4, "max-memory": "1G",
    }))
    .unwrap();
    assert_eq!((job.options.shared.patch_size, job.options.shared.search_vote_iters), (7, 2));
    assert_eq!((job.options.own.weight.clone(), job.options.own.segment_count), (vec![0.5], Some(3)));
    assert_eq!((job.seed, job.max_memory), (4, Some(1 << 30)));
    // Serialized flat: every option next to the job's own fields, and back to the same job.
    let value = serde_json::to_value(&job).unwrap();
    for name in ["patch-size", "weight", "segment-guide", "extra-pass-3x3", "seed", "max-memory"] {
        assert!(value.get(name).is_some(), "{name} in {value}");
    }
    assert_eq!(serde_json::from_value::<StylizeJob>(value).unwrap(), job);
    // A name of another job, or no job, is refused by name.
    for (description, name) in [
        (json!({ "size": [8, 8], "segments": true }), "segments"),
        (json!({ "size": [8, 8], "patchsize": 5 }), "patchsize"),
    ] {
        let error = serde_json::from_value::<TextureJob>(description).unwrap_err().to_string();
        assert!(error.contains(name), "{error}");
    }
    assert!(serde_json::from_value::<InpaintJob>(json!({ "tileable": true })).is_err());
    assert!(serde_json::from_value::<VideoJob>(json!({ "band": 2 })).is_err());
    let zoom: ZoomJob = serde_json::from_value(json!({ "size": [8, 8], "levels": 2 })).unwrap();
    assert_eq!((zoom.options.own.levels, zoom.options.own.factor), (2, 2.0));
    let presynth: PresynthJob = serde_json::from_value(json!({ "segment-count": 4 })).unwrap();
    assert_eq!(presynth.texture_size(), [256, 256]);
    // Defaults are the engine's.
    let params = StylizeJob::new().params(false).unwrap();
    let engine = motif_stylize::Params::DEFAULT.with_seed(1);
    assert_eq!(params, engine);
    // Declared ranges are checked with the option's name.
    let job: TextureJob = serde_json::from_value(json!({ "size": [8, 8], "structure-weight": -1 })).unwrap();
    assert!(job.params().unwrap_err().to_string().contains("structure-weight"));
}

/// Every job's entry names exactly what its description holds (its fields, then its options),
/// so front ends list a job's names from `JOBS` alone.
#[test]
fn every_entry_names_what_its_description_holds() {
    use motif_jobs::curve::CurveJob;
    use motif_jobs::points::{DomainSpec, PointsJob};
    use motif_jobs::strokes::{StrokesJob, TargetSpec};
    use motif_jobs::stylize::{InpaintJob, PresynthJob, StylizeJob, TextureJob, VideoJob, ZoomJob};
    use motif_jobs::tiles::TilesJob;
    use motif_jobs::{Job, JobEntry};
    use std::collections::BTreeSet;

    fn held<J: Job>(job: &J) -> (&'static str, BTreeSet<String>) {
        let value = serde_json::to_value(job).unwrap();
        (J::NAME, value.as_object().unwrap().keys().cloned().collect())
    }
    let jobs = [
        held(&CurveJob::new(1.0, 1.0)),
        held(&PointsJob::new(1.0, DomainSpec::Box(vec![1.0, 1.0]))),
        held(&StrokesJob::new(Some(1.0), TargetSpec::Rect([1.0, 1.0]))),
        held(&StylizeJob::new()),
        held(&PresynthJob::new()),
        held(&TextureJob::new(1, 1)),
        held(&InpaintJob::new()),
        held(&ZoomJob::new(1, 1)),
        held(&VideoJob::new()),
        held(&TilesJob::new()),
    ];
    let listed: Vec<&str> = motif_jobs::JOBS.iter().map(|entry| entry.name).collect();
    assert_eq!(jobs.iter().map(|(name, _)| *name).collect::<Vec<_>>(), listed, "JOBS lists every job, in order");
    for (name, keys) in jobs {
        let entry = JobEntry::named(name).unwrap();
        let names: BTreeSet<String> = entry.names().into_iter().collect();
        assert_eq!(keys, names, "{name}");
        assert!(!entry.summary.is_empty() && !entry.details.is_empty(), "{name}");
    }
}

/// Both ends of every declared range pass the engine's own `validate`: a declaration is never
/// looser or stricter than the engine it sets (curve's ranges are checked on a real run in its
/// own tests, as its parameters need an exemplar).
#[test]
fn the_ends_of_every_declared_range_pass_the_engine() {
    use motif_jobs::points::PointsJob;
    use motif_jobs::strokes::StrokesJob;
    use motif_jobs::stylize::{PresynthJob, StylizeJob, TextureJob, VideoJob};
    use serde_json::{Value, json};

    fn checked<J: serde::de::DeserializeOwned, T>(
        description: Value,
        params: impl Fn(&J) -> Result<T, motif_jobs::JobError>,
    ) -> Result<(), String> {
        let job: J = serde_json::from_value(description).map_err(|error| error.to_string())?;
        params(&job).map(drop).map_err(|error| error.to_string())
    }
    type Check = fn(Value) -> Result<(), String>;
    let jobs: [(&str, Value, Check); 6] = [
        ("points", json!({ "domain": { "box": [10, 10] } }), |d| checked(d, |j: &PointsJob| j.params(2, &[]))),
        ("strokes", json!({ "scale": 1, "target": { "rect": [10, 10] } }), |d| checked(d, StrokesJob::params)),
        ("stylize", json!({}), |d| checked(d, |j: &StylizeJob| j.params(false))),
        ("presynth", json!({}), |d| checked(d, PresynthJob::params)),
        ("texture", json!({ "size": [8, 8] }), |d| checked(d, TextureJob::params)),
        ("video", json!({}), |d| checked(d, VideoJob::params)),
    ];
    let mut failures = Vec::new();
    for (name, base, check) in jobs {
        let entry = motif_jobs::JobEntry::named(name).unwrap();
        for spec in (entry.options)() {
            let Some((low, high)) = spec.range else { continue };
            for end in [low, high] {
                let mut description = base.clone();
                description[spec.name.as_str()] = match spec.kind {
                    Kind::Integer => json!(end as u64),
                    Kind::Numbers => json!([end]),
                    Kind::Weights => json!({ "mark": end }),
                    _ => json!(end),
                };
                // An option that only makes sense with a flag gets it (one that needs an input
                // is checked without it: inputs are not part of a description).
                let options = (entry.options)();
                if let Some(flag) =
                    options.iter().find(|o| Some(o.name.as_str()) == spec.requires && o.kind == Kind::Flag)
                {
                    description[flag.name.as_str()] = json!(true);
                }
                if let Err(error) = check(description) {
                    failures.push(format!("{name} --{} {end}: {error}", spec.name));
                }
            }
        }
    }
    assert!(failures.is_empty(), "declared ends the engine refuses:\n{}", failures.join("\n"));
}
