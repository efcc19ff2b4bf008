//! `motif points`: repetitive structure synthesis from point samples in 2D and 3D (Roveri et al.
//! 2015), wired to PLY/CSV point files, SVG regions and strokes, JSON polylines and PNG previews.

mod bench;
mod corpus;
mod demo;
mod meshes;
mod preview;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use clap::Args;
use motif_core::{Polygon, Polyline};
use motif_io::{ColumnKind, PointFormat, PointTable};
use motif_jobs::Job;
use motif_jobs::points::{
    DOMAIN_SYNTAX, DomainArgument, DomainSpec, FieldMaps, Output, PointSet, PointsInputs, PointsJob, PointsOptions,
    StrokeSpec, SurfaceSpec, parse_scale_along,
};
use serde_json::Value;

use crate::context::Context;
use crate::gallery::Demo;
use crate::job_args::JobArgs;

/// Options of `motif points`.
#[derive(Args, Debug)]
pub struct PointsArgs {
    /// Exemplar points: PLY (ascii or binary) or CSV with columns x, y [, z], an optional integer
    /// `element` column (points sharing an id form a rigid element) and any float attributes.
    #[arg(long, value_name = "EX.ply")]
    pub exemplar: PathBuf,
    /// Output domain: `box:W,H` (2D) or `box:W,H,D` (3D) from the origin, an SVG file whose first
    /// path's outline is the region (2D), `volume:MESH.obj|ply`, the inside of a closed triangle
    /// mesh (3D; non-manifold meshes are fine, open ones are refused), or `surface:MESH.obj|ply`,
    /// the surface of a mesh (open or closed) for a 2D exemplar: the output is 3D, every point on
    /// the mesh, the exemplar's plane laid on the tangent planes (see --surface-directions).
    #[arg(
        long,
        value_name = "box:W,H[,D]|REGION.svg|volume:MESH.obj|surface:MESH.obj",
        required_unless_present = "along",
        conflicts_with = "along"
    )]
    pub domain: Option<String>,
    /// Brush stroke: an SVG path (2D; its first subpath) or a JSON polyline `[[x,y(,z)],...]`
    /// (2D or 3D). The exemplar's x axis follows the stroke's tangent.
    #[arg(long, value_name = "PATH.svg|PATH.json")]
    pub along: Option<PathBuf>,
    /// Brush width (output units, > 0) for --along: the tube of this diameter around the stroke is
    /// filled.
    #[arg(long, value_name = "W", requires = "along")]
    pub brush_width: Option<f64>,
    /// Exemplar scale at the start and end of the stroke, varying linearly along it (each > 0).
    #[arg(long, value_name = "A,B", requires = "along")]
    pub scale_along: Option<String>,
    /// Every option of the synthesis, declared in `motif_jobs::points::PointsOptions`.
    #[command(flatten)]
    pub options: JobArgs<PointsOptions>,
    /// Progressive synthesis: a previous result (PLY/CSV) to extend. Its points stay fixed except
    /// within --keep-margin of the new domain.
    #[arg(long, value_name = "PREVIOUS.ply")]
    pub existing: Option<PathBuf>,
    /// Also reconstruct the output as a surface (3D points with normals `nx`, `ny`, `nz`): an
    /// implicit MLS surface polygonized with surface nets, written as OBJ.
    #[arg(long, value_name = "OUT.obj")]
    pub surface_out: Option<PathBuf>,
    /// Discrete elements as meshes: with --surface-out, writes one copy of this mesh (OBJ or PLY)
    /// per output element (per point, or per `element` id) instead of a reconstruction, standing
    /// on the point (the middle of its bounding box in x and y, its lowest z, go to the point)
    /// with the frame there: the mesh's x, y, z axes go to the exemplar's axes at that point (on a
    /// surface: the direction field, its cross product with the normal, the normal).
    #[arg(long, value_name = "ELEMENT.obj", requires = "surface_out")]
    pub element_mesh: Option<PathBuf>,
    /// The element mesh's largest side, in exemplar units (> 0; default: the exemplar's mean
    /// nearest-neighbour spacing); scale fields multiply it.
    #[arg(long, value_name = "S", requires = "element_mesh")]
    pub element_size: Option<f64>,
    /// On a surface domain, where the exemplar's x axis points: `curvature` (default: the
    /// principal direction of least curvature, a cylinder's axis; where the surface bends the same
    /// way in every direction it fades into the world x axis, projected), `X,Y,Z` (one direction,
    /// projected on each tangent plane), or a CSV/PLY file of vectors `x,y,z`, one per mesh vertex
    /// in the mesh's order, interpolated across each triangle.
    #[arg(long, value_name = "curvature|X,Y,Z|VECTORS.csv", requires = "domain")]
    pub surface_directions: Option<String>,
    /// Rotation field painted as an image (2D), stretched over the domain's bounding box (same
    /// aspect ratio): 360° × grey (black and white 0°, mid-grey 180°), added to --rotation.
    #[arg(long, value_name = "MAP.png")]
    pub rotation_map: Option<PathBuf>,
    /// Scale field painted as an image (2D), over the domain's bounding box: 2^(2·grey − 1)
    /// (black 0.5, mid-grey 1, white 2), times --scale.
    #[arg(long, value_name = "MAP.png")]
    pub scale_map: Option<PathBuf>,
    /// Output points (PLY binary unless the name ends in .csv).
    #[arg(long, value_name = "OUT.ply")]
    pub out: PathBuf,
    /// Write PLY as ascii instead of binary.
    #[arg(long)]
    pub ascii: bool,
    /// Preview PNG: exemplar (left) and output (right); 2D as discs, 3D as an orthographic view.
    #[arg(long, value_name = "OUT.png")]
    pub preview: Option<PathBuf>,
    /// Attribute that colours the preview (default: red/green/blue columns if present, else the
    /// first attribute, else element ids).
    #[arg(long, value_name = "NAME")]
    pub colour_by: Option<String>,
}

