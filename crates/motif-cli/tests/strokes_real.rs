//! `motif strokes` on the real-data corpus (`data/real/strokes/`, nine public-domain drawings)
//! through `motif bench --engine strokes --case corpus`: counts, overlaps against the reference's
//! rate, border fragments, and spacing against reference elements placed at random.

use std::process::Command;

fn corpus_figures(seed: &str) -> serde_json::Map<String, serde_json::Value> {
    let dir = tempfile::tempdir().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_motif"))
        .current_dir(dir.path())
        .args(["bench", "--engine", "strokes", "--case", "corpus", "--seed", seed, "--out", "b.json"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("b.json")).unwrap()).unwrap();
    value["engines"]["strokes"]["corpus"].as_object().unwrap().clone()
}

fn number(value: &serde_json::Value) -> f64 {
    value.as_f64().unwrap()
}

#[test]
fn real_drawings_keep_their_count_overlap_and_spacing() {
    for seed in ["1", "2"] {
        let cases = corpus_figures(seed);
        assert!(cases.len() >= 9, "{:?}", cases.keys());
        let mut closer_than_random = 0;
        let mut overlaps_prevented = 0;
        for (name, case) in &cases {
            let fidelity = &case["fidelity"];
            // Removing elements to avoid overlaps costs at most a tenth of the count.
            let (output, expected) = (number(&case["output_elements"]), number(&case["expected_elements"]));
            assert!(output >= 0.9 * expected && output <= expected + 1.0, "{name}: {output} of {expected}");
            // No more overlap than the reference shows (within two elements in a hundred).
            let reference = number(&fidelity["reference"]["overlap_rate"]);
            for run in ["output", "output_with_position_variation"] {
                let rate = number(&fidelity[run]["overlap_rate"]);
                assert!(rate <= reference + 0.02, "{name} {run}: overlap {rate} against the reference's {reference}");
            }
            if number(&fidelity["output_with_overlaps_allowed"]["overlap_rate"]) > reference + 0.05 {
                overlaps_prevented += 1;
            }
            let spacing = number(&fidelity["output_with_position_variation"]["spacing"]);
            if spacing < number(&fidelity["random"]["spacing"]) {
                closer_than_random += 1;
            }
        }
        // Without the resolution, elements overlap where the reference's do not.
        assert!(overlaps_prevented >= 3, "seed {seed}: {overlaps_prevented}");
        // With position variation, the spacing of real drawings is closer to theirs than a random
        // placement's is, but for the bundled hatching (lamp) whose bundles no layout keeps.
        assert!(closer_than_random >= 7, "seed {seed}: {closer_than_random} of {}", cases.len());
        // The cropped drawing's cut spines are recognised and not copied.
        let cropped = &cases["cactus_spines_cropped"];
        assert!(number(&cropped["fragment_elements"]) >= 5.0, "{cropped}");
    }
}
