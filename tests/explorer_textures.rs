//! The explorer's details of a hit on a patterned surface: the pattern's value O (with its
//! swatch) and the texture coordinates it was read at, drawn into a TestBackend.

use std::path::Path;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use raytree::render::preview::ColorMode;
use raytree::tui::app::Focus;
use raytree::tui::{input, ui, update, App, Msg};

#[test]
fn details_of_a_hit_on_a_uv_checker() {
    let mut app = App::open(
        Some(Path::new("lessons/16-textures/scene.yaml")),
        ColorMode::TrueColor,
    )
    .expect("opens");
    update(&mut app, Msg::Resize(160, 48));
    app.render_now();
    // Pixel (55, 58) sees the globe.
    update(&mut app, Msg::Pick(55, 58));
    let tab = KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE);
    if let Some(msg) = input::key(&app, &tab) {
        update(&mut app, msg);
    }
    assert_eq!(app.focus, Focus::Tree);
    let n = app.tree.selected_node().unwrap();
    let hit = n.hit.as_ref().unwrap();
    assert_eq!(hit.object, "globe");
    let uv = hit.uv.expect("texture coordinates");
    let color = n
        .local
        .as_ref()
        .unwrap()
        .color
        .expect("the pattern's colour");
    let text = ui::screen_text(&app, 160, 48);
    assert!(
        text.contains(&format!(
            "texture (u, v) = ({}, {})",
            raytree::trace::text::num(uv.x),
            raytree::trace::text::num(uv.y)
        )),
        "{text}"
    );
    assert!(text.contains("O = (0.9, 0.2, 0.2)  (uv_checker 8×4, uv mapping at (u, v) = "));
    assert_eq!(color, glam::DVec3::new(0.9, 0.2, 0.2));
    insta::assert_snapshot!("uv_checker_details_160x48", text);
}
