//! The stylize cases of `motif demo`: a map stylized with segments, the pre-synthesized speed-up,
//! a tileable texture and a hole filled in a real texture.

use motif_core::{FloatImage, RgbaImage};
use motif_stylize::samples;

use crate::gallery::{Demo, DemoCase};

fn to_png(image: &FloatImage) -> RgbaImage {
    RgbaImage::from_float(image)
}

/// Built-in examples: a map stylized with segments, the pre-synthesized speed-up, a tileable
/// texture.
pub(super) fn demo(demo: &mut Demo) -> anyhow::Result<()> {
    map_cases(demo)?;
    tile_case(demo)?;
    stone_hole_case(demo)?;
    super::video_bench::demo_case(demo)
}

/// A map stylized in crayon with segments, then with pre-synthesized textures per segment.
fn map_cases(demo: &mut Demo) -> anyhow::Result<()> {
    // Directory arguments are given as full paths (Demo resolves only file names).
    let debug_dir = demo.path("stylize-debug").to_string_lossy().into_owned();
    let presynth_dir = demo.path("stylize-presynth").to_string_lossy().into_owned();
    let source_guide = samples::map_guide(160, 160, 5, 11);
    let style = samples::crayon_style(&source_guide, 12);
    let target_guide = samples::map_guide(224, 160, 5, 13);
    motif_io::write_png(&demo.path("stylize-A.png"), &to_png(&source_guide))?;
    motif_io::write_png(&demo.path("stylize-A1.png"), &to_png(&style))?;
    motif_io::write_png(&demo.path("stylize-B.png"), &to_png(&target_guide))?;
    demo.case(DemoCase {
        title: "stylize: a map in crayon".into(),
        description: "Guided patch synthesis (StyLit energy with the occurrence penalty) transfers a crayon \
                      style A' drawn over map A onto a new map B; segments keep water, grass and roads apart."
            .into(),
        inputs: vec![
            ("style A'".into(), "stylize-A1.png".into()),
            ("source guide A".into(), "stylize-A.png".into()),
            ("target guide B".into(), "stylize-B.png".into()),
        ],
        outputs: vec![
            ("output B'".into(), "stylize-B1.png".into()),
            ("field".into(), "stylize-debug/nnf.png".into()),
            ("error".into(), "stylize-debug/error.png".into()),
        ],
        args: [
            "stylize",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "stylize-B.png",
            "--segments",
            "--debug-dir",
            &debug_dir,
            "--out",
            "stylize-B1.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    demo.case(DemoCase {
        title: "presynth: one texture per segment".into(),
        description: "Each map segment's crayon texture is synthesized once (seamless, from that segment's \
                      style patches) and cached (§3.7)."
            .into(),
        inputs: vec![("style A'".into(), "stylize-A1.png".into()), ("source guide A".into(), "stylize-A.png".into())],
        outputs: (1..=5).map(|i| (format!("segment {i}"), format!("stylize-presynth/segment-{i}.png"))).collect(),
        args: [
            "presynth",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "--size",
            "64x64",
            "--out-dir",
            &presynth_dir,
        ]
        .map(String::from)
        .to_vec(),
    })?;
    demo.case(DemoCase {
        title: "stylize --presynth --band 4: only the edges".into(),
        description: "Pixels at least 4 px from a segment edge are copied from the cached textures; only the \
                      band around the edges is optimized, orders of magnitude faster than a full synthesis."
            .into(),
        inputs: vec![("target guide B".into(), "stylize-B.png".into())],
        outputs: vec![("output B'".into(), "stylize-B1-band4.png".into())],
        args: [
            "stylize",
            "--style",
            "stylize-A1.png",
            "--guide",
            "stylize-A.png",
            "stylize-B.png",
            "--presynth",
            &presynth_dir,
            "--band",
            "4",
            "--out",
            "stylize-B1-band4.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}

/// A seamless tile grown from a small exemplar.
fn tile_case(demo: &mut Demo) -> anyhow::Result<()> {
    let exemplar = samples::crayon_style(&samples::map_guide(64, 64, 2, 14), 15);
    motif_io::write_png(&demo.path("texture-exemplar.png"), &to_png(&exemplar))?;
    demo.case(DemoCase {
        title: "texture: a seamless tile".into(),
        description: "Non-guided texture optimization grows a 160×160 texture from a 64×64 exemplar; with \
                      --tileable its patches wrap around, so copies of it tile without seams."
            .into(),
        inputs: vec![("exemplar".into(), "texture-exemplar.png".into())],
        outputs: vec![("texture".into(), "texture-tile.png".into())],
        args: [
            "texture",
            "--exemplar",
            "texture-exemplar.png",
            "--size",
            "160x160",
            "--tileable",
            "--out",
            "texture-tile.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}

/// A disc-shaped hole in a real stone texture, filled from the rest of it.
fn stone_hole_case(demo: &mut Demo) -> anyhow::Result<()> {
    // Real data: a hole cut into GIMP's stone pattern (GPL-3+, data/real/stylize), painted red so
    // that any copy of it would show, filled from the rest of the image.
    let stone_path = demo.path("inpaint-stone.png");
    motif_io::write_bytes(&stone_path, include_bytes!("../../../../../data/real/stylize/stone33.png"))?;
    let stone = motif_io::read_image(&stone_path)?;
    let (width, height) = (stone.width(), stone.height());
    let mut mask = RgbaImage::new(width, height);
    let mut holed = stone.clone();
    for (i, (pixel, hole)) in holed.pixels_mut().iter_mut().zip(mask.pixels_mut()).enumerate() {
        let (x, y) = ((i % width) as f64 - 78.0, (i / width) as f64 - 70.0);
        let inside = x * x + y * y < 28.0 * 28.0;
        *hole = if inside { [255, 255, 255, 255] } else { [0, 0, 0, 255] };
        if inside {
            *pixel = [220, 30, 30, 255];
        }
    }
    motif_io::write_png(&demo.path("inpaint-stone-hole.png"), &holed)?;
    motif_io::write_png(&demo.path("inpaint-stone-mask.png"), &mask)?;
    demo.case(DemoCase {
        title: "inpaint: a hole in a real stone texture".into(),
        description: "A disc cut out of GIMP's stone pattern (156×156; the hole painted red) is filled from \
                      the rest of the image: only patches wholly outside the hole are copied, with the \
                      occurrence penalty, and every pixel outside it is kept exactly."
            .into(),
        inputs: vec![
            ("image".into(), "inpaint-stone-hole.png".into()),
            ("hole".into(), "inpaint-stone-mask.png".into()),
        ],
        outputs: vec![("filled".into(), "inpaint-stone-filled.png".into())],
        args: [
            "inpaint",
            "--image",
            "inpaint-stone-hole.png",
            "--mask",
            "inpaint-stone-mask.png",
            "--out",
            "inpaint-stone-filled.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}
