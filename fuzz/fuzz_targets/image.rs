//! PNG and JPEG decoding: an image within the size limit or an error naming the file.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = std::path::Path::new("fuzzed.png");
    if let Ok(image) = motif_io::decode_image(data.to_vec(), name) {
        assert!(image.width() * image.height() <= 1 << 28);
    }
});
