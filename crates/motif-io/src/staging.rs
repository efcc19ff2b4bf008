//! How outputs reach the disk: each through a temporary file beside it that a rename puts in
//! place, so that no output is ever half-written; during a run (see [`begin_outputs`]) the renames
//! wait until the run has succeeded, so that a run failing part-way leaves every previous file as
//! it was; and a signal handler can remove the temporary files of writes in progress.

use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use crate::{IoError, Result};

/// Temporary files being written now (each removed from the list once renamed or dropped).
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every temporary file a write has not finished with: for a signal handler, so that an
/// interrupted run leaves no `.motif-*.tmp` behind (the outputs themselves are only ever replaced
/// whole, by a rename).
pub fn remove_temporaries() {
    remove_temporaries_where(|_| true);
}

pub(crate) fn remove_temporaries_where(chosen: impl Fn(&Path) -> bool) {
    let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    temporaries.retain(|path| {
        if !chosen(path) {
            return true;
        }
        // Already renamed or removed: nothing to do.
        let _ = std::fs::remove_file(path);
        false
    });
}

fn track(path: &Path, live: bool) {
    let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    if live {
        temporaries.push(path.to_path_buf());
    } else {
        temporaries.retain(|p| p != path);
    }
}

/// A written temporary file waiting for its rename onto `path`.
struct Pending {
    temporary: tempfile::NamedTempFile,
    path: PathBuf,
}

thread_local! {
    /// `Some` between [`begin_outputs`] and [`commit_outputs`] or [`discard_outputs`]: the writes
    /// of this thread whose renames wait. (Per thread: a command writes from the thread that runs
    /// it, and tests running side by side do not share the mode.)
    static PENDING: std::cell::RefCell<Option<Vec<Pending>>> = const { std::cell::RefCell::new(None) };
}

/// From now on, writes leave their temporary files in place until [`commit_outputs`] renames them
/// all (or [`discard_outputs`] removes them): a run's outputs appear together, and only when the
/// whole run succeeded.
pub fn begin_outputs() {
    PENDING.with(|pending| *pending.borrow_mut() = Some(Vec::new()));
}

/// Renames every waiting output into place, in the order written, and returns to writing at once.
pub fn commit_outputs() -> Result<()> {
    let pending = PENDING.with(|pending| pending.borrow_mut().take()).unwrap_or_default();
    let mut result = Ok(());
    for Pending { temporary, path } in pending {
        let temporary_path = temporary.path().to_path_buf();
        if result.is_ok() {
            result = temporary.persist(&path).map(drop).map_err(|error| IoError::io(&path, error.error));
        }
        // Not renamed: dropping the temporary file removes it.
        track(&temporary_path, false);
    }
    result
}

/// Removes every waiting output's temporary file (the previous files stay as they were) and
/// returns to writing at once.
pub fn discard_outputs() {
    let pending = PENDING.with(|pending| pending.borrow_mut().take()).unwrap_or_default();
    for Pending { temporary, .. } in pending {
        let temporary_path = temporary.path().to_path_buf();
        drop(temporary);
        track(&temporary_path, false);
    }
}

/// Runs `fill` on a temporary file beside `path`, then renames it onto `path` (at once, or when
/// the run's outputs are committed).
pub(crate) fn write_with(path: &Path, fill: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>) -> Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".motif-").suffix(".tmp");
    // The temporary file becomes the output: give it the mode any tool's output gets (0666 less
    // the umask), not a temporary file's private 0600.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut temporary = builder.tempfile_in(directory).map_err(|source| IoError::io(path, source))?;
    let temporary_path = temporary.path().to_path_buf();
    track(&temporary_path, true);
    let filled = fill(temporary.as_file_mut())
        .and_then(|()| temporary.as_file_mut().sync_all())
        .map_err(|source| IoError::io(path, source));
    if let Err(error) = filled {
        track(&temporary_path, false);
        return Err(error);
    }
    // Staged writes stay tracked until committed or discarded.
    let staged = PENDING.with(|pending| match pending.borrow_mut().as_mut() {
        Some(waiting) => {
            waiting.push(Pending { temporary, path: path.to_path_buf() });
            None
        }
        None => Some(temporary),
    });
    let Some(temporary) = staged else {
        return Ok(());
    };
    let written = temporary.persist(path).map(drop).map_err(|error| IoError::io(path, error.error));
    track(&temporary_path, false);
    written
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    #[test]
    fn interrupted_writes_leave_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.bin");
        // A write interrupted in the middle: the signal handler's clean-up runs inside `fill`.
        let result = write_with(&out, |file| {
            file.write_all(b"half")?;
            // (Only this test's files: other tests write in parallel.)
            remove_temporaries_where(|p| p.starts_with(dir.path()));
            Err(std::io::Error::other("interrupted"))
        });
        assert!(result.is_err());
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert!(left.is_empty(), "{left:?}");
        assert!(TEMPORARIES.lock().unwrap().iter().all(|p| !p.starts_with(dir.path())));
    }

    #[test]
    fn staged_outputs_appear_together_or_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        crate::write_text(&a, "old a").unwrap();
        begin_outputs();
        crate::write_text(&a, "new a").unwrap();
        crate::write_text(&b, "new b").unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a", "nothing moves before the commit");
        assert!(!b.exists());
        discard_outputs();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert!(!b.exists());
        let names = || -> Vec<String> {
            let mut names: Vec<String> = std::fs::read_dir(dir.path())
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into())
                .collect();
            names.sort();
            names
        };
        assert_eq!(names(), ["a.txt"], "no temporary left");
        begin_outputs();
        crate::write_text(&a, "new a").unwrap();
        crate::write_text(&b, "new b").unwrap();
        commit_outputs().unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b");
        assert_eq!(names(), ["a.txt", "b.txt"]);
    }
}
