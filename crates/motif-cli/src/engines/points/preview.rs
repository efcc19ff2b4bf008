//! The `motif points --preview` picture: exemplar and output side by side (2D discs, 3D as an
//! orthographic view), then their g(r) curves and nearest-neighbour histograms.

use anyhow::Context as _;
use motif_core::Point;
use motif_core::TriangleMesh;
use motif_io::{StrokePaint, SvgWriter};
use motif_jobs::points::{Fidelity, PointSet};

/// A colour for `t` in [0, 1] (dark blue → teal → yellow).
fn ramp(t: f64) -> [u8; 4] {
    let t = t.clamp(0.0, 1.0);
    let stops = [[40.0, 30.0, 110.0], [30.0, 150.0, 140.0], [250.0, 220.0, 40.0]];
    let (a, b, f) = if t < 0.5 { (stops[0], stops[1], t * 2.0) } else { (stops[1], stops[2], t * 2.0 - 1.0) };
    [(a[0] + (b[0] - a[0]) * f) as u8, (a[1] + (b[1] - a[1]) * f) as u8, (a[2] + (b[2] - a[2]) * f) as u8, 255]
}

/// Per-point colours, and the value range an attribute was mapped from (to colour the output
/// like the exemplar).
type Colours = (Vec<[u8; 4]>, Option<(f64, f64)>);

