//! The explorer under any sequence of keys, clicks, drags, wheel turns and terminal sizes (one
//! cell to wide), on the lesson list and on scenes of every kind: every event is handled, every
//! screen is drawn whole (as many lines as the terminal has), and the picked pixel stays in the
//! image.

use std::path::Path;

mod common;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseEvent, MouseEventKind};
use proptest::prelude::*;
use raytree::render::preview::ColorMode;
use raytree::tui::{input, ui, update, App, Msg};

/// Where the explorer starts: the lesson list, lessons with CSG, triangles, a path-traced
/// scene and textures, and a mirror scene of the tests.
const TARGETS: [Option<&str>; 7] = [
    None,
    Some("lessons/08-pixel-intensity"),
    Some("lessons/10-csg"),
    Some("lessons/11-triangles"),
    Some("lessons/15-path-tracing"),
    Some("lessons/16-textures"),
    Some("tests/scenes/explorer-mirror.yaml"),
];

fn key(code: KeyCode, modifiers: KeyModifiers) -> Event {
    Event::Key(KeyEvent::new(code, modifiers))
}

/// Any event the explorer reads from a terminal, the keys it maps weighted up.
fn event() -> impl Strategy<Value = Event> {
    let chars = prop::sample::select(
        "qgs+-=[]npcdvbm<>,.CrawoeHJKLhjkl? 0123456789,x\u{e9}"
            .chars()
            .collect::<Vec<_>>(),
    );
    let special = prop::sample::select(vec![
        KeyCode::Left,
        KeyCode::Right,
        KeyCode::Up,
        KeyCode::Down,
        KeyCode::Enter,
        KeyCode::Tab,
        KeyCode::BackTab,
        KeyCode::Backspace,
        KeyCode::PageUp,
        KeyCode::PageDown,
        KeyCode::Home,
        KeyCode::End,
        KeyCode::F(1),
    ]);
    let modifiers = prop::sample::select(vec![
        KeyModifiers::NONE,
        KeyModifiers::NONE,
        KeyModifiers::SHIFT,
        KeyModifiers::CONTROL,
    ]);
    let mouse = prop::sample::select(vec![
        MouseEventKind::Down(crossterm::event::MouseButton::Left),
        MouseEventKind::Drag(crossterm::event::MouseButton::Left),
        MouseEventKind::Up(crossterm::event::MouseButton::Left),
        MouseEventKind::ScrollUp,
        MouseEventKind::ScrollDown,
    ]);
    prop_oneof![
        // 'q' and Esc end the session early: rarer than the rest.
        8 => (chars, modifiers.clone())
            .prop_filter("no quit", |(c, m)| !(*c == 'q' || *c == 'c' && *m == KeyModifiers::CONTROL))
            .prop_map(|(c, m)| key(KeyCode::Char(c), m)),
        4 => (special, modifiers).prop_map(|(k, m)| key(k, m)),
        3 => (mouse, 0u16..200, 0u16..70).prop_map(|(kind, column, row)| {
            Event::Mouse(MouseEvent {
                kind,
                column,
                row,
                modifiers: KeyModifiers::NONE,
            })
        }),
        1 => (1u16..220, 1u16..70).prop_map(|(w, h)| Event::Resize(w, h)),
        1 => Just(key(KeyCode::Esc, KeyModifiers::NONE)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn any_events_are_handled_and_drawn(
        target in prop::sample::select(TARGETS.to_vec()),
        (w, h) in (1u16..200, 1u16..60),
        events in prop::collection::vec(event(), 1..40),
    ) {
        common::private_data();
        let mut app = App::open(target.map(Path::new), ColorMode::Ascii).expect("opens");
        update(&mut app, Msg::Resize(w, h));
        app.render_now();
        for ev in &events {
            if let Some(msg) = input::event(&app, ev) {
                update(&mut app, msg);
            }
            app.render_now();
            let (w, h) = app.size;
            let text = ui::screen_text(&app, w, h);
            prop_assert_eq!(text.lines().count(), h as usize);
            if app.quit {
                break;
            }
            if let Some(scene) = app.file.scene.as_ref() {
                let (x, y) = app.tree.pixel();
                prop_assert!(x < scene.camera.width && y < scene.camera.height,
                    "pixel {},{} outside {}×{}", x, y, scene.camera.width, scene.camera.height);
            }
        }
    }
}
