//! One portable program, two copies of the fast wing: compiled for any x86-64 (SSE2) and for
//! x86-64-v3 (AVX2), picked when it runs (`raytree::fast::simd`). Both copies must render every
//! image to the last bit as the other does, so as the textbook core does (`fast_paths.rs`
//! checks the copy this processor picks against the core).
//!
//! The level is asked of the processor once per process, so each copy is run in a process of
//! its own: `RAYTREE_CPU_LEVEL=x86-64` makes the program use the baseline copy on a newer
//! processor.

mod common;

use std::path::Path;
use std::process::Command;

/// The PPM image `raytree render` writes for a scene, small, with the level forced down or
/// not, and the level `--stats` reports.
fn render(scene: &Path, baseline: bool, extra: &[&str]) -> (Vec<u8>, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_raytree"));
    cmd.arg("render")
        .arg(scene)
        .args(["-o", "-", "--width", "40", "--height", "30", "--stats"])
        .args(extra)
        .env_remove("RAYTREE_CPU_LEVEL");
    if baseline {
        cmd.env("RAYTREE_CPU_LEVEL", "x86-64");
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

/// Whether this processor runs the x86-64-v3 copy (then the two runs below do use both).
fn processor_is_v3() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        // Every feature `raytree::fast::simd` asks for its x86-64-v3 copy.
        has!("avx")
            && has!("avx2")
            && has!("fma")
            && has!("bmi1")
            && has!("bmi2")
            && has!("lzcnt")
            && has!("movbe")
            && has!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

fn assert_copies_agree(scene: &Path, extra: &[&str]) {
    let (best, best_level) = render(scene, false, extra);
    let (baseline, baseline_level) = render(scene, true, extra);
    assert_eq!(baseline_level, "x86-64", "{}", scene.display());
    if processor_is_v3() {
        assert_eq!(best_level, "x86-64-v3", "{}", scene.display());
    }
    assert!(best.starts_with(b"P6"), "{}: not a PPM", scene.display());
    assert!(
        best == baseline,
        "{} {extra:?}: the {best_level} and x86-64 copies render different images",
        scene.display()
    );
}

/// Every lesson scene, with the scene's own samples per pixel.
#[test]
fn every_lesson_scene_renders_the_same_with_both_copies() {
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
fn every_peer_scene_renders_the_same_with_both_copies() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers");
    let many = std::env::temp_dir().join(format!("raytree-cpu-levels-{}.yaml", std::process::id()));
    std::fs::write(&many, common::many_spheres(10_000)).unwrap();
    for scene in [dir.join("whitted.yaml"), dir.join("csg.yaml"), many.clone()] {
        assert_copies_agree(&scene, &["--spp", "16"]);
        assert_copies_agree(&scene, &["--spp", "4", "--accel", "none"]);
    }
    std::fs::remove_file(&many).unwrap();
}