/// Per-point colours of a set.
fn colours(set: &PointSet, colour_by: Option<&str>, range: Option<(f64, f64)>) -> anyhow::Result<Colours> {
    let names = &set.attribute_names;
    let find = |name: &str| names.iter().position(|n| n == name);
    if colour_by.is_none()
        && let (Some(r), Some(g), Some(b)) = (find("red"), find("green"), find("blue"))
    {
        let max = (0..set.len()).flat_map(|i| [r, g, b].map(|c| set.attributes_of(i)[c])).fold(0.0, f64::max);
        let scale = if max > 1.0 { 1.0 } else { 255.0 };
        let list = (0..set.len())
            .map(|i| {
                let a = set.attributes_of(i);
                [a[r], a[g], a[b]].map(|v| (v * scale).clamp(0.0, 255.0) as u8)
            })
            .map(|[r, g, b]| [r, g, b, 255])
            .collect();
        return Ok((list, None));
    }
    let column = match colour_by {
        Some(name) => Some(find(name).with_context(|| format!("--colour-by {name}: no such attribute"))?),
        None => (!names.is_empty()).then_some(0),
    };
    if let Some(c) = column {
        let values: Vec<f64> = (0..set.len()).map(|i| set.attributes_of(i)[c]).collect();
        let (low, high) = range.unwrap_or_else(|| {
            (
                values.iter().copied().fold(f64::INFINITY, f64::min),
                values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        });
        let span = (high - low).max(1e-12);
        return Ok((values.iter().map(|v| ramp((v - low) / span)).collect(), Some((low, high))));
    }
    if let Some(elements) = &set.elements {
        return Ok((
            elements
                .iter()
                .map(|&e| {
                    if e < 0 {
                        [60, 60, 60, 255]
                    } else {
                        ramp(((e as u64).wrapping_mul(2654435761) % 1000) as f64 / 1000.0)
                    }
                })
                .collect(),
            None,
        ));
    }
    Ok((vec![[40, 40, 60, 255]; set.len()], None))
}

/// Projects a set for drawing: 2D as is, 3D by an orthographic view (turned 35° about z and
/// tilted 30°), returning screen points and depth shades.
fn project(set: &PointSet) -> Vec<(f64, f64, f64)> {
    (0..set.len())
        .map(|i| {
            let p = set.position(i);
            if set.dimension == 2 { (p[0], p[1], 1.0) } else { view([p[0], p[1], p[2]]) }
        })
        .collect()
}

/// The 3D view of the preview: turned 35° about z, tilted 30°; screen x, screen y (down) and depth.
fn view(p: [f64; 3]) -> (f64, f64, f64) {
    let (sa, ca) = 35f64.to_radians().sin_cos();
    let (sb, cb) = 30f64.to_radians().sin_cos();
    let x = ca * p[0] - sa * p[1];
    let y1 = sa * p[0] + ca * p[1];
    let depth = cb * y1 + sb * p[2];
    let up = -sb * y1 + cb * p[2];
    (x, -up, depth)
}

/// Screen points (from [`view`]) fitted into a square panel of side `size` at `left`.
struct Fit {
    low: (f64, f64),
    scale: f64,
    left: f64,
}

impl Fit {
    const MARGIN: f64 = 16.0;

    fn new(screen: &[(f64, f64, f64)], left: f64, size: f64) -> Self {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for &(x, y, _) in screen {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        let extent = (x1 - x0).max(y1 - y0).max(1e-9);
        Self { low: (x0, y0), scale: (size - 2.0 * Self::MARGIN) / extent, left }
    }

    fn point(&self, p: (f64, f64, f64)) -> Point {
        let m = Self::MARGIN;
        Point::new(self.left + m + (p.0 - self.low.0) * self.scale, m + (p.1 - self.low.1) * self.scale)
    }
}

/// How brightly a screen triangle is lit: 0.25 + 0.75 × the cosine between its normal and the view
/// direction (two-sided). In view coordinates (x right, y down, depth away) the normal's depth
/// component is that cosine, up to the normal's length.
fn light([a, b, c]: [(f64, f64, f64); 3]) -> f64 {
    let (u, w) = ((b.0 - a.0, b.1 - a.1, b.2 - a.2), (c.0 - a.0, c.1 - a.1, c.2 - a.2));
    let normal = (u.1 * w.2 - u.2 * w.1, u.2 * w.0 - u.0 * w.2, u.0 * w.1 - u.1 * w.0);
    let length = (normal.0 * normal.0 + normal.1 * normal.1 + normal.2 * normal.2).sqrt().max(1e-300);
    0.25 + 0.75 * (normal.2 / length).abs()
}

/// A reconstructed surface or placed element meshes, shaded, over an optional grey backdrop (the
/// surface domain the elements sit on): triangles far to near (painter's order), each lit by the
/// cosine between its normal and the view direction (two-sided, flat shading).
fn draw_mesh_panel(
    svg: &mut SvgWriter,
    surface: &TriangleMesh,
    backdrop: Option<&TriangleMesh>,
    left: f64,
    size: f64,
    title: &str,
) {
    let mut mesh = surface.clone();
    let backdrop_triangles = backdrop.map_or(0, |b| b.triangles.len());
    if let Some(backdrop) = backdrop {
        let offset = mesh.vertices.len() as u32;
        mesh.vertices.extend_from_slice(&backdrop.vertices);
        mesh.triangles.extend(backdrop.triangles.iter().map(|t| t.map(|v| v + offset)));
    }
    let first_backdrop = mesh.triangles.len() - backdrop_triangles;
    let screen: Vec<(f64, f64, f64)> = mesh.vertices.iter().map(|&v| view(v)).collect();
    let fit = Fit::new(&screen, left, size);
    let depth = |t: &[u32; 3]| t.iter().map(|&v| screen[v as usize].2).sum::<f64>();
    let mut order: Vec<usize> = (0..mesh.triangles.len()).collect();
    order.sort_by(|&a, &b| depth(&mesh.triangles[b]).total_cmp(&depth(&mesh.triangles[a])).then(a.cmp(&b)));
    svg.rect(left, 0.0, size, size, None, Some([255, 255, 255, 255]));
    for t in order {
        let corners = mesh.triangles[t].map(|v| screen[v as usize]);
        let light = light(corners);
        let fill = if t >= first_backdrop {
            let grey = (120.0 + 110.0 * light) as u8;
            [grey, grey, grey, 255]
        } else if backdrop_triangles > 0 {
            // Elements on a grey surface: a warm colour that stands out from it.
            [(120.0 + 135.0 * light) as u8, (60.0 + 100.0 * light) as u8, (30.0 + 50.0 * light) as u8, 255]
        } else {
            [(90.0 + 140.0 * light) as u8, (110.0 + 120.0 * light) as u8, (150.0 + 90.0 * light) as u8, 255]
        };
        svg.polyline(&corners.map(|p| fit.point(p)), true, None, Some(fill));
    }
    svg.text(Point::new(left + 6.0, 12.0), 11.0, [90, 90, 90, 255], title);
}

/// Points on the surface domain they were synthesized on: the mesh flat-shaded in grey and every
/// point a disc in its colour, drawn together far to near (painter's order), so that the near
/// side of the mesh hides the points on its far side and the surface's shape reads. A point is
/// drawn half a mean edge nearer than it is, in front of the triangles around it.
fn draw_points_on_mesh(
    svg: &mut SvgWriter,
    (set, colours): (&PointSet, &[[u8; 4]]),
    mesh: &TriangleMesh,
    left: f64,
    size: f64,
    title: &str,
) {
    let screen: Vec<(f64, f64, f64)> = mesh.vertices.iter().map(|&v| view(v)).collect();
    let fit = Fit::new(&screen, left, size);
    let edge = |a: u32, b: u32| {
        let (p, q) = (mesh.vertices[a as usize], mesh.vertices[b as usize]);
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    let edges: f64 = mesh.triangles.iter().map(|t| edge(t[0], t[1]) + edge(t[1], t[2]) + edge(t[2], t[0])).sum();
    let lift = 0.5 * edges / (3 * mesh.triangles.len()).max(1) as f64;
    let points = project(set);
    // Far to near: (depth, triangle or point index, is a point).
    let mut items: Vec<(f64, usize, bool)> = mesh
        .triangles
        .iter()
        .enumerate()
        .map(|(t, triangle)| (triangle.iter().map(|&v| screen[v as usize].2).sum::<f64>() / 3.0, t, false))
        .chain(points.iter().enumerate().map(|(i, p)| (p.2 - lift, i, true)))
        .collect();
    items.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.2.cmp(&b.2)).then(a.1.cmp(&b.1)));
    let side = (size - 2.0 * Fit::MARGIN) / fit.scale;
    let radius = (0.3 * (side * side / set.len().max(1) as f64).sqrt() * fit.scale).clamp(1.0, 6.0);
    svg.rect(left, 0.0, size, size, None, Some([255, 255, 255, 255]));
    for (_, index, is_point) in items {
        if is_point {
            svg.circle(fit.point(points[index]), radius, None, Some(colours[index]));
            continue;
        }
        let corners = mesh.triangles[index].map(|v| screen[v as usize]);
        let grey = (110.0 + 130.0 * light(corners)) as u8;
        svg.polyline(&corners.map(|p| fit.point(p)), true, None, Some([grey, grey, grey, 255]));
    }
    svg.text(Point::new(left + 6.0, 12.0), 11.0, [90, 90, 90, 255], title);
}

fn draw_panel(svg: &mut SvgWriter, set: &PointSet, colours: &[[u8; 4]], left: f64, size: f64, title: &str) {
    let projected = project(set);
    let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    let (mut d0, mut d1) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y, d) in &projected {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
        d0 = d0.min(d);
        d1 = d1.max(d);
    }
    let extent = (x1 - x0).max(y1 - y0).max(1e-9);
    let margin = 16.0;
    let scale = (size - 2.0 * margin) / extent;
    let spacing = (extent * extent / set.len().max(1) as f64).sqrt();
    let radius = (0.3 * spacing * scale).clamp(1.0, 8.0);
    let mut order: Vec<usize> = (0..projected.len()).collect();
    // Far points first (painter's order); 2D points all have the same depth.
    order.sort_by(|&a, &b| projected[b].2.total_cmp(&projected[a].2).then(a.cmp(&b)));
    svg.rect(left, 0.0, size, size, None, Some([255, 255, 255, 255]));
    for i in order {
        let (x, y, d) = projected[i];
        let shade = if set.dimension == 3 { 1.0 - 0.5 * (d - d0) / (d1 - d0).max(1e-12) } else { 1.0 };
        let c = colours[i];
        let fill = [(c[0] as f64 * shade) as u8, (c[1] as f64 * shade) as u8, (c[2] as f64 * shade) as u8, 255];
        let centre = Point::new(left + margin + (x - x0) * scale, margin + (y - y0) * scale);
        svg.circle(centre, radius, None, Some(fill));
    }
    svg.text(Point::new(left + 6.0, 12.0), 11.0, [90, 90, 90, 255], title);
}