/// Converts a point table into a point set (see `motif_jobs::columns`); integer columns other
/// than `element` are attributes that are always discrete (returned second).
pub(crate) fn table_to_points(table: &PointTable, what: &str) -> anyhow::Result<(PointSet, Vec<String>)> {
    let columns: Vec<motif_jobs::columns::Column> = table
        .columns
        .iter()
        .enumerate()
        .map(|(c, column)| motif_jobs::columns::Column {
            name: column.name.clone(),
            integer: column.kind == ColumnKind::Int,
            values: (0..table.rows).map(|row| table.row(row)[c]).collect(),
        })
        .collect();
    Ok(motif_jobs::columns::point_set(&columns, what)?)
}

/// Converts a point set into a point table (attributes listed in `integer` are written as ints).
pub(crate) fn points_to_table(set: &PointSet, integer: &[String]) -> PointTable {
    let columns = motif_jobs::columns::columns(set, integer);
    let rows = set.len();
    let values = (0..rows).flat_map(|row| columns.iter().map(move |column| column.values[row])).collect();
    let columns = columns
        .iter()
        .map(|column| motif_io::Column {
            name: column.name.clone(),
            kind: if column.integer { ColumnKind::Int } else { ColumnKind::Float },
        })
        .collect();
    PointTable { columns, rows, values }
}

fn read_polygon(path: &Path) -> anyhow::Result<Vec<[f64; 2]>> {
    let document = motif_io::read_svg(path)?;
    let first = &document.paths[0];
    let polylines = Polyline::from_bez_path(&first.path, 0.05)
        .with_context(|| format!("{}: cannot flatten the first path", path.display()))?;
    let outline =
        polylines.into_iter().next().with_context(|| format!("{}: the first path is empty", path.display()))?;
    // Checked here too, so the error names the file.
    Polygon::new(outline.points().to_vec())
        .with_context(|| format!("{}: the region is not a usable polygon", path.display()))?;
    Ok(outline.points().iter().map(|p| [p.x, p.y]).collect())
}

fn read_stroke_points(path: &Path) -> anyhow::Result<Vec<Vec<f64>>> {
    let is_json = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_json {
        let value: Value = motif_io::read_json(path)?;
        let list = match &value {
            Value::Array(_) => &value,
            Value::Object(map) => map
                .get("points")
                .with_context(|| format!("{}: expected a list of points or {{\"points\": [...]}}", path.display()))?,
            _ => bail!("{}: expected a list of points [[x, y(, z)], ...]", path.display()),
        };
        let points: Vec<Vec<f64>> = serde_json::from_value(list.clone())
            .with_context(|| format!("{}: expected a list of points [[x, y(, z)], ...]", path.display()))?;
        return Ok(points);
    }
    let document = motif_io::read_svg(path)?;
    let polylines = Polyline::from_bez_path(&document.paths[0].path, 0.05)
        .with_context(|| format!("{}: cannot flatten the first path", path.display()))?;
    let line = polylines.into_iter().next().with_context(|| format!("{}: the first path is empty", path.display()))?;
    Ok(line.points().iter().map(|p| vec![p.x, p.y]).collect())
}

