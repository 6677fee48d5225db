//! One portable program, three copies of the fast wing: compiled for any x86-64 (SSE2), for
//! x86-64-v3 (AVX2) and for x86-64-v4 (AVX-512), picked when it runs (`raytree::fast::simd`).
//! Every copy must render every image to the last bit as the others do, so as the textbook
//! core does (`fast_paths.rs` checks the copy this processor picks against the core).
//!
//! The level is asked of the processor once per process, so each copy is run in a process of
//! its own: `RAYTREE_CPU_LEVEL=x86-64` (or `x86-64-v3`, `x86-64-v4`) makes the program use
//! that copy where the processor runs it.

mod common;

use std::path::Path;
use std::process::Command;

/// The PPM image `raytree render` writes for a scene, small, with the level forced down to
/// `level` or not, and the level `--stats` reports.
fn render(scene: &Path, level: Option<&str>, extra: &[&str]) -> (Vec<u8>, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_raytree"));
    cmd.arg("render")
        .arg(scene)
        .args(["-o", "-", "--width", "40", "--height", "30", "--stats"])
        .args(extra)
        .env_remove("RAYTREE_CPU_LEVEL");
    if let Some(level) = level {
        cmd.env("RAYTREE_CPU_LEVEL", level);
    }
    let out = cmd.output().expect("raytree runs");
    assert!(
        out.status.success(),
        "{}: {}",
        scene.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    let level = stderr
        .lines()
        .find_map(|l| l.strip_prefix("instructions of the fast wing"))
        .expect("--stats names the level")
        .trim()
        .to_string();
    (out.stdout, level)
}

/// The best copy this processor runs: every feature `raytree::fast::simd` asks for it.
fn best_level() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        let v3 = has!("avx")
            && has!("avx2")
            && has!("fma")
            && has!("bmi1")
            && has!("bmi2")
            && has!("lzcnt")
            && has!("movbe")
            && has!("popcnt");
        let v4 = v3
            && has!("avx512f")
            && has!("avx512vl")
            && has!("avx512dq")
            && has!("avx512bw")
            && has!("avx512cd");
        if v4 {
            return "x86-64-v4";
        }
        if v3 {
            return "x86-64-v3";
        }
    }
    "x86-64"
}

/// The copies this processor runs, each named, render the image the program renders with the
/// copy it picks itself, which is one of them.
fn assert_copies_agree(scene: &Path, extra: &[&str]) {
    let (picked, picked_level) = render(scene, None, extra);
    assert!(picked.starts_with(b"P6"), "{}: not a PPM", scene.display());
    let runs: &[&str] = match best_level() {
        "x86-64-v4" => &["x86-64-v4", "x86-64-v3", "x86-64"],
        "x86-64-v3" => &["x86-64-v3", "x86-64"],
        _ => &["x86-64"],
    };
    assert!(runs.contains(&picked_level.as_str()), "{picked_level}");
    for &named in runs {
        let (image, level) = render(scene, Some(named), extra);
        assert_eq!(level, named, "{}", scene.display());
        assert!(
            image == picked,
            "{} {extra:?}: the {picked_level} and {named} copies render different images",
            scene.display(),
        );
    }
}

/// Every lesson scene, with the scene's own samples per pixel.
#[test]
fn every_lesson_scene_renders_the_same_with_every_copy() {
    let scenes = common::lesson_scene_files();
    assert!(
        scenes.len() >= 40,
        "only {} lesson scenes found",
        scenes.len()
    );
    for scene in &scenes {
        assert_copies_agree(scene, &[]);
    }
}

/// The peer scenes (Whitted's spheres, CSG objects, 10 000 spheres in a BVH), at 16 samples
/// per pixel as they are measured, and without the BVH (every object in lanes).
#[test]
fn every_peer_scene_renders_the_same_with_every_copy() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers");
    let many = std::env::temp_dir().join(format!("raytree-cpu-levels-{}.yaml", std::process::id()));
    std::fs::write(&many, common::many_spheres(10_000)).unwrap();
    for scene in [dir.join("whitted.yaml"), dir.join("csg.yaml"), many.clone()] {
        assert_copies_agree(&scene, &["--spp", "16"]);
        assert_copies_agree(&scene, &["--spp", "4", "--accel", "none"]);
    }
    std::fs::remove_file(&many).unwrap();
}
