//! Flags built from a job's declared options ([`motif_jobs::options`]): one clap argument per
//! option, named, typed, documented and defaulted as the job declares it, read back into the
//! job's options struct. No option of a job is written in this crate.
//!
//! The parsers here check only the type (a whole number, a finite number, one of the names, a
//! size `WxH`, a position `X,Y`, pairs `A:B,...`); the ranges are checked by the job, once, for
//! every front end.

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
    let (name, value) = text.split_once('=').ok_or_else(|| format!("{text:?}: give NAME=W, a name and a number"))?;
    Ok((name.trim().to_string(), number(value).map_err(|error| format!("{text:?}: {error}"))?))
}

/// `WxH`: two whole numbers.
fn size(text: &str) -> Result<Value, String> {
    let (w, h) = text.split_once(['x', 'X']).ok_or("expected WxH, for example 800x600")?;
    let parse = |v: &str| v.trim().parse::<u64>().map_err(|_| format!("`{v}` is not a positive integer"));
    Ok(Value::from(vec![parse(w)?, parse(h)?]))
}

/// `X,Y`: two integers.
fn position(text: &str) -> Result<Value, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [x, y] = parts.as_slice() else { return Err("expected X,Y (two integers)".into()) };
    let parse = |v: &str| v.parse::<i64>().map_err(|_| format!("`{v}` is not an integer"));
    Ok(Value::from(vec![parse(x)?, parse(y)?]))
}

/// `A:B,...`: pairs of finite numbers.
fn pairs(text: &str) -> Result<Value, String> {
    text.split(',')
        .map(|pair| {
            let (a, b) = pair.split_once(':').ok_or_else(|| format!("{pair:?} is not A:B (e.g. 0.5:2)"))?;
            let parse = |v: &str| number(v).map_err(|error| format!("{pair:?}: {error}"));
            Ok(Value::from(vec![parse(a)?, parse(b)?]))
        })
        .collect()
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
        Kind::Integer => arg.value_parser(whole).allow_hyphen_values(true),
        Kind::Number => arg.value_parser(number).allow_hyphen_values(true),
        Kind::Choice(names) => arg.value_parser(PossibleValuesParser::new(names.iter().copied())),
        Kind::Numbers => arg.value_parser(number).value_delimiter(',').num_args(1..).action(ArgAction::Append),
        Kind::Names => arg.value_delimiter(','),
        Kind::Weights => arg.value_parser(weight).value_delimiter(',').action(ArgAction::Append),
        Kind::Size => arg.value_parser(size),
        Kind::Position => arg.value_parser(position).allow_hyphen_values(true),
        Kind::Pairs => arg.value_parser(pairs),
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
        Kind::Size | Kind::Position | Kind::Pairs => matches.get_one::<Value>(&id).cloned().unwrap_or(Value::Null),
        _ => matches.get_one::<String>(&id).map_or(Value::Null, |v| Value::from(v.clone())),
    }
}

/// The options given on the command line, read as the job reads them; a value the job refuses
/// (an integer too large for its type) is named by its flag.
fn read<O: Declared>(given: Map<String, Value>) -> Result<O, clap::Error> {
    serde_json::from_value(Value::Object(given.clone())).map_err(|error| {
        let refused = given.into_iter().find(|(name, value)| {
            let alone = Map::from_iter([(name.clone(), value.clone())]);
            serde_json::from_value::<O>(Value::Object(alone)).is_err()
        });
        let message = match refused {
            Some((name, value)) => format!("invalid value '{value}' for '--{name}': {error}\n"),
            None => format!("{error}\n"),
        };
        clap::Error::raw(clap::error::ErrorKind::ValueValidation, message)
    })
}

