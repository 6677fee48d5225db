//! Inputs the fuzzers once found a defect with (`tests/fuzz/regressions/`), replayed through
//! the fuzz targets' own checks on stable Rust, so a defect that comes back fails the ordinary
//! test run.

#[path = "fuzz/checks/intersect.rs"]
mod intersect;

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