/// One plot of the statistics panel: curves of the exemplar (black) and the output (orange) over
/// `[0, 4)` spacings, in the box `(left, top, width, height)`.
fn draw_curves(
    svg: &mut SvgWriter,
    (left, top, width, height): (f64, f64, f64, f64),
    curves: [&[f64]; 2],
    title: &str,
) {
    svg.rect(left, top, width, height, Some(StrokePaint { width: 1.0, colour: [200, 200, 200, 255] }), None);
    let peak = curves.iter().flat_map(|c| c.iter()).copied().fold(1e-12, f64::max) * 1.1;
    for (curve, colour) in curves.iter().zip([[30, 30, 30, 255], [230, 120, 20, 255]]) {
        let points: Vec<Point> = curve
            .iter()
            .enumerate()
            .map(|(b, v)| {
                let x = left + (b as f64 + 0.5) / curve.len() as f64 * width;
                Point::new(x, top + height - v / peak * height)
            })
            .collect();
        svg.polyline(&points, false, Some(StrokePaint { width: 1.5, colour }), None);
    }
    svg.text(Point::new(left + 4.0, top + 12.0), 10.0, [90, 90, 90, 255], title);
}

/// The statistics panel: g(r) and the nearest-neighbour histogram of exemplar and output, and the
/// figures against both baselines.
fn draw_statistics(svg: &mut SvgWriter, fidelity: &Fidelity, left: f64, size: f64) {
    svg.rect(left, 0.0, size, size, None, Some([255, 255, 255, 255]));
    let (e, o) = (&fidelity.exemplar_statistics, &fidelity.output_statistics);
    let plot = (left + 10.0, 24.0, size - 20.0, 0.5 * size - 60.0);
    draw_curves(svg, plot, [&e.radial_distribution, &o.radial_distribution], "g(r), r in 0–4 spacings");
    let plot = (left + 10.0, 0.5 * size - 20.0, size - 20.0, 0.5 * size - 60.0);
    draw_curves(svg, plot, [&e.nearest_histogram, &o.nearest_histogram], "nearest-neighbour distances, 0–4 spacings");
    let lines = [
        "black: exemplar, orange: output".to_string(),
        format!("density {:.0} % of the exemplar's", 100.0 * fidelity.density_ratio),
        format!(
            "NN distance {:.3} (random {:.3}, tiled copy {:.3})",
            fidelity.output.nearest_neighbour, fidelity.random.nearest_neighbour, fidelity.tiled.nearest_neighbour
        ),
        format!(
            "g(r) distance {:.3} (random {:.3}, tiled copy {:.3})",
            fidelity.output.radial_distribution,
            fidelity.random.radial_distribution,
            fidelity.tiled.radial_distribution
        ),
    ];
    for (row, line) in lines.iter().enumerate() {
        svg.text(Point::new(left + 10.0, size - 64.0 + 16.0 * row as f64), 11.0, [60, 60, 60, 255], line);
    }
}

