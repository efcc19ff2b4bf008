//! How outputs reach the disk: each through a temporary file beside it that a rename puts in
//! place, so that no output is ever half-written; during a run (see [`begin_outputs`]) the renames
//! wait until the run has succeeded and are then done together ([`commit_outputs`]: all of them,
//! or, when one fails, none), so that a run failing at any point leaves every previous file as it
//! was; and a signal handler ([`stop_outputs`]) removes the temporary files of writes in progress,
//! after letting a commit in progress finish.
//!
//! Temporary files are named `.motif-<pid>-<random>.tmp`: the first write into a folder removes
//! those that processes no longer running left there (a run killed with SIGKILL, which no handler
//! sees). Unnamed temporary files (Linux `O_TMPFILE`, then `linkat`) would leave nothing even
//! then, but are not used: `linkat` cannot replace a file, so each would still need a named step
//! before its rename at the commit, and every staged output would hold an open descriptor until
//! the commit (a video of a few thousand frames exceeds the usual limit of 1024).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Duration;

use crate::{IoError, Result};

/// Temporary files being written now, or waiting for their commit (each removed from the list
/// once renamed or dropped), and folders made for outputs not committed yet.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Held while a commit renames its files: [`stop_outputs`] waits for it, so that an interrupted
/// process has either all of a run's outputs in place or none.
static COMMIT: Mutex<()> = Mutex::new(());

/// Set by [`stop_outputs`]: no write starts and no commit renames anything afterwards.
static STOPPED: AtomicBool = AtomicBool::new(false);

/// Folders whose stale temporary files have already been looked for.
static SWEPT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// A temporary file of a process that is gone is removed once its owner is known to be gone
/// (and at least this old: a moment to tell a starting process's file from a leftover).
const STALE_AFTER_OWNER_GONE: Duration = Duration::from_secs(1);
/// A temporary file whose owner cannot be told (earlier versions' names, or no `/proc`) is
/// removed once this old.
const STALE_UNKNOWN_OWNER: Duration = Duration::from_secs(3600);

/// For a signal handler: waits for a commit in progress to finish, then removes every
/// temporary file a write or a waiting output has not finished with (and the folders made for
/// them), and refuses every later write and commit, so that an interrupted run leaves either all
/// of its outputs or none of them, and no `.motif-*.tmp` behind.
pub fn stop_outputs() {
    let _commit = COMMIT.lock().unwrap_or_else(PoisonError::into_inner);
    STOPPED.store(true, Ordering::SeqCst);
    remove_temporaries_where(|_| true);
}

pub(crate) fn remove_temporaries_where(chosen: impl Fn(&Path) -> bool) {
    let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    // Folders come after the files made in them: removed in reverse, emptied first.
    let mut kept = Vec::new();
    for path in temporaries.drain(..).rev() {
        if !chosen(&path) {
            kept.push(path);
        } else if path.is_dir() {
            // Removed only when empty (nothing else was put there meanwhile).
            let _ = std::fs::remove_dir(&path);
        } else {
            // Already renamed or removed: nothing to do.
            let _ = std::fs::remove_file(&path);
        }
    }
    kept.reverse();
    *temporaries = kept;
}

fn untrack(path: &Path) {
    let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    temporaries.retain(|p| p != path);
}

fn stopped(path: &Path) -> IoError {
    IoError::io(path, std::io::Error::new(std::io::ErrorKind::Interrupted, "interrupted"))
}

/// A written temporary file waiting for its rename onto `path`.
struct Pending {
    temporary: tempfile::TempPath,
    path: PathBuf,
}

/// The outputs of a run in progress.
#[derive(Default)]
struct Staged {
    pending: Vec<Pending>,
    /// Folders made for the outputs, outermost first: removed again if the run fails.
    folders: Vec<PathBuf>,
}

thread_local! {
    /// `Some` between [`begin_outputs`] and [`commit_outputs`] or [`discard_outputs`]: the writes
    /// of this thread whose renames wait. (Per thread: a command writes from the thread that runs
    /// it, and tests running side by side do not share the mode.)
    static STAGED: std::cell::RefCell<Option<Staged>> = const { std::cell::RefCell::new(None) };
}

