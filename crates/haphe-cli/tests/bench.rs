//! `haphe bench` end to end on tiny configurations: the JSON records and their fields, both
//! libraries measured, the plots written. Timings are never asserted.

use std::path::PathBuf;
use std::process::{Command, Output};

fn haphe(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_haphe"))
        .args(args)
        .output()
        .expect("the haphe binary runs")
}

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haphe-bench-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// The timed query kinds, as named in the records.
const TIMED: [&str; 7] = [
    "free_space",
    "segment",
    "segment_random",
    "inside",
    "inside_random",
    "walk",
    "floor",
];

#[test]
fn json_has_a_record_per_mesh_query_and_method_with_the_documented_fields() {
    let dir = scratch("json");
    let json = dir.join("bench.json");
    let out = haphe(&[
        "bench",
        "--sizes",
        "500,2000",
        "--samples",
        "300",
        "--json",
        json.to_str().expect("a UTF-8 path"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = String::from_utf8_lossy(&out.stdout);
    for heading in [
        "## free_space",
        "## walk",
        "## build and memory",
        "## targets",
    ] {
        assert!(table.contains(heading), "{heading} missing from\n{table}");
    }

    let text = std::fs::read_to_string(&json).expect("the JSON file is written");
    let records: Vec<serde_json::Value> = serde_json::from_str(&text).expect("a JSON array");
    let meshes = ["blob-500", "blob-2k", "thin-plate-500", "thin-plate-2k"];
    for r in &records {
        for field in ["mesh", "family", "query", "method"] {
            assert!(r[field].is_string(), "{field} in {r}");
        }
        for field in [
            "triangles",
            "samples",
            "p50_ns",
            "p99_ns",
            "p999_ns",
            "max_ns",
        ] {
            assert!(r[field].is_number(), "{field} in {r}");
        }
        assert!(
            meshes.contains(&r["mesh"].as_str().unwrap_or_default()),
            "{r}"
        );
        let p = |f: &str| r[f].as_f64().unwrap_or(f64::NAN);
        assert!(
            p("p50_ns") <= p("p99_ns")
                && p("p99_ns") <= p("p999_ns")
                && p("p999_ns") <= p("max_ns"),
            "percentiles out of order in {r}"
        );
    }
    let find = |mesh: &str, query: &str, method: &str| {
        records
            .iter()
            .find(|r| r["mesh"] == mesh && r["query"] == query && r["method"] == method)
    };
    for mesh in meshes {
        for query in TIMED {
            let haphe =
                find(mesh, query, "haphe").unwrap_or_else(|| panic!("{mesh} {query} haphe"));
            assert!(haphe["samples"].as_u64() > Some(0), "{haphe}");
            assert_eq!(
                haphe["allocations"], 0,
                "haphe's query path allocates nothing: {haphe}"
            );
            if query != "floor" {
                let parry =
                    find(mesh, query, "parry").unwrap_or_else(|| panic!("{mesh} {query} parry"));
                assert!(parry["vs_haphe_p50"].is_number() || parry["vs_haphe_p50"].is_null());
                assert!(
                    find(mesh, query, "brute_force").is_some(),
                    "brute force runs on meshes this small: {mesh} {query}"
                );
            }
        }
        for method in ["haphe", "parry"] {
            let build =
                find(mesh, "build", method).unwrap_or_else(|| panic!("{mesh} build {method}"));
            assert!(build["bytes"].as_u64() > Some(0), "{build}");
        }
        assert!(find(mesh, "decode", "haphe").is_some(), "{mesh} decode");
        let zones = find(mesh, "zones", "haphe").unwrap_or_else(|| panic!("{mesh} zones"));
        assert!(zones["p50_ns"].as_f64() > Some(0.0), "{zones}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn plot_writes_one_png_per_query_kind() {
    let dir = scratch("plot");
    let plots = dir.join("plots");
    let out = haphe(&[
        "bench",
        "--sizes",
        "500,2000",
        "--shapes",
        "sphere",
        "--samples",
        "100",
        "--plot",
        plots.to_str().expect("a UTF-8 path"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for query in TIMED.iter().chain(&["build", "decode", "zones"]) {
        let png = plots.join(format!("{query}.png"));
        let bytes = std::fs::read(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display()));
        assert!(
            bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.len() > 1000,
            "{} is not a plot ({} bytes)",
            png.display(),
            bytes.len()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_arguments_are_refused_with_a_message() {
    let out = haphe(&["bench", "--sizes", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("at least 1"));
    let out = haphe(&["bench", "--shapes", "teapot", "--sizes", "100"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("teapot"));
}
