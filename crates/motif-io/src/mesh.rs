//! Triangle meshes: OBJ (through `tobj`) and PLY (through `ply-rs-bw`), polygons fanned into
//! triangles.

use std::path::Path;

use motif_core::TriangleMesh;
use ply_rs_bw::ply::{DefaultElement, Property};

use crate::{IoError, Result};

/// The most vertices or triangles read (a guard against absurd files).
const MAX_ELEMENTS: usize = 50_000_000;

/// Reads an OBJ or PLY mesh (by extension); fails on anything else, and on files without
/// triangles.
pub fn read_mesh(path: &Path) -> Result<TriangleMesh> {
    let bytes = crate::read_bytes(path)?;
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let mesh = match extension.as_deref() {
        Some("obj") => parse_obj(&bytes, path)?,
        Some("ply") => parse_ply_mesh(&bytes, path)?,
        _ => return Err(IoError::format(path, "is not a mesh file: expected an .obj or .ply file")),
    };
    if mesh.triangles.is_empty() {
        return Err(IoError::format(path, "the mesh has no faces (a volume or surface needs triangles)"));
    }
    Ok(mesh)
}

fn parse_obj(bytes: &[u8], path: &Path) -> Result<TriangleMesh> {
    // Point and line records are not faces: left out rather than turned into flat triangles.
    let options = tobj::LoadOptions { triangulate: true, single_index: false, ignore_points: true, ignore_lines: true };
    // Materials are not needed: a missing .mtl is not an error.
    let (models, _) =
        tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|error| IoError::format(path, format!("is not a valid OBJ file: {error}")))?;
    let mut mesh = TriangleMesh::default();
    for model in models {
        let offset = mesh.vertices.len();
        let positions = &model.mesh.positions;
        if offset + positions.len() / 3 > MAX_ELEMENTS {
            return Err(IoError::format(path, format!("has more than {MAX_ELEMENTS} vertices")));
        }
        mesh.vertices.extend(positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        for face in model.mesh.indices.chunks_exact(3) {
            let index = |i: u32| -> Result<u32> {
                u32::try_from(offset + i as usize).map_err(|_| IoError::format(path, "has too many vertices"))
            };
            mesh.triangles.push([index(face[0])?, index(face[1])?, index(face[2])?]);
        }
        if mesh.triangles.len() > MAX_ELEMENTS {
            return Err(IoError::format(path, format!("has more than {MAX_ELEMENTS} triangles")));
        }
    }
    Ok(weld(mesh))
}

/// Writes a mesh as OBJ text (`v` and `f` records, 1-based indices), atomically.
pub fn write_obj(path: &Path, mesh: &TriangleMesh, comment: &str) -> Result<()> {
    use std::fmt::Write as _;
    let mut text = String::with_capacity(32 * (mesh.vertices.len() + mesh.triangles.len()) + 64);
    for line in comment.lines() {
        let _ = writeln!(text, "# {line}");
    }
    for v in &mesh.vertices {
        let _ = writeln!(text, "v {} {} {}", v[0], v[1], v[2]);
    }
    for t in &mesh.triangles {
        let _ = writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    crate::write_text(path, &text)
}

/// Merges vertices at bit-identical positions: `tobj` gives every object, group and material
/// section of an OBJ file its own copy of the vertices it uses, so a closed surface split into
/// sections would otherwise look open along the section borders.
fn weld(mesh: TriangleMesh) -> TriangleMesh {
    let mut first: std::collections::BTreeMap<[u64; 3], u32> = std::collections::BTreeMap::new();
    let mut vertices = Vec::new();
    let remap: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|v| {
            *first.entry(v.map(f64::to_bits)).or_insert_with(|| {
                vertices.push(*v);
                (vertices.len() - 1) as u32
            })
        })
        .collect();
    let triangles = mesh.triangles.iter().map(|t| t.map(|i| remap[i as usize])).collect();
    TriangleMesh { vertices, triangles }
}

