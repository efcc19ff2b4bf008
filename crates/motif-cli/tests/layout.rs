//! The house rules that code review alone would let slip: the CLI's modules import each other
//! without a cycle, no source file in the workspace outgrows a reader's head, and front ends go
//! through motif-jobs.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn rust_files(folder: &Path, found: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            found.push(path);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`engines/points/mod.rs` → `engines`).
fn module_of(source: &Path, file: &Path) -> String {
    let relative = file.strip_prefix(source).unwrap();
    let first = relative.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
    first.trim_end_matches(".rs").to_string()
}

/// `crate::name` mentions in code (comments and doc comments left out).
fn crate_references(text: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if !name.is_empty() {
                found.insert(name);
            }
        }
        // `use crate::{a, b::c}` lists.
        if let Some(at) = code.find("use crate::{") {
            for item in code[at + "use crate::{".len()..].split([',', '}']) {
                let name: String = item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if !name.is_empty() {
                    found.insert(name);
                }
            }
        }
    }
    found
}

#[test]
fn cli_modules_import_each_other_without_a_cycle() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&source, &mut files);
    let modules: BTreeSet<String> = files.iter().map(|f| module_of(&source, f)).collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in &files {
        let from = module_of(&source, file);
        if from == "main" {
            continue;
        }
        let text = std::fs::read_to_string(file).unwrap();
        for to in crate_references(&text) {
            assert!(to != "main" && to != "Cli", "{}: modules below main must not use main's items", file.display());
            if to != from && modules.contains(&to) {
                edges.entry(from.clone()).or_default().insert(to);
            }
        }
    }
    // Depth-first search for a back edge.
    fn visit(
        node: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) {
        state.insert(node.to_string(), 1);
        path.push(node.to_string());
        for next in edges.get(node).into_iter().flatten() {
            match state.get(next.as_str()) {
                Some(1) => panic!("import cycle: {} → {next}", path.join(" → ")),
                Some(_) => {}
                None => visit(next, edges, state, path),
            }
        }
        path.pop();
        state.insert(node.to_string(), 2);
    }
    let mut state = BTreeMap::new();
    for node in edges.keys() {
        if !state.contains_key(node) {
            visit(node, &edges, &mut state, &mut Vec::new());
        }
    }
    assert!(edges.contains_key("engines") && edges["engines"].contains("registry"), "{edges:?}");
}

#[test]
fn no_source_file_outgrows_a_reader() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    rust_files(&crates, &mut files);
    let long: Vec<String> = files
        .iter()
        .filter(|f| !f.components().any(|c| c.as_os_str() == "target"))
        .filter_map(|f| {
            let lines = std::fs::read_to_string(f).unwrap().lines().count();
            (lines > 620).then(|| format!("{} ({lines} lines)", f.display()))
        })
        .collect();
    assert!(files.len() > 50, "found only {} files", files.len());
    assert!(long.is_empty(), "split these by concern: {long:?}");
}

/// The engine paths (`motif_points::…`) in `file`'s code before its test module, outside the
/// built-in samples, as `file:line: text`.
fn engine_paths(file: &Path) -> Vec<String> {
    let engines = ["motif_curve::", "motif_points::", "motif_strokes::", "motif_stylize::"];
    let mut found = Vec::new();
    for (number, line) in std::fs::read_to_string(file).unwrap().lines().enumerate() {
        if line.trim() == "#[cfg(test)]" {
            break;
        }
        let code = line.split("//").next().unwrap_or("");
        if engines.iter().any(|engine| code.split(engine).skip(1).any(|rest| !rest.starts_with("samples"))) {
            found.push(format!("{}:{}: {}", file.display(), number + 1, line.trim()));
        }
    }
    found
}

/// Front ends reach the engines only through motif-jobs (ARCHITECTURE.md's layers): no engine
/// path in Python's, the page's or the CLI's running code, outside the built-in samples demos
/// start from; the CLI's bench, corpus and demo files, which call engine measures and reference
/// implementations, are the exception. Python depends on no engine crate.
#[test]
fn front_ends_reach_the_engines_only_through_jobs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let measuring = |file: &Path| {
        let name = file.file_stem().unwrap().to_string_lossy();
        ["bench", "video_bench", "native_bench", "corpus", "demo"].contains(&name.as_ref())
    };
    let mut found = Vec::new();
    for front_end in ["python/src", "web/src", "crates/motif-cli/src"] {
        let mut files = Vec::new();
        rust_files(&root.join(front_end), &mut files);
        assert!(!files.is_empty(), "no Rust file in {front_end}");
        found.extend(files.iter().filter(|file| !measuring(file)).flat_map(|file| engine_paths(file)));
    }
    assert!(found.is_empty(), "go through motif_jobs instead: {found:#?}");
    let manifest = std::fs::read_to_string(root.join("python/Cargo.toml")).unwrap();
    for engine in ["motif-curve", "motif-points", "motif-strokes", "motif-stylize"] {
        assert!(!manifest.contains(engine), "python/Cargo.toml depends on {engine}");
    }
}