/// Reads a point file into a point set.
fn read_set(path: &Path, what: &str) -> anyhow::Result<(PointSet, Vec<String>)> {
    let table = motif_io::read_points(path)?;
    table_to_points(&table, what).with_context(|| format!("{}", path.display()))
}

/// The job the arguments describe, with the domain's files read (`motif_jobs::points` turns it
/// into engine parameters, as it does for every front end).
fn job_of(args: &PointsArgs, seed: u64) -> anyhow::Result<PointsJob> {
    let domain = if let Some(along) = &args.along {
        let Some(width) = args.brush_width else { bail!("--along needs --brush-width W") };
        let scale_along = args.scale_along.as_deref().map(parse_scale_along).transpose()?;
        DomainSpec::Stroke(StrokeSpec { points: read_stroke_points(along)?, width, scale_along })
    } else {
        let argument: Option<DomainArgument> = args.domain.as_deref().map(str::parse).transpose()?;
        if args.surface_directions.is_some() && !argument.as_ref().is_some_and(DomainArgument::is_surface) {
            bail!("--surface-directions needs --domain surface:MESH.obj");
        }
        match argument {
            Some(DomainArgument::Box(sizes)) => DomainSpec::Box(sizes),
            Some(DomainArgument::Volume(file)) => {
                let domain = DomainSpec::Volume(motif_io::read_mesh(&file)?);
                domain.check_mesh().with_context(|| format!("--domain volume:{}", file.display()))?;
                domain
            }
            Some(DomainArgument::Surface(file)) => {
                let mesh = motif_io::read_mesh(&file)?;
                let directions = meshes::surface_directions(args.surface_directions.as_deref())?;
                let domain = DomainSpec::Surface(SurfaceSpec { mesh, directions });
                domain.check_mesh().with_context(|| {
                    let field = args.surface_directions.as_deref().map(|d| format!(" with --surface-directions {d}"));
                    format!("--domain surface:{}{}", file.display(), field.unwrap_or_default())
                })?;
                domain
            }
            Some(DomainArgument::Region(file)) => DomainSpec::Region(read_polygon(&file)?),
            None => bail!("give --domain {DOMAIN_SYNTAX}, or --along PATH with --brush-width"),
        }
    };
    Ok(PointsJob { seed, options: args.options.options.clone(), ..PointsJob::with_domain(domain) })
}

/// Runs `motif points`.
pub(crate) fn run(args: &PointsArgs, context: &mut Context) -> anyhow::Result<()> {
    let inputs = input_paths(args);
    context.check_output(&args.out, &inputs)?;
    for extra in args.preview.iter().chain(&args.surface_out) {
        context.check_output(extra, &inputs)?;
    }
    let (exemplar, integer) = read_set(&args.exemplar, "exemplar")?;
    let element = read_element_mesh(args)?;
    check_surface_out(args, &exemplar, element.is_some())?;
    let existing = match &args.existing {
        Some(path) => Some(read_set(path, "existing points")?.0),
        None => None,
    };
    let job = PointsJob { max_memory: Some(context.max_memory), ..job_of(args, context.seed)? };
    let shown_exemplar = args.preview.as_ref().map(|_| exemplar.clone());
    let maps =
        FieldMaps { rotation: read_map(&args.rotation_map, context)?, scale: read_map(&args.scale_map, context)? };
    // Checked here so that the error names the files.
    let mut checked = job.params(exemplar.dimension, &integer)?;
    maps.apply(&job.engine_domain()?, exemplar.dimension, &mut checked).with_context(|| {
        let files: Vec<String> = [("--rotation-map", &args.rotation_map), ("--scale-map", &args.scale_map)]
            .iter()
            .filter_map(|(flag, file)| file.as_ref().map(|f| format!("{flag} {}", f.display())))
            .collect();
        files.join(", ")
    })?;
    let run = job.run(PointsInputs { exemplar, existing, integer_columns: &integer, maps }, context.progress())?;
    let output = run.output;
    let format = match PointFormat::from_path(&args.out) {
        PointFormat::PlyBinary if args.ascii => PointFormat::PlyAscii,
        format => format,
    };
    motif_io::write_points(&args.out, &points_to_table(&output.points, &integer), format)?;
    let surface = write_surface(args, &output, element.as_ref())?;
    if let (Some(preview), Some(exemplar)) = (&args.preview, &shown_exemplar) {
        // Elements are drawn on the surface they were placed on.
        let domain_mesh = match &job.domain {
            DomainSpec::Surface(spec) => Some(&spec.mesh),
            _ => None,
        };
        let backdrop = element.as_ref().and(domain_mesh);
        let svg = preview::preview_svg(
            exemplar,
            &output.points,
            &output.report.fidelity,
            args.colour_by.as_deref(),
            surface.as_ref(),
            backdrop,
            domain_mesh,
        )?;
        context.check_render(output.report.estimated_memory_bytes, &svg, 1.0)?;
        let image = motif_io::render_svg(&svg, 1.0, Path::new("preview"))?;
        motif_io::write_png(preview, &image)?;
    }
    context.job_figures(run.figures);
    context.summary(&summary(&output));
    Ok(())
}

