//! The only motif crate that touches files.
//!
//! Engines are pure; everything that reads or writes a file goes through here, so that every error
//! names its file and every write is atomic (a temporary file in the target's directory, then a
//! rename, so a crash never leaves a half-written output and an output never replaces an input by
//! accident halfway).
//!
//! - `staging`: the temporary files, the renames that wait until a run has succeeded and then
//!   happen all together or not at all ([`begin_outputs`], [`commit_outputs`],
//!   [`discard_outputs`]), the folders made for outputs ([`create_folder`]), the check that a
//!   folder takes files ([`check_folder_writable`]) and [`stop_outputs`] for a signal handler.
//! - [`raster`]: PNG (8-bit RGBA/RGB/grey/grey-alpha, 16-bit read), JPEG and WebP (read) via `image`.
//! - [`svg`]: SVG read through `usvg` (paths as `kurbo` paths in document coordinates, transforms
//!   applied, with stroke and fill), SVG write ([`SvgWriter`]) and rasterization via `resvg`.
//! - [`points`]: point tables as PLY (ascii or binary, via `ply-rs-bw`) or CSV (via `csv`).
//! - `mesh`: triangle meshes read from OBJ (via `tobj`, sections welded) or PLY faces
//!   ([`read_mesh`]), and written as OBJ ([`write_obj`]).
//! - [`json`]: reports and piece lists via `serde_json`.
//! - `legend`: map legends ([`read_legend`]: a folder of textures, a JSON file, or the built-in
//!   one).
//! - `maps`: OpenStreetMap extracts in ([`read_osm`], via `osmpbf`) and tile pyramids out
//!   ([`write_pmtiles`], via `pmtiles`).

mod frames;
pub mod json;
mod legend;
mod maps;
mod mesh;
pub mod points;
pub mod raster;
mod staging;
pub mod svg;

use std::io::Write;
use std::path::{Path, PathBuf};

pub use frames::FramePattern;
pub use json::{read_json, write_json};
pub use legend::read_legend;
pub use maps::{OsmCounts, PyramidInfo, read_osm, write_pmtiles};
pub use mesh::{read_mesh, write_obj};
pub use points::{Column, ColumnKind, PointFormat, PointTable, parse_points, read_points, write_points};
pub use raster::{
    ImageBudget, MAX_MAP_PIXELS, MAX_PIXELS, Rgba16, decode_image, decode_image_within, encode_png, read_image,
    read_image_within, read_png16, read_png16_within, write_png, write_png16,
};
pub(crate) use staging::write_with;
pub use staging::{begin_outputs, check_folder_writable, commit_outputs, create_folder, discard_outputs, stop_outputs};
pub use svg::{StrokePaint, SvgDocument, SvgPath, SvgWriter, parse_svg, read_svg, render_svg};

/// A file could not be read or written; always names the file.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The operating system refused (missing file, permissions, full disk...).
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file exists but its content is not what was expected.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with it, and what is expected.
        message: String,
    },
}

impl IoError {
    /// A format error for `path`.
    pub fn format(path: &Path, message: impl Into<String>) -> Self {
        IoError::Format { path: path.to_path_buf(), message: message.into() }
    }

    fn io(path: &Path, source: std::io::Error) -> Self {
        IoError::Io { path: path.to_path_buf(), source }
    }
}

/// Result alias for this crate.
pub type Result<T> = std::result::Result<T, IoError>;

/// Reads a whole file.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|source| IoError::io(path, source))
}

/// Reads a whole UTF-8 text file.
pub fn read_text(path: &Path) -> Result<String> {
    let bytes = read_bytes(path)?;
    String::from_utf8(bytes).map_err(|_| IoError::format(path, "is not UTF-8 text"))
}

/// Writes `bytes` to `path` atomically: a temporary file in the same directory, flushed, then
/// renamed over `path`.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    write_with(path, |file| file.write_all(bytes))
}

/// Writes UTF-8 text atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_bytes(path, text.as_bytes())
}

/// The memory this process may use, bytes: the machine's (`MemTotal` in `/proc/meminfo`), or the
/// control group's limit (`/sys/fs/cgroup/memory.max`) when that is lower. `None` where neither
/// can be read (other systems): callers then use a fixed default.
pub fn physical_memory() -> Option<u64> {
    let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|text| {
        let line = text.lines().find(|line| line.starts_with("MemTotal:"))?;
        let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        kib.checked_mul(1024)
    });
    // "max" (no limit) does not parse and leaves the machine's figure.
    let limit =
        std::fs::read_to_string("/sys/fs/cgroup/memory.max").ok().and_then(|text| text.trim().parse::<u64>().ok());
    match (total, limit) {
        (Some(total), Some(limit)) => Some(total.min(limit)),
        (total, limit) => total.or(limit),
    }
}

/// Resets this process's peak resident memory (Linux: `5` into `/proc/self/clear_refs`), so that
/// [`peak_memory`] then gives the peak of what runs next. False where that is not possible.
pub fn reset_peak_memory() -> bool {
    std::fs::write("/proc/self/clear_refs", b"5").is_ok()
}

/// This process's peak resident memory, bytes (`VmHWM` in `/proc/self/status`); `None` on
/// other systems.
pub fn peak_memory() -> Option<u64> {
    status_bytes("VmHWM:")
}

/// This process's resident memory now, bytes (`VmRSS` in `/proc/self/status`: the program, its
/// threads' stacks and the allocator's pages); `None` on other systems.
pub fn resident_memory() -> Option<u64> {
    status_bytes("VmRSS:")
}

