//! `motif points` on small cases of the real-data corpus (`data/real/points/`, the cases marked
//! `"use": "test"`; the bench uses the others): density, fidelity against the random baseline,
//! labels, the count bound of sampling control, and clear errors for unusable attribute columns.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn corpus(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/points").join(file)
}

fn motif(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_motif")).current_dir(dir).args(args).output().unwrap()
}

/// Runs a corpus case and returns its report.
fn run_case(file: &str, neighbourhood: &str, domain: &str, init: &str, seed: &str) -> serde_json::Value {
    run_case_with(file, neighbourhood, domain, init, seed, &[]).0
}

/// Runs a corpus case with extra flags; returns its report and the output CSV.
fn run_case_with(
    file: &str,
    neighbourhood: &str,
    domain: &str,
    init: &str,
    seed: &str,
    extra: &[&str],
) -> (serde_json::Value, String) {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = corpus(file);
    let mut args = vec![
        "--seed",
        seed,
        "points",
        "--exemplar",
        exemplar.to_str().unwrap(),
        "--neighbourhood",
        neighbourhood,
        "--domain",
        domain,
        "--init",
        init,
        "--out",
        "out.csv",
        "--report",
        "report.json",
    ];
    args.extend_from_slice(extra);
    let output = motif(dir.path(), &args);
    assert!(output.status.success(), "{file}: {}", String::from_utf8_lossy(&output.stderr));
    let points = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    (motif_io::read_json(&dir.path().join("report.json")).unwrap(), points)
}

fn figure(report: &serde_json::Value, set: &str, distance: &str) -> f64 {
    report["fidelity"][set][distance].as_f64().unwrap()
}

/// Density within ±3 % (issue 34) from patches and from random points, and both distances under half the
/// random set's (fixed seeds): 71 Swedish pines (inhibited, 96 × 100 dm) and 65 Japanese pines
/// (close to random, unit square, observation window given) and 62 redwood seedlings (clustered,
/// unit square) from either start. The Swedish pines from random points
/// sit near the bound since sampling control leaves a surplus over the count tolerance to the
/// pair-statistics refinement's thinning (which took the patches start, seeds 1–6, from g(r)
/// 0.149–0.190, three seeds over half the random set's, to 0.127–0.155): from random points seed
/// 1's g(r) distance is then 0.173 against half the random set's 0.170 (0.154 when sampling control
/// removed the surplus itself); over seeds 1–6 the mean g(r) distance is 0.158 against 0.143 and
/// the nearest-neighbour distance 0.009 against 0.012, so that row allows 0.55×.
#[test]
fn small_real_patterns_keep_their_density_and_beat_a_random_set() {
    let cases = [
        ("swedishpines.csv", "32", "box:192,200", "patches", Some(0.5), None),
        ("swedishpines.csv", "32", "box:192,200", "random", Some(0.55), None),
        ("japanesepines.csv", "0.26", "box:2,2", "patches", Some(0.5), Some("1,1")),
        ("japanesepines.csv", "0.26", "box:2,2", "random", Some(0.5), Some("1,1")),
        ("redwood.csv", "0.16", "box:2,2", "patches", Some(0.5), None),
        ("redwood.csv", "0.16", "box:2,2", "random", Some(0.5), None),
    ];
    for (file, neighbourhood, domain, init, fraction, window) in cases {
        for seed in ["1", "2"] {
            let extra = window.map(|w| vec!["--exemplar-window", w]).unwrap_or_default();
            let report = run_case_with(file, neighbourhood, domain, init, seed, &extra).0;
            let density = report["fidelity"]["density_ratio"].as_f64().unwrap();
            assert!((density - 1.0).abs() <= 0.03 + 1e-9, "{file} {init} seed {seed}: density {density}");
            let Some(fraction) = fraction else { continue };
            for distance in ["nearest_neighbour", "radial_distribution"] {
                let (output, random) = (figure(&report, "output", distance), figure(&report, "random", distance));
                assert!(
                    output < fraction * random,
                    "{file} {init} seed {seed}: {distance} {output} against random {random} (must be < {fraction}×)"
                );
            }
        }
    }
}