/// Every file `args` reads (exemplar, existing points, stroke, domain file, direction and maps,
/// element mesh), for the output checks.
fn input_paths(args: &PointsArgs) -> Vec<&Path> {
    let mut inputs: Vec<&Path> = vec![&args.exemplar];
    if let Some(existing) = &args.existing {
        inputs.push(existing);
    }
    inputs.extend(args.along.as_deref());
    // A domain that is not a box is a region SVG, an input too.
    let region = args.domain.as_deref().filter(|domain| !domain.starts_with("box:")).map(|domain| {
        Path::new(domain.strip_prefix("volume:").or_else(|| domain.strip_prefix("surface:")).unwrap_or(domain))
    });
    inputs.extend(region);
    let directions_file =
        args.surface_directions.as_deref().filter(|d| *d != "curvature" && !d.contains(',')).map(Path::new);
    inputs.extend(directions_file);
    inputs.extend(args.rotation_map.as_deref());
    inputs.extend(args.scale_map.as_deref());
    inputs.extend(args.element_mesh.as_deref());
    inputs
}

/// The columns of the normals nx, ny, nz in `set`, if it has them.
fn normal_columns(set: &PointSet) -> Option<[usize; 3]> {
    let find = |name: &str| set.attribute_names.iter().position(|n| n == name);
    Some([find("nx")?, find("ny")?, find("nz")?])
}

/// `--element-mesh` with its anchor (the base's middle) moved to the origin, and its largest side.
fn read_element_mesh(args: &PointsArgs) -> anyhow::Result<Option<(motif_core::TriangleMesh, f64)>> {
    let Some(path) = &args.element_mesh else { return Ok(None) };
    if let Some(size) = args.element_size
        && !(size.is_finite() && size > 0.0)
    {
        bail!("--element-size {size}: give a size > 0 (exemplar units)");
    }
    let mut mesh = motif_io::read_mesh(path)?;
    let Some((low, high)) = mesh.bounds() else {
        bail!("--element-mesh {}: the mesh has no triangles", path.display())
    };
    let side = (0..3).map(|a| high[a] - low[a]).fold(0.0, f64::max);
    if !(side > 0.0 && side.is_finite()) {
        bail!("--element-mesh {}: the mesh has no extent", path.display());
    }
    // The anchor that goes to each point: the base's middle.
    let anchor = [0.5 * (low[0] + high[0]), 0.5 * (low[1] + high[1]), low[2]];
    mesh.vertices.iter_mut().for_each(|v| *v = std::array::from_fn(|a| v[a] - anchor[a]));
    Ok(Some((mesh, side)))
}

/// Without element meshes, `--surface-out` reconstructs from normals: the exemplar must be 3D with
/// nx, ny, nz, and `--attributes` must keep them.
fn check_surface_out(args: &PointsArgs, exemplar: &PointSet, has_element: bool) -> anyhow::Result<()> {
    if args.surface_out.is_some() && !has_element && (exemplar.dimension != 3 || normal_columns(exemplar).is_none()) {
        bail!(
            "--surface-out needs a 3D exemplar with normals (attributes nx, ny, nz); {} is {}D with attributes [{}]",
            args.exemplar.display(),
            exemplar.dimension,
            exemplar.attribute_names.join(", ")
        );
    }
    if let (Some(_), false, Some(chosen)) = (&args.surface_out, has_element, &args.options.attributes)
        && let Some(missing) = ["nx", "ny", "nz"].iter().find(|name| !chosen.iter().any(|c| c == *name))
    {
        bail!(
            "--surface-out needs the normals nx, ny, nz among the synthesized attributes, but --attributes {} leaves \
             out {missing}: add nx,ny,nz to --attributes or drop --surface-out",
            chosen.join(",")
        );
    }
    Ok(())
}

/// A rotation or scale map image, read within the run's memory budget.
fn read_map(file: &Option<PathBuf>, context: &Context) -> anyhow::Result<Option<motif_core::ToneMap>> {
    let budget = motif_io::ImageBudget::map(context.max_memory);
    file.as_deref()
        .map(|file| Ok(motif_core::ToneMap::from_image(&motif_io::read_image_within(file, budget)?)))
        .transpose()
}