/// From now on, writes leave their temporary files in place until [`commit_outputs`] renames them
/// all (or [`discard_outputs`] removes them): a run's outputs appear together, and only when the
/// whole run succeeded.
pub fn begin_outputs() {
    STAGED.with(|staged| *staged.borrow_mut() = Some(Staged::default()));
}

/// What an output replaces, kept during a commit so that a failed commit can put it back.
enum Previous {
    /// There was no file.
    None,
    /// A second link to the previous file, under a temporary name.
    Kept(tempfile::TempPath),
    /// There was a file, but it could not be kept (a file system without hard links).
    Lost,
}

fn keep_previous(path: &Path) -> Previous {
    if std::fs::symlink_metadata(path).is_err() {
        return Previous::None;
    }
    let linked = temporary_builder().make_in(folder_of(path), |backup| std::fs::hard_link(path, backup));
    match linked {
        Ok(backup) => Previous::Kept(backup.into_temp_path()),
        Err(_) => Previous::Lost,
    }
}

/// Renames every waiting output into place, in the order written, and returns to writing at once.
/// When a rename fails, the outputs already renamed are put back as they were (the previous files
/// are kept as second links until the commit is done), and the folders made for the run are
/// removed: a run's outputs replace the previous files all together or not at all.
pub fn commit_outputs() -> Result<()> {
    let staged = STAGED.with(|staged| staged.borrow_mut().take()).unwrap_or_default();
    let _commit = COMMIT.lock().unwrap_or_else(PoisonError::into_inner);
    if STOPPED.load(Ordering::SeqCst) {
        let path = staged.pending.first().map_or_else(PathBuf::new, |p| p.path.clone());
        discard(staged);
        return Err(stopped(&path));
    }
    let mut done: Vec<(PathBuf, Previous)> = Vec::new();
    let mut failure = None;
    let mut pending = staged.pending.into_iter();
    for Pending { temporary, path } in pending.by_ref() {
        let previous = keep_previous(&path);
        let temporary_path = temporary.to_path_buf();
        match temporary.persist(&path) {
            Ok(()) => done.push((path, previous)),
            Err(error) => {
                // Dropping the temporary file and the kept link removes them.
                failure = Some(IoError::io(&path, error.error));
                untrack(&temporary_path);
                break;
            }
        }
        untrack(&temporary_path);
    }
    let Some(failure) = failure else {
        // Dropping the kept links removes them; the folders stay.
        drop(done);
        for folder in &staged.folders {
            untrack(folder);
        }
        return Ok(());
    };
    for (path, previous) in done.into_iter().rev() {
        match previous {
            Previous::Kept(backup) => {
                let _ = backup.persist(&path);
            }
            Previous::None => {
                let _ = std::fs::remove_file(&path);
            }
            Previous::Lost => {}
        }
    }
    discard(Staged { pending: pending.collect(), folders: staged.folders });
    Err(failure)
}

/// Removes every waiting output's temporary file (the previous files stay as they were) and
/// the folders made for them, and returns to writing at once.
pub fn discard_outputs() {
    let staged = STAGED.with(|staged| staged.borrow_mut().take()).unwrap_or_default();
    discard(staged);
}

fn discard(staged: Staged) {
    for Pending { temporary, .. } in staged.pending {
        let temporary_path = temporary.to_path_buf();
        drop(temporary);
        untrack(&temporary_path);
    }
    for folder in staged.folders.iter().rev() {
        // Only an empty folder goes: one that something else was put into meanwhile stays.
        let _ = std::fs::remove_dir(folder);
        untrack(folder);
    }
}

/// Makes the folder `path` and any missing folder above it, for outputs to be written into.
/// During a run (see [`begin_outputs`]) the folders made are removed again when the run fails.
pub fn create_folder(path: &Path) -> Result<()> {
    let mut missing = Vec::new();
    let mut current = Some(path);
    while let Some(folder) = current.filter(|f| !f.as_os_str().is_empty() && std::fs::symlink_metadata(f).is_err()) {
        missing.push(folder.to_path_buf());
        current = folder.parent();
    }
    for folder in missing.into_iter().rev() {
        let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
        if STOPPED.load(Ordering::SeqCst) {
            return Err(stopped(&folder));
        }
        match std::fs::create_dir(&folder) {
            Ok(()) => {}
            Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists && folder.is_dir() => continue,
            Err(error) => return Err(IoError::io(&folder, error)),
        }
        let staged = STAGED.with(|staged| match staged.borrow_mut().as_mut() {
            Some(staged) => {
                staged.folders.push(folder.clone());
                true
            }
            None => false,
        });
        if staged {
            temporaries.push(folder);
        }
    }
    if !path.is_dir() {
        return Err(IoError::format(path, "is not a folder"));
    }
    Ok(())
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    }
}

