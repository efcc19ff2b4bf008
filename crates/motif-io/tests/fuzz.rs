//! Property tests of every file reader on random and mutated input: each returns `Ok` with a
//! consistent value or an error naming the file, never panics, hangs or allocates without bound.
//! Fixed seeds and a bounded number of cases keep the suite fast and repeatable; `fuzz/` holds
//! cargo-fuzz targets of the same readers for longer runs.

use std::path::Path;

use motif_io::{PointFormat, decode_image, parse_points, parse_svg};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(20261202), failure_persistence: None, ..Config::default() }
}

/// Byte edits applied to a valid file: overwrite, truncate, insert.
#[derive(Debug, Clone)]
enum Edit {
    Set(usize, u8),
    Truncate(usize),
    Insert(usize, Vec<u8>),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        4 => (any::<usize>(), any::<u8>()).prop_map(|(at, byte)| Edit::Set(at, byte)),
        1 => any::<usize>().prop_map(Edit::Truncate),
        1 => (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..16)).prop_map(|(at, b)| Edit::Insert(at, b)),
    ];
    proptest::collection::vec(edit, 1..6)
}

fn mutate(seed: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for edit in edits {
        match edit {
            _ if bytes.is_empty() => {}
            Edit::Set(at, byte) => {
                let at = at % bytes.len();
                bytes[at] = *byte;
            }
            Edit::Truncate(at) => bytes.truncate(at % bytes.len()),
            Edit::Insert(at, inserted) => {
                let at = at % bytes.len();
                bytes.splice(at..at, inserted.iter().copied());
            }
        }
    }
    bytes
}

fn png_seed() -> Vec<u8> {
    let mut bytes = Vec::new();
    let pixels: Vec<u8> = (0..12 * 9 * 4).map(|i| (i * 37 % 251) as u8).collect();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(encoder, &pixels, 12, 9, image::ExtendedColorType::Rgba8).unwrap();
    bytes
}

fn jpeg_seed() -> Vec<u8> {
    let mut bytes = Vec::new();
    let pixels: Vec<u8> = (0..16 * 16 * 3).map(|i| (i * 53 % 251) as u8).collect();
    let encoder = image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, 80);
    image::ImageEncoder::write_image(encoder, &pixels, 16, 16, image::ExtendedColorType::Rgb8).unwrap();
    bytes
}

fn webp_seed() -> Vec<u8> {
    let mut bytes = Vec::new();
    let pixels: Vec<u8> = (0..14 * 10 * 4).map(|i| (i * 29 % 251) as u8).collect();
    let encoder = image::codecs::webp::WebPEncoder::new_lossless(&mut bytes);
    image::ImageEncoder::write_image(encoder, &pixels, 14, 10, image::ExtendedColorType::Rgba8).unwrap();
    bytes
}

const PLY_ASCII: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                         property int label\nend_header\n0 0 1\n1.5 2 0\n3 -1 1\n";
const CSV: &str = "x,y,dbh\n0,0,12.5\n1.5,2,3\n3,-1,40\n";
const SVG: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="60"><path d="M 5 5 C 20 40 60 -10 95 30" stroke="#204080" stroke-width="3" fill="none"/><rect x="10" y="10" width="20" height="8"/></svg>"##;

fn ply_binary_seed() -> Vec<u8> {
    let mut bytes =
        b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nend_header\n"
            .to_vec();
    for value in [0.0f32, 1.0, 2.5, -3.0] {
        bytes.extend_from_slice(&value.to_le_bytes());
    }
    bytes
}

fn check_image(bytes: Vec<u8>) {
    let name = Path::new("fuzzed.png");
    match decode_image(bytes, name) {
        Ok(image) => assert!(image.width() > 0 && image.height() > 0 && image.width() * image.height() <= 1 << 28),
        Err(error) => assert!(error.to_string().contains("fuzzed.png"), "{error}"),
    }
}

fn check_points(bytes: &[u8], format: PointFormat) {
    let name = Path::new("fuzzed.ply");
    match parse_points(bytes, format, name) {
        Ok(table) => {
            assert!(table.rows > 0);
            assert_eq!(table.values.len(), table.rows * table.columns.len());
        }
        Err(error) => assert!(error.to_string().contains("fuzzed.ply"), "{error}"),
    }
}

fn check_svg(text: &str) {
    match parse_svg(text, Path::new("fuzzed.svg")) {
        Ok(document) => assert!(!document.paths.is_empty()),
        Err(error) => assert!(error.to_string().contains("fuzzed.svg"), "{error}"),
    }
}

#[test]
fn seeds_are_valid_files() {
    assert_eq!(decode_image(png_seed(), Path::new("seed.png")).unwrap().width(), 12);
    assert_eq!(decode_image(jpeg_seed(), Path::new("seed.jpg")).unwrap().width(), 16);
    assert_eq!(decode_image(webp_seed(), Path::new("seed.webp")).unwrap().width(), 14);
    assert_eq!(parse_points(PLY_ASCII.as_bytes(), PointFormat::PlyAscii, Path::new("a.ply")).unwrap().rows, 3);
    assert_eq!(parse_points(&ply_binary_seed(), PointFormat::PlyBinary, Path::new("b.ply")).unwrap().rows, 2);
    assert_eq!(parse_points(CSV.as_bytes(), PointFormat::Csv, Path::new("c.csv")).unwrap().rows, 3);
    assert_eq!(parse_svg(SVG, Path::new("d.svg")).unwrap().paths.len(), 2);
}

proptest! {
    #![proptest_config(config(192))]

    #[test]
    fn images_from_random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..256)) {
        check_image(bytes);
    }

    #[test]
    fn mutated_pngs(edits in edits()) {
        check_image(mutate(&png_seed(), &edits));
    }

    #[test]
    fn mutated_jpegs(edits in edits()) {
        check_image(mutate(&jpeg_seed(), &edits));
    }

    #[test]
    fn mutated_webps(edits in edits()) {
        check_image(mutate(&webp_seed(), &edits));
    }

    #[test]
    fn points_from_random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..256), csv in any::<bool>()) {
        check_points(&bytes, if csv { PointFormat::Csv } else { PointFormat::PlyAscii });
    }

    #[test]
    fn mutated_ascii_ply(edits in edits()) {
        check_points(&mutate(PLY_ASCII.as_bytes(), &edits), PointFormat::PlyAscii);
    }

    #[test]
    fn mutated_binary_ply(edits in edits()) {
        check_points(&mutate(&ply_binary_seed(), &edits), PointFormat::PlyBinary);
    }

    #[test]
    fn mutated_csv(edits in edits()) {
        check_points(&mutate(CSV.as_bytes(), &edits), PointFormat::Csv);
    }

    #[test]
    fn svg_from_random_text(text in ".{0,200}") {
        check_svg(&text);
    }

    #[test]
    fn mutated_svg(edits in edits()) {
        check_svg(&String::from_utf8_lossy(&mutate(SVG.as_bytes(), &edits)));
    }
}
