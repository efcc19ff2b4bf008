//! Flags built from a job's declared options ([`motif_jobs::options`]): one clap argument per
//! option, named, typed, documented and defaulted as the job declares it, read back into the
//! job's options struct. No option of a job is written in this crate.
//!
//! The parsers here check only the type (a whole number, a finite number, one of the names); the
//! ranges are checked by the job, once, for every front end.

use std::marker::PhantomData;

use clap::builder::PossibleValuesParser;
use clap::parser::ValueSource;
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches};
use motif_jobs::options::{Declared, Kind, OptionSpec};
use serde_json::{Map, Value};

/// A job's options as flags: `#[command(flatten)] options: JobArgs<PointsOptions>`.
#[derive(Debug, Clone)]
pub struct JobArgs<O> {
    /// The options as parsed (declared defaults for the flags not given).
    pub options: O,
    declared: PhantomData<O>,
}

impl<O> std::ops::Deref for JobArgs<O> {
    type Target = O;
    fn deref(&self) -> &O {
        &self.options
    }
}

/// The clap id of an option: its field name, as derived arguments are named.
fn id(spec: &OptionSpec) -> String {
    spec.name.replace('-', "_")
}

fn number(text: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| format!("{text:?} is not a number"))?;
    if value.is_finite() { Ok(value) } else { Err("NaN and infinite values are not allowed".into()) }
}

fn whole(text: &str) -> Result<u64, String> {
    text.trim().parse().map_err(|_| format!("{text:?} is not a whole number ≥ 0"))
}

fn weight(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| format!("{text:?}: give NAME=W, e.g. diameter=0.5"))?;
    Ok((name.trim().to_string(), number(value).map_err(|error| format!("{text:?}: {error}"))?))
}

/// The clap argument of one declared option.
fn arg_of(spec: &OptionSpec) -> Arg {
    let mut arg = Arg::new(id(spec)).long(spec.name.clone()).help(spec.described());
    if !spec.value_name.is_empty() {
        arg = arg.value_name(spec.value_name);
    }
    if let Some(default) = spec.default.clone().filter(|_| spec.kind != Kind::Flag) {
        arg = arg.default_value(default);
    }
    if let Some(other) = spec.requires {
        arg = arg.requires(other);
    }
    match spec.kind {
        Kind::Flag => arg.action(ArgAction::SetTrue),
        Kind::Integer => arg.value_parser(whole),
        Kind::Number => arg.value_parser(number).allow_hyphen_values(true),
        Kind::Choice(names) => arg.value_parser(PossibleValuesParser::new(names.iter().copied())),
        Kind::Numbers => arg.value_parser(number).value_delimiter(',').num_args(1..).action(ArgAction::Append),
        Kind::Names => arg.value_delimiter(','),
        Kind::Weights => arg.value_parser(weight).action(ArgAction::Append),
        _ => arg,
    }
}

/// The value of one option given on the command line, as the job's JSON holds it.
fn value_of(spec: &OptionSpec, matches: &ArgMatches) -> Value {
    let id = id(spec);
    match spec.kind {
        Kind::Flag => Value::Bool(matches.get_flag(&id)),
        Kind::Integer => matches.get_one::<u64>(&id).map_or(Value::Null, |&v| Value::from(v)),
        Kind::Number => matches.get_one::<f64>(&id).map_or(Value::Null, |&v| Value::from(v)),
        Kind::Numbers => matches.get_many::<f64>(&id).map_or(Value::Null, |v| v.copied().collect()),
        Kind::Weights => Value::Object(
            matches
                .get_many::<(String, f64)>(&id)
                .map(|pairs| pairs.map(|(name, w)| (name.clone(), Value::from(*w))).collect())
                .unwrap_or_default(),
        ),
        Kind::Names => matches.get_many::<String>(&id).map_or(Value::Null, |v| v.cloned().collect()),
        _ => matches.get_one::<String>(&id).map_or(Value::Null, |v| Value::from(v.clone())),
    }
}

impl<O: Declared> FromArgMatches for JobArgs<O> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Map::new();
        for spec in O::options() {
            if matches.value_source(&id(&spec)) == Some(ValueSource::CommandLine) {
                given.insert(spec.name.clone(), value_of(&spec, matches));
            }
        }
        let options = serde_json::from_value(Value::Object(given))
            .map_err(|error| clap::Error::raw(clap::error::ErrorKind::ValueValidation, format!("{error}\n")))?;
        Ok(Self { options, declared: PhantomData })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl<O: Declared> Args for JobArgs<O> {
    fn augment_args(command: Command) -> Command {
        command.args(O::options().iter().map(arg_of))
    }

    fn augment_args_for_update(command: Command) -> Command {
        Self::augment_args(command)
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;
    use motif_jobs::points::PointsOptions;
    use motif_points::{Initialization, Window};

    use super::*;

    #[derive(Parser, Debug)]
    #[command(allow_negative_numbers = true)]
    struct Command {
        #[command(flatten)]
        options: JobArgs<PointsOptions>,
    }

    fn parse(args: &[&str]) -> Result<PointsOptions, clap::Error> {
        Command::try_parse_from(std::iter::once("motif").chain(args.iter().copied())).map(|c| c.options.options)
    }

    #[test]
    fn flags_not_given_take_the_declared_defaults() {
        assert_eq!(parse(&[]).unwrap(), PointsOptions::default());
    }

    #[test]
    fn every_kind_of_flag_reads_back_into_the_options() {
        let options = parse(&[
            "--init",
            "random",
            "--patch-candidates",
            "3",
            "--rotation",
            "-30",
            "--exemplar-window",
            "1,2,5,6",
            "--attributes",
            "a,b",
            "--attribute-weight",
            "a=0.5",
            "--attribute-weight",
            "b=2",
            "--window",
            "box",
            "--reference",
        ])
        .unwrap();
        assert_eq!(options.init, Initialization::Random);
        assert_eq!(options.patch_candidates, 3);
        assert_eq!(options.rotation, -30.0);
        assert_eq!(options.exemplar_window, Some(vec![1.0, 2.0, 5.0, 6.0]));
        assert_eq!(options.attributes, Some(vec!["a".to_string(), "b".to_string()]));
        assert_eq!(options.attribute_weight.get("b"), Some(&2.0));
        assert_eq!(options.window, Window::Box);
        assert!(options.reference && !options.no_sampling_control);
    }

    #[test]
    fn values_of_the_wrong_type_name_the_flag() {
        for (flag, value) in [("--patch-candidates", "-2"), ("--patch-size", "NaN"), ("--init", "grid")] {
            let error = parse(&[flag, value]).unwrap_err().to_string();
            assert!(error.contains(flag), "{flag} {value}: {error}");
        }
        assert!(parse(&["--attribute-weight", "a"]).unwrap_err().to_string().contains("NAME=W"));
    }
}
