//! Scene parsing and compilation on arbitrary bytes: an error or a scene, never a panic; a
//! scene that compiles renders a tiny image with no NaN.
#![no_main]

use libfuzzer_sys::fuzz_target;
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::{parse, Limits};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match parse(text, "fuzz.yaml", None, &Limits::default()) {
        Err(e) => {
            let shown = e.to_string();
            assert!(!shown.contains('\n'), "multi-line error: {shown}");
            assert!(e.line >= 1 && e.column >= 1);
        }
        Ok(mut scene) => {
            scene.camera = scene.camera.resized(4, 3);
            let options = RenderOptions { max_depth: scene.max_depth.min(3), spp: 1, ..RenderOptions::of(&scene) };
            let (image, _) = render_simple(&scene, options);
            assert!(image.first_non_finite().is_none(), "NaN pixel");
        }
    }
});
