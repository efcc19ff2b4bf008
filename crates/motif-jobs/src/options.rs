//! Options declared once: name, type, range, default and help of every option of a job.
//!
//! A job's options are one struct written with [`declare_options!`](crate::declare_options): each
//! field's doc comment is its help, its `= expression` its default (the engine's `Params::DEFAULT`
//! where the engine has one), and `[value_name: "N", range: (1.0, 256.0)]` what a command line
//! shows and accepts. The macro derives the struct's serde form (kebab-case names, unknown names
//! refused, every field optional) and [`Declared::options`], the list every front end reads: the
//! CLI builds its flags from it, Python its keywords, type stubs and `motif.options()`, the page
//! its controls, and `docs/cli.md` is generated from the CLI. Nothing else names an option.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::JobError;
use motif_core::InvalidParameter;
use motif_core::error::number;

/// What an option holds, as every front end sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "type", content = "values")]
#[non_exhaustive]
pub enum Kind {
    /// On or off (a flag on the command line, `True`/`False` in Python).
    Flag,
    /// A whole number.
    Integer,
    /// A finite number.
    Number,
    /// One of a few names.
    Choice(&'static [&'static str]),
    /// A list of numbers (comma-separated on the command line).
    Numbers,
    /// A list of names (comma-separated on the command line).
    Names,
    /// Named numbers, `NAME=W` (comma-separated or repeated on the command line; a dict in
    /// Python).
    Weights,
    /// A size in whole numbers, `[W, H]` (`WxH` on the command line).
    Size,
    /// A position in integers, `[X, Y]` (`X,Y` on the command line).
    Position,
    /// A list of number pairs, `[[A, B], ...]` (`A:B,...` on the command line).
    Pairs,
    /// An sRGB colour, `"#RRGGBB"` (a string everywhere).
    Colour,
}

/// One option of a job, as declared.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptionSpec {
    /// The name, kebab-case as on the command line (Python writes `_` for `-`).
    pub name: String,
    /// What it holds.
    pub kind: Kind,
    /// Its help: what it does, and when it matters.
    pub help: String,
    /// Its default as typed on the command line; `None` when unset by default (the help says what
    /// is inferred then).
    pub default: Option<String>,
    /// The placeholder of its value in a usage line.
    pub value_name: &'static str,
    /// The allowed range of its numbers, both ends included.
    pub range: Option<(f64, f64)>,
    /// Another input or option it only makes sense with.
    pub requires: Option<&'static str>,
}

impl OptionSpec {
    /// An option named after its field, with no range.
    pub fn new(field: &str, kind: Kind, help: &str, default: Option<String>) -> Self {
        Self {
            name: field.replace('_', "-"),
            kind,
            help: help_text(help),
            default,
            value_name: "",
            range: None,
            requires: None,
        }
    }

    /// The placeholder of the value in a usage line.
    #[must_use]
    pub fn value_name(mut self, value_name: &'static str) -> Self {
        self.value_name = value_name;
        self
    }

    /// The allowed range, both ends included.
    #[must_use]
    pub fn range(mut self, (low, high): (f64, f64)) -> Self {
        self.range = Some((low, high));
        self
    }

    /// Another input or option this one needs.
    #[must_use]
    pub fn requires(mut self, other: &'static str) -> Self {
        self.requires = Some(other);
        self
    }

    /// The help with the range appended, as front ends show it.
    pub fn described(&self) -> String {
        match self.range {
            Some((low, high)) if high < f64::MAX => format!("{} Allowed: {}–{}.", self.help, number(low), number(high)),
            Some((low, _)) => format!("{} Allowed: ≥ {}.", self.help, number(low)),
            None => self.help.clone(),
        }
    }
}

