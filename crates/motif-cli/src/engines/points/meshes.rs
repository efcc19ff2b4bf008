//! The options about meshes beyond the domain itself: `--surface-directions` and the element
//! meshes placed on the output (`--element-mesh`).

use std::path::Path;

use anyhow::{Context, bail};
use motif_jobs::points::DirectionsSpec;

use super::table_to_points;

/// The element mesh placed on every output element (each free point, each `element` id at its
/// points' centroid), scaled so that its largest side is `size` exemplar units (default: the
/// exemplar's mean spacing), then by the frame there.
pub(super) fn place_elements(
    output: &motif_jobs::points::Output,
    mesh: &motif_core::TriangleMesh,
    side: f64,
    size: Option<f64>,
) -> anyhow::Result<motif_core::TriangleMesh> {
    let points = &output.points;
    let scale_of = |frame: &[[f64; 3]; 3]| (0..3).map(|i| frame[i][0] * frame[i][0]).sum::<f64>().sqrt();
    let mean_scale = output.frames.iter().map(scale_of).sum::<f64>() / output.frames.len().max(1) as f64;
    let size = size.unwrap_or(output.report.fidelity.spacing / mean_scale.max(1e-300));
    let factor = size / side;
    let position =
        |i: usize| -> [f64; 3] { std::array::from_fn(|a| points.position(i).get(a).copied().unwrap_or(0.0)) };
    let mut placements = Vec::new();
    let mut elements: std::collections::BTreeMap<i64, (usize, [f64; 3], usize)> = std::collections::BTreeMap::new();
    for i in 0..points.len() {
        let frame = output.frames[i].map(|row| row.map(|v| v * factor));
        match points.elements.as_ref().map_or(-1, |ids| ids[i]) {
            id if id < 0 => placements.push((position(i), frame)),
            id => {
                let entry = elements.entry(id).or_insert((i, [0.0; 3], 0));
                let p = position(i);
                (0..3).for_each(|a| entry.1[a] += p[a]);
                entry.2 += 1;
            }
        }
    }
    for (first, sum, count) in elements.values() {
        let frame = output.frames[*first].map(|row| row.map(|v| v * factor));
        placements.push((sum.map(|v| v / *count as f64), frame));
    }
    const MAX_TRIANGLES: usize = 20_000_000;
    mesh.placed_copies(&placements, MAX_TRIANGLES).ok_or_else(|| {
        anyhow::anyhow!(
            "{} elements × {} triangles is more than {MAX_TRIANGLES} triangles; use a simpler element mesh",
            placements.len(),
            mesh.triangles.len()
        )
    })
}

/// `--surface-directions`: `curvature`, `X,Y,Z` or a file of one vector per vertex.
pub(super) fn surface_directions(spec: Option<&str>) -> anyhow::Result<DirectionsSpec> {
    let Some(spec) = spec else { return Ok(DirectionsSpec::Curvature) };
    if spec == "curvature" {
        return Ok(DirectionsSpec::Curvature);
    }
    let numbers: Option<Vec<f64>> = spec.split(',').map(|s| s.trim().parse::<f64>().ok()).collect();
    if let Some(values) = numbers {
        return match values[..] {
            [x, y, z] => Ok(DirectionsSpec::Constant([x, y, z])),
            _ => bail!("--surface-directions {spec}: give three numbers X,Y,Z, `curvature` or a file of vectors"),
        };
    }
    let path = Path::new(spec);
    let table = motif_io::read_points(path)?;
    let (vectors, _) = table_to_points(&table, "surface directions").with_context(|| format!("{}", path.display()))?;
    if vectors.dimension != 3 {
        bail!(
            "--surface-directions {}: the vectors have {} coordinates; give x,y,z for each mesh vertex",
            path.display(),
            vectors.dimension
        );
    }
    Ok(DirectionsSpec::PerVertex((0..vectors.len()).map(|i| std::array::from_fn(|a| vectors.position(i)[a])).collect()))
}
