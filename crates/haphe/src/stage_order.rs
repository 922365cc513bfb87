//! The stages depend on each other in one direction: a stage's code names (`crate::…`) only
//! the stages numbered before it in the crate's documentation, and the support modules
//! (`array`, `names`, `par`, `rng`). The oracles of [`crate::verify`] sit above every stage: a stage's tests
//! may use them, its code may not.

use std::path::Path;

/// The stages in the order they depend on each other (the numbers of the crate docs).
const STAGES: [&str; 7] = ["mesh", "map", "query", "scene", "proxy", "servo", "volume"];

/// Modules every stage may use.
const SUPPORT: [&str; 4] = ["array", "names", "par", "rng"];

/// The modules named by `crate::name` paths in the code of `text` (not in comments, not
/// in a test module: the code after the first `#[cfg(test)]`).
fn named_modules(text: &str) -> Vec<String> {
    let mut names = Vec::new();
    for line in text.lines() {
        let code = line.trim_start();
        if code.starts_with("#[cfg(test)]") {
            break;
        }
        if code.starts_with("//") {
            continue;
        }
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            names.push(name);
        }
    }
    names
}

/// Every `.rs` file under `dir`, except test files (`tests.rs`, `tests/`).
fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "tests" {
                sources(&path, out);
            }
        } else if name.ends_with(".rs") && name != "tests.rs" {
            out.push(path);
        }
    }
}

#[test]
fn no_stage_names_a_later_stage_or_the_oracles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut upward = Vec::new();
    let mut files_read = 0;
    for (level, stage) in STAGES.iter().enumerate() {
        let mut files = Vec::new();
        sources(&src.join(stage), &mut files);
        files.push(src.join(format!("{stage}.rs")).clone());
        for file in files.iter().filter(|f| f.exists()) {
            files_read += 1;
            let text = std::fs::read_to_string(file).unwrap();
            for name in named_modules(&text) {
                let allowed =
                    SUPPORT.contains(&name.as_str()) || STAGES[..=level].contains(&name.as_str());
                if !allowed {
                    upward.push(format!("{} names crate::{name}", file.display()));
                }
            }
        }
    }
    assert!(files_read > 50, "read only {files_read} source files");
    assert!(
        upward.is_empty(),
        "arrows pointing up:\n{}",
        upward.join("\n")
    );
}

#[test]
fn the_scan_sees_code_and_skips_comments_and_tests() {
    let text = "use crate::query::Segment;\n// crate::servo in a comment\n\
                let x = crate::map::CellSize::new();\n#[cfg(test)]\nuse crate::verify::x;\n";
    assert_eq!(named_modules(text), ["query", "map"]);
}
