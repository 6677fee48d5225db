//! The README's scene examples must be valid scenes, and its first two commands must exist.

use raytree::scene::{parse, Limits};

#[test]
fn every_scene_example_in_the_readme_parses() {
    let readme = include_str!("../README.md");
    let mut count = 0;
    let mut rest = readme;
    while let Some(start) = rest.find("```yaml\n") {
        let body = &rest[start + 8..];
        let end = body.find("```").expect("closed block");
        let block = &body[..end];
        if block.trim_start().starts_with("camera:") {
            parse(block, "README.md", None, &Limits::default())
                .unwrap_or_else(|e| panic!("{e}\n{block}"));
            count += 1;
        }
        rest = &body[end..];
    }
    assert!(count >= 1);
}

#[test]
fn the_readme_opens_with_the_explorer_and_the_tests() {
    let readme = include_str!("../README.md");
    let block = readme.split("```sh\n").nth(1).unwrap();
    let mut lines = block.lines();
    let explore = lines.next().unwrap();
    assert!(
        explore.starts_with("cargo run --release -- explore lessons/"),
        "{explore}"
    );
    let lesson = explore.split_whitespace().nth(5).unwrap();
    assert!(std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(lesson)
        .join("exercises.yaml")
        .is_file());
    assert!(lines.next().unwrap().starts_with("cargo test"));
}