impl<O: Declared> FromArgMatches for JobArgs<O> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Map::new();
        for spec in O::options() {
            if matches.value_source(&id(&spec)) == Some(ValueSource::CommandLine) {
                given.insert(spec.name.clone(), value_of(&spec, matches));
            }
        }
        Ok(Self { options: read(given)?, declared: PhantomData })
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
    use motif_curve::{ClosedMode, Method};
    use motif_jobs::curve::CurveOptions;
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

    #[derive(Parser, Debug)]
    #[command(allow_negative_numbers = true)]
    struct CurveCommand {
        #[command(flatten)]
        options: JobArgs<CurveOptions>,
    }

    fn parse_curve(args: &[&str]) -> Result<CurveOptions, clap::Error> {
        let args = std::iter::once("motif").chain(args.iter().copied());
        CurveCommand::try_parse_from(args).map(|c| c.options.options)
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
    fn named_numbers_are_comma_separated_or_repeated() {
        use motif_jobs::strokes::StrokesOptions;
        #[derive(Parser, Debug)]
        struct Strokes {
            #[command(flatten)]
            options: JobArgs<StrokesOptions>,
        }
        let strokes = |args: &[&str]| {
            Strokes::try_parse_from(std::iter::once("motif").chain(args.iter().copied())).map(|c| c.options.options)
        };
        let options =
            strokes(&["--thresholds", "shape=0.2,col=0.3", "--thresholds", "ov=2", "--fit", "contour"]).unwrap();
        let thresholds = &options.thresholds;
        assert_eq!(
            [thresholds.get("shape"), thresholds.get("col"), thresholds.get("ov")],
            [Some(0.2), Some(0.3), Some(2.0)]
        );
        assert_eq!(options.fit, motif_strokes::FitPoints::Contour);
        assert_eq!(strokes(&[]).unwrap(), StrokesOptions::default());
        let error = strokes(&["--thresholds", "shape=0.2,colour=0.3"]).unwrap_err().to_string();
        assert!(error.contains("colour=0.3") && error.contains("col or attr"), "{error}");
        assert!(strokes(&["--fit", "outline"]).unwrap_err().to_string().contains("--fit"));
        let weights = parse(&["--attribute-weight", "a=0.5,b=2"]).unwrap().attribute_weight;
        assert_eq!((weights.get("a"), weights.get("b")), (Some(&0.5), Some(&2.0)));
    }

    #[test]
    fn values_of_the_wrong_type_name_the_flag() {
        for (flag, value) in [("--patch-candidates", "-2"), ("--patch-size", "NaN"), ("--init", "grid")] {
            let error = parse(&[flag, value]).unwrap_err().to_string();
            assert!(error.contains(flag), "{flag} {value}: {error}");
        }
        assert!(parse(&["--attribute-weight", "a"]).unwrap_err().to_string().contains("NAME=W"));
    }

    #[test]
    fn sizes_positions_pairs_and_choices_read_back_into_the_options() {
        assert_eq!(parse_curve(&[]).unwrap(), CurveOptions::default());
        let options = parse_curve(&[
            "--canvas",
            "800x600",
            "--pin-first",
            "-3,4",
            "--width-profile",
            "0:0.5,1:1.5",
            "--closed",
            "no",
            "--method",
            "synth",
            "--cut-alpha",
            "12",
            "--width",
            "-2",
        ])
        .unwrap();
        assert_eq!((options.canvas, options.pin_first), (Some([800, 600]), Some([-3, 4])));
        assert_eq!(options.width_profile, vec![[0.0, 0.5], [1.0, 1.5]]);
        assert_eq!((options.closed, options.method), (ClosedMode::Open, Method::Synthesis));
        assert_eq!((options.cut_alpha, options.width), (12, Some(-2.0)));
    }

    #[test]
    fn malformed_sizes_positions_and_pairs_name_the_flag() {
        let cases = [
            ("--canvas", "800", "WxH"),
            ("--canvas", "8x-1", "positive integer"),
            ("--pin-first", "1,2,3", "X,Y"),
            ("--width-profile", "0.5", "A:B"),
            ("--width-profile", "0:NaN", "NaN"),
            ("--closed", "approximate", "approx"),
            ("--cut-alpha", "300", "u8"),
        ];
        for (flag, value, words) in cases {
            let error = parse_curve(&[flag, value]).unwrap_err().to_string();
            assert!(error.contains(flag) && error.contains(words), "{flag} {value}: {error}");
        }
    }
}
