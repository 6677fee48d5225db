//! A scene built in Rust code: a red ball, a mirror behind the eye, one point light. One ray
//! is traced from the eye through the middle of the picture, and its ray tree printed node by
//! node: the primary ray and its shadow ray to the light, the reflection off the ball back to
//! the mirror, and the mirror's reflection onto the ball again, until `max_depth` rays.
//!
//! ```text
//! cargo run --example trace_a_ray
//! ```

use glam::DVec3;
use raytree::geometry::Ray;
use raytree::scene::{MaterialDesc, SceneBuilder, SceneError};
use raytree::trace::{RayNode, Termination, Tracer};

fn main() -> Result<(), SceneError> {
    let scene = SceneBuilder::new()
        .camera(DVec3::new(0.0, 0.0, -5.0), DVec3::ZERO, DVec3::Y, 40.0)
        .image_size(64, 48)
        .background(DVec3::splat(0.1))
        .ambient(DVec3::splat(0.2))
        .max_depth(4)
        .point_light(DVec3::new(-4.0, 5.0, -6.0), DVec3::ONE)
        .material(
            "red",
            MaterialDesc::new(DVec3::new(0.9, 0.1, 0.1))
                .kd(0.7)
                .ks(0.3)
                .shininess(30.0)
                .kr(0.2),
        )
        .material("mirror", MaterialDesc::new(DVec3::ONE).kd(0.1).kr(0.8))
        .sphere(DVec3::ZERO, 1.0, "red")
        .named("ball")
        .plane(DVec3::new(0.0, 0.0, -8.0), DVec3::Z, "mirror")
        .named("mirror")
        .build()?;

    let ray = Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z);
    let tree = Tracer::new(&scene).inspect(&ray);
    print_tree(&tree);
    Ok(())
}

/// One line per ray, indented by its depth in the tree.
fn print_tree(node: &RayNode) {
    let indent = "  ".repeat(node.depth as usize);
    let what = match &node.hit {
        Some(hit) => format!(
            "hits {} at t = {:.4}, point ({:.3}, {:.3}, {:.3})",
            hit.object, hit.t, hit.point.x, hit.point.y, hit.point.z
        ),
        None => match node.shadow {
            Some(s) => format!(
                "reaches light {} with s = {s}",
                node.light.as_deref().unwrap_or("?")
            ),
            None => match node.terminated {
                Some(Termination::Background) | None => "hits nothing".to_string(),
                Some(why) => format!("not traced ({})", why.name()),
            },
        },
    };
    println!(
        "{indent}{} ray, weight {:.3}: {what}; colour ({:.4}, {:.4}, {:.4})",
        node.kind.name(),
        node.weight,
        node.color.x,
        node.color.y,
        node.color.z
    );
    for child in &node.children {
        print_tree(child);
    }
}