/// Writes `--surface-out`: the element meshes placed on the points, or else a surface reconstructed
/// from their normals. Returns the mesh written.
fn write_surface(
    args: &PointsArgs,
    output: &Output,
    element: Option<&(motif_core::TriangleMesh, f64)>,
) -> anyhow::Result<Option<motif_core::TriangleMesh>> {
    let Some(path) = &args.surface_out else { return Ok(None) };
    if let Some((mesh, side)) = element {
        let placed = meshes::place_elements(output, mesh, *side, args.element_size)
            .with_context(|| format!("--element-mesh {}", args.element_mesh.as_deref().unwrap_or(path).display()))?;
        motif_io::write_obj(path, &placed, "element meshes placed by motif points")?;
        return Ok(Some(placed));
    }
    let Some(columns) = normal_columns(&output.points) else {
        bail!("--surface-out {}: the synthesized points have no normals (nx, ny, nz)", path.display());
    };
    let positions: Vec<[f64; 3]> =
        (0..output.points.len()).map(|i| std::array::from_fn(|a| output.points.position(i)[a])).collect();
    let normals: Vec<[f64; 3]> =
        (0..output.points.len()).map(|i| columns.map(|c| output.points.attributes_of(i)[c])).collect();
    let mesh = motif_jobs::points::reconstruct_surface(&positions, &normals)
        .with_context(|| format!("cannot reconstruct a surface for {}", path.display()))?;
    motif_io::write_obj(path, &mesh, "surface reconstructed by motif points (implicit MLS, surface nets)")?;
    Ok(Some(mesh))
}

/// The run's summary line: counts, final energy and fidelity against the random and tiled baselines.
fn summary(output: &Output) -> String {
    format!(
        "motif points: {} points ({} added, {} removed; density {:.0} % of the exemplar's), T = {:.4}, \
         nearest-neighbour distance {:.3} (random {:.3}, tiled {:.3}), g(r) distance {:.3} (random {:.3}, tiled {:.3})",
        output.points.len(),
        output.report.added,
        output.report.removed,
        100.0 * output.report.fidelity.density_ratio,
        output.report.final_energy,
        output.report.fidelity.output.nearest_neighbour,
        output.report.fidelity.random.nearest_neighbour,
        output.report.fidelity.tiled.nearest_neighbour,
        output.report.fidelity.output.radial_distribution,
        output.report.fidelity.random.radial_distribution,
        output.report.fidelity.tiled.radial_distribution,
    )
}

/// The points engine in the registry.
pub(crate) struct Points;

impl crate::registry::Engine for Points {
    fn name(&self) -> &'static str {
        "points"
    }

    fn demo(&self, gallery: &mut Demo<'_>) -> anyhow::Result<()> {
        demo::demo(gallery)
    }

    fn bench(&self, bench: &crate::suite::Bench) -> anyhow::Result<serde_json::Value> {
        bench::bench(bench)
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;
    use motif_points::Refinement;

    use super::*;

    #[derive(Parser)]
    struct Command {
        #[command(flatten)]
        args: PointsArgs,
    }

    /// The job a `motif points` command line with these extra flags describes.
    fn job(extra: &[&str], seed: u64) -> PointsJob {
        let base =
            ["points", "--exemplar", "ex.csv", "--neighbourhood", "1.5", "--domain", "box:10,8", "--out", "out.ply"];
        let command = Command::parse_from(base.iter().chain(extra));
        job_of(&command.args, seed).unwrap()
    }

    /// The command line's defaults are the job's (and so the engine's): a run from the CLI and one
    /// from any other front end with the same options get the same parameters.
    #[test]
    fn command_line_defaults_are_the_jobs() {
        let plain = PointsJob::new(1.5, DomainSpec::Box(vec![10.0, 8.0]));
        // Params hold closures (fields), so they are compared as printed.
        let printed = |job: &PointsJob| format!("{:?}", job.params(2, &[]).unwrap());
        assert_eq!(printed(&job(&[], 1)), printed(&plain));
        let extra = ["--refine", "none", "--patch-candidates", "3", "--attribute-weight", "dbh=0.5"];
        let params = job(&extra, 4).params(2, &[]).unwrap();
        assert_eq!(params.refinement, Refinement::None);
        assert_eq!(params.patch_candidates, 3);
        assert_eq!(params.attribute_weights, vec![("dbh".to_string(), 0.5)]);
        assert_eq!(params.seed, 4);
    }
}
