//! Files that once broke a reader, or would break a careless one, each named after what it
//! checks; every one must give an error that names the file and says what is wrong (the table
//! below), never a panic or a giant allocation. `tests/regressions/` holds them;
//! `scripts/regression_files.py` made them.

use std::path::{Path, PathBuf};

use motif_io::{ImageBudget, read_image_within, read_points, read_svg};

fn file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/regressions").join(name)
}

/// (file, what the error must say).
const CASES: &[(&str, &str)] = &[
    ("png-header-declares-20000x20000.png", "20000×20000"),
    ("png-header-declares-16384x16384.png", "16384×16384; decoding it needs about 3.00 GiB, more than the 50.00 MiB"),
    ("png-cut-to-a-third.png", "cannot decode"),
    ("jpeg-cut-before-its-end.jpg", "the JPEG is truncated"),
    ("png-zero-width.png", "Invalid image dimensions"),
    ("text-named-png.png", "is not a PNG, JPEG or WebP"),
    ("ply-declares-two-billion-vertices.ply", "not a valid PLY"),
    ("ply-binary-declares-two-billion-vertices.ply", "not a valid PLY"),
    ("ply-without-vertex-element.ply", "no `vertex` element"),
    ("ply-list-length-255-without-data.ply", "not a valid PLY"),
    ("csv-word-in-a-number-column.csv", "`one` is not a number"),
    ("csv-ragged-row.csv", "line: 3"),
    ("csv-header-only.csv", "holds no points"),
    ("csv-empty.csv", "holds no points"),
    ("svg-without-a-path.svg", "contains no path"),
    ("svg-not-xml.svg", "not a valid SVG"),
    ("svg-billion-laughs.svg", "not a valid SVG"),
];

fn read(path: &Path) -> Result<(), String> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let result = match extension {
        // Images are read as under `--max-memory 50M`: a large declared size is refused from its header.
        "png" | "jpg" => read_image_within(path, ImageBudget::max_memory(50 << 20)).map(drop),
        "ply" | "csv" => read_points(path).map(drop),
        "svg" => read_svg(path).map(drop),
        other => panic!("no reader for .{other}"),
    };
    result.map_err(|error| error.to_string())
}

#[test]
fn every_regression_file_gives_its_error() {
    let mut listed: Vec<&str> = CASES.iter().map(|(name, _)| *name).collect();
    listed.sort_unstable();
    let mut present: Vec<String> = std::fs::read_dir(file(""))
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    present.sort_unstable();
    assert_eq!(listed, present, "every committed regression file has a row in CASES");
    for (name, expected) in CASES {
        let message = read(&file(name)).expect_err(name);
        assert!(message.contains(name) && message.contains(expected), "{name}: {message}");
    }
}
