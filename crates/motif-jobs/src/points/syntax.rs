//! The text forms of a points domain and a brush's scale, as the command line writes them
//! (`--domain box:40,30`, `--scale-along 1,0.3`): parsed here, once, for every front end that
//! takes text. Files are named, not read (reading is the front end's, through motif-io).

use std::path::PathBuf;

use motif_core::InvalidParameter;

/// What `--domain` may say, for help texts and errors.
pub const DOMAIN_SYNTAX: &str = "box:W,H[,D] | REGION.svg | volume:MESH.obj | surface:MESH.obj";

/// A domain as text names it: a box's sizes, or a file that holds the region or mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum DomainArgument {
    /// `box:W,H` or `box:W,H,D`: a box from the origin.
    Box(Vec<f64>),
    /// `volume:MESH`: the inside of a closed mesh.
    Volume(PathBuf),
    /// `surface:MESH`: the surface of a mesh.
    Surface(PathBuf),
    /// Any other text: an SVG file whose first path outlines the region.
    Region(PathBuf),
}

impl std::str::FromStr for DomainArgument {
    type Err = InvalidParameter;

    fn from_str(text: &str) -> Result<Self, InvalidParameter> {
        if let Some(sizes) = text.strip_prefix("box:") {
            let sizes = numbers(sizes, "domain", text)?;
            if sizes.len() != 2 && sizes.len() != 3 {
                return Err(InvalidParameter::new("domain", text, "box: with 2 sizes (W,H) or 3 (W,H,D)"));
            }
            return Ok(Self::Box(sizes));
        }
        let file = |rest: &str| {
            if rest.is_empty() {
                Err(InvalidParameter::new("domain", text, format!("a mesh file after the colon ({DOMAIN_SYNTAX})")))
            } else {
                Ok(PathBuf::from(rest))
            }
        };
        if let Some(rest) = text.strip_prefix("volume:") {
            return file(rest).map(Self::Volume);
        }
        if let Some(rest) = text.strip_prefix("surface:") {
            return file(rest).map(Self::Surface);
        }
        if text.is_empty() {
            return Err(InvalidParameter::new("domain", "an empty text", DOMAIN_SYNTAX));
        }
        Ok(Self::Region(PathBuf::from(text)))
    }
}

impl DomainArgument {
    /// Whether the domain is a mesh surface (which `--surface-directions` needs).
    pub fn is_surface(&self) -> bool {
        matches!(self, Self::Surface(_))
    }
}

/// `--scale-along A,B` (the brush's scale at its start and end) or `A` (both ends).
pub fn parse_scale_along(text: &str) -> Result<[f64; 2], InvalidParameter> {
    match numbers(text, "scale-along", text)?[..] {
        [a, b] => Ok([a, b]),
        [a] => Ok([a, a]),
        _ => Err(InvalidParameter::new("scale-along", text, "A,B (the scale at the start and end) or A")),
    }
}

/// Comma-separated numbers.
fn numbers(list: &str, name: &str, whole: &str) -> Result<Vec<f64>, InvalidParameter> {
    list.split(',')
        .map(|part| {
            part.trim().parse::<f64>().map_err(|_| {
                InvalidParameter::new(name, whole, format!("numbers separated by commas; {part:?} is not a number"))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{DomainArgument, parse_scale_along};

    #[test]
    fn domains_parse_as_the_help_says() {
        assert_eq!("box:40,30".parse(), Ok(DomainArgument::Box(vec![40.0, 30.0])));
        assert_eq!("box: 4, 5 ,6".parse(), Ok(DomainArgument::Box(vec![4.0, 5.0, 6.0])));
        assert_eq!("volume:bull.obj".parse(), Ok(DomainArgument::Volume("bull.obj".into())));
        assert!("surface:torus.obj".parse::<DomainArgument>().unwrap().is_surface());
        assert_eq!("region.svg".parse(), Ok(DomainArgument::Region("region.svg".into())));
    }

    #[test]
    fn bad_domains_say_what_is_allowed() {
        for (text, says) in [
            ("box:4", "2 sizes"),
            ("box:1,2,3,4", "2 sizes"),
            ("box:", "\"\" is not a number"),
            ("box:4,x", "\"x\" is not a number"),
            ("volume:", "a mesh file"),
            ("", "box:W,H"),
        ] {
            let error = text.parse::<DomainArgument>().unwrap_err().to_string();
            assert!(error.contains("domain") && error.contains(says), "{text:?}: {error}");
        }
    }

    #[test]
    fn scale_along_takes_one_or_two_numbers() {
        assert_eq!(parse_scale_along("1,0.3"), Ok([1.0, 0.3]));
        assert_eq!(parse_scale_along("2"), Ok([2.0, 2.0]));
        for bad in ["1,2,3", "a,1", ""] {
            assert!(parse_scale_along(bad).unwrap_err().to_string().contains("scale-along"), "{bad}");
        }
    }
}