/// Temporary files are `.motif-<pid>-<random>.tmp`, the mode any tool's output gets.
fn temporary_builder() -> tempfile::Builder<'static, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(temporary_prefix()).suffix(".tmp");
    // The temporary file becomes the output: give it the mode any tool's output gets (0666 less
    // the umask), not a temporary file's private 0600.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder
}

/// `.motif-<pid>-`, made once.
fn temporary_prefix() -> &'static str {
    static PREFIX: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    PREFIX.get_or_init(|| format!(".motif-{}-", std::process::id()))
}

/// True when the process `pid` runs; `None` where that cannot be told (no `/proc`).
fn running(pid: u32) -> Option<bool> {
    Path::new("/proc/self").exists().then(|| Path::new(&format!("/proc/{pid}")).exists())
}

/// True for a temporary file named `name` that no running process will finish: one of a process
/// that is gone, or, where the owner cannot be told, one older than an hour.
fn stale(name: &str, age: Duration) -> bool {
    let Some(middle) = name.strip_prefix(".motif-").and_then(|rest| rest.strip_suffix(".tmp")) else {
        return false;
    };
    let owner = middle.split_once('-').and_then(|(pid, _)| pid.parse::<u32>().ok());
    match owner.map(|pid| (pid, running(pid))) {
        Some((pid, _)) if pid == std::process::id() => false,
        Some((_, Some(running))) => !running && age >= STALE_AFTER_OWNER_GONE,
        _ => age >= STALE_UNKNOWN_OWNER,
    }
}

