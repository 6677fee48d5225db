//! A lesson's scene read from its YAML file: the ray tree of lesson 08's centre pixel, the
//! lecture's pixel-intensity exercise, printed node by node.
//!
//! ```text
//! cargo run --example lesson_pixel [SCENE.yaml]
//! ```

use std::path::PathBuf;

use raytree::scene::{load, Limits};
use raytree::trace::{RayNode, Tracer};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lessons/08-pixel-intensity/scene.yaml")
        });
    let scene = load(&path, &Limits::default())?;
    let (x, y) = (scene.camera.width / 2, scene.camera.height / 2);
    let inspection = Tracer::new(&scene).inspect_pixel(x, y);
    println!("pixel ({x}, {y}) of {}:", path.display());
    print_tree(&inspection.tree);
    Ok(())
}

/// One line per ray, indented by its depth in the tree.
fn print_tree(node: &RayNode) {
    let indent = "  ".repeat(node.depth as usize);
    let hit = node.hit.as_ref().map_or("nothing".to_string(), |h| {
        format!("{} at t = {:.4}", h.object, h.t)
    });
    println!(
        "{indent}{} (weight {:.3}) hits {hit}: intensity {:.4}",
        node.kind.name(),
        node.weight,
        node.color.x
    );
    for child in &node.children {
        print_tree(child);
    }
}
