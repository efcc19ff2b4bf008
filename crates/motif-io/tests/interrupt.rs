//! An interrupt during a commit (the signal handler calls `stop_outputs`) lets the commit finish:
//! a run's outputs are all in place or none. (A test binary of its own: once stopped, a process
//! writes nothing more.)

use std::time::Duration;

#[test]
fn an_interrupt_during_the_commit_waits_for_every_rename() {
    let dir = tempfile::tempdir().unwrap();
    let count = 400;
    let paths: Vec<_> = (0..count).map(|i| dir.path().join(format!("frame-{i:04}.txt"))).collect();
    for path in &paths {
        motif_io::write_text(path, "old").unwrap();
    }
    motif_io::begin_outputs();
    for path in &paths {
        motif_io::write_text(path, "new").unwrap();
    }
    let first = paths[0].clone();
    // The handler's thread: as soon as the first output is in place, the commit is under way.
    let handler = std::thread::spawn(move || {
        let start = std::time::Instant::now();
        while std::fs::read_to_string(&first).unwrap() != "new" && start.elapsed() < Duration::from_secs(20) {
            std::hint::spin_loop();
        }
        motif_io::stop_outputs();
    });
    motif_io::commit_outputs().unwrap();
    handler.join().unwrap();
    let new = paths.iter().filter(|path| std::fs::read_to_string(path).unwrap() == "new").count();
    assert_eq!(new, count, "every output replaced, not {new} of {count}");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".motif-"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
    // Once stopped, nothing is written any more.
    let error = motif_io::write_text(&dir.path().join("late.txt"), "late").unwrap_err();
    assert!(error.to_string().contains("interrupted"), "{error}");
    assert!(!dir.path().join("late.txt").exists());
}