/// The preview image's SVG (rendered at scale 1): exemplar and output side by side, then their
/// statistics. The output is drawn as `surface` (a reconstructed surface or placed elements, on
/// `backdrop`) when given, else as points on `domain_mesh` (a surface domain), else as points.
pub(super) fn preview_svg(
    exemplar: &PointSet,
    output: &PointSet,
    fidelity: &Fidelity,
    colour_by: Option<&str>,
    surface: Option<&TriangleMesh>,
    backdrop: Option<&TriangleMesh>,
    domain_mesh: Option<&TriangleMesh>,
) -> anyhow::Result<String> {
    let size = 420.0;
    let mut svg = SvgWriter::new(3.0 * size + 20.0, size);
    let (exemplar_colours, range) = colours(exemplar, colour_by, None)?;
    let (output_colours, _) = colours(output, colour_by, range)?;
    draw_panel(&mut svg, exemplar, &exemplar_colours, 0.0, size, &format!("exemplar ({} points)", exemplar.len()));
    match surface {
        Some(mesh) => {
            let title = format!("output surface ({} points, {} triangles)", output.len(), mesh.triangles.len());
            draw_mesh_panel(&mut svg, mesh, backdrop, size + 10.0, size, &title);
        }
        None => match domain_mesh {
            Some(mesh) => {
                let title = format!("output ({} points on {} triangles)", output.len(), mesh.triangles.len());
                draw_points_on_mesh(&mut svg, (output, &output_colours), mesh, size + 10.0, size, &title);
            }
            None => {
                let title = format!("output ({} points)", output.len());
                draw_panel(&mut svg, output, &output_colours, size + 10.0, size, &title);
            }
        },
    }
    draw_statistics(&mut svg, fidelity, 2.0 * size + 20.0, size);
    Ok(svg.finish())
}
