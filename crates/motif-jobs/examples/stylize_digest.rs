//! The stylize job of the playground's determinism check, natively: the page's built-in map
//! (96 pixels square) and crayon style, pre-synthesized, then a target guide with a painted
//! rectangle stylized in band mode. Prints the FNV-1a digest of the result's RGBA bytes, which
//! `web/test_page.py` compares with the page's WebAssembly result:
//! `cargo run --release -p motif-jobs --example stylize_digest`.

use std::io::Write;

use motif_core::{NoProgress, RgbaImage};
use motif_jobs::Job;
use motif_jobs::stylize::{PresynthInputs, PresynthJob, StylizeInputs, StylizeJob};

/// Side of the map, the painted rectangle `[x0, x1) × [y0, y1)`, the palette entry painted.
const SIDE: usize = 96;
const RECTANGLE: [usize; 4] = [20, 50, 30, 60];
const COLOUR: usize = 1;

fn main() {
    // As `StylizePanel::new(96)` in web/src/lib.rs builds it.
    let guide = motif_stylize::samples::map_guide(SIDE, SIDE, 4, 1);
    let style = motif_stylize::samples::crayon_style(&guide, 1);
    let presynth: PresynthJob = serde_json::from_value(serde_json::json!({ "size": [SIDE, SIDE] })).expect("job");
    let inputs = PresynthInputs { style: style.clone(), guide: guide.clone() };
    let textures = presynth.run(inputs, &mut NoProgress).expect("presynth").textures;
    // The front ends hand the engine 8-bit images.
    let style = motif_core::ByteImage::from_float(&style);
    let source = RgbaImage::from_float(&guide);
    // The palette as `StylizePanel::palette` gives it.
    let colour = &textures[COLOUR].colour;
    let paint: Vec<u8> = colour.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8).collect();
    let mut pixels: Vec<[u8; 4]> = source.pixels().to_vec();
    for y in RECTANGLE[2]..RECTANGLE[3] {
        for x in RECTANGLE[0]..RECTANGLE[1] {
            pixels[y * SIDE + x] = [paint[0], paint[1], paint[2], 255];
        }
    }
    let target = RgbaImage::from_pixels(SIDE, SIDE, pixels).expect("target");
    let mut job: StylizeJob = serde_json::from_str(r#"{"band": 4}"#).expect("job");
    job.options.own.segments = true;
    let guides = vec![motif_jobs::stylize::guide_pair(&source, &target)];
    let run = job
        .run(StylizeInputs { textures: Some(textures), ..StylizeInputs::new(style, guides) }, &mut NoProgress)
        .expect("run");
    let image = RgbaImage::from_float(&run.output.image);
    let mut digest = 0xcbf2_9ce4_8422_2325_u64;
    for &byte in image.as_bytes() {
        digest = (digest ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
    }
    let mut out = std::io::stdout().lock();
    writeln!(out, "side {SIDE} rectangle {RECTANGLE:?} colour {COLOUR}").expect("stdout");
    writeln!(out, "{}x{} image, digest {digest:016x}", image.width(), image.height()).expect("stdout");
}