fn parse_ply_mesh(bytes: &[u8], path: &Path) -> Result<TriangleMesh> {
    let parser = ply_rs_bw::parser::Parser::<DefaultElement>::new();
    let ply = parser
        .read_ply(&mut std::io::Cursor::new(bytes))
        .map_err(|error| IoError::format(path, format!("is not a valid PLY file: {error}")))?;
    let number = |property: Option<&Property>| -> Option<f64> {
        Some(match property? {
            Property::Float(v) => f64::from(*v),
            Property::Double(v) => *v,
            Property::Int(v) => f64::from(*v),
            Property::UInt(v) => f64::from(*v),
            Property::Short(v) => f64::from(*v),
            Property::UShort(v) => f64::from(*v),
            Property::Char(v) => f64::from(*v),
            Property::UChar(v) => f64::from(*v),
            _ => return None,
        })
    };
    let mut mesh = TriangleMesh::default();
    for (index, vertex) in ply.payload.get("vertex").map(Vec::as_slice).unwrap_or(&[]).iter().enumerate() {
        let coordinate = |name: &str| {
            number(vertex.get(name))
                .ok_or_else(|| IoError::format(path, format!("vertex {index} has no numeric `{name}` property")))
        };
        mesh.vertices.push([coordinate("x")?, coordinate("y")?, coordinate("z")?]);
    }
    let count = mesh.vertices.len();
    for (index, face) in ply.payload.get("face").map(Vec::as_slice).unwrap_or(&[]).iter().enumerate() {
        let list: Vec<i64> = match face.get("vertex_indices").or_else(|| face.get("vertex_index")) {
            Some(Property::ListInt(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            Some(Property::ListUInt(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            Some(Property::ListShort(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            Some(Property::ListUShort(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            Some(Property::ListUChar(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            Some(Property::ListChar(v)) => v.iter().map(|&i| i64::from(i)).collect(),
            _ => return Err(IoError::format(path, format!("face {index} has no `vertex_indices` list"))),
        };
        if list.len() < 3 {
            return Err(IoError::format(path, format!("face {index} has {} vertices (at least 3)", list.len())));
        }
        let checked = |i: i64| -> Result<u32> {
            if i < 0 || i as usize >= count {
                return Err(IoError::format(path, format!("face {index} refers to vertex {i} of {count}")));
            }
            Ok(i as u32)
        };
        for k in 1..list.len() - 1 {
            mesh.triangles.push([checked(list[0])?, checked(list[k])?, checked(list[k + 1])?]);
        }
        if mesh.triangles.len() > MAX_ELEMENTS {
            return Err(IoError::format(path, format!("has more than {MAX_ELEMENTS} triangles")));
        }
    }
    Ok(weld(mesh))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_and_ply_give_the_same_triangles() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("quad.obj");
        std::fs::write(&obj, "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        let ply = dir.path().join("quad.ply");
        std::fs::write(
            &ply,
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
        )
        .unwrap();
        let (a, b) = (read_mesh(&obj).unwrap(), read_mesh(&ply).unwrap());
        assert_eq!(a.vertices, b.vertices);
        assert_eq!(a.triangles.len(), 2);
        assert_eq!(b.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn sections_of_an_obj_share_their_vertices_and_lines_are_not_faces() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("two.obj");
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no first\nf 1 2 3\no second\nusemtl red\nf 1 3 4\nl 1 2\np 3\n";
        std::fs::write(&obj, text).unwrap();
        let mesh = read_mesh(&obj).unwrap();
        assert_eq!(mesh.vertices.len(), 4);
        assert_eq!(mesh.triangles.len(), 2);
        let shared: Vec<u32> = mesh.triangles[0].iter().filter(|v| mesh.triangles[1].contains(v)).copied().collect();
        assert_eq!(shared.len(), 2, "{mesh:?}");
    }

    #[test]
    fn written_obj_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = TriangleMesh {
            vertices: vec![[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, 2.25, -1.0]],
            triangles: vec![[0, 1, 2]],
        };
        let path = dir.path().join("out.obj");
        write_obj(&path, &mesh, "a test").unwrap();
        assert_eq!(read_mesh(&path).unwrap(), mesh);
    }

    #[test]
    fn bad_mesh_files_name_the_file_and_the_problem() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            ("points.obj", "v 0 0 0\nv 1 0 0\n", "no faces"),
            (
                "bad.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n3 0 1 2\n",
                "refers to vertex",
            ),
            ("mesh.stl", "solid", "expected an .obj or .ply"),
            ("garbage.ply", "not a ply", "not a valid PLY"),
        ];
        for (name, text, message) in cases {
            let path = dir.path().join(name);
            std::fs::write(&path, text).unwrap();
            let error = read_mesh(&path).unwrap_err().to_string();
            assert!(error.contains(name) && error.contains(message), "{name}: {error}");
        }
    }
}
