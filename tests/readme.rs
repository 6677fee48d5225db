//! The README's scene examples must be valid scenes, its first two commands must exist, and its
//! table of asks must name every ask an exercise may make.

use raytree::lessons::Ask;
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

/// Every `ask` exercises.yaml accepts, as written there: the list serde gives when it refuses
/// an unknown one, so a new ask is in it without anyone adding it here.
fn every_ask() -> Vec<String> {
    let refused = serde_json::from_str::<Ask>("\"no such ask\"").unwrap_err();
    let message = refused.to_string();
    let (_, list) = message
        .split_once("expected one of ")
        .unwrap_or_else(|| panic!("{message}"));
    let asks: Vec<String> = list
        .split(", ")
        .map(|a| a.split('`').nth(1).unwrap().to_string())
        .collect();
    // Each one reads back, so the list is the asks and not a misread message.
    for a in &asks {
        serde_json::from_str::<Ask>(&format!("\"{a}\"")).unwrap_or_else(|e| panic!("{a}: {e}"));
    }
    asks
}

#[test]
fn the_ask_table_names_every_ask() {
    let readme = include_str!("../README.md");
    let (_, after) = readme
        .split_once("`ask` is one of:")
        .expect("the ask table");
    let documented: Vec<&str> = after
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .filter_map(|l| l.strip_prefix("| `")?.split('`').next())
        .collect();
    let asks = every_ask();
    assert!(asks.len() >= 20, "{asks:?}");
    let missing: Vec<&String> = asks
        .iter()
        .filter(|a| !documented.contains(&a.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "the README's ask table leaves out {missing:?}"
    );
    let unknown: Vec<&&str> = documented
        .iter()
        .filter(|d| !asks.iter().any(|a| a == *d))
        .collect();
    assert!(
        unknown.is_empty(),
        "the README's ask table names no such ask {unknown:?}"
    );
}
