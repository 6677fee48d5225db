//! Inputs the fuzzers once found a defect with (`tests/fuzz/regressions/`), replayed through
//! the fuzz targets' own checks on stable Rust, so a defect that comes back fails the ordinary
//! test run.

#[path = "fuzz/checks/intersect.rs"]
mod intersect;

#[path = "fuzz/checks/split.rs"]
mod split;

/// The saved inputs of one fuzz target (`tests/fuzz/regressions/TARGET-*`).
fn saved(target: &str) -> Vec<Vec<u8>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/regressions");
    let mut inputs = vec![];
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with(&format!("{target}-")) {
            inputs.push(std::fs::read(&path).unwrap());
        }
    }
    inputs
}

/// Issue 29's case among them: an object named `x[` at the end of a large list and a light
/// named `y]` after it, which made the parallel loader refuse a valid scene.
#[test]
fn every_saved_split_input_loads_alike_on_any_number_of_threads() {
    let inputs = saved("split");
    assert!(!inputs.is_empty(), "no saved split inputs");
    for input in inputs {
        let text = split::text_of(&input).expect("UTF-8");
        split::check(&text);
    }
}

#[test]
fn every_saved_intersect_input_passes_the_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz/regressions");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("intersect-")
        {
            intersect::check(&std::fs::read(&path).unwrap());
            count += 1;
        }
    }
    assert!(count >= 1, "no saved intersect inputs");
}
