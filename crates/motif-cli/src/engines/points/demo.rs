//! `motif demo` cases of the points engine.

use std::path::Path;

use motif_core::TriangleMesh;
use motif_io::PointFormat;
use motif_points::PointSet;
use motif_points::samples::{hex_exemplar, lattice_exemplar, leaf_exemplar};

use super::points_to_table;
use crate::gallery::{Demo, DemoCase};

fn write_set(path: &Path, set: &PointSet) -> anyhow::Result<()> {
    motif_io::write_points(path, &points_to_table(set, &[]), PointFormat::PlyAscii)?;
    Ok(())
}

/// Built-in examples for `motif demo`.
pub(super) fn demo(demo: &mut Demo) -> anyhow::Result<()> {
    hex_cases(demo)?;
    element_and_lattice_cases(demo)?;
    let bull = atoms_in_bull(demo)?;
    pines_on_bull(demo, bull)
}

/// A hexagonal exemplar synthesized into a box and brushed along a stroke.
fn hex_cases(demo: &mut Demo) -> anyhow::Result<()> {
    write_set(&demo.path("points-hex.ply"), &hex_exemplar(16, 16, 0.12, 3))?;
    demo.case(DemoCase {
        title: "points: a jittered hexagonal grid in a box".into(),
        description: "A 256-point hexagonal exemplar with a striped `shade` attribute (detected as discrete: whole \
                      numbers) is synthesized into a 14×10 box from copied exemplar patches: matching by gradient \
                      descent from 5 random starts and the neighbours' matches per quadrature point, merging of \
                      positions then attributes, multi-scale window shrinking and sampling control."
            .into(),
        inputs: vec![("exemplar".into(), "points-hex.ply".into())],
        outputs: vec![("preview".into(), "points-hex-box.png".into()), ("points".into(), "points-hex-box.ply".into())],
        args: [
            "points",
            "--exemplar",
            "points-hex.ply",
            "--neighbourhood",
            "1.2",
            "--domain",
            "box:14,10",
            "--out",
            "points-hex-box.ply",
            "--preview",
            "points-hex-box.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    motif_io::write_text(
        &demo.path("points-stroke.svg"),
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"40\" height=\"20\" viewBox=\"0 0 40 20\">\
         <path d=\"M2 14 C 12 0, 26 22, 38 6\" fill=\"none\" stroke=\"black\"/></svg>\n",
    )?;
    demo.case(DemoCase {
        title: "points: a brush stroke with growing scale".into(),
        description: "The same exemplar brushed along a curve 3 units wide: the exemplar's rows follow the stroke's \
                      tangent and its scale grows from 0.8 to 1.3 along the stroke."
            .into(),
        inputs: vec![("exemplar".into(), "points-hex.ply".into()), ("stroke".into(), "points-stroke.svg".into())],
        outputs: vec![
            ("preview".into(), "points-hex-stroke.png".into()),
            ("points".into(), "points-hex-stroke.ply".into()),
        ],
        args: [
            "points",
            "--exemplar",
            "points-hex.ply",
            "--neighbourhood",
            "1.2",
            "--along",
            "points-stroke.svg",
            "--brush-width",
            "3",
            "--scale-along",
            "0.8,1.3",
            "--out",
            "points-hex-stroke.ply",
            "--preview",
            "points-hex-stroke.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}

/// Rigid three-point leaves among free points, and a 3D lattice.
fn element_and_lattice_cases(demo: &mut Demo) -> anyhow::Result<()> {
    write_set(&demo.path("points-leaves.ply"), &leaf_exemplar(5))?;
    demo.case(DemoCase {
        title: "points: rigid elements mixed with free points".into(),
        description: "Three-point leaves (discrete elements, moved rigidly: translation and rotation) mixed with free \
                      background points, synthesized into a box from patch initialization. Colours are element ids."
            .into(),
        inputs: vec![("exemplar".into(), "points-leaves.ply".into())],
        outputs: vec![
            ("preview".into(), "points-leaves-box.png".into()),
            ("points".into(), "points-leaves-box.ply".into()),
        ],
        args: [
            "points",
            "--exemplar",
            "points-leaves.ply",
            "--neighbourhood",
            "2.5",
            "--domain",
            "box:15,12",
            "--init",
            "patches",
            "--out",
            "points-leaves-box.ply",
            "--preview",
            "points-leaves-box.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    write_set(&demo.path("points-lattice.ply"), &lattice_exemplar(216, 7))?;
    demo.case(DemoCase {
        title: "points: a 3D lattice in a box".into(),
        description: "A 216-point 3D exemplar (alternating shifted cells, with a radius attribute) synthesized into a \
                      5×5×4 box; the preview is an orthographic view, darker points are farther."
            .into(),
        inputs: vec![("exemplar".into(), "points-lattice.ply".into())],
        outputs: vec![
            ("preview".into(), "points-lattice-box.png".into()),
            ("points".into(), "points-lattice-box.ply".into()),
        ],
        args: [
            "points",
            "--exemplar",
            "points-lattice.ply",
            "--neighbourhood",
            "1.0",
            "--domain",
            "box:5,5,4",
            "--quadrature-spacing",
            "1.5",
            "--out",
            "points-lattice-box.ply",
            "--preview",
            "points-lattice-box.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}

/// Protein atoms filling a real closed mesh; returns the mesh (CGAL's bull) scaled to 78 Å.
fn atoms_in_bull(demo: &mut Demo) -> anyhow::Result<TriangleMesh> {
    // Real data in a real volume: protein atoms (PDB 1TII, CC0) fill CGAL's bull (CC0), scaled from
    // its unit length to 78 Å so that it holds about 1 500 atoms at the exemplar's density.
    let bull_path = demo.path("points-bull.obj");
    motif_io::write_bytes(&bull_path, include_bytes!("../../../../../data/real/meshes/bull.obj"))?;
    let mut bull = motif_io::read_mesh(&bull_path)?;
    bull.vertices.iter_mut().for_each(|v| *v = v.map(|c| 78.0 * c));
    motif_io::write_obj(&demo.path("points-bull-78.obj"), &bull, "CGAL's bull.off (CC0), scaled by 78")?;
    motif_io::write_bytes(
        &demo.path("points-protein-atoms.csv"),
        include_bytes!("../../../../../data/real/points/protein_atoms.csv"),
    )?;
    demo.case(DemoCase {
        title: "points: protein atoms inside a bull".into(),
        description: "192 atoms of a real protein structure (PDB 1TII, 15 Å cube, labelled C, N, O, S) fill the \
                      inside of a real closed mesh (CGAL's bull, 12 396 triangles, scaled to 78 Å): the volume \
                      domain counts ray crossings with exact orientation tests, and the atom labels stay discrete."
            .into(),
        inputs: vec![
            ("exemplar".into(), "points-protein-atoms.csv".into()),
            ("volume".into(), "points-bull-78.obj".into()),
        ],
        outputs: vec![
            ("preview".into(), "points-bull-atoms.png".into()),
            ("points".into(), "points-bull-atoms.ply".into()),
        ],
        args: [
            "points",
            "--exemplar",
            "points-protein-atoms.csv",
            "--exemplar-window",
            "15,15,15",
            "--neighbourhood",
            "2.8",
            "--domain",
            "volume:points-bull-78.obj",
            "--colour-by",
            "label",
            "--out",
            "points-bull-atoms.ply",
            "--preview",
            "points-bull-atoms.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(bull)
}

/// Pine positions laid on the surface of `bull` (scaled to 78 Å) rescaled to 400 units.
fn pines_on_bull(demo: &mut Demo, mut bull: TriangleMesh) -> anyhow::Result<()> {
    // A real planar pattern on a real surface: the 71 Swedish pines (spatstat, GPL-2+ data; see
    // data/real/points) on the bull scaled to 400 units (pines in decimetres: about 1 300 trees),
    // each planted as CGAL's tripod (CC0), lying along the direction of least curvature.
    bull.vertices.iter_mut().for_each(|v| *v = v.map(|c| c * 400.0 / 78.0));
    motif_io::write_obj(&demo.path("points-bull-400.obj"), &bull, "CGAL's bull.off (CC0), scaled by 400")?;
    motif_io::write_bytes(
        &demo.path("points-swedishpines.csv"),
        include_bytes!("../../../../../data/real/points/swedishpines.csv"),
    )?;
    motif_io::write_bytes(
        &demo.path("points-tripod.obj"),
        include_bytes!("../../../../../data/real/meshes/tripod.obj"),
    )?;
    demo.case(DemoCase {
        title: "points: pine positions planted on a bull's surface".into(),
        description: "The 71 trees of a real Swedish pine plot (spatstat, decimetres) laid on the surface of a real \
                      mesh (CGAL's bull, 12 396 triangles, scaled to 400 dm): copies of the plot laid in the \
                      tangent planes, then optimized with the points kept on the mesh; each tree is drawn as \
                      CGAL's tripod, lying along the direction of least curvature."
            .into(),
        inputs: vec![
            ("exemplar".into(), "points-swedishpines.csv".into()),
            ("surface".into(), "points-bull-400.obj".into()),
            ("element mesh".into(), "points-tripod.obj".into()),
        ],
        outputs: vec![
            ("preview".into(), "points-bull-pines.png".into()),
            ("points".into(), "points-bull-pines.ply".into()),
            ("elements".into(), "points-bull-tripods.obj".into()),
        ],
        args: [
            "points",
            "--exemplar",
            "points-swedishpines.csv",
            "--neighbourhood",
            "32",
            "--domain",
            "surface:points-bull-400.obj",
            "--element-mesh",
            "points-tripod.obj",
            "--element-size",
            "12",
            "--surface-out",
            "points-bull-tripods.obj",
            "--out",
            "points-bull-pines.ply",
            "--preview",
            "points-bull-pines.png",
        ]
        .map(String::from)
        .to_vec(),
    })?;
    Ok(())
}