/// Clustered real patterns (issue 35): from patches and from random points, the g(r) and
/// nearest-neighbour distances within 1.5× of a tiled copy's, and the mean cluster size nearer the
/// exemplar's than a random set's. Relocation (docs/points.md) forms the clusters; before it, the
/// redwood from random points stayed at 0.75–0.79 × the random set's g(r) distance. Redwood
/// (seeds 1–4, both starts: 0.80–1.29 × the tiled copy's g(r) distance) and the Finnish pines.
#[test]
fn clustered_real_patterns_form_their_clusters_from_either_start() {
    let cases = [
        ("redwood.csv", "0.16", "box:2,2", "1,1", "patches", "1"),
        ("redwood.csv", "0.16", "box:2,2", "1,1", "random", "1"),
        ("redwood.csv", "0.16", "box:2,2", "1,1", "random", "2"),
        ("finpines.csv", "1.6", "box:20,20", "10,10", "random", "1"),
    ];
    for (file, neighbourhood, domain, window, init, seed) in cases {
        let report = run_case_with(file, neighbourhood, domain, init, seed, &["--exemplar-window", window]).0;
        for distance in ["nearest_neighbour", "radial_distribution"] {
            let (output, tiled) = (figure(&report, "output", distance), figure(&report, "tiled", distance));
            assert!(output <= 1.5 * tiled, "{file} {init} seed {seed}: {distance} {output}, tiled copy {tiled}");
        }
        // How far a ratio is from 1, either way.
        let cluster = |set: &str| {
            let ratio = figure(&report, set, "cluster_size_ratio");
            ratio.max(1.0 / ratio)
        };
        assert!(
            cluster("output") < cluster("random"),
            "{file} {init} seed {seed}: cluster size ratio {} against a random set's {}",
            figure(&report, "output", "cluster_size_ratio"),
            figure(&report, "random", "cluster_size_ratio")
        );
    }
}

/// A real 3D continuous structure (issue 35): CGAL's fin, a curved sheet of 757 points with
/// normals, grown in a box and inside the bull's volume (at half scale, so that ~500 points fit)
/// keeps its layers: the nearest-neighbour and g(r) distances within 1.5× of a tiled copy's, the
/// mean local thickness (points off the plane of their 12 nearest neighbours) within 1.5× of the
/// exemplar's (the fin's is 0.49 spacings; a random set's is 2.8× that), and `--surface-out`
/// reconstructs a surface from the output's normals. Measured (seed 1): box 1.17×, bull 1.11×.
#[test]
fn a_real_sheet_keeps_its_layers_in_a_box_and_in_a_mesh_volume() {
    let surface = tempfile::tempdir().unwrap();
    let obj = surface.path().join("sheet.obj");
    let bull = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/meshes/bull.obj");
    let volume = format!("volume:{}", bull.to_str().unwrap());
    let window = ["--exemplar-window", "1.1593,0.7426,0.7861"];
    let cases: [(&str, Vec<&str>); 2] = [
        ("box:1.739,1.114,1.179", window.to_vec()),
        (&volume, [&window[..], &["--scale", "0.5", "--surface-out", obj.to_str().unwrap()]].concat()),
    ];
    for (domain, extra) in cases {
        let report = run_case_with("fin_sheet.csv", "0.058", domain, "patches", "1", &extra).0;
        for distance in ["nearest_neighbour", "radial_distribution"] {
            let (output, tiled) = (figure(&report, "output", distance), figure(&report, "tiled", distance));
            assert!(output <= 1.5 * tiled, "{domain}: {distance} {output}, tiled copy {tiled}");
        }
        let (output, random) =
            (figure(&report, "output", "thickness_ratio"), figure(&report, "random", "thickness_ratio"));
        assert!(output <= 1.5 && random > 2.0, "{domain}: thickness {output} × the exemplar's, random {random}");
    }
    let mesh = std::fs::read_to_string(&obj).unwrap();
    let faces = mesh.lines().filter(|l| l.starts_with("f ")).count();
    assert!(faces > 1000, "{faces} faces reconstructed");
}