/// A `kB` figure of `/proc/self/status`, in bytes.
fn status_bytes(key: &str) -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|line| line.starts_with(key))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// True when `a` and `b` name the same file, or would once created: the same file through
/// another spelling, a symbolic link or a hard link (same device and inode), or, for a file that
/// does not exist yet, the same place (the nearest existing folder above it canonicalized).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    if let (Ok(a), Ok(b)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        use std::os::unix::fs::MetadataExt;
        return (a.dev(), a.ino()) == (b.dev(), b.ino());
    }
    match (full_path(a), full_path(b)) {
        (Some(a), Some(b)) => a == b,
        _ => a == b,
    }
}

/// `path` made absolute with its links resolved as far as it exists; the missing rest is
/// appended as spelled, `.` and `..` resolved (nothing missing can be a link).
fn full_path(path: &Path) -> Option<PathBuf> {
    use std::path::Component;
    let components: Vec<Component<'_>> = path.components().collect();
    for existing in (0..=components.len()).rev() {
        let prefix: PathBuf = components[..existing].iter().collect();
        let prefix = if prefix.as_os_str().is_empty() { PathBuf::from(".") } else { prefix };
        let Ok(mut full) = prefix.canonicalize() else { continue };
        for component in &components[existing..] {
            match component {
                Component::ParentDir => {
                    full.pop();
                }
                Component::Normal(name) => full.push(name),
                _ => {}
            }
        }
        return Some(full);
    }
    None
}

/// The file `name` of `folder`, for a name read from a file in that folder (a cache manifest):
/// refused unless it is one plain file name (no folder, no `..`, not absolute) and, where it
/// exists, stays in `folder` once links are followed.
pub fn file_in_folder(folder: &Path, name: &str) -> Result<PathBuf> {
    let mut components = Path::new(name).components();
    let plain = matches!((components.next(), components.next()), (Some(std::path::Component::Normal(_)), None));
    if !plain {
        return Err(IoError::format(
            folder,
            format!("names the file {name:?}, which is not a file of this folder (a plain file name is expected)"),
        ));
    }
    let path = folder.join(name);
    if let (Ok(full), Ok(folder_full)) = (path.canonicalize(), folder.canonicalize())
        && full.parent() != Some(folder_full.as_path())
    {
        return Err(IoError::format(
            &path,
            format!(
                "leads out of {} (a link to {}); only the folder's own files are read",
                folder.display(),
                full.display()
            ),
        ));
    }
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_content_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_text(&path, "first").unwrap();
        write_text(&path, "second").unwrap();
        assert_eq!(read_text(&path).unwrap(), "second");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names.len(), 1);
    }

    #[test]
    #[cfg(unix)]
    fn outputs_get_the_mode_of_any_new_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let ours = dir.path().join("ours.txt");
        write_text(&ours, "x").unwrap();
        // A file made the plain way gets 0666 less the umask, whatever the umask is.
        let plain = dir.path().join("plain.txt");
        std::fs::File::create(&plain).unwrap();
        let mode = |path: &Path| std::fs::metadata(path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&ours), mode(&plain));
    }

    #[test]
    fn errors_name_the_file() {
        let error = read_bytes(Path::new("/nonexistent/motif/file.png")).unwrap_err();
        assert!(error.to_string().contains("/nonexistent/motif/file.png"), "{error}");
        let error = write_text(Path::new("/nonexistent/motif/out.txt"), "x").unwrap_err();
        assert!(error.to_string().contains("out.txt"), "{error}");
    }

    #[test]
    fn same_file_sees_through_relative_paths() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.png");
        std::fs::write(&a, b"x").unwrap();
        assert!(same_file(&a, &dir.path().join(".").join("a.png")));
        assert!(!same_file(&a, &dir.path().join("b.png")));
        assert!(same_file(&dir.path().join("new.png"), &dir.path().join("new.png")));
        // Files and folders that do not exist yet, spelled two ways.
        let new = dir.path().join("new").join("level.png");
        assert!(same_file(&new, &dir.path().join("new").join(".").join("x").join("..").join("level.png")));
        assert!(!same_file(&new, &dir.path().join("new").join("other.png")));
    }

    #[test]
    #[cfg(unix)]
    fn same_file_sees_through_links() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.png");
        std::fs::write(&a, b"x").unwrap();
        let hard = dir.path().join("hard.png");
        std::fs::hard_link(&a, &hard).unwrap();
        let soft = dir.path().join("soft.png");
        std::os::unix::fs::symlink(&a, &soft).unwrap();
        assert!(same_file(&a, &hard));
        assert!(same_file(&soft, &a));
        let copy = dir.path().join("copy.png");
        std::fs::copy(&a, &copy).unwrap();
        assert!(!same_file(&a, &copy));
    }

    #[test]
    fn files_named_by_a_manifest_stay_in_its_folder() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("segment-1.png"), b"x").unwrap();
        assert_eq!(file_in_folder(dir.path(), "segment-1.png").unwrap(), dir.path().join("segment-1.png"));
        for name in ["/etc/passwd", "../x.png", "sub/x.png", "..", ".", ""] {
            let error = file_in_folder(dir.path(), name).unwrap_err();
            assert!(error.to_string().contains("not a file of this folder"), "{name}: {error}");
        }
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/etc/passwd", dir.path().join("out.png")).unwrap();
            let error = file_in_folder(dir.path(), "out.png").unwrap_err();
            assert!(error.to_string().contains("leads out of"), "{error}");
            std::os::unix::fs::symlink(dir.path().join("segment-1.png"), dir.path().join("in.png")).unwrap();
            assert!(file_in_folder(dir.path(), "in.png").is_ok());
        }
    }
}
