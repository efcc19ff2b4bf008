//! SVG documents: paths or an error.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(document) = motif_io::parse_svg(text, std::path::Path::new("fuzzed.svg")) {
            assert!(!document.paths.is_empty());
        }
    }
});