/// With the default refinement only the seams between patches move: the points copied into
/// patch interiors come out exactly where the copies alone put them, and there are many of them.
/// The pair-statistics refinement after it moves only the points within its band of the seams.
/// Moving every point leaves far fewer in place.
#[test]
fn patch_interiors_stay_as_copied() {
    let case = |refine: &str, statistics: &str| {
        let extra = ["--refine", refine, "--statistics-iterations", statistics];
        run_case_with("swedishpines.csv", "32", "box:192,200", "patches", "3", &extra)
    };
    let (_, copies) = case("none", "0");
    let copied: std::collections::BTreeSet<&str> = copies.lines().skip(1).collect();
    let (report, seams) = case("seams", "0");
    let interiors = report["patch_interior_points"].as_u64().unwrap() as usize;
    let kept = seams.lines().skip(1).filter(|l| copied.contains(l)).count();
    assert!(interiors >= copied.len() / 5, "{interiors} interior points of {}", copied.len());
    assert!(kept >= interiors, "{kept} points in place, {interiors} interior points");
    let (refined_report, refined) = case("seams", "40");
    let movable = refined_report["pair_statistics"]["movable_points"].as_u64().unwrap() as usize;
    let output_points = refined_report["output_points"].as_u64().unwrap() as usize;
    let refined_kept = refined.lines().skip(1).filter(|l| copied.contains(l)).count();
    assert!(movable < output_points, "{movable} of {output_points} points movable");
    assert!(refined_kept + movable >= output_points, "{refined_kept} in place, {movable} movable of {output_points}");
    let (everywhere_report, everywhere) = case("everywhere", "0");
    assert_eq!(everywhere_report["patch_interior_points"].as_u64(), Some(0));
    let moved_kept = everywhere.lines().skip(1).filter(|l| copied.contains(l)).count();
    assert!(moved_kept < kept / 2, "{moved_kept} in place when every point moves, {kept} with seams only");
}

/// The observation window sets the exemplar's density; one that misses a point is refused.
#[test]
fn the_exemplar_window_sets_the_density_and_must_hold_every_point() {
    let density = |extra: &[&str]| {
        let (report, _) = run_case_with("swedishpines.csv", "32", "box:192,200", "patches", "1", extra);
        report["expected_points"].as_f64().unwrap()
    };
    let window = density(&["--exemplar-window", "96,100"]);
    assert!((window - 71.0 * 4.0).abs() < 3.0, "{window} expected points for 4 windows of 71 pines");
    let corners = density(&["--exemplar-window", "0,0,96,100"]);
    assert!((window - corners).abs() < 1e-9);
    let dir = tempfile::tempdir().unwrap();
    let exemplar = corpus("swedishpines.csv");
    let exemplar = exemplar.to_str().unwrap();
    for (window, expected) in
        [("50,50", "hold every exemplar point"), ("96,100,5", "2 sizes or 4 corner values for a 2D exemplar")]
    {
        let output = motif(
            dir.path(),
            &["points", "--exemplar", exemplar, "--neighbourhood", "32", "--domain", "box:192,200"]
                .into_iter()
                .chain(["--exemplar-window", window, "--out", "out.csv"])
                .collect::<Vec<_>>(),
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{window}: {stderr}");
        assert!(stderr.contains("exemplar-window") && stderr.contains(expected), "{window}: {stderr}");
        assert!(!dir.path().join("out.csv").exists());
    }
}

/// A clustered exemplar (62 redwood seedlings) emptied the domain before sampling control had a
/// bound; now it keeps at least 90 % of the expected count.
#[test]
fn sampling_control_cannot_empty_a_clustered_domain() {
    let report = run_case("redwood.csv", "0.16", "box:2,2", "random", "1");
    let expected = report["expected_points"].as_f64().unwrap();
    let count = report["output_points"].as_f64().unwrap();
    assert!(count >= 0.9 * expected - 1.0, "{count} points for {expected} expected");
    assert!(report["points_removed"].as_f64().unwrap() <= 0.5 * report["initial_points"].as_f64().unwrap());
}

/// A multi-type pattern (3D protein atoms labelled by element) comes out with only the
/// exemplar's labels, written as integers.
#[test]
fn a_label_column_keeps_only_the_exemplar_labels() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = corpus("protein_atoms.csv");
    let output = motif(
        dir.path(),
        &[
            "points",
            "--exemplar",
            exemplar.to_str().unwrap(),
            "--neighbourhood",
            "2.8",
            "--domain",
            "box:12,12,12",
            "--out",
            "out.csv",
        ],
    );
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let text = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,label"));
    let labels: std::collections::BTreeSet<&str> = lines.map(|l| l.rsplit(',').next().unwrap()).collect();
    assert!(!labels.is_empty() && labels.iter().all(|l| ["0", "1", "2", "3"].contains(l)), "{labels:?}");
}