/// Doc-comment lines as one paragraph: leading spaces trimmed, lines joined by spaces, blank
/// lines kept as paragraph breaks.
fn help_text(doc: &str) -> String {
    let mut text = String::new();
    for line in doc.lines().map(str::trim) {
        if line.is_empty() {
            text.push_str("\n\n");
        } else {
            if !text.is_empty() && !text.ends_with('\n') {
                text.push(' ');
            }
            text.push_str(line);
        }
    }
    text.trim().to_string()
}

/// A type an option can hold: its [`Kind`] and how its default is shown.
pub trait OptionValue {
    /// What front ends see.
    const KIND: Kind;
    /// The value as typed on the command line; `None` for "unset".
    fn shown(&self) -> Option<String>;
}

impl OptionValue for f64 {
    const KIND: Kind = Kind::Number;
    fn shown(&self) -> Option<String> {
        Some(number(*self))
    }
}

impl OptionValue for f32 {
    const KIND: Kind = Kind::Number;
    fn shown(&self) -> Option<String> {
        // The shortest decimal that reads back as this `f32` (not the `f64` widening's digits).
        Some(number(self.to_string().parse().unwrap_or(f64::from(*self))))
    }
}

/// Whole-number option types, shown as written.
macro_rules! integer_option {
    ($($type:ty),+) => {$(
        impl OptionValue for $type {
            const KIND: Kind = Kind::Integer;
            fn shown(&self) -> Option<String> {
                Some(self.to_string())
            }
        }
    )+};
}

integer_option!(u8, u32, usize);

impl OptionValue for bool {
    const KIND: Kind = Kind::Flag;
    fn shown(&self) -> Option<String> {
        self.then(|| "true".to_string())
    }
}

impl<T: OptionValue> OptionValue for Option<T> {
    const KIND: Kind = T::KIND;
    fn shown(&self) -> Option<String> {
        self.as_ref().and_then(OptionValue::shown)
    }
}

impl OptionValue for Vec<f64> {
    const KIND: Kind = Kind::Numbers;
    fn shown(&self) -> Option<String> {
        (!self.is_empty()).then(|| self.iter().map(|&v| number(v)).collect::<Vec<_>>().join(","))
    }
}

impl OptionValue for Vec<f32> {
    const KIND: Kind = Kind::Numbers;
    fn shown(&self) -> Option<String> {
        (!self.is_empty()).then(|| self.iter().filter_map(OptionValue::shown).collect::<Vec<_>>().join(","))
    }
}

impl OptionValue for Vec<String> {
    const KIND: Kind = Kind::Names;
    fn shown(&self) -> Option<String> {
        (!self.is_empty()).then(|| self.join(","))
    }
}

impl OptionValue for std::collections::BTreeMap<String, f64> {
    const KIND: Kind = Kind::Weights;
    fn shown(&self) -> Option<String> {
        (!self.is_empty())
            .then(|| self.iter().map(|(k, v)| format!("{k}={}", number(*v))).collect::<Vec<_>>().join(","))
    }
}

impl OptionValue for [usize; 2] {
    const KIND: Kind = Kind::Size;
    fn shown(&self) -> Option<String> {
        Some(format!("{}x{}", self[0], self[1]))
    }
}

impl OptionValue for [i32; 2] {
    const KIND: Kind = Kind::Position;
    fn shown(&self) -> Option<String> {
        Some(format!("{},{}", self[0], self[1]))
    }
}

impl OptionValue for Vec<[f64; 2]> {
    const KIND: Kind = Kind::Pairs;
    fn shown(&self) -> Option<String> {
        (!self.is_empty())
            .then(|| self.iter().map(|[a, b]| format!("{}:{}", number(*a), number(*b))).collect::<Vec<_>>().join(","))
    }
}

/// An sRGB colour option value, written `#RRGGBB` (or `RRGGBB`, either case).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct Colour(pub [u8; 3]);

