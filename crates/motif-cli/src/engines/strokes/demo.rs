//! `motif demo` cases of the strokes engine.

use std::path::Path;

use kurbo::BezPath;
use motif_core::Point;
use motif_io::SvgWriter;
use motif_strokes::samples::{FigureField, HatchRow, figure_field, hatch_row};

use super::{blob, wave, write_strokes_svg};
use crate::gallery::{Demo, DemoCase};

fn write_path_svg(path: &Path, shape: &BezPath, width: f64, height: f64, closed: bool) -> anyhow::Result<()> {
    let mut writer = SvgWriter::new(width, height);
    let fill = closed.then_some([235, 235, 225, 255]);
    writer.path(shape, Some(motif_io::StrokePaint { width: 1.0, colour: [90, 90, 90, 255] }), fill);
    motif_io::write_text(path, &writer.finish())?;
    Ok(())
}

fn strs(items: &[&str]) -> Vec<String> {
    items.iter().map(|s| s.to_string()).collect()
}

/// The built-in examples: sketchy hatching along a wave (1D) and small figures in a blob (2D).
pub(super) fn demo(demo: &mut Demo) -> anyhow::Result<()> {
    hatching_along_wave(demo)?;
    brushes_along_arc(demo)?;
    figures_in_blob(demo)?;
    cactus_spines(demo)?;
    Ok(())
}

/// Sketchy hatches along a wave (1D).
fn hatching_along_wave(demo: &mut Demo) -> anyhow::Result<()> {
    // 1D: sketchy hatches (three overlapping strokes each) whose tilt turns smoothly and whose
    // colours alternate, with irregular spacing.
    let row = HatchRow { count: 36, jitter: 2.0, ..HatchRow::default() };
    let hatches = hatch_row(
        &row,
        Point::new(20.0, 40.0),
        |i| 0.5 * (i as f64 * 0.25).sin(),
        |i| if i % 2 == 0 { [30, 40, 120, 255] } else { [170, 60, 30, 255] },
        demo.seed(),
    );
    write_strokes_svg(&demo.path("strokes-hatch-reference.svg"), &hatches, 330.0, 80.0)?;
    write_path_svg(&demo.path("strokes-wave.svg"), &wave(30.0, 970.0, 130.0, 70.0, 4), 1000.0, 260.0, false)?;
    demo.case(DemoCase {
        title: "strokes: sketchy hatching along a curve".into(),
        description: "A 1D reference of 36 hatches, each drawn as three overlapping strokes, is clustered at ε = 4 \
                      (one element per hatch) and synthesized along a wave: colours keep alternating, the tilt \
                      turns smoothly (5-ring neighbourhoods), and the reference's irregular spacing comes back \
                      through its shift vectors."
            .into(),
        inputs: vec![
            ("reference".into(), "strokes-hatch-reference.svg".into()),
            ("path".into(), "strokes-wave.svg".into()),
        ],
        outputs: vec![
            ("analysis".into(), "strokes-hatch-analysis.svg".into()),
            ("output".into(), "strokes-hatch-output.png".into()),
        ],
        args: strs(&[
            "strokes",
            "--reference",
            "strokes-hatch-reference.svg",
            "--scale",
            "4",
            "--along",
            "strokes-wave.svg",
            "--position-variation",
            "--analysis",
            "strokes-hatch-analysis.svg",
            "--out",
            "strokes-hatch-output.svg",
            "--png",
            "strokes-hatch-output.png",
        ]),
    })?;

    Ok(())
}

/// Brush strokes of varying width along an arc (1D).
fn brushes_along_arc(demo: &mut Demo) -> anyhow::Result<()> {
    // 1D: single brush strokes whose width swells and shrinks along the row, fitted by contour.
    let brush_row = HatchRow { count: 30, spacing: 14.0, length: 18.0, strokes_per_hatch: 1, ..HatchRow::default() };
    let mut brushes = hatch_row(&brush_row, Point::new(20.0, 30.0), |_| 0.35, |_| [60, 60, 60, 255], demo.seed());
    for (i, brush) in brushes.iter_mut().enumerate() {
        brush.width = 2.0 + 2.5 * (1.0 + (i as f64 * 0.35).sin());
    }
    write_strokes_svg(&demo.path("strokes-brush-reference.svg"), &brushes, 460.0, 60.0)?;
    let mut arc = BezPath::new();
    arc.move_to((40.0, 260.0));
    arc.curve_to((200.0, 20.0), (800.0, 20.0), (960.0, 260.0));
    write_path_svg(&demo.path("strokes-arc.svg"), &arc, 1000.0, 300.0, false)?;
    demo.case(DemoCase {
        title: "strokes: brush strokes of changing thickness".into(),
        description: concat!(
            "Element boxes fitted to the stroked contour (--fit contour) carry each brush stroke's width; with ",
            "5-ring neighbourhoods and shape and superimposition thresholds tightened to 0.03 L (the paper uses ",
            "0.1 L), the smooth swelling and thinning of the reference carries over to an arc."
        )
        .into(),
        inputs: vec![
            ("reference".into(), "strokes-brush-reference.svg".into()),
            ("path".into(), "strokes-arc.svg".into()),
        ],
        outputs: vec![("output".into(), "strokes-brush-output.png".into())],
        args: strs(&[
            "strokes",
            "--reference",
            "strokes-brush-reference.svg",
            "--scale",
            "3",
            "--fit",
            "contour",
            "--thresholds",
            "shape=0.03,sup=0.03",
            "--along",
            "strokes-arc.svg",
            "--out",
            "strokes-brush-output.svg",
            "--png",
            "strokes-brush-output.png",
        ]),
    })?;

    Ok(())
}