#[test]
fn a_constant_attribute_is_kept_and_a_missing_value_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut constant = String::from("x,y,height\n");
    let mut missing = String::from("x,y,height\n");
    for i in 0..40 {
        let (x, y) = ((i % 8) as f64 * 1.1, (i / 8) as f64 * 0.9);
        constant.push_str(&format!("{x},{y},2.5\n"));
        missing.push_str(&format!("{x},{y},{}\n", if i == 7 { "NaN".to_string() } else { format!("{}", i % 3) }));
    }
    std::fs::write(dir.path().join("constant.csv"), constant).unwrap();
    std::fs::write(dir.path().join("missing.csv"), missing).unwrap();
    let run = |file: &str| {
        motif(
            dir.path(),
            &["points", "--exemplar", file, "--neighbourhood", "2", "--domain", "box:10,10", "--out", "out.csv"],
        )
    };
    // A column with one value (a normal's zero component) carries no structure: it is written
    // back, exactly, at every output point.
    let output = run("constant.csv");
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let written = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    let mut lines = written.lines();
    assert_eq!(lines.next(), Some("x,y,height"));
    assert!(lines.clone().count() > 50 && lines.all(|line| line.ends_with(",2.5")), "{written}");
    std::fs::remove_file(dir.path().join("out.csv")).unwrap();
    let output = run("missing.csv");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("non-finite") && stderr.contains("\"height\""), "{stderr}");
    assert!(!dir.path().join("out.csv").exists());
}

/// Quilting keeps the count of an inhomogeneous exemplar: the traced chain runs along its window's
/// diagonal, so sources drawn where a whole patch fits all hold more chain than the window's
/// average. The copies alone (before sampling control) must come within 25 % of the count the
/// density asks for (they were at +47 % and +41 % for these seeds when sources were judged on
/// their seams only; +23 % and +21 % now), and the synthesis, which corrects the rest, within 10 %.
#[test]
fn copies_of_an_inhomogeneous_exemplar_keep_its_density() {
    let density = |seed: &str, refine: &str| {
        let (report, _) = run_case_with(
            "chain_contours.csv",
            "30",
            "box:400,400",
            "patches",
            seed,
            &["--exemplar-window", "200,200", "--refine", refine],
        );
        report["fidelity"]["density_ratio"].as_f64().unwrap()
    };
    for seed in ["1", "2"] {
        let copies = density(seed, "none");
        assert!((copies - 1.0).abs() <= 0.25, "seed {seed}: copies at density {copies}");
    }
    let synthesized = density("1", "seams");
    assert!((synthesized - 1.0).abs() <= 0.1, "synthesis at density {synthesized}");
}

