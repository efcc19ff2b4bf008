//! `motif demo` cases of the curve engine.

use motif_curve::samples::gold_chain;

use super::heart_svg;
use crate::gallery::{Demo, DemoCase};

/// Built-in examples for `motif demo`.
pub(super) fn demo(demo: &mut Demo) -> anyhow::Result<()> {
    let chain = gold_chain(160, 44, 32.0, 28.0);
    motif_io::write_png(&demo.path("curve-chain.png"), &chain)?;
    motif_io::write_text(&demo.path("curve-heart.svg"), &heart_svg(200.0, 190.0, 330.0))?;
    demo.case(DemoCase {
        title: "curve: a chain along a heart (closed, exact)".into(),
        description: "A procedural chain strip with anti-aliased alpha is synthesized along a closed heart: \
                      undistorted rotated pieces of the exemplar, placed by a globally optimal dynamic program, \
                      the cycle certified optimal (closed_certified), fold-overs at the dip and the tip kept \
                      empty, seams stitched. The \
                      debug overlay shows the ribbon, the pieces, the forbidden areas and each seam's cost \
                      (green = cheap, red = expensive)."
            .into(),
        inputs: vec![("exemplar".into(), "curve-chain.png".into()), ("curve".into(), "curve-heart.svg".into())],
        outputs: vec![
            ("pattern".into(), "curve-heart-chain.png".into()),
            ("debug overlay".into(), "curve-heart-debug.png".into()),
            ("pieces".into(), "curve-heart-pieces.json".into()),
        ],
        args: [
            "curve",
            "--exemplar",
            "curve-chain.png",
            "--path",
            "curve-heart.svg",
            "--width",
            "48",
            "--piece-length",
            "16",
            "--closed",
            "exact",
            "--stitch",
            "--out",
            "curve-heart-chain.png",
            "--pieces",
            "curve-heart-pieces.json",
            "--debug-overlay",
            "curve-heart-debug.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    demo.case(DemoCase {
        title: "curve: the classic repeat baseline on the same heart".into(),
        description: "The same exemplar mapped along the arc length and repeated, as pattern brushes do: links \
                      are stretched outside bends, squeezed inside and cut where the tile wraps (see \
                      distortion_max and wrap_seams)."
            .into(),
        inputs: vec![("exemplar".into(), "curve-chain.png".into()), ("curve".into(), "curve-heart.svg".into())],
        outputs: vec![("pattern".into(), "curve-heart-repeat.png".into())],
        args: [
            "curve",
            "--exemplar",
            "curve-chain.png",
            "--path",
            "curve-heart.svg",
            "--width",
            "48",
            "--piece-length",
            "16",
            "--method",
            "repeat",
            "--out",
            "curve-heart-repeat.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}