/// Small figures filling a blob (2D).
fn figures_in_blob(demo: &mut Demo) -> anyhow::Result<()> {
    // 2D: small three-stroke figures of two kinds on a jittered grid, filling a blob.
    let field = FigureField { columns: 8, rows: 6, ..FigureField::default() };
    let figures = figure_field(&field, Point::new(20.0, 20.0), demo.seed());
    write_strokes_svg(&demo.path("strokes-figures-reference.svg"), &figures, 240.0, 180.0)?;
    write_path_svg(&demo.path("strokes-blob.svg"), &blob(300.0, 300.0, 240.0), 600.0, 600.0, true)?;
    demo.case(DemoCase {
        title: "strokes: small figures in a region".into(),
        description: "A 2D reference of 48 small figures (three-armed stars and triangles, three strokes each) is \
                      clustered at ε = 8, related by its unskewed Delaunay graph and synthesized inside a blob \
                      with a clipped centroidal Voronoi layout, 2-ring neighbourhoods and a little parameter \
                      exchange."
            .into(),
        inputs: vec![
            ("reference".into(), "strokes-figures-reference.svg".into()),
            ("region".into(), "strokes-blob.svg".into()),
        ],
        outputs: vec![
            ("analysis".into(), "strokes-figures-analysis.svg".into()),
            ("output".into(), "strokes-figures-output.png".into()),
        ],
        args: strs(&[
            "strokes",
            "--reference",
            "strokes-figures-reference.svg",
            "--scale",
            "8",
            "--region",
            "strokes-blob.svg",
            "--variation",
            "0.5",
            "--analysis",
            "strokes-figures-analysis.svg",
            "--out",
            "strokes-figures-output.svg",
            "--png",
            "strokes-figures-output.png",
        ]),
    })?;
    Ok(())
}

/// Spines from a real drawing shading a real photo (2D).
fn cactus_spines(demo: &mut Demo) -> anyhow::Result<()> {
    // 2D on real data: spines cut from a public-domain cactus drawing shade a public-domain photo
    // (both from `data/real/strokes/`, built into the binary so the demo needs no checkout).
    motif_io::write_bytes(
        &demo.path("strokes-spines-reference.svg"),
        include_bytes!("../../../../../data/real/strokes/cactus_spines_cropped.svg"),
    )?;
    motif_io::write_bytes(
        &demo.path("strokes-photo.png"),
        include_bytes!("../../../../../data/real/strokes/photo_astronaut.png"),
    )?;
    demo.case(DemoCase {
        title: "strokes: hatching that shades a photo".into(),
        description: "Spines cut from an openclipart cactus drawing (57 elements at ε = 6; the 20 cut by the \
                      drawing's frame are not copied) fill a square whose density map and scale map are a NASA \
                      portrait: dark tones get smaller, denser spines, light tones few large ones (weighted \
                      centroidal Voronoi seeds), and no two spines overlap."
            .into(),
        inputs: vec![
            ("reference".into(), "strokes-spines-reference.svg".into()),
            ("density and scale map".into(), "strokes-photo.png".into()),
        ],
        outputs: vec![("output".into(), "strokes-photo-output.png".into())],
        args: strs(&[
            "strokes",
            "--reference",
            "strokes-spines-reference.svg",
            "--scale",
            "6",
            "--rect",
            "1400,1400",
            "--density-map",
            "strokes-photo.png",
            "--scale-map",
            "strokes-photo.png",
            "--out",
            "strokes-photo-output.svg",
            "--png",
            "strokes-photo-output.png",
            "--png-scale",
            "0.4",
        ]),
    })?;

    Ok(())
}