/// Quilting steers each patch's source to the parts of the exemplar copied least so far, so the
/// copies use the exemplar more evenly than sources judged by their seams and count alone (which
/// over-weight the exemplar's middle, where whole patches fit), over six seeds of two real cases
/// (usage variation 25–27 % lower in sum), and never less evenly on one seed. The Swedish pines
/// fill 3 × 3 patches of two thirds of the exemplar's side each: on one seed of six the balanced
/// choice is as uneven as the plain one.
#[test]
fn balanced_patches_copy_the_exemplar_more_evenly() {
    for (file, neighbourhood, domain, window, total) in
        [("swedishpines.csv", "32", "box:192,200", "96,100", 0.92), ("redwood.csv", "0.16", "box:2,2", "1,1", 0.8)]
    {
        let (mut plain_sum, mut balanced_sum) = (0.0, 0.0);
        for seed in ["1", "2", "3", "4", "5", "6"] {
            let variation = |balance: &str| {
                let extra = ["--patch-balance", balance, "--exemplar-window", window, "--refine", "none"];
                let (report, _) = run_case_with(file, neighbourhood, domain, "patches", seed, &extra);
                report["patch_usage_variation"].as_f64().unwrap()
            };
            let (plain, balanced) = (variation("0"), variation("0.5"));
            assert!(balanced < 1.01 * plain, "{file} seed {seed}: usage variation {balanced} balanced, {plain} not");
            (plain_sum, balanced_sum) = (plain_sum + plain, balanced_sum + balanced);
        }
        assert!(balanced_sum < total * plain_sum, "{file}: usage variation {balanced_sum} balanced, {plain_sum} not");
    }
}

/// Runs `motif points` with the default (inferred) parameters on a corpus case with its
/// observation window; returns the report and the output CSV.
fn run_default(file: &str, domain: &str, window: &str, seed: &str) -> (serde_json::Value, String) {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = corpus(file);
    let args = ["--seed", seed, "points", "--exemplar", exemplar.to_str().unwrap(), "--domain", domain];
    let rest = ["--exemplar-window", window, "--out", "out.csv", "--report", "report.json"];
    let output = motif(dir.path(), &args.into_iter().chain(rest).collect::<Vec<_>>());
    assert!(output.status.success(), "{file}: {}", String::from_utf8_lossy(&output.stderr));
    let points = std::fs::read_to_string(dir.path().join("out.csv")).unwrap();
    (motif_io::read_json(&dir.path().join("report.json")).unwrap(), points)
}

/// Issue 34: the output's density is within ±3 % of the exemplar's with the default parameters.
/// The Swedish and Japanese pines came out at 0.90–0.92 (held at sampling control's old 10 %
/// bound, since T prefers fewer points where windows reach past the exemplar's window), redwood
/// at 1.07 (copies over the count that too few movable points could correct). Fidelity stays under
/// half the random set's.
#[test]
fn real_patterns_keep_their_density_within_three_percent() {
    let cases = [
        ("swedishpines.csv", "box:192,200", "96,100"),
        ("japanesepines.csv", "box:2,2", "1,1"),
        ("redwood.csv", "box:2,2", "1,1"),
    ];
    for (file, domain, window) in cases {
        for seed in ["1", "3"] {
            let (report, _) = run_default(file, domain, window, seed);
            let density = report["fidelity"]["density_ratio"].as_f64().unwrap();
            assert!((density - 1.0).abs() <= 0.03 + 1e-9, "{file} seed {seed}: density {density}");
            let distance = |set: &str| figure(&report, set, "nearest_neighbour");
            assert!(distance("output") < 0.5 * distance("random"), "{file} seed {seed}: {report}");
        }
    }
}

/// Issue 34: continuous attributes stay within the exemplar's range (longleaf's trunk diameters,
/// 2.0–75.9 cm, seed 3 gave −61 before the attribute step was bounded; the spruces' 0.16–0.37 m).
#[test]
fn attributes_stay_within_the_exemplar_range() {
    let range = |csv: &str, name: &str| {
        let column = csv.lines().next().unwrap().split(',').position(|c| c == name).unwrap();
        let values = csv.lines().skip(1).map(|l| l.split(',').nth(column).unwrap().parse::<f64>().unwrap());
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| (low.min(v), high.max(v)))
    };
    for (file, name, domain, window) in
        [("longleaf.csv", "dbh", "box:400,400", "200,200"), ("spruces.csv", "diameter", "box:112,76", "56,38")]
    {
        let exemplar = range(&std::fs::read_to_string(corpus(file)).unwrap(), name);
        let (_, points) = run_default(file, domain, window, "3");
        let output = range(&points, name);
        assert!(output.0 >= exemplar.0 && output.1 <= exemplar.1, "{file}: {name} {output:?}, exemplar {exemplar:?}");
    }
}