/// Removes, once per folder and process, the temporary files earlier runs left in `folder` when
/// they were killed (see [`stale`]). Errors are ignored: this only tidies up.
fn sweep(folder: &Path) {
    let key = folder.canonicalize().unwrap_or_else(|_| folder.to_path_buf());
    {
        let mut swept = SWEPT.lock().unwrap_or_else(PoisonError::into_inner);
        if swept.contains(&key) {
            return;
        }
        swept.push(key);
    }
    let Ok(entries) = std::fs::read_dir(folder) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let Ok(metadata) = entry.metadata() else { continue };
        let age = metadata.modified().ok().and_then(|modified| modified.elapsed().ok()).unwrap_or_default();
        if metadata.is_file() && stale(name, age) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Checks, before any work, that an output can be written into `folder`: makes a temporary file
/// there and removes it (a folder that exists can still refuse files: `/proc`, a read-only
/// mount, permissions). Also removes the temporary files killed runs left there.
pub fn check_folder_writable(folder: &Path) -> Result<()> {
    static PROBES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    sweep(folder);
    let probe = folder.join(format!("{}probe{}.tmp", temporary_prefix(), PROBES.fetch_add(1, Ordering::Relaxed)));
    match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(file) => {
            drop(file);
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        // (Left by this process: the folder takes files.)
        Err(error) if error.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(error) => Err(IoError::format(folder, format!("cannot make a file there: {error}"))),
    }
}

/// Runs `fill` on a temporary file beside `path`, then renames it onto `path` (at once, or when
/// the run's outputs are committed).
pub(crate) fn write_with(path: &Path, fill: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>) -> Result<()> {
    let directory = folder_of(path);
    sweep(directory);
    let mut temporary = {
        // Made and listed under the lock, so that a signal handler removes it or sees no write.
        let mut temporaries = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
        if STOPPED.load(Ordering::SeqCst) {
            return Err(stopped(path));
        }
        let temporary = temporary_builder().tempfile_in(directory).map_err(|source| IoError::io(path, source))?;
        temporaries.push(temporary.path().to_path_buf());
        temporary
    };
    let temporary_path = temporary.path().to_path_buf();
    let filled = fill(temporary.as_file_mut())
        .and_then(|()| temporary.as_file_mut().sync_all())
        .map_err(|source| IoError::io(path, source));
    if let Err(error) = filled {
        drop(temporary);
        untrack(&temporary_path);
        return Err(error);
    }
    // Closed now: a run may stage more outputs than a process may hold open files.
    let temporary = temporary.into_temp_path();
    // Staged writes stay listed until committed or discarded.
    let unstaged = STAGED.with(|staged| match staged.borrow_mut().as_mut() {
        Some(staged) => {
            staged.pending.push(Pending { temporary, path: path.to_path_buf() });
            None
        }
        None => Some(temporary),
    });
    let Some(temporary) = unstaged else {
        return Ok(());
    };
    let written = temporary.persist(path).map_err(|error| IoError::io(path, error.error));
    untrack(&temporary_path);
    written
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
        names.sort();
        names
    }

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
        assert_eq!(names(dir.path()), ["a.txt"], "no temporary left");
        begin_outputs();
        crate::write_text(&a, "new a").unwrap();
        crate::write_text(&b, "new b").unwrap();
        commit_outputs().unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b");
        assert_eq!(names(dir.path()), ["a.txt", "b.txt"]);
    }

    /// A rename that fails at the commit (here: a name too long for the file system, which only
    /// the rename finds out) puts back the outputs already renamed and removes the new ones.
    #[test]
    fn a_failed_commit_puts_every_previous_file_back() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        crate::write_text(&a, "old a").unwrap();
        let too_long = dir.path().join(format!("{}.json", "r".repeat(300)));
        begin_outputs();
        crate::write_text(&a, "new a").unwrap();
        crate::write_text(&b, "new b").unwrap();
        crate::write_text(&too_long, "report").unwrap();
        let error = commit_outputs().unwrap_err();
        assert!(error.to_string().contains("rrrr"), "{error}");
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert_eq!(names(dir.path()), ["a.txt"], "no new output, kept link or temporary left");
    }

    #[test]
    fn folders_made_for_a_failed_run_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        let deep = dir.path().join("new").join("deeper");
        begin_outputs();
        create_folder(&deep).unwrap();
        crate::write_text(&deep.join("a.txt"), "a").unwrap();
        discard_outputs();
        assert!(names(dir.path()).is_empty());
        begin_outputs();
        create_folder(&deep).unwrap();
        crate::write_text(&deep.join("a.txt"), "a").unwrap();
        commit_outputs().unwrap();
        assert_eq!(names(&deep), ["a.txt"]);
        // A file in the way is an error naming it.
        let error = create_folder(&deep.join("a.txt")).unwrap_err();
        assert!(error.to_string().contains("a.txt"), "{error}");
    }

    #[test]
    fn stale_temporaries_are_those_of_processes_gone() {
        let minute = Duration::from_secs(60);
        let ours = format!(".motif-{}-abc123.tmp", std::process::id());
        assert!(!stale(&ours, minute * 1000), "this process's own");
        // (A pid above Linux's largest possible, 2^22: never running.)
        assert!(stale(".motif-999999999-abc123.tmp", minute));
        assert!(!stale(".motif-999999999-abc123.tmp", Duration::ZERO), "just made");
        assert!(!stale(".motif-abc123.tmp", minute), "an earlier version's name, young");
        assert!(stale(".motif-abc123.tmp", minute * 61));
        assert!(!stale("motif-999999999-abc123.tmp", minute * 1000));
        assert!(!stale(".motif-999999999-abc123.png", minute * 1000));
        if running(1).is_some() {
            assert!(!stale(".motif-1-abc123.tmp", minute * 1000), "a running process's file");
        }
    }

    #[test]
    fn the_first_write_into_a_folder_removes_what_killed_runs_left() {
        let dir = tempfile::tempdir().unwrap();
        let dead = dir.path().join(".motif-999999999-abc123.tmp");
        let live = dir.path().join(format!(".motif-{}-abc123.tmp", std::process::id()));
        let other = dir.path().join(".motif-notes.txt");
        for path in [&dead, &live, &other] {
            std::fs::write(path, b"x").unwrap();
        }
        let old = std::time::SystemTime::now() - Duration::from_secs(120);
        std::fs::File::options().write(true).open(&dead).unwrap().set_modified(old).unwrap();
        crate::write_text(&dir.path().join("out.txt"), "x").unwrap();
        assert!(!dead.exists());
        assert!(live.exists() && other.exists());
    }
}