impl TryFrom<String> for Colour {
    type Error = String;
    fn try_from(text: String) -> Result<Self, String> {
        let digits = text.trim().trim_start_matches('#');
        let refused = || format!("`{text}` is not a colour: write #RRGGBB in hexadecimal, e.g. #8b1a1a");
        if digits.len() != 6 || !digits.chars().all(|c| c.is_ascii_hexdigit()) {
            return Err(refused());
        }
        let channel = |k: usize| u8::from_str_radix(&digits[2 * k..2 * k + 2], 16).map_err(|_| refused());
        Ok(Self([channel(0)?, channel(1)?, channel(2)?]))
    }
}

impl From<Colour> for String {
    fn from(Colour([r, g, b]): Colour) -> Self {
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

impl OptionValue for Colour {
    const KIND: Kind = Kind::Colour;
    fn shown(&self) -> Option<String> {
        Some(String::from(*self))
    }
}

/// Declares an engine enum as a [`Kind::Choice`] option value, named as its serde form is.
#[macro_export]
macro_rules! choice_option {
    ($type:ty: $($name:literal),+ $(,)?) => {
        impl $crate::options::OptionValue for $type {
            const KIND: $crate::options::Kind = $crate::options::Kind::Choice(&[$($name),+]);
            fn shown(&self) -> Option<String> {
                serde_json::to_value(self).ok().and_then(|value| value.as_str().map(str::to_string))
            }
        }
    };
}

/// A struct of options declared once (see the module's documentation).
pub trait Declared: Default + Serialize + DeserializeOwned {
    /// Every option, in declaration order.
    fn options() -> Vec<OptionSpec>;

    /// Checks every number against its declared range, naming the option.
    fn check_ranges(&self) -> Result<(), JobError> {
        let values = serde_json::to_value(self).unwrap_or(Value::Null);
        for spec in Self::options() {
            let Some((low, high)) = spec.range else { continue };
            let numbers: Vec<f64> = match values.get(&spec.name) {
                Some(Value::Number(n)) => n.as_f64().into_iter().collect(),
                Some(Value::Array(list)) => list.iter().filter_map(Value::as_f64).collect(),
                Some(Value::Object(map)) => map.values().filter_map(Value::as_f64).collect(),
                _ => Vec::new(),
            };
            if let Some(&bad) = numbers.iter().find(|&&v| !(v.is_finite() && v >= low && v <= high)) {
                let allowed = match spec.kind {
                    Kind::Integer => format!("must be an integer between {} and {}", number(low), number(high)),
                    _ if high == f64::MAX => format!("must be at least {}", number(low)),
                    _ => format!("must be between {} and {}", number(low), number(high)),
                };
                return Err(InvalidParameter::new(spec.name, number(bad), allowed).into());
            }
        }
        Ok(())
    }
}

/// Two declarations as one: the options of `A` (shared by several jobs) then those of `B` (one
/// job's own). Its serde form is one flat map; a name neither declares is refused (by `B`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Joined<A, B> {
    /// The shared options.
    pub shared: A,
    /// The job's own options.
    pub own: B,
}

impl<A: Declared, B: Declared> Declared for Joined<A, B> {
    fn options() -> Vec<OptionSpec> {
        let mut options = A::options();
        options.extend(B::options());
        options
    }
}

/// A value's fields as a JSON map (empty when it is not a map).
fn fields_of<T: Serialize, E: serde::ser::Error>(value: &T) -> Result<serde_json::Map<String, Value>, E> {
    match serde_json::to_value(value).map_err(E::custom)? {
        Value::Object(map) => Ok(map),
        _ => Ok(serde_json::Map::new()),
    }
}

impl<A: Serialize, B: Serialize> Serialize for Joined<A, B> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = fields_of::<A, S::Error>(&self.shared)?;
        map.extend(fields_of::<B, S::Error>(&self.own)?);
        map.serialize(serializer)
    }
}

