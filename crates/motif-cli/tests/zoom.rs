//! `motif zoom` end to end on a real texture: one PNG per level, each the requested size, each
//! agreeing with the centre of the level above, and bad factors refused.

use std::path::Path;
use std::process::{Command, Output};

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

#[test]
fn zoom_levels_are_written_and_agree_with_their_parents() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stone = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/stylize/stone33.png");
    let stone = stone.to_str().unwrap();
    let args =
        ["zoom", "--exemplar", stone, "--size", "96x80", "--factor", "2", "--levels", "3", "--out-dir", "levels"];
    let output = motif(d, &args);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let levels: Vec<motif_core::RgbaImage> =
        (1..=3).map(|level| motif_io::read_image(&d.join(format!("levels/zoom-{level:02}.png"))).unwrap()).collect();
    for pair in levels.windows(2) {
        let (parent, child) = (&pair[0], &pair[1]);
        assert_eq!((child.width(), child.height()), (96, 80));
        // Each 2 × 2 block of the child, averaged, against the parent pixel it magnifies.
        let mut total = 0.0;
        for y in 0..40 {
            for x in 0..48 {
                let block: f64 = (0..4)
                    .map(|k| child.get(2 * x + k % 2, 2 * y + k / 2))
                    .map(|p| (0..3).map(|c| f64::from(p[c])).sum::<f64>())
                    .sum::<f64>()
                    / 12.0;
                let p = parent.get(24 + x, 20 + y);
                total += (block - (0..3).map(|c| f64::from(p[c])).sum::<f64>() / 3.0).abs();
            }
        }
        let mean = total / (40.0 * 48.0);
        assert!(mean < 25.0, "a zoom level differs from its parent's centre by {mean:.1} levels on average");
    }
    // Same seed, same bytes.
    let again = motif(d, &["zoom", "--exemplar", stone, "--size", "96x80", "--levels", "3", "--out-dir", "again"]);
    assert!(again.status.success());
    for level in 1..=3 {
        let name = format!("zoom-{level:02}.png");
        assert_eq!(
            std::fs::read(d.join("levels").join(&name)).unwrap(),
            std::fs::read(d.join("again").join(&name)).unwrap()
        );
    }
    let bad = motif(d, &["zoom", "--exemplar", stone, "--size", "96x80", "--factor", "30", "--out-dir", "never"]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("invalid factor"));
    assert!(!d.join("never").exists());
}
