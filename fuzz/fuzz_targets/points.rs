//! PLY (ascii and binary) and CSV point files: a consistent table or an error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use motif_io::PointFormat;

fuzz_target!(|data: &[u8]| {
    let name = std::path::Path::new("fuzzed.ply");
    for format in [PointFormat::PlyAscii, PointFormat::Csv] {
        if let Ok(table) = motif_io::parse_points(data, format, name) {
            assert_eq!(table.values.len(), table.rows * table.columns.len());
        }
    }
});