impl<'de, A: Declared, B: Declared> serde::Deserialize<'de> for Joined<A, B> {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error as _;
        let map = serde_json::Map::<String, Value>::deserialize(deserializer)?;
        let shared_names: Vec<String> = A::options().into_iter().map(|spec| spec.name).collect();
        let (shared, own): (serde_json::Map<String, Value>, serde_json::Map<String, Value>) =
            map.into_iter().partition(|(name, _)| shared_names.contains(name));
        Ok(Self {
            shared: serde_json::from_value(Value::Object(shared)).map_err(D::Error::custom)?,
            own: serde_json::from_value(Value::Object(own)).map_err(D::Error::custom)?,
        })
    }
}

/// A job's description as it arrives: its own fields `F`, and the rest, which must be its options.
#[derive(Debug, serde::Deserialize)]
pub struct Described<F> {
    #[serde(flatten)]
    fields: F,
    #[serde(flatten)]
    rest: serde_json::Map<String, Value>,
}

impl<F> Described<F> {
    /// The job's own fields and its options, read from the rest (unknown names refused).
    pub fn split<O: Declared>(self) -> Result<(F, O), String> {
        let options = serde_json::from_value(Value::Object(self.rest)).map_err(|error| error.to_string())?;
        Ok((self.fields, options))
    }
}

/// Declares a struct of options: fields with doc comments (the help), an optional
/// `[value_name: "N", range: (LOW, HIGH), requires: "other"]` and `= default`.
///
/// ```
/// motif_jobs::declare_options! {
///     /// Options of an example.
///     pub struct ExampleOptions {
///         /// Candidate sources judged per patch.
///         [value_name: "N", range: (1.0, 256.0)]
///         patch_candidates: usize = 48,
///         /// Gaussian width σ (default: half the mean spacing).
///         [value_name: "SIGMA"]
///         sigma: Option<f64> = None,
///     }
/// }
/// use motif_jobs::options::Declared;
/// let options = ExampleOptions::options();
/// assert_eq!(options[0].name, "patch-candidates");
/// assert_eq!(options[0].default.as_deref(), Some("48"));
/// let parsed: ExampleOptions = serde_json::from_str(r#"{"sigma": 2}"#).unwrap();
/// assert_eq!((parsed.patch_candidates, parsed.sigma), (48, Some(2.0)));
/// assert!(serde_json::from_str::<ExampleOptions>(r#"{"patch-candidates": 0}"#).unwrap().check_ranges().is_err());
/// ```
#[macro_export]
macro_rules! declare_options {
    (
        $(#[doc = $struct_doc:literal])*
        pub struct $name:ident {
            $(
                $(#[doc = $doc:literal])*
                $([$($key:ident : $value:expr),* $(,)?])?
                $field:ident : $type:ty = $default:expr
            ),* $(,)?
        }
    ) => {
        $(#[doc = $struct_doc])*
        #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
        #[serde(rename_all = "kebab-case", deny_unknown_fields, default)]
        pub struct $name {
            $(
                $(#[doc = $doc])*
                pub $field: $type,
            )*
        }

        impl Default for $name {
            fn default() -> Self {
                Self { $($field: $default,)* }
            }
        }

        impl $crate::options::Declared for $name {
            fn options() -> Vec<$crate::options::OptionSpec> {
                let defaults = Self::default();
                vec![$(
                    $crate::options::OptionSpec::new(
                        stringify!($field),
                        <$type as $crate::options::OptionValue>::KIND,
                        concat!($($doc, "\n"),*),
                        $crate::options::OptionValue::shown(&defaults.$field),
                    )$($(.$key($value))*)?,
                )*]
            }
        }
    };
}

crate::declare_options! {
    /// How front ends flatten the curves of the SVG files they read (a curve's path, a stroke
    /// reference, a region's outline), declared once.
    pub struct SvgOptions {
        /// Curve flattening tolerance for SVG paths, in the drawing's units (pixels): the largest
        /// distance between a curve and the polyline that replaces it.
        [value_name: "T", range: (0.001, 100.0)]
        tolerance: f64 = 0.1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn help_joins_lines_and_keeps_paragraphs() {
        assert_eq!(help_text(" One line\n continued.\n\n Second."), "One line continued.\n\nSecond.");
    }
}
