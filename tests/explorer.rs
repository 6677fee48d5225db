//! The terminal explorer, driven without a terminal: keys become messages, `update` changes
//! the model, and screens are drawn into ratatui's TestBackend and snapshotted as plain text
//! (no colours, so the snapshots are stable). One test runs the real binary inside tmux.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod common;

use common::tmux::{have_tmux, Tmux};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use raytree::render::preview::ColorMode;
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::Limits;
use raytree::trace::{RayKind, Tracer};
use raytree::tui::app::{Focus, Screen};
use raytree::tui::{input, ui, update, App, Msg};

const MIRROR: &str = "tests/scenes/explorer-mirror.yaml";
const CSG: &str = "tests/scenes/explorer-csg.yaml";

/// An explorer on `target` in a `w` × `h` terminal, its preview rendered.
fn open(target: &str, color: ColorMode, (w, h): (u16, u16)) -> App {
    common::private_data();
    let mut app = App::open(Some(Path::new(target)), color).expect("opens");
    update(&mut app, Msg::Resize(w, h));
    app.render_now();
    app
}

fn key_event(code: KeyCode) -> KeyEvent {
    let shift = matches!(code, KeyCode::Char(c) if c.is_ascii_uppercase());
    KeyEvent::new(
        code,
        if shift {
            KeyModifiers::SHIFT
        } else {
            KeyModifiers::NONE
        },
    )
}

/// Presses a key as the event loop would: key → message → update; then renders the preview
/// synchronously so screens are deterministic.
fn press(app: &mut App, code: KeyCode) {
    if let Some(msg) = input::key(app, &key_event(code)) {
        update(app, msg);
    }
    app.render_now();
}

fn press_shift(app: &mut App, code: KeyCode) {
    if let Some(msg) = input::key(app, &KeyEvent::new(code, KeyModifiers::SHIFT)) {
        update(app, msg);
    }
    app.render_now();
}

fn keys(app: &mut App, s: &str) {
    for c in s.chars() {
        press(app, KeyCode::Char(c));
    }
}

fn screen(app: &App) -> String {
    ui::screen_text(app, app.size.0, app.size.1)
}

/// A folder of its own for a test's files, below target/ (relative, so screens that show
/// the path are the same on every machine).
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new("target/explorer-tests").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn root_color(app: &App) -> glam::DVec3 {
    app.tree.full_tree().unwrap().color
}

fn traced_color(app: &App, depth: u32) -> glam::DVec3 {
    let scene = app.file.scene.as_ref().unwrap();
    let ray = scene
        .camera
        .pixel_ray(app.tree.pixel().0, app.tree.pixel().1);
    Tracer::new(scene).with_depth(depth).inspect(&ray).color
}

// ---------------------------------------------------------------------------------------
// Snapshots

#[test]
fn preview_and_tree_at_80x24() {
    // ASCII mode: the preview's ramp characters show the image in the snapshot.
    let mut app = open(MIRROR, ColorMode::Ascii, (80, 24));
    update(&mut app, Msg::Pick(20, 15));
    insta::assert_snapshot!("preview_tree_80x24", screen(&app));
}

#[test]
fn preview_and_tree_at_160x48() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    insta::assert_snapshot!("preview_tree_160x48", screen(&app));
}

#[test]
fn details_of_a_reflection_node() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.focus, Focus::Tree);
    // primary → its shadow ray → its reflection.
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    let n = app.tree.selected_node().unwrap();
    assert_eq!(n.kind, RayKind::Reflection);
    assert_eq!(n.hit.as_ref().unwrap().object, "glass");
    let text = screen(&app);
    assert!(text.contains("details · reflection"));
    assert!(text.contains("kr·I_r"));
    assert!(text.contains("kt·I_t"));
    insta::assert_snapshot!("reflection_details_160x48", text);
    // The same at 80 × 24: the details scroll.
    update(&mut app, Msg::Resize(80, 24));
    app.render_now();
    insta::assert_snapshot!("reflection_details_80x24", screen(&app));
}

#[test]
fn csg_panel() {
    let mut app = open(CSG, ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Pick(20, 15));
    press(&mut app, KeyCode::Char('c'));
    assert!(app.csg.shown());
    let text = screen(&app);
    assert!(text.contains("object lens"));
    assert!(text.contains("intersection lens: [8.334689, 11.638107]"));
    insta::assert_snapshot!("csg_80x24", text);

    // A ray that misses one sphere's bounding box: that node is pruned, and marked so.
    let mut app = open(CSG, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(10, 8));
    press(&mut app, KeyCode::Char('c'));
    let text = screen(&app);
    assert!(text.contains("object pair"));
    assert!(text.contains("sphere bottom: pruned: ray misses its bounding box"));
    insta::assert_snapshot!("csg_160x48", text);
    press(&mut app, KeyCode::Char('c'));
    assert!(!app.csg.shown());
    assert!(screen(&app).contains("details · primary ray"));
}

#[test]
fn help_screen() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    press(&mut app, KeyCode::Char('?'));
    assert!(app.show_help);
    let text = screen(&app);
    for (k, what) in ui::KEYS {
        assert!(
            text.contains(what) || text.contains(&what.to_uppercase()),
            "{k}: {what}"
        );
    }
    insta::assert_snapshot!("help_80x24", text);
    press(&mut app, KeyCode::Char('x'));
    assert!(!app.show_help, "any key closes the help");
    assert!(!app.quit);
}

/// A lesson of our own (the real ones are still being written), with a pixel exercise.
fn demo_lesson(name: &str) -> PathBuf {
    let root = scratch(name);
    let dir = root.join("01-demo");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(MIRROR, dir.join("scene.yaml")).unwrap();
    std::fs::write(
        dir.join("README.md"),
        "# 01 — A demo lesson\n\nPick the pixel (20, 15): the ray hits the mirror ball, and the \
         mirror sends a ray on to the glass ball, which both reflects and refracts.\n\n\
         ## What to do\n\n1. Find the primary ray's intensity.\n2. Find the reflection \
         node's intensity.\n\n```\np ──► mirror ──► glass\n```\n\n**Answer (root):** see \
         the tree.\n",
    )
    .unwrap();
    // A ray exercise whose ray happens to be pixel (10, 12)'s primary ray.
    let scene = raytree::scene::load(Path::new(MIRROR), &Default::default()).unwrap();
    let ray = scene.camera.pixel_ray(10, 12);
    let v = |v: glam::DVec3| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z);
    std::fs::write(
        dir.join("exercises.yaml"),
        format!(
            "title: A demo lesson\nsummary: One pixel, a mirror and a glass ball.\nexercises:\n  \
             - id: root\n    question: What is the intensity of pixel (20, 15)?\n    \
             ask: intensity\n    pixel: [20, 15]\n  - id: mirror-t\n    question: How far \
             from the eye is the mirror ball along that ray?\n    ask: hit_t\n    \
             pixel: [20, 15]\n  - id: ray-t\n    question: Where does this ray hit?\n    \
             ask: hit_t\n    ray: {{ origin: {}, direction: {} }}\n",
            v(ray.origin),
            v(ray.dir)
        ),
    )
    .unwrap();
    root
}

/// A README as teachers write them: emphasis, a nested list, a table, code and a link, laid
/// out as Markdown (no `**` or `|` left over, columns lined up, items hanging under their text).
#[test]
fn lesson_readme_renders_markdown() {
    let root = demo_lesson("lesson-markdown");
    let dir = root.join("01-demo");
    std::fs::write(
        dir.join("README.md"),
        "# 01 — Markdown\n\nThe *local* term is **ka·Ia·O**, written `I = ka Ia O` in the \
         [notes](https://example.org/notes).\n\n\
         1. Trace the primary ray through the pixel centre and find its nearest hit point on \
         the mirror ball.\n   - then its shadow ray,\n   - then its reflection.\n\
         2. Add the terms.\n\n\
         | term | symbol | value |\n|---|---|---:|\n| ambient | ka·Ia | 0.1 |\n\
         | diffuse | kd·(n·l) | 0.45 |\n\n\
         ```\nI = 0.1 + 0.45\n  = 0.55\n```\n\n> A quote, *softly*.\n",
    )
    .unwrap();
    let app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    assert!(app.lesson_open());
    let text = screen(&app);
    assert!(!text.contains("**") && !text.contains("|---"), "{text}");
    assert!(text.contains("ambient │ ka·Ia"), "{text}");
    insta::assert_snapshot!("lesson_markdown_160x48", text);
}

/// A figure drawn in a code block is never wrapped, which would break its lines apart: the pane
/// shows it through a window that ← → move once the README has the focus, with ‹ › where it
/// goes on. A shell command wider than the pane wraps instead.
#[test]
fn a_wide_figure_in_a_readme_stays_whole_and_moves_sideways() {
    let root = demo_lesson("lesson-figure");
    let dir = root.join("01-demo");
    let rule = "-".repeat(70);
    std::fs::write(
        dir.join("README.md"),
        format!(
            "# 01 — A figure\n\n```\nleft  +{rule}+  right\n      | eye ──► ball{}|\n```\n\n\
             ```sh\nraytree render lessons/01-demo/scene.yaml --width 640 --height 480 -o \
             demo.png\n```\n",
            " ".repeat(58)
        ),
    )
    .unwrap();
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    let pane = app.panes().lesson.expect("the README is open");
    let text = pane_text(&app, pane);
    let rows: Vec<&str> = text.lines().collect();
    // 85 cells of figure in a pane 62 wide: cut at the right edge, not wrapped.
    assert_eq!(pane.width - 2, 62);
    assert!(
        rows[2].starts_with("left  +---") && rows[2].ends_with("-›"),
        "{text}"
    );
    assert!(rows[3].starts_with("      | eye ──► ball"), "{text}");
    assert!(!text.contains("right"), "{text}");
    assert!(text.contains("raytree render lessons/01-demo/scene.yaml --width 640 --height"));
    assert!(
        text.contains("\n    480 -o demo.png"),
        "the command wraps: {text}"
    );
    assert!(screen(&app).contains("Tab, ← →: the figures sideways"));

    // ← → move the pixel until the README has the focus.
    while app.focus != Focus::Lesson {
        press(&mut app, KeyCode::Tab);
    }
    for _ in 0..3 {
        press(&mut app, KeyCode::Right);
    }
    let moved = pane_text(&app, pane);
    let rows: Vec<&str> = moved.lines().collect();
    // As far as the widest line goes: its last 61 cells after the ‹.
    assert_eq!(app.lesson.as_ref().unwrap().pan, 85 - 62);
    assert!(
        rows[2].starts_with('‹') && rows[2].ends_with("-+  right"),
        "{moved}"
    );
    assert!(
        rows[3].starts_with('‹') && rows[3].trim_end().ends_with('|'),
        "{moved}"
    );
    assert!(
        moved.contains("\n    480 -o demo.png"),
        "commands stay: {moved}"
    );
    insta::assert_snapshot!("lesson_figure_moved_sideways", moved);
    for _ in 0..3 {
        press(&mut app, KeyCode::Left);
    }
    assert_eq!(pane_text(&app, pane), text);

    // Moved sideways, then a terminal wide enough for the whole figure: it is shown whole.
    for _ in 0..3 {
        press(&mut app, KeyCode::Right);
    }
    update(&mut app, Msg::Resize(260, 48));
    let wide = app.panes().lesson.unwrap();
    assert!(wide.width - 2 >= 85, "{wide:?}");
    let whole = pane_text(&app, wide);
    assert!(
        whole.contains("left  +---") && whole.contains("-+  right"),
        "{whole}"
    );
    assert!(!whole.contains('‹') && !whole.contains('›'), "{whole}");
}

#[test]
fn lesson_panel_with_a_checked_answer() {
    let root = demo_lesson("lesson-panel");
    let dir = root.join("01-demo");
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    assert!(app.lesson_open());
    let text = screen(&app);
    assert!(text.contains("A demo lesson"));
    assert!(text.contains("What to do"));
    insta::assert_snapshot!("lesson_readme_160x48", text);

    press(&mut app, KeyCode::Char('a'));
    assert_eq!(app.focus, Focus::Lesson);
    assert_eq!(app.tree.pixel(), (20, 15), "the exercise's pixel is picked");
    // The right answer to `root`, as raytree computes it.
    let lesson = &app.lesson.as_ref().unwrap().lesson;
    let ex = lesson.exercise("root").unwrap();
    let expected = raytree::lessons::work(lesson, ex).unwrap().expected.show();
    press(&mut app, KeyCode::Enter);
    keys(&mut app, &expected);
    press(&mut app, KeyCode::Enter);
    let answered = app.lesson.as_ref().unwrap().answers[0].as_ref().unwrap();
    assert!(answered.result.as_ref().unwrap().correct);
    // A wrong answer to the second exercise.
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Enter);
    keys(&mut app, "1.5");
    press(&mut app, KeyCode::Enter);
    let answered = app.lesson.as_ref().unwrap().answers[1].as_ref().unwrap();
    assert!(!answered.result.as_ref().unwrap().correct);
    // The ray exercise picks the pixel whose primary ray it is.
    press(&mut app, KeyCode::Down);
    assert_eq!(app.tree.pixel(), (10, 12));
    assert!(screen(&app).contains("the primary ray of pixel 10,12"));
    press(&mut app, KeyCode::Up);
    press(&mut app, KeyCode::Up);
    assert_eq!(app.tree.pixel(), (20, 15));
    let text = screen(&app);
    assert!(text.contains("right:"));
    insta::assert_snapshot!("lesson_answer_160x48", text);
    // w: the worked solution, below the verdict.
    press(&mut app, KeyCode::Char('w'));
    let text = screen(&app);
    assert!(text.contains("worked solution (w hides):"), "{text}");
    press(&mut app, KeyCode::Char('w'));
    assert!(!screen(&app).contains("worked solution (w hides):"));
    // Esc leaves the exercises without quitting; q would quit.
    press(&mut app, KeyCode::Esc);
    assert!(!app.quit);
    assert_eq!(app.focus, Focus::Preview);
}

/// The explorer's answer box, driven with keys on lesson 08: the README's hand-worked answer
/// to the first exercise is typed in and marked right. (That the number itself is right is
/// pinned in tests/lessons.rs against raytree's computation; here the UI is under test.)
#[test]
fn a_real_lesson_opens_and_checks_answers() {
    let dir = Path::new("lessons/08-pixel-intensity");
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (80, 24));
    press(&mut app, KeyCode::Char('a'));
    let lesson = &app.lesson.as_ref().unwrap().lesson;
    let ex = &lesson.exercises[0];
    let (_, hand_worked) = lesson
        .stated_answers()
        .into_iter()
        .find(|(id, _)| *id == ex.id)
        .expect("lesson 08's README states the first exercise's answer");
    press(&mut app, KeyCode::Enter);
    keys(&mut app, &hand_worked);
    press(&mut app, KeyCode::Enter);
    let text = screen(&app);
    assert!(text.contains("right:"), "{text}");
}

/// In a 40 × 12 terminal the lesson panel has three rows inside its border: lesson 08's
/// exercises there keep the prompt (how to answer, then the answer given and its verdict) in
/// sight, with the selected exercise above it, and the footer says which of the nine
/// exercises is shown. At every height from there up the prompt stays, and a footer never
/// counts an empty range.
#[test]
fn the_exercises_keep_the_prompt_in_a_small_terminal() {
    let dir = Path::new("lessons/08-pixel-intensity");
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (40, 12));
    press(&mut app, KeyCode::Char('a'));
    let lesson = app.lesson.as_ref().unwrap().lesson.clone();
    let count = lesson.exercises.len();
    assert_eq!(count, 9);
    // (The mark beside the exercise depends on whether another test answered it already.)
    let selected = |text: &str, id: &str| {
        text.lines()
            .any(|l| l.contains('▶') && l.contains(&format!(" {id}  ")))
    };
    let text = screen(&app);
    assert!(selected(&text, "local-a"), "{text}");
    assert!(text.contains("Enter: answer as"), "{text}");
    assert!(text.contains(&format!(" exercise 1 of {count} ")), "{text}");

    // The last exercise: the footer follows the selection.
    for _ in 1..count {
        press(&mut app, KeyCode::Down);
    }
    let last = &lesson.exercises[count - 1].id;
    let text = screen(&app);
    assert!(selected(&text, last), "{text}");
    assert!(
        text.contains(&format!(" exercise {count} of {count} ")),
        "{text}"
    );

    // Typed on the message line, the answer is kept and its verdict shown in the pinned rows.
    press(&mut app, KeyCode::Enter);
    keys(&mut app, "0.5");
    assert!(screen(&app).contains(&format!("answer to {last}: 0.5")));
    press(&mut app, KeyCode::Enter);
    let text = screen(&app);
    assert!(text.contains("your answer: 0.5"), "{text}");
    assert!(text.contains("wrong"), "{text}");

    for h in 12..=48 {
        let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (40, h));
        press(&mut app, KeyCode::Char('a'));
        let text = screen(&app);
        assert!(text.contains("Enter: answer as"), "40×{h}: {text}");
        assert!(!text.contains("–0 "), "40×{h}: {text}");
        let listed = (0..count)
            .filter(|&i| text.contains(&format!("  {}  ", lesson.exercises[i].id)))
            .count();
        if listed < count {
            assert!(text.contains(&format!("1 of {count}")), "40×{h}: {text}");
        }
    }
}

#[test]
fn lesson_list() {
    let root = demo_lesson("lesson-list");
    let mut app = App::open_lessons(&root, ColorMode::TrueColor);
    update(&mut app, Msg::Resize(80, 24));
    assert_eq!(app.screen, Screen::Lessons);
    let text = screen(&app);
    assert!(text.contains("01-demo"));
    insta::assert_snapshot!("lesson_list_80x24", text);
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.screen, Screen::Scene);
    assert!(app.lesson_open());
    assert!(app.file.scene.is_some());
}

/// A copy of the lesson `from`'s files in a lesson folder `to` beside it.
fn copy_lesson(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, to.join(path.file_name().unwrap())).unwrap();
    }
}

/// `o` over a lesson of the user's own folder of lessons (exported or copied, not named by
/// `--lessons`) lists that folder, the open lesson selected, and opens its lessons; over a
/// lesson alone in its folder it lists the lessons root's, as without a lesson.
#[test]
fn o_lists_the_folder_of_lessons_the_open_lesson_came_from() {
    common::private_data();
    let root = demo_lesson("own-lessons");
    copy_lesson(&root.join("01-demo"), &root.join("02-again"));
    // A folder that is no lesson is not listed.
    std::fs::create_dir_all(root.join("notes")).unwrap();
    let mut app = open(
        root.join("02-again").to_str().unwrap(),
        ColorMode::TrueColor,
        (80, 24),
    );
    press(&mut app, KeyCode::Char('o'));
    assert_eq!(app.screen, Screen::Lessons);
    let list = app.list.as_ref().unwrap();
    assert_eq!(list.root, root);
    let dirs: Vec<&Path> = list.entries.iter().map(|e| e.dir.as_path()).collect();
    assert_eq!(dirs, [root.join("01-demo"), root.join("02-again")]);
    assert_eq!(list.selected, 1, "the open lesson is selected");
    let text = screen(&app);
    assert!(
        text.contains("01-demo") && text.contains("02-again"),
        "{text}"
    );
    press(&mut app, KeyCode::Up);
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.screen, Screen::Scene);
    assert_eq!(app.file.path, Some(root.join("01-demo").join("scene.yaml")));
    press(&mut app, KeyCode::Char('o'));
    assert_eq!(app.list.as_ref().unwrap().root, root);
    assert_eq!(app.list.as_ref().unwrap().selected, 0);

    // A lesson alone in its folder: the usual lessons root.
    let lone = demo_lesson("lone-lesson");
    let mut app = open(
        lone.join("01-demo").to_str().unwrap(),
        ColorMode::TrueColor,
        (80, 24),
    );
    press(&mut app, KeyCode::Char('o'));
    assert_eq!(
        app.list.as_ref().unwrap().root,
        raytree::lessons::lessons_root().unwrap()
    );
}

#[test]
fn live_reload_keeps_the_last_good_scene_and_shows_the_error() {
    let dir = scratch("live-reload");
    let path = dir.join("scene.yaml");
    let good = std::fs::read_to_string(MIRROR).unwrap();
    std::fs::write(&path, &good).unwrap();
    let mut app = open(path.to_str().unwrap(), ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Pick(40, 30));
    let before = root_color(&app);

    // A typo: the file no longer parses.
    std::fs::write(&path, good.replace("radius: 1 }", "radius: [1 }")).unwrap();
    update(&mut app, Msg::Tick);
    let err = app.file.error.clone().expect("the broken file is reported");
    assert!(
        err.starts_with("target/explorer-tests/live-reload/scene.yaml:"),
        "{err}"
    );
    assert!(app.file.scene.is_some(), "the last good scene stays");
    assert_eq!(root_color(&app), before);
    let text = screen(&app);
    assert!(text.contains("✗ target/explorer-tests/live-reload/scene.yaml:"));
    insta::assert_snapshot!("reload_error_80x24", text);

    // Fixed, and smaller: the picked pixel is kept inside the image.
    let smaller = good
        .replace("width: 48, height: 36", "width: 24, height: 18")
        .replace("background: [0.2, 0.3, 0.5]", "background: [0.5, 0.3, 0.2]");
    std::fs::write(&path, smaller).unwrap();
    update(&mut app, Msg::Tick);
    assert!(app.file.error.is_none());
    assert_eq!(app.image_size(), (24, 18));
    assert_eq!(app.tree.pixel(), (23, 17));
    let note = app.message_text().unwrap().0;
    assert!(
        note.ends_with("(fixed) · the image is now 24 × 18: pixel 40,30 moved to 23,17"),
        "{note}"
    );
    assert!(app.preview.job.is_some(), "the preview renders again");
    // Nothing changed: nothing happens.
    let generation = app.preview.generation;
    update(&mut app, Msg::Tick);
    assert_eq!(app.preview.generation, generation);
}

/// A reload error from a scene deep in folders, at 80 columns: its place wraps over the first
/// line, and the lines below still show why (the path alone filled the two lines there were).
#[test]
fn a_reload_error_shows_why_below_a_long_path() {
    let dir = scratch("reload-long-path")
        .join("home/student/courses/computer-graphics/raytree-lessons/06-refraction");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.yaml");
    let good = std::fs::read_to_string(MIRROR).unwrap();
    std::fs::write(&path, &good).unwrap();
    let mut app = open(path.to_str().unwrap(), ColorMode::TrueColor, (80, 24));
    std::fs::write(&path, good.replace("radius: 1 }", "radius: -1 }")).unwrap();
    update(&mut app, Msg::Tick);
    assert!(app.file.error.is_some());
    let text = screen(&app);
    assert!(text.contains("radius must be > 0"), "{text}");
    assert!(text.contains("(the last good scene stays)"), "{text}");
}

/// A scene reloads when a file it reads changes, not only its own: the torus's mesh shrunk to
/// half its size on disk, the picked pixel on its rim now sees the background. Nothing
/// changed: nothing reloads.
#[test]
fn live_reload_follows_the_mesh_a_scene_reads() {
    let dir = scratch("live-reload-mesh");
    for file in ["torus.yaml", "torus.obj"] {
        std::fs::copy(Path::new("lessons/11-triangles").join(file), dir.join(file)).unwrap();
    }
    let mut app = open(
        dir.join("torus.yaml").to_str().unwrap(),
        ColorMode::TrueColor,
        (80, 24),
    );
    let (w, h) = app.image_size();
    // The pixel on the torus nearest the image's left edge along the middle row.
    let rim = (0..w)
        .find(|&x| {
            update(&mut app, Msg::Pick(x, h / 2));
            app.tree.full_tree().unwrap().hit.is_some()
        })
        .expect("the torus crosses the middle row");
    let generation = app.preview.generation;
    update(&mut app, Msg::Tick);
    assert_eq!(app.preview.generation, generation, "nothing changed");

    let obj = std::fs::read_to_string(dir.join("torus.obj")).unwrap();
    let half: String = obj
        .lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(xyz) => {
                let v: Vec<f64> = xyz.split_whitespace().map(|c| c.parse().unwrap()).collect();
                format!("v {} {} {}\n", v[0] / 2.0, v[1] / 2.0, v[2] / 2.0)
            }
            None => format!("{l}\n"),
        })
        .collect();
    std::fs::write(dir.join("torus.obj"), half).unwrap();
    update(&mut app, Msg::Tick);
    assert!(app.file.error.is_none(), "{:?}", app.file.error);
    assert_ne!(
        app.preview.generation, generation,
        "the preview renders again"
    );
    update(&mut app, Msg::Pick(rim, h / 2));
    assert!(
        app.tree.full_tree().unwrap().hit.is_none(),
        "pixel {rim},{}: the shrunk torus is no longer there",
        h / 2
    );
}

// ---------------------------------------------------------------------------------------
// Keys and state

/// The message line's key hint follows the focus: arrows pick a pixel in the preview, select
/// a ray in the tree, scroll a panel; a warning is not replaced by a hint.
#[test]
fn the_key_hint_follows_the_focus() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (120, 36));
    assert!(
        screen(&app).contains("←↑↓→ pick a pixel"),
        "{}",
        screen(&app)
    );
    press(&mut app, KeyCode::Tab);
    let text = screen(&app);
    assert!(
        text.contains("↑↓ select a ray") && !text.contains("pick a pixel"),
        "{text}"
    );
    press(&mut app, KeyCode::Tab);
    assert!(
        screen(&app).contains("scroll the panel"),
        "{}",
        screen(&app)
    );
    press(&mut app, KeyCode::BackTab);
    assert!(screen(&app).contains("↑↓ select a ray"), "{}", screen(&app));
    // A click moves the focus, and the hint with it (it stayed the preview's).
    press(&mut app, KeyCode::BackTab);
    assert!(screen(&app).contains("←↑↓→ pick a pixel"));
    let p = app.panes();
    update(&mut app, Msg::Click(p.tree.x + 5, p.tree.y + 2));
    assert_eq!(app.focus, Focus::Tree);
    let text = screen(&app);
    assert!(
        text.contains("↑↓ select a ray") && !text.contains("pick a pixel"),
        "{text}"
    );
}

/// A good pick after a refused one leaves the keys' hint on the message line, not nothing.
#[test]
fn a_good_pick_after_a_bad_one_shows_the_keys_again() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (120, 36));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "abc");
    press(&mut app, KeyCode::Enter);
    let refused = app.message_text().unwrap().0;
    assert!(!refused.contains("pick a pixel"), "{refused}");
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "7,7");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (7, 7));
    let text = screen(&app);
    assert!(text.contains("←↑↓→ pick a pixel"), "{text}");
}

/// Level stepping, then another pixel: the message line speaks of the new pixel's levels
/// (it kept the old pixel's "level 1 gave …").
#[test]
fn the_level_note_follows_the_picked_pixel() {
    let mut app = open(
        "lessons/08-pixel-intensity",
        ColorMode::TrueColor,
        (160, 48),
    );
    press(&mut app, KeyCode::Char('n'));
    press(&mut app, KeyCode::Char('n'));
    let before = app.message_text().unwrap().0;
    assert!(before.starts_with("level 2 of 5"), "{before}");
    press(&mut app, KeyCode::Right);
    assert_eq!(app.tree.pixel(), (31, 30));
    let after = app.message_text().unwrap().0;
    assert_eq!(Some(after.clone()), app.tree.level_note().map(|n| n.0));
    assert_ne!(after, before);
}

#[test]
fn cursor_moves_and_clamps_at_the_edges() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    assert_eq!(app.tree.pixel(), (24, 18), "starts at the centre");
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Char('l'));
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Char('j'));
    press(&mut app, KeyCode::Char('k'));
    assert_eq!(app.tree.pixel(), (26, 19));
    press(&mut app, KeyCode::Char('h'));
    press(&mut app, KeyCode::Left);
    press(&mut app, KeyCode::Up);
    assert_eq!(app.tree.pixel(), (24, 18));
    // Big steps: H J K L and shift + arrows move 10 pixels.
    press(&mut app, KeyCode::Char('L'));
    assert_eq!(app.tree.pixel(), (34, 18));
    press_shift(&mut app, KeyCode::Down);
    assert_eq!(app.tree.pixel(), (34, 28));
    press(&mut app, KeyCode::Char('J'));
    assert_eq!(app.tree.pixel(), (34, 35), "clamped at the bottom edge");
    press(&mut app, KeyCode::Char('L'));
    assert_eq!(app.tree.pixel(), (44, 35));
    press(&mut app, KeyCode::Char('L'));
    assert_eq!(app.tree.pixel(), (47, 35), "clamped at the right edge");
    for _ in 0..6 {
        press(&mut app, KeyCode::Char('H'));
        press_shift(&mut app, KeyCode::Up);
    }
    assert_eq!(app.tree.pixel(), (0, 0));
    press(&mut app, KeyCode::Left);
    press(&mut app, KeyCode::Up);
    assert_eq!(app.tree.pixel(), (0, 0));
    // The tree follows the pixel.
    let scene = app.file.scene.clone().unwrap();
    let ray = scene.camera.pixel_ray(0, 0);
    assert_eq!(app.tree.full_tree().unwrap().direction, ray.dir);
}

#[test]
fn goto_typed_coordinates() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "3,4");
    assert!(screen(&app).contains("go to pixel x,y: 3,4"));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (3, 4));
    assert!(app.prompt.is_none());
    // Outside the image: refused, said so.
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "48, 2");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (3, 4));
    assert!(screen(&app).contains("pixel 48,2 is outside the 48 × 36 image"));
    // Typing is typing: q in a prompt is a letter; Backspace and Esc work.
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "q1");
    press(&mut app, KeyCode::Backspace);
    press(&mut app, KeyCode::Backspace);
    keys(&mut app, "47 35");
    assert!(!app.quit);
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (47, 35));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "1,1");
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.tree.pixel(), (47, 35));
    assert!(!app.quit);
}

#[test]
fn a_good_pick_clears_the_error_of_a_bad_one() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "10,abc");
    press(&mut app, KeyCode::Enter);
    let error = "expected a pixel x,y (two whole numbers), got `10,abc`";
    assert!(screen(&app).contains(error));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "10,20");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (10, 20));
    assert!(!screen(&app).contains(error), "{}", screen(&app));
    // So does one outside the image.
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "48,2");
    press(&mut app, KeyCode::Enter);
    let outside = "pixel 48,2 is outside the 48 × 36 image";
    assert!(screen(&app).contains(outside));
    press(&mut app, KeyCode::Char('g'));
    keys(&mut app, "3,4");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.tree.pixel(), (3, 4));
    assert!(!screen(&app).contains(outside), "{}", screen(&app));
}

#[test]
fn depth_keys_retrace_at_that_depth() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Pick(20, 15));
    assert_eq!(app.tree.depth(), 4);
    let full = root_color(&app);
    assert_eq!(full, traced_color(&app, 4));
    press(&mut app, KeyCode::Char('-'));
    assert_eq!(app.tree.depth(), 3);
    assert_eq!(root_color(&app), traced_color(&app, 3));
    press(&mut app, KeyCode::Char('['));
    press(&mut app, KeyCode::Char('-'));
    assert_eq!(app.tree.depth(), 1);
    // Depth 1: the primary ray only (local light), its reflection not traced.
    let tree = app.tree.full_tree().unwrap();
    let local = tree.local.as_ref().unwrap().total();
    assert_eq!(tree.color, local);
    assert!(tree.color != full);
    assert!(tree
        .children
        .iter()
        .any(|c| c.terminated == Some(raytree::trace::Termination::MaxDepth)));
    press(&mut app, KeyCode::Char('-'));
    assert_eq!(app.tree.depth(), 1, "no lower than 1");
    press(&mut app, KeyCode::Char('+'));
    press(&mut app, KeyCode::Char(']'));
    press(&mut app, KeyCode::Char('='));
    assert_eq!(app.tree.depth(), 4);
    assert_eq!(root_color(&app), full);
    // The preview is rendered at the depth too.
    press(&mut app, KeyCode::Char('-'));
    assert!(app.preview.stats.unwrap().reflection_rays > 0);
    let status = screen(&app);
    assert!(status.contains("depth 3"));
}

#[test]
fn level_stepping_collects_intensity_level_by_level() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    let full = root_color(&app);
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(app.tree.level(), Some(1));
    let shown = app.tree.shown_tree().unwrap();
    assert_eq!(shown.color, traced_color(&app, 1));
    assert!(shown.secondary().all(|c| c.terminated.is_some()));
    let text = screen(&app);
    assert!(text.contains("level 1 of 4"));
    press(&mut app, KeyCode::Char('n'));
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(app.tree.level(), Some(3));
    assert_eq!(app.tree.shown_tree().unwrap().color, traced_color(&app, 3));
    assert_eq!(app.tree.partials().len(), 4);
    for (k, p) in app.tree.partials().iter().enumerate() {
        assert_eq!(*p, traced_color(&app, k as u32 + 1));
    }
    insta::assert_snapshot!("levels_160x48", screen(&app));
    press(&mut app, KeyCode::Char('p'));
    assert_eq!(app.tree.level(), Some(2));
    press(&mut app, KeyCode::Char('n'));
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(app.tree.level(), Some(4));
    assert_eq!(app.tree.shown_tree().unwrap().color, full);
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(
        app.tree.level(),
        None,
        "past the last level: the whole tree again"
    );
    assert!(screen(&app).contains("all 4 levels collected"));
    // Moving the pixel while stepping keeps the level.
    press(&mut app, KeyCode::Char('p'));
    assert_eq!(app.tree.level(), Some(3));
    press(&mut app, KeyCode::Right);
    assert_eq!(app.tree.level(), Some(3));
    assert_eq!(app.tree.shown_tree().unwrap().color, traced_color(&app, 3));
}

#[test]
fn tree_expands_and_collapses() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    let all = app.tree.rows().len();
    assert_eq!(
        all,
        app.tree.full_tree().unwrap().size(),
        "small trees open fully"
    );
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Left);
    assert_eq!(app.tree.rows().len(), 1, "the root closed");
    assert!(screen(&app).contains("▶▸ primary: hit mirror"));
    press(&mut app, KeyCode::Right);
    assert_eq!(app.tree.rows().len(), all);
    // Down to the reflection, close it, and Left again goes to the parent.
    press(&mut app, KeyCode::Char('j'));
    press(&mut app, KeyCode::Char('j'));
    assert_eq!(app.tree.selected(), vec![1]);
    press(&mut app, KeyCode::Enter);
    let closed = app.tree.rows().len();
    assert!(closed < all);
    press(&mut app, KeyCode::Char(' '));
    assert_eq!(app.tree.rows().len(), all);
    // Left closes an open ray, and on a closed one goes to the parent.
    press(&mut app, KeyCode::Char('h'));
    assert_eq!(app.tree.rows().len(), closed);
    press(&mut app, KeyCode::Char('h'));
    assert_eq!(app.tree.selected(), Vec::<usize>::new());
    // e: everything open, then everything closed but the root.
    press(&mut app, KeyCode::Char('e'));
    assert_eq!(app.tree.rows().len(), all);
    press(&mut app, KeyCode::Char('e'));
    assert_eq!(
        app.tree.rows().len(),
        1 + app.tree.full_tree().unwrap().children.len()
    );
    // A click on a tree line selects it.
    let p = app.panes();
    update(&mut app, Msg::Click(p.tree.x + 5, p.tree.y + 2));
    assert_eq!(app.tree.selected(), vec![0]);
    assert_eq!(app.focus, Focus::Tree);
}

#[test]
fn a_click_on_the_preview_picks_that_pixel() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    let p = app.panes();
    let cell = |app: &App| {
        raytree::tui::layout::pixel_cell(&p, app.image_size(), app.tree.pixel()).unwrap()
    };
    // A cell covers a few pixels of the scene: a click picks the one in its middle, and the
    // marker lands on the cell clicked.
    for (col, row) in [
        (p.image.x, p.image.y),
        (p.image.right() - 1, p.image.bottom() - 1),
        (p.image.x + 7, p.image.y + 3),
    ] {
        update(&mut app, Msg::Click(col, row));
        assert_eq!(cell(&app), (col, row));
        let line = screen(&app).lines().nth(row as usize).unwrap().to_string();
        assert_eq!(line.chars().nth(col as usize), Some('+'), "{line}");
    }
    update(&mut app, Msg::Click(p.image.x, p.image.y));
    assert!(
        app.tree.pixel().0 < 48 / p.image_px.0 + 1
            && app.tree.pixel().1 < 2 * 36 / p.image_px.1 + 1
    );
    // A click outside the preview picks nothing.
    let before = app.tree.pixel();
    update(&mut app, Msg::Click(p.tree.x + 3, p.tree.bottom() - 2));
    assert_eq!(app.tree.pixel(), before);
}

#[test]
fn quitting() {
    for k in [KeyCode::Char('q'), KeyCode::Esc] {
        let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
        press(&mut app, k);
        assert!(app.quit);
    }
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    press(&mut app, KeyCode::Char('?'));
    press(&mut app, KeyCode::Char('q'));
    assert!(app.quit, "q quits from the help too");
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    let ctrl_c = KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL);
    let msg = input::key(&app, &ctrl_c).unwrap();
    update(&mut app, msg);
    assert!(app.quit);
}

/// Esc goes back a step: it closes the diagram, then the CSG panel, and only then quits (it
/// used to quit with a panel open, where a student presses it to close the panel).
#[test]
fn esc_closes_the_open_panels_before_it_quits() {
    let mut app = open(CSG, ColorMode::TrueColor, (160, 48));
    press(&mut app, KeyCode::Char('c'));
    press(&mut app, KeyCode::Char('d'));
    assert!(app.diagram.open && app.csg.shown());
    press(&mut app, KeyCode::Esc);
    assert!(!app.diagram.open && app.csg.shown() && !app.quit);
    press(&mut app, KeyCode::Esc);
    assert!(!app.csg.shown() && !app.quit);
    press(&mut app, KeyCode::Esc);
    assert!(app.quit);
}

/// In a scene without a BVH, b says so each time and switches nothing (the second b used to
/// say "BVH boxes hidden"); v without the diagram says how to open it.
#[test]
fn b_in_a_scene_without_a_bvh_switches_nothing() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (120, 36));
    for _ in 0..2 {
        press(&mut app, KeyCode::Char('b'));
        let note = app.message_text().unwrap().0;
        assert!(
            note.starts_with("this scene has no BVH: ") && note.contains(" few enough"),
            "{note}"
        );
    }
    press(&mut app, KeyCode::Char('v'));
    let note = app.message_text().unwrap().0;
    assert!(note.ends_with("(d opens the diagram)"), "{note}");
}

/// s in a lesson of one scene says so, rather than "(1 of 1) · s: the lesson's next scene".
#[test]
fn s_in_a_lesson_of_one_scene_says_so() {
    let mut app = open(
        "lessons/08-pixel-intensity",
        ColorMode::TrueColor,
        (120, 36),
    );
    press(&mut app, KeyCode::Char('s'));
    let note = app.message_text().unwrap().0;
    assert_eq!(
        note,
        "this lesson has one scene, scene.yaml, and it is shown"
    );
}

/// The CSG panel writes a secondary ray's origin and its segments against the size of the
/// tree's numbers, as the details pane does: lesson 08's reflection ray leaves the floor at the
/// origin, (0, 0, 0), not (4.44089e-16, 3.46409e-10, 0), and its segment at the bias is 0.
#[test]
fn the_csg_panel_writes_rounding_as_zero() {
    let mut app = open(
        "lessons/08-pixel-intensity",
        ColorMode::TrueColor,
        (160, 48),
    );
    press(&mut app, KeyCode::Char('c'));
    let text = screen(&app);
    assert!(text.contains("reflection ray (0, 0, 0) → "), "{text}");
    assert!(!text.contains("e-1"), "{text}");
}

/// The help in a terminal too short for it says how many rows it leaves out; in the lesson
/// list it shows the list's keys, not the scene's.
#[test]
fn the_help_fits_its_terminal_and_its_screen() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (100, 20));
    press(&mut app, KeyCode::Char('?'));
    let text = screen(&app);
    assert!(
        text.contains("more rows: a taller terminal shows every key"),
        "{text}"
    );
    let root = demo_lesson("help-in-the-list");
    let mut app = App::open_lessons(&root, ColorMode::TrueColor);
    update(&mut app, Msg::Resize(80, 24));
    press(&mut app, KeyCode::Char('?'));
    let text = screen(&app);
    assert!(
        text.contains("choose a lesson") && !text.contains("PICK A PIXEL"),
        "{text}"
    );
}

#[test]
fn the_tree_root_is_the_rendered_pixel() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    let scene = app.file.scene.clone().unwrap();
    for depth in [4, 2] {
        if app.tree.depth() != depth {
            app = app.with_depth(depth);
        }
        let (image, _) = render_simple(
            &scene,
            RenderOptions {
                max_depth: depth,
                spp: 1,
                ..RenderOptions::of(&scene)
            },
        );
        for (x, y) in [(20, 15), (32, 14), (0, 0), (24, 30), (47, 35)] {
            update(&mut app, Msg::Pick(x, y));
            assert_eq!(
                root_color(&app),
                image.get(x, y),
                "pixel {x},{y} depth {depth}"
            );
        }
    }
}

#[test]
fn the_preview_follows_the_terminal_size() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    let small = app.preview.size;
    let img = app.preview.image.as_ref().unwrap();
    assert_eq!((img.width, img.height), small);
    // 4:3 scene, kept.
    assert!((small.0 as f64 / small.1 as f64 - 48.0 / 36.0).abs() < 0.1);
    update(&mut app, Msg::Resize(160, 48));
    assert!(app.preview.job.is_some(), "a resize asks for a new preview");
    assert!(app.preview.size.0 > small.0);
    app.render_now();
    let img = app.preview.image.as_ref().unwrap();
    assert_eq!((img.width, img.height), app.preview.size);
    // The picked pixel is the scene's, whatever the terminal.
    assert_eq!(app.image_size(), (48, 36));
    // A render of an older generation is ignored.
    let generation = app.preview.generation;
    update(&mut app, Msg::Resize(100, 30));
    assert!(app.preview.generation > generation);
}

#[test]
fn the_worker_renders_a_draft_then_the_full_preview() {
    use raytree::tui::worker::{Pass, Worker};
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Resize(160, 48));
    let job = app.take_job().unwrap();
    let mut worker = Worker::spawn();
    worker.submit(job);
    let draft = worker.recv_timeout(Duration::from_secs(20)).unwrap();
    assert_eq!(draft.pass, Pass::Draft);
    let full = worker.recv_timeout(Duration::from_secs(20)).unwrap();
    assert_eq!(full.pass, Pass::Final);
    assert_eq!((full.image.width, full.image.height), app.preview.size);
    update(&mut app, Msg::Rendered(draft));
    assert!(app.preview.running);
    update(&mut app, Msg::Rendered(full));
    assert!(!app.preview.running);
}

/// The median of `n` runs of `f`.
fn median(n: usize, mut f: impl FnMut()) -> Duration {
    let mut times: Vec<Duration> = (0..n)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed()
        })
        .collect();
    times.sort();
    times[n / 2]
}

/// Prints how long a pick takes (key → model → redrawn screen) and full preview renders.
#[test]
fn timings() {
    use raytree::tui::worker::{render_pass, Job, Pass};
    let dir = if Path::new("lessons/08-pixel-intensity/scene.yaml").is_file() {
        "lessons/08-pixel-intensity"
    } else {
        MIRROR
    };
    let mut app = open(dir, ColorMode::TrueColor, (160, 48));
    let mut term = ratatui::Terminal::new(ratatui::backend::TestBackend::new(160, 48)).unwrap();
    term.draw(|f| ui::draw(f, &app)).unwrap();
    let mut right = true;
    let pick = median(21, || {
        let k = if right { KeyCode::Right } else { KeyCode::Left };
        right = !right;
        let msg = input::key(&app, &key_event(k)).unwrap();
        update(&mut app, msg);
        term.draw(|f| ui::draw(f, &app)).unwrap();
    });
    assert!(
        app.take_job().is_none(),
        "picking does not re-render the preview"
    );
    update(&mut app, Msg::Resize(100, 30));
    update(&mut app, Msg::Resize(160, 48));
    let job = app.take_job().unwrap();
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let render = |job: &Job| median(5, || drop(render_pass(job, Pass::Final, &cancel, &|_| {})));
    let pane = render(&job);
    // And if the preview had the whole 160 × 48 terminal.
    let (w, h) = app.image_size();
    let (fw, fh) = raytree::tui::layout::fit(160, 48, w as f64 / h as f64);
    let whole = Job {
        width: fw,
        height: fh,
        ..job.clone()
    };
    let full = render(&whole);
    println!(
        "explorer timings ({dir}, 160×48 terminal): key → redrawn tree {pick:?}; \
         preview pane {}×{} px {pane:?}; whole-terminal preview {fw}×{fh} px {full:?}",
        job.width, job.height
    );
    // The worst case the depth keys allow: glass at the maximum depth.
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48)).with_depth(16);
    update(&mut app, Msg::Pick(31, 14));
    let mut right = true;
    let deep = median(21, || {
        update(&mut app, Msg::Move(if right { 1 } else { -1 }, 0));
        right = !right;
        term.draw(|f| ui::draw(f, &app)).unwrap();
    });
    println!(
        "explorer timings: pick at depth 16 through glass ({} rays in the tree): {deep:?}",
        app.tree.full_tree().unwrap().size(),
    );
}

// ---------------------------------------------------------------------------------------
// The ray diagram pane

const L08: &str = "lessons/08-pixel-intensity";

/// Braille cells on a screen: the rays and outlines the canvas drew.
fn braille(text: &str) -> usize {
    text.chars()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
        .count()
}

/// The rows of the screen inside a pane (its border excluded), as text.
fn pane_text(app: &App, r: ratatui::layout::Rect) -> String {
    screen(app)
        .lines()
        .skip(r.y as usize + 1)
        .take(r.height.saturating_sub(2) as usize)
        .map(|l| {
            l.chars()
                .skip(r.x as usize + 1)
                .take(r.width as usize - 2)
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_diagram_pane_draws_the_exercise_from_the_front_at_both_sizes() {
    for (size, name) in [
        ((80, 24), "diagram_l08_80x24"),
        ((160, 48), "diagram_l08_160x48"),
    ] {
        let mut app = open(L08, ColorMode::TrueColor, size);
        update(&mut app, Msg::Pick(30, 30));
        press(&mut app, KeyCode::Char('d'));
        let p = app.panes();
        let r = p.diagram.expect("d opens the diagram");
        assert!(
            p.tree.width > 0 && p.lower.or(p.lesson).is_some(),
            "it shares the screen"
        );
        let text = screen(&app);
        assert!(text.contains("rays · front view (x →, y ↑)"), "{text}");
        assert!(braille(&pane_text(&app, r)) > 40, "{text}");
        assert!(
            text.contains("━prim") || text.contains("━primary"),
            "the legend: {text}"
        );
        // The four surfaces are named where they are drawn.
        let inside = pane_text(&app, r);
        for name in ["a", "b", "c", "d"] {
            assert!(inside.contains(name), "{name} in\n{inside}");
        }
        insta::assert_snapshot!(name, text);
        press(&mut app, KeyCode::Char('d'));
        assert!(app.panes().diagram.is_none());
    }
}

#[test]
fn the_diagram_views_of_the_mirror_scene_and_a_selected_ray() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    press(&mut app, KeyCode::Char('d'));
    // v: top, then side.
    press(&mut app, KeyCode::Char('v'));
    assert!(screen(&app).contains("rays · top view (x →, z ↑)"));
    insta::assert_snapshot!("diagram_top_160x48", screen(&app));
    press(&mut app, KeyCode::Char('v'));
    let side = screen(&app);
    assert!(side.contains("rays · side view (z →, y ↑)"));
    insta::assert_snapshot!("diagram_side_160x48", side);
    // The reflection towards the glass ball selected: drawn in yellow over the others.
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.focus, Focus::Tree);
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    assert_eq!(app.tree.selected_node().unwrap().kind, RayKind::Reflection);
    let mut term = ratatui::Terminal::new(ratatui::backend::TestBackend::new(160, 48)).unwrap();
    term.draw(|f| ui::draw(f, &app)).unwrap();
    let buf = term.backend().buffer();
    let r = app.panes().diagram.unwrap();
    let yellow = (r.x..r.right())
        .flat_map(|x| (r.y..r.bottom()).map(move |y| (x, y)))
        .filter(|&(x, y)| {
            buf[(x, y)].fg == ratatui::style::Color::LightYellow
                && braille(buf[(x, y)].symbol()) == 1
        })
        .count();
    assert!(
        yellow > 3,
        "the selected ray is highlighted ({yellow} cells)"
    );
    insta::assert_snapshot!("diagram_selected_80x24", {
        update(&mut app, Msg::Resize(80, 24));
        screen(&app)
    });
    // Zoom and pan change what is shown; v frames the rays again.
    let before = screen(&app);
    press(&mut app, KeyCode::Char('>'));
    assert!(app.diagram.zoom > 1.0);
    assert_ne!(screen(&app), before);
    press(&mut app, KeyCode::Char('<'));
    press(&mut app, KeyCode::Char('v'));
    assert_eq!(app.diagram.zoom, 1.0);
}

#[test]
fn level_stepping_reveals_the_rays_in_the_diagram_level_by_level() {
    let mut app = open(L08, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(30, 30));
    press(&mut app, KeyCode::Char('d'));
    let r = app.panes().diagram.unwrap();
    let full = braille(&pane_text(&app, r));
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(app.tree.level(), Some(1));
    let one = pane_text(&app, r);
    let text = screen(&app);
    assert!(text.contains("not yet revealed"), "{text}");
    assert!(!text.contains("not traced: max depth"), "{text}");
    insta::assert_snapshot!("diagram_level_1_160x48", text);
    press(&mut app, KeyCode::Char('n'));
    press(&mut app, KeyCode::Char('n'));
    assert_eq!(app.tree.level(), Some(3));
    let three = pane_text(&app, r);
    insta::assert_snapshot!("diagram_level_3_160x48", screen(&app));
    // The rays appear level by level in a frame that stays put.
    assert!(braille(&one) < braille(&three), "{one}\n---\n{three}");
    assert!(braille(&three) <= full);
    let mut small = open(L08, ColorMode::TrueColor, (80, 24));
    update(&mut small, Msg::Pick(30, 30));
    press(&mut small, KeyCode::Char('d'));
    press(&mut small, KeyCode::Char('n'));
    insta::assert_snapshot!("diagram_level_1_80x24", screen(&small));
    keys(&mut small, "nn");
    insta::assert_snapshot!("diagram_level_3_80x24", screen(&small));
}

#[test]
fn the_bvh_overlay_shows_the_boxes_the_ray_visited_and_their_count() {
    let mut app = open(
        "lessons/12-acceleration/many.yaml",
        ColorMode::TrueColor,
        (160, 48),
    );
    update(&mut app, Msg::Pick(160, 120));
    press(&mut app, KeyCode::Char('d'));
    press(&mut app, KeyCode::Char('b'));
    let text = screen(&app);
    let scene = app.file.scene.clone().unwrap();
    let ray = scene.camera.pixel_ray(160, 120);
    let v = scene.visited_boxes(&ray, f64::INFINITY, false);
    let count = format!(
        "BVH: {} of {} boxes visited",
        v.boxes.len(),
        scene.bvh_nodes()
    );
    assert!(text.contains(&count), "{count}\n{text}");
    insta::assert_snapshot!("diagram_bvh_160x48", text);
    update(&mut app, Msg::Resize(80, 24));
    insta::assert_snapshot!("diagram_bvh_80x24", screen(&app));
    // Without a BVH the message says why.
    let mut small = open(L08, ColorMode::TrueColor, (80, 24));
    press(&mut small, KeyCode::Char('b'));
    assert!(screen(&small).contains("no BVH"), "{}", screen(&small));
}

#[test]
fn m_marks_where_the_rays_landed_on_the_preview() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    assert!(!screen(&app).contains('◆'));
    press(&mut app, KeyCode::Char('m'));
    let text = screen(&app);
    let p = app.panes();
    // The reflection lands on the glass ball, which the preview shows right of the mirror.
    let marks: Vec<(u16, u16)> = text
        .lines()
        .enumerate()
        .flat_map(|(y, l)| {
            l.chars()
                .enumerate()
                .filter(|c| c.1 == '◆')
                .map(move |(x, _)| (x as u16, y as u16))
        })
        .collect();
    let marks: Vec<(u16, u16)> = marks
        .into_iter()
        .filter(|&(x, y)| p.image.contains(ratatui::layout::Position::new(x, y)))
        .collect();
    assert!(!marks.is_empty(), "{text}");
    let scene = app.file.scene.clone().unwrap();
    let tree = app.tree.full_tree().unwrap();
    let glass = tree.find("reflection").unwrap().hit.as_ref().unwrap().point;
    let at = raytree::diagram::marks::image_position(&scene.camera, glass).unwrap();
    // The cell that holds the landing point: the preview's pixels over the image's, and two
    // of them a cell, stacked.
    let ((w, h), (pw, ph)) = (app.image_size(), p.image_px);
    let cell = (
        p.image.x + (at.x / w as f64 * pw as f64) as u16,
        p.image.y + (at.y / h as f64 * ph as f64 / 2.0) as u16,
    );
    assert!(marks.contains(&cell), "{cell:?} in {marks:?}");
    press(&mut app, KeyCode::Char('m'));
    assert!(!screen(&app).contains('◆'));
    // A pixel of the background has no rays to mark: m says so.
    update(&mut app, Msg::Pick(0, 0));
    assert!(app.tree.full_tree().unwrap().hit.is_none());
    press(&mut app, KeyCode::Char('m'));
    let note = app.message_text().unwrap().0;
    assert!(note.starts_with("hit marks on: none to show"), "{note}");
}

// ---------------------------------------------------------------------------------------
// The real binary in a real terminal (tmux)

/// Starts `raytree explore MIRROR` (with `env` before it) in a detached 100 × 30 tmux session
/// on a server of its own; after the explorer exits, the shell records its exit status and the
/// terminal's modes (stty -a), then prints DONE.
fn start_in_tmux(name: &str, env: &str) -> (Tmux, PathBuf, PathBuf) {
    start_in_tmux_on(name, env, MIRROR)
}

/// `start_in_tmux` on another scene or lesson.
fn start_in_tmux_on(name: &str, env: &str, target: &str) -> (Tmux, PathBuf, PathBuf) {
    let bin = env!("CARGO_BIN_EXE_raytree");
    let dir = scratch(name);
    let status = dir.join("status");
    let stty = dir.join("stty");
    let tmux = Tmux::new(name);
    tmux.start(&format!(
        "{env} '{bin}' explore {target}; echo \"exit $?\" > '{}'; stty -a > '{}'; echo DONE; sleep 60",
        status.display(),
        stty.display()
    ));
    (tmux, status, stty)
}

/// The terminal is back to normal: cooked mode with echo, main screen, no mouse reporting,
/// cursor shown.
fn assert_restored(tmux: &Tmux, stty: &Path) {
    let modes = std::fs::read_to_string(stty).unwrap();
    let words: Vec<&str> = modes.split_whitespace().collect();
    assert!(
        words.contains(&"icanon") && words.contains(&"echo"),
        "{modes}"
    );
    assert_eq!(tmux.flag("#{alternate_on}"), "0");
    assert_eq!(tmux.flag("#{mouse_any_flag}"), "0");
    assert_eq!(tmux.flag("#{cursor_flag}"), "1", "the cursor is shown");
}

#[test]
fn in_tmux() {
    if !have_tmux() {
        return;
    }
    let (tmux, status, stty) = start_in_tmux("tmux", "");
    tmux.wait_for(&["ray tree · pixel 24,18", "preview"]);
    tmux.wait_for(&["preview 100%"]);
    assert_eq!(tmux.flag("#{alternate_on}"), "1");
    assert_eq!(tmux.flag("#{mouse_any_flag}"), "1");
    tmux.run(&["send-keys", "-t", "explore", "Right", "Right", "j"]);
    tmux.wait_for(&["pixel 26,19", "primary: hit"]);
    tmux.run(&["send-keys", "-t", "explore", "?"]);
    tmux.wait_for(&["keys (any key closes", "move the picked pixel"]);
    tmux.run(&["send-keys", "-t", "explore", "q"]);
    let after = tmux.wait_for(&["DONE"]);
    let code = std::fs::read_to_string(&status).unwrap();
    assert_eq!(code.trim(), "exit 0", "{after}");
    assert_restored(&tmux, &stty);
    assert!(
        !after.contains("ray tree ·"),
        "the explorer's screen is gone:\n{after}"
    );
}

#[test]
fn in_tmux_the_diagram_pane_draws_braille_and_its_legend() {
    if !have_tmux() {
        return;
    }
    let (tmux, status, stty) = start_in_tmux_on("tmux-diagram", "", L08);
    tmux.wait_for(&["ray tree · pixel"]);
    tmux.run(&["send-keys", "-t", "explore", "d"]);
    let shown = tmux.wait_for(&["rays · front view", "━prim"]);
    assert!(braille(&shown) > 20, "{shown}");
    tmux.run(&["send-keys", "-t", "explore", "q"]);
    let after = tmux.wait_for(&["DONE"]);
    let code = std::fs::read_to_string(&status).unwrap();
    assert_eq!(code.trim(), "exit 0", "{after}");
    assert_restored(&tmux, &stty);
    assert_eq!(
        braille(&after),
        0,
        "the explorer's screen is gone:\n{after}"
    );
}

/// `preview` in a terminal that reports 0 columns (as some containers' and CI runners' do)
/// takes that as unknown: `COLUMNS` where it is set, else 80, not the narrowest preview of 4.
#[test]
fn in_tmux_a_terminal_of_zero_columns_previews_at_columns_or_80() {
    if !have_tmux() {
        return;
    }
    let bin = env!("CARGO_BIN_EXE_raytree");
    let dir = scratch("tmux-zero-columns");
    let (with, without) = (dir.join("with"), dir.join("without"));
    let tmux = Tmux::new("tmux-zero-columns");
    tmux.start(&format!(
        "stty cols 0 rows 0; NO_COLOR=1 COLUMNS=100 '{bin}' preview {MIRROR} --ascii > '{}'; \
         NO_COLOR=1 COLUMNS= '{bin}' preview {MIRROR} --ascii > '{}'; echo DONE; sleep 60",
        with.display(),
        without.display()
    ));
    tmux.wait_for(&["DONE"]);
    let widths = |file: &Path| -> Vec<usize> {
        let text = std::fs::read_to_string(file).unwrap();
        text.lines().map(|l| l.chars().count()).collect()
    };
    assert!(
        widths(&with).iter().all(|&w| w == 100),
        "{:?}",
        widths(&with)
    );
    assert!(
        widths(&without).iter().all(|&w| w == 80),
        "{:?}",
        widths(&without)
    );
}

/// Ctrl-Z stops the explorer as it stops any program in a shell, and so does SIGTSTP from
/// outside: while it is stopped the terminal is the shell's again (main screen, no mouse
/// reports, the cursor shown), and `fg` brings back the full screen, drawn whole, its keys
/// working. (The explorer stopped with the terminal in its own modes, and after `fg` drew
/// nothing and read keys a line at a time.)
#[test]
fn in_tmux_ctrl_z_and_fg_leave_and_bring_back_the_explorer() {
    if !have_tmux() {
        return;
    }
    let bin = env!("CARGO_BIN_EXE_raytree");
    let tmux = Tmux::new("tmux-suspend");
    tmux.start("PS1='$ ' exec bash --norc --noprofile -i");
    let command = format!("'{bin}' explore {L08}");
    tmux.run(&["send-keys", "-t", "explore", &command, "Enter"]);
    tmux.wait_for(&["ray tree · pixel 30,30", "preview"]);
    let shell = tmux.flag("#{pane_pid}");
    for (k, how) in ["Ctrl-Z", "SIGTSTP"].into_iter().enumerate() {
        if how == "Ctrl-Z" {
            tmux.run(&["send-keys", "-t", "explore", "C-z"]);
        } else {
            let explorer = Command::new("pgrep").args(["-P", &shell]).output().unwrap();
            let pid = String::from_utf8_lossy(&explorer.stdout).trim().to_string();
            assert!(!pid.is_empty(), "the explorer runs under the shell");
            let killed = Command::new("kill").args(["-TSTP", &pid]).status().unwrap();
            assert!(killed.success());
        }
        tmux.wait_until(&format!("{how} stops the explorer"), |t| {
            t.flag("#{alternate_on}") == "0" && t.capture().contains("Stopped")
        });
        assert_eq!(tmux.flag("#{mouse_any_flag}"), "0", "{how}");
        assert_eq!(tmux.flag("#{cursor_flag}"), "1", "{how}");
        tmux.run(&["send-keys", "-t", "explore", "clear; fg", "Enter"]);
        tmux.wait_for(&["ray tree · pixel", "primary: hit a"]);
        assert_eq!(tmux.flag("#{alternate_on}"), "1", "{how}");
        assert_eq!(tmux.flag("#{mouse_any_flag}"), "1", "{how}");
        tmux.run(&["send-keys", "-t", "explore", "Right"]);
        tmux.wait_for(&[&format!("ray tree · pixel {},30", 31 + k)]);
    }
    tmux.run(&["send-keys", "-t", "explore", "q"]);
    tmux.wait_until("the explorer ends", |t| t.flag("#{alternate_on}") == "0");
    assert_eq!(tmux.flag("#{mouse_any_flag}"), "0");
    assert_eq!(tmux.flag("#{cursor_flag}"), "1");
}

#[test]
fn in_tmux_a_panic_restores_the_terminal() {
    if !have_tmux() {
        return;
    }
    let (tmux, status, stty) = start_in_tmux("tmux-panic", "RAYTREE_EXPLORE_TEST_PANIC=1");
    let after = tmux.wait_for(&["DONE"]);
    // The panic message is printed on the restored main screen, readable.
    assert!(after.contains("a deliberate panic"), "{after}");
    let code = std::fs::read_to_string(&status).unwrap();
    assert_eq!(code.trim(), "exit 101", "{after}");
    assert_restored(&tmux, &stty);
}

#[test]
fn in_tmux_a_crash_in_the_render_thread_is_reported_and_resizing_to_one_cell_survives() {
    if !have_tmux() {
        return;
    }
    let (tmux, status, stty) =
        start_in_tmux("tmux-worker-panic", "RAYTREE_EXPLORE_TEST_PANIC=worker");
    let screen = tmux.wait_for(&["renderer crashed", "ray tree ·"]);
    assert!(
        screen.contains("ray tree ·"),
        "the explorer keeps running:\n{screen}"
    );
    // Squeeze the terminal to one cell and back: nothing breaks, everything is drawn again.
    tmux.run(&["resize-window", "-t", "explore", "-x", "1", "-y", "1"]);
    std::thread::sleep(std::time::Duration::from_millis(400));
    tmux.run(&["resize-window", "-t", "explore", "-x", "100", "-y", "30"]);
    tmux.wait_for(&["ray tree ·"]);
    tmux.run(&["send-keys", "-t", "explore", "q"]);
    let after = tmux.wait_for(&["DONE"]);
    let code = std::fs::read_to_string(&status).unwrap();
    assert_eq!(code.trim(), "exit 0", "{after}");
    assert_restored(&tmux, &stty);
}

// ---------------------------------------------------------------------------------------
// The command line around it

fn explore_cli(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .arg("explore")
        .args(args)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn explore_without_a_terminal_or_with_a_bad_scene_says_why() {
    let (code, err) = explore_cli(&[MIRROR]);
    assert_eq!(code, 2);
    assert!(err.contains("explore needs a terminal"), "{err}");
    // A scene error is reported first, with file, line and column.
    let dir = scratch("cli-bad-scene");
    let bad = dir.join("scene.yaml");
    std::fs::write(
        &bad,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: oops }\n",
    )
    .unwrap();
    let (code, err) = explore_cli(&[bad.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.starts_with("raytree: target/explorer-tests/cli-bad-scene/scene.yaml:1:"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    let (code, err) = explore_cli(&[MIRROR, "--pixel", "48,0"]);
    assert_eq!(code, 2);
    assert!(err.contains("outside the 48 × 36 image"), "{err}");
    let (code, err) = explore_cli(&["tests/scenes"]);
    assert_eq!(code, 2);
    assert!(err.contains("not a lesson folder"), "{err}");
    // The lesson list has no pixel and no depth: a usage error naming what they need (it was
    // "pixel 5,50 is outside the 0 × 0 image", and --depth went unheeded).
    for flags in [&["--pixel", "5,50"][..], &["--depth", "2"]] {
        let (code, err) = explore_cli(flags);
        assert_eq!(code, 2, "{flags:?}");
        assert!(
            err.contains("<TARGET>") && err.contains("Usage"),
            "{flags:?}: {err}"
        );
    }
}

/// `--allow-huge` raises the explorer's budgets as it does the other commands': the scene
/// over the pixel budget that `explore` refuses, saying to use the flag, opens with it; and a
/// scene edited over the budget while it is open reloads with it, and without it is refused
/// with the same hint (the last good scene stays).
#[test]
fn allow_huge_opens_and_reloads_a_scene_over_the_budget() {
    let dir = scratch("allow-huge");
    let path = dir.join("scene.yaml");
    let good = std::fs::read_to_string(MIRROR).unwrap();
    let huge = good.replace("width: 48, height: 36", "width: 100000, height: 100000");
    assert_ne!(huge, good);
    std::fs::write(&path, &huge).unwrap();
    let file = path.to_str().unwrap();
    let (code, err) = explore_cli(&[file]);
    assert_eq!(code, 2);
    assert!(
        err.contains("exceeds the budget") && err.contains("--allow-huge"),
        "{err}"
    );
    // Loaded, it goes on to ask for a terminal, which the test has not.
    let (code, err) = explore_cli(&[file, "--allow-huge"]);
    assert_eq!(code, 2);
    assert!(err.contains("explore needs a terminal"), "{err}");
    let help = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(["explore", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("--allow-huge"), "{help}");

    std::fs::write(&path, &good).unwrap();
    let mut strict = open(file, ColorMode::TrueColor, (80, 24));
    let mut huge_app =
        App::open_within(Some(&path), ColorMode::TrueColor, Limits::huge()).expect("opens");
    update(&mut huge_app, Msg::Resize(80, 24));
    std::fs::write(&path, &huge).unwrap();
    update(&mut strict, Msg::Tick);
    update(&mut huge_app, Msg::Tick);
    let err = strict.file.error.clone().expect("over the budget");
    assert!(err.contains("--allow-huge"), "{err}");
    assert_eq!(strict.image_size(), (48, 36), "the last good scene stays");
    assert_eq!(huge_app.file.error, None);
    assert_eq!(huge_app.image_size(), (100_000, 100_000));
    huge_app.render_now();
    assert!(huge_app.preview.image.is_some(), "its preview is drawn");
}

#[test]
fn panels_scroll_within_their_content() {
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Pick(20, 15));
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.focus, Focus::Lower);
    for _ in 0..5 {
        press(&mut app, KeyCode::PageDown);
    }
    let (max, _) = app.scroll_limits();
    assert!(max > 0);
    assert_eq!(
        app.tree.details_scroll(),
        max,
        "no further than the last line"
    );
    assert!(screen(&app).contains("sum  I ="));
    press(&mut app, KeyCode::Up);
    assert_eq!(app.tree.details_scroll(), max - 1);
    for _ in 0..3 {
        press(&mut app, KeyCode::PageUp);
    }
    assert_eq!(app.tree.details_scroll(), 0);
    // The CSG panel scrolls to the selected ray's section.
    let mut app = open(MIRROR, ColorMode::TrueColor, (80, 24));
    update(&mut app, Msg::Pick(20, 15));
    press(&mut app, KeyCode::Char('c'));
    assert_eq!(app.csg.scroll(), 0);
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    assert!(app.csg.scroll() > 0);
    let text = screen(&app);
    assert!(text.contains("▶ reflection ray"), "{text}");
}

#[test]
fn a_glossy_cone_is_folded_under_its_mean_until_opened() {
    let mut app = open(
        "tests/scenes/explorer-glossy.yaml",
        ColorMode::TrueColor,
        (160, 48),
    );
    update(&mut app, Msg::Pick(20, 26));
    let tree = app.tree.full_tree().cloned().unwrap();
    // The cone's rays are the renderer's own for this pixel: the root is the rendered value.
    let scene = app.file.scene.clone().unwrap();
    let film = raytree::render::film::Film::new(&scene, RenderOptions::of(&scene));
    assert_eq!(tree.color, film.lone_pixel(&mut film.tracer(), 20, 26));
    let cone = tree.children.iter().position(|c| c.samples == Some(4));
    let cone = cone.expect("the floor's reflection is a cone of 4 rays");
    // Folded: the cone is one line, its 4 sampled rays hidden.
    let folded = app.tree.rows().len();
    assert!(app
        .tree
        .rows()
        .iter()
        .any(|r| r.path == vec![cone] && !r.open));
    assert!(screen(&app).contains("glossy reflection: mean of 4 rays"));
    insta::assert_snapshot!("glossy_cone_folded_160x48", screen(&app));
    // Opened: the sampled rays appear below it.
    press(&mut app, KeyCode::Tab);
    while app.tree.selected() != vec![cone] {
        press(&mut app, KeyCode::Char('j'));
    }
    press(&mut app, KeyCode::Right);
    assert!(app.tree.rows().len() >= folded + 4);
}

#[test]
fn a_supersampled_pixel_shows_its_rendered_value_above_the_centre_ray() {
    let mut app = open("lessons/13-antialiasing", ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(1, 1));
    let scene = app.file.scene.clone().unwrap();
    let film = raytree::render::film::Film::new(&scene, RenderOptions::of(&scene));
    let rendered = film.lone_pixel(&mut film.tracer(), 1, 1);
    let (value, how) = app.tree.pixel_value().cloned().expect("16 spp, adaptive");
    assert_eq!(value, rendered);
    assert!(how.contains("adaptive"), "{how}");
    // The tree itself follows the centre ray, which lands on the card.
    assert_eq!(app.tree.full_tree().unwrap().color, glam::DVec3::ONE);
    assert!(screen(&app).contains("pixel = 0.625"));
    // A one-ray scene needs no such line.
    let plain = open(MIRROR, ColorMode::TrueColor, (160, 48));
    assert!(plain.tree.pixel_value().is_none());
}

// ---------------------------------------------------------------------------------------
// A class relies on it (issue 28)

/// The exercise selected with `a` and moved to with ↓ (`n` times).
fn select_exercise(app: &mut App, n: usize) {
    press(app, KeyCode::Char('a'));
    for _ in 0..n {
        press(app, KeyCode::Down);
    }
}

fn scene_name(app: &App) -> String {
    app.file
        .path
        .as_ref()
        .and_then(|p| p.file_name())
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Defect 7: a lesson's extra scene belongs to the lesson: opened alone, `a` still finds the
/// lesson's exercises.
#[test]
fn an_extra_scene_of_a_lesson_opens_with_its_lesson() {
    let mut app = open(
        "lessons/03-local-illumination/phong.yaml",
        ColorMode::TrueColor,
        (160, 48),
    );
    assert_eq!(scene_name(&app), "phong.yaml");
    press(&mut app, KeyCode::Char('a'));
    assert!(app.exercises_active(), "{}", screen(&app));
    assert!(!screen(&app).contains("no lesson here"));
}

/// Defect 7: `s` steps through the lesson's scenes; an exercise posed on another scene switches
/// the view to it.
#[test]
fn exercises_and_the_s_key_switch_between_a_lessons_scenes() {
    let mut app = open(
        "lessons/03-local-illumination",
        ColorMode::TrueColor,
        (160, 48),
    );
    assert_eq!(scene_name(&app), "scene.yaml");
    // specular-phong, the fourth exercise, is posed on phong.yaml.
    select_exercise(&mut app, 3);
    let l = app.lesson.as_ref().unwrap();
    assert_eq!(l.lesson.exercises[l.exercise].id, "specular-phong");
    assert_eq!(scene_name(&app), "phong.yaml");
    assert_eq!(app.tree.pixel(), (80, 60));
    // Back up to an exercise of scene.yaml.
    press(&mut app, KeyCode::Up);
    assert_eq!(scene_name(&app), "scene.yaml");
    press(&mut app, KeyCode::Esc);
    let mut seen = vec![scene_name(&app)];
    for _ in 0..3 {
        press(&mut app, KeyCode::Char('s'));
        seen.push(scene_name(&app));
        assert!(app.lesson.is_some());
    }
    assert_eq!(
        seen,
        ["scene.yaml", "color.yaml", "phong.yaml", "scene.yaml"]
    );
}

/// In a narrow tree pane a row gives up the end of its label ("…"), never its intensity: at
/// 40 × 12 lesson 08's rows read "I = 0." where they read I = 0.4621 and 0.9721.
#[test]
fn a_narrow_tree_pane_cuts_the_label_not_the_intensity() {
    let app = open("lessons/08-pixel-intensity", ColorMode::TrueColor, (40, 12));
    let text = screen(&app);
    let rows: Vec<&str> = text.lines().filter(|l| l.contains("I = ")).collect();
    assert!(rows.len() >= 2, "{text}");
    for row in rows {
        let value = row.split("I = ").nth(1).unwrap();
        let digits = value.trim_start_matches(|c: char| c.is_ascii_digit() || c == '.');
        let number = &value[..value.len() - digits.len()];
        assert!(
            number.len() >= 5 && number.parse::<f64>().is_ok(),
            "{row}\n{text}"
        );
    }
    assert!(text.contains("…"), "{text}");
}

/// An exercise that names no depth is asked at the scene's own max_depth, whatever depth an
/// earlier exercise or the keys chose: in lesson 07, depth-5 after depth-3 is the README's
/// 0.777809 at depth 5 (it showed depth 3's 0.6467, which the check marks wrong), and so after
/// `-` too.
#[test]
fn an_exercise_without_a_depth_goes_back_to_the_scenes() {
    let mut app = open(
        "lessons/07-recursion-depth",
        ColorMode::TrueColor,
        (160, 48),
    );
    select_exercise(&mut app, 2);
    let l = app.lesson.as_ref().unwrap();
    assert_eq!(l.lesson.exercises[l.exercise].id, "depth-3");
    assert_eq!(app.tree.depth(), 3);
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    let l = app.lesson.as_ref().unwrap();
    assert_eq!(l.lesson.exercises[l.exercise].id, "depth-5");
    assert_eq!(app.tree.depth(), 5);
    assert!(
        (root_color(&app).x - 0.777809).abs() < 1e-6,
        "{}",
        root_color(&app)
    );
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('-'));
    assert_eq!(app.tree.depth(), 4);
    // `a` goes back to the exercise last selected, depth-5.
    select_exercise(&mut app, 0);
    assert_eq!(app.tree.depth(), 5);
}

/// Esc from the exercises goes back to the picture and says that a second Esc quits (the
/// exercise's "Esc: back" stayed on screen, and the next Esc ended the session); an exercise
/// worked in the other highlight model than the scene's says the tree is not in it (lesson 08's
/// pixel-p-phong: Phong's 0.793042, the tree Blinn's 0.870161).
#[test]
fn the_message_line_says_what_esc_and_the_tree_will_do() {
    let mut app = open(
        "lessons/08-pixel-intensity",
        ColorMode::TrueColor,
        (160, 48),
    );
    select_exercise(&mut app, 8);
    let l = app.lesson.as_ref().unwrap();
    assert_eq!(l.lesson.exercises[l.exercise].id, "pixel-p-phong");
    let (note, _) = app.message_text().unwrap();
    assert!(
        note.contains("worked in Phong's (r·v)^m where the tree shows Blinn's (h·n)^m"),
        "{note}"
    );
    assert!((root_color(&app).x - 0.870161).abs() < 1e-6);
    press(&mut app, KeyCode::Esc);
    assert!(!app.quit);
    let (note, _) = app.message_text().unwrap();
    assert!(
        note.contains("Esc or q: quit") && !note.contains("Esc: back"),
        "{note}"
    );
    press(&mut app, KeyCode::Esc);
    assert!(app.quit);
}

/// An exercise asked at another depth renders the preview at that depth (the preview used to
/// be requested before the tree was traced there, at the depth before: lesson 07's depth-1
/// showed the depth-5 picture with "depth 1" beside it).
#[test]
fn an_exercise_at_another_depth_renders_the_preview_at_it() {
    let mut app = open(
        "lessons/07-recursion-depth",
        ColorMode::TrueColor,
        (160, 48),
    );
    app.render_now();
    assert_eq!(app.tree.depth(), 5);
    select_exercise(&mut app, 0);
    let l = app.lesson.as_ref().unwrap();
    assert_eq!(l.lesson.exercises[l.exercise].id, "depth-1");
    assert_eq!(app.tree.depth(), 1);
    assert_eq!(app.preview.depth, Some(1));
    // The same picture and rays as depth 1 reached by keys.
    let mut keyed = open(
        "lessons/07-recursion-depth",
        ColorMode::TrueColor,
        (160, 48),
    );
    for _ in 0..4 {
        press(&mut keyed, KeyCode::Char('-'));
    }
    assert_eq!(keyed.tree.depth(), 1);
    let rays = |a: &App| a.preview.stats.map(|s| s.rays());
    assert_eq!(rays(&app), rays(&keyed));
    let pixels = |a: &App| a.preview.image.as_ref().unwrap().pixels.clone();
    assert_eq!(pixels(&app), pixels(&keyed));
}

/// The levels line keeps the level being stepped: at 80 columns lesson 08's five levels do
/// not fit, and the earliest give way to "…" (the line used to end at "5:", cut mid-value).
#[test]
fn the_levels_line_keeps_the_latest_levels() {
    let mut app = open("lessons/08-pixel-intensity", ColorMode::TrueColor, (80, 24));
    for _ in 0..5 {
        press(&mut app, KeyCode::Char('n'));
    }
    let text = screen(&app);
    let line = text
        .lines()
        .find(|l| l.contains("levels:"))
        .unwrap_or_else(|| panic!("{text}"));
    let line = line.trim_end().trim_end_matches('│').trim_end();
    assert!(line.contains("levels: … → "), "{line}");
    assert!(line.ends_with("4: 0.8702 → 5: 0.8702"), "{line}");
}

/// The first path's line in lesson 15's tree, too long for an 80-column pane, ends in "…"
/// (it used to stop mid-word: "… → back → righ").
#[test]
fn a_paths_line_cut_short_says_so() {
    let app = open("lessons/15-path-tracing", ColorMode::TrueColor, (80, 24));
    let text = screen(&app);
    let paths: Vec<&str> = text.lines().filter(|l| l.contains(" path 1: ")).collect();
    assert!(!paths.is_empty(), "{text}");
    for line in paths {
        let inside = line.trim_end().trim_end_matches('│').trim_end();
        assert!(inside.ends_with('…'), "{line}");
    }
}

/// Lesson 08's pixel-p-phong has a note longer than a 140-column line: its subject is cut
/// short, not its keys, so "Esc: back" stays on screen (it used to be the part cut off).
#[test]
fn a_long_exercise_note_keeps_its_keys_on_screen() {
    let mut app = open(
        "lessons/08-pixel-intensity",
        ColorMode::TrueColor,
        (140, 40),
    );
    select_exercise(&mut app, 8);
    let (note, _) = app.message_text().unwrap();
    assert!(note.chars().count() > 140, "{note}");
    let text = screen(&app);
    let last = text.lines().last().unwrap().trim_end();
    assert!(
        last.starts_with("exercise pixel-p-phong: pixel 30,30, worked in Phong's")
            && last.ends_with("… · Enter: answer · w: worked solution · Esc: back"),
        "{last}"
    );
}

/// Defect 7: a ray exercise shows the tree of its ray and selects the node asked about. In
/// lesson 06, the ray from (−3, 4, 0) along (0.6, −0.8, 0) meets the slab's top at t = 5 and its
/// refraction leaves the bottom at (0.436436, −1, 0) (README).
#[test]
fn a_ray_exercise_shows_the_tree_of_its_ray() {
    let mut app = open("lessons/06-refraction", ColorMode::TrueColor, (160, 48));
    // exit-point, the second exercise: node refraction.
    select_exercise(&mut app, 1);
    let root = app.tree.full_tree().unwrap();
    assert!((root.origin - glam::DVec3::new(-3.0, 4.0, 0.0)).length() < 1e-12);
    assert!((root.direction - glam::DVec3::new(0.6, -0.8, 0.0)).length() < 1e-12);
    assert!((root.hit.as_ref().unwrap().t - 5.0).abs() < 1e-9);
    let node = app.tree.selected_node().unwrap();
    assert_eq!(node.kind, RayKind::Refraction);
    let p = node.hit.as_ref().unwrap().point;
    assert!(
        (p - glam::DVec3::new(0.436436, -1.0, 0.0)).length() < 1e-6,
        "{p}"
    );
    let text = screen(&app);
    assert!(text.contains("ray (-3, 4, 0)"), "{text}");
    // Moving the cursor goes back to the pixels.
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::BackTab);
    update(&mut app, Msg::Pick(10, 10));
    assert_eq!(
        app.tree.full_tree().unwrap().origin,
        app.file.scene.as_ref().unwrap().camera.eye()
    );
}

/// Defect 8: in a path-traced scene the tree pane first shows the pixel's rendered estimate and
/// the paths sampled for it; the Whitted tree below is labelled as a reading of the centre ray
/// only. It must fit at 100 columns.
#[test]
fn a_path_traced_pixel_shows_its_estimate_and_paths_before_the_whitted_reading() {
    let mut app = open("lessons/15-path-tracing", ColorMode::TrueColor, (100, 40));
    update(&mut app, Msg::Pick(32, 20));
    let scene = app.file.scene.clone().unwrap();
    let film = raytree::render::film::Film::new(&scene, RenderOptions::of(&scene));
    let rendered = film.lone_pixel(&mut film.tracer(), 32, 20);
    let text = screen(&app);
    // The rendered value as the tree pane writes it: three decimals, final zeros dropped.
    let short = |v: f64| {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    let [r, g, b] = rendered.to_array().map(short);
    let estimate = format!("estimate ({r}, {g}, {b})");
    let lines: Vec<&str> = text.lines().collect();
    let at = |what: &str| lines.iter().position(|l| l.contains(what));
    let est = at("estimate").unwrap_or_else(|| panic!("no estimate:\n{text}"));
    assert!(lines[est].contains(&estimate), "{estimate}\n{text}");
    let path = at("path 1").unwrap_or_else(|| panic!("no sampled path:\n{text}"));
    let whitted = at("Whitted reading").unwrap_or_else(|| panic!("no label:\n{text}"));
    let root = at("primary").unwrap();
    assert!(est < path && path < whitted && whitted < root, "{text}");
}

/// Defect 3 as the issue saw it: lesson 14, pixel 80,60, where 15 of the sphere light's 16
/// shadow rays pass the shelf.
#[test]
fn the_tree_says_how_much_of_a_soft_shadow_is_blocked() {
    let mut app = open(
        "lessons/14-monte-carlo-glossy",
        ColorMode::TrueColor,
        (160, 48),
    );
    update(&mut app, Msg::Pick(80, 60));
    let text = screen(&app);
    assert!(text.contains("partly blocked (15 of 16 clear)"), "{text}");
    assert!(!text.contains("blocked by shelf, s"), "{text}");
}

/// A copy of lesson 05 (a mirror, a ball) in a scratch folder, with `solutions: hidden`.
fn hidden_lesson(name: &str) -> PathBuf {
    let dir = scratch(name);
    for f in ["scene.yaml", "weights.yaml", "README.md"] {
        std::fs::copy(Path::new("lessons/05-reflection").join(f), dir.join(f)).unwrap();
    }
    let exercises = std::fs::read_to_string("lessons/05-reflection/exercises.yaml").unwrap();
    std::fs::write(
        dir.join("exercises.yaml"),
        exercises.replacen("exercises:", "solutions: hidden\nexercises:", 1),
    )
    .unwrap();
    dir
}

/// Answers exercise `i` of the open lesson with raytree's own value.
fn answer_right(app: &mut App, i: usize) {
    let l = &app.lesson.as_ref().unwrap().lesson;
    let ex = &l.exercises[i];
    let value = raytree::lessons::work(l, ex).unwrap().expected.show();
    update(app, Msg::Exercises);
    let at = app.lesson.as_ref().unwrap().exercise;
    for _ in at..i {
        update(app, Msg::Down);
    }
    for _ in i..at {
        update(app, Msg::Up);
    }
    update(app, Msg::Submit);
    for c in value.chars() {
        update(app, Msg::Input(c));
    }
    update(app, Msg::Submit);
}

/// With `solutions: hidden`, no worked solutions, and the tree and details show no intensity
/// until every intensity exercise of the scene is answered right.
#[test]
fn hidden_solutions_hide_intensities_until_answered() {
    let dir = hidden_lesson("hidden-solutions");
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(80, 60));
    let text = screen(&app);
    assert!(text.contains("I = ?"), "{text}");
    assert!(!text.contains("I = 0."), "{text}");
    press(&mut app, KeyCode::Char('a'));
    press(&mut app, KeyCode::Char('w'));
    assert!(screen(&app).contains("hidden"), "{}", screen(&app));
    assert!(!screen(&app).contains("worked solution (w hides):"));
    let asks: Vec<usize> = {
        let l = &app.lesson.as_ref().unwrap().lesson;
        l.exercises
            .iter()
            .enumerate()
            .filter(|(_, e)| {
                use raytree::lessons::Ask::*;
                matches!(e.ask, Intensity | Local | Diffuse | Specular | PixelValue)
            })
            .map(|(k, _)| k)
            .collect()
    };
    let (last, rest) = asks.split_last().unwrap();
    for &k in rest {
        answer_right(&mut app, k);
    }
    assert!(screen(&app).contains("I = ?"), "one left: still hidden");
    answer_right(&mut app, *last);
    let text = screen(&app);
    assert!(!text.contains("I = ?"), "{text}");
    assert!(text.contains("I = 0."), "{text}");
}

/// A right answer is kept: the exercise list marks it, and so do a new session's exercise list
/// and lesson list.
#[test]
fn right_answers_are_marked_and_kept_between_sessions() {
    let dir = hidden_lesson("progress");
    std::fs::write(
        dir.join("exercises.yaml"),
        std::fs::read_to_string("lessons/05-reflection/exercises.yaml").unwrap(),
    )
    .unwrap();
    let mut app = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    answer_right(&mut app, 4);
    let solved = |app: &App| app.lesson.as_ref().unwrap().solved.clone();
    assert_eq!(solved(&app).len(), 1);
    let mut again = open(dir.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    assert_eq!(solved(&again), solved(&app));
    press(&mut again, KeyCode::Char('a'));
    let text = screen(&again);
    assert!(text.contains("✓ mirror-local"), "{text}");
    let mut list = App::open_lessons(dir.parent().unwrap(), ColorMode::TrueColor);
    update(&mut list, Msg::Resize(100, 30));
    let at = list
        .list
        .as_ref()
        .unwrap()
        .entries
        .iter()
        .position(|e| e.dir == dir)
        .unwrap();
    for _ in 0..at {
        update(&mut list, Msg::Down);
    }
    let text = screen(&list);
    assert!(text.contains(" 1/11"), "{text}");
    assert!(text.contains("✓ mirror-local"), "{text}");
}

/// Lesson 10's CSG exercises are objects made of the same spheres A, B and C in one place:
/// the diagram names each sphere once, by the plain sphere that comes first in the file, not by
/// whichever object was drawn last over it.
#[test]
fn the_diagram_names_coinciding_objects_by_the_first() {
    let mut app = open("lessons/10-csg", ColorMode::TrueColor, (160, 48));
    press(&mut app, KeyCode::Char('d'));
    let r = app.panes().diagram.expect("the diagram pane");
    let inside = pane_text(&app, r);
    let words: Vec<&str> = inside
        .split(|c: char| !c.is_alphanumeric() && c != '_')
        .collect();
    for name in ["A", "B", "C"] {
        assert!(words.contains(&name), "{name} in\n{inside}");
    }
    for name in ["AplusBplusC", "AminusB", "BminusA_cap_C", "Aplus_BcapC"] {
        assert!(!words.contains(&name), "{name} in\n{inside}");
    }
}

/// Below 30 × 8 the explorer draws no panes but says so, the whole message wrapped to the
/// screen, down to 20 × 6; q still quits.
#[test]
fn a_terminal_too_small_is_told_so_in_full() {
    for (w, h) in [(29, 24), (40, 6), (20, 6)] {
        let mut app = open(MIRROR, ColorMode::TrueColor, (w, h));
        let text = screen(&app);
        let words = text.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(
            words.contains(&format!(
                "The terminal is {w} × {h}: the explorer needs 30 × 8 at least. Enlarge it, or press q."
            )),
            "{w} × {h}:\n{text}"
        );
        press(&mut app, KeyCode::Char('q'));
        assert!(app.quit);
    }
}

/// A scene that asks for more than 16 levels is explored at its own depth while its tree stays
/// small: lesson 07's `depth-deep` exercise, whose worked answer (the README's geometric series
/// of the mirror's bounces, 0.570874 / 0.68) is 0.839520.
#[test]
fn a_deep_scene_with_a_small_tree_is_explored_at_its_own_depth() {
    let dir = scratch("deep-mirror");
    let lesson = std::fs::read_to_string("lessons/07-recursion-depth/scene.yaml").unwrap();
    let deep = dir.join("deep.yaml");
    std::fs::write(&deep, lesson.replace("max_depth: 5", "max_depth: 40")).unwrap();
    let mut app = open(deep.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(80, 60));
    assert_eq!(app.tree.depth(), 40);
    assert_eq!(app.tree.depth_cut_from(), None);
    assert_eq!(app.preview.depth, Some(40));
    let intensity = root_color(&app).x;
    assert!((intensity - 0.839520).abs() < 5e-7, "{intensity}");
    assert!(screen(&app).contains("depth 40 "));
}

/// Where each level doubles the tree (a glass ball inside a mirrored sphere: every ray comes
/// back to the ball and splits again), the tree is traced as deep as it stays within the
/// budget, and the screen says so: the deepest depth whose tree holds at most `TREE_BUDGET`
/// rays, counted by the tracer itself.
#[test]
fn a_tree_that_doubles_each_level_stops_at_the_budget_and_says_so() {
    use raytree::tui::{FREE_DEPTH, TREE_BUDGET};
    let dir = scratch("doubling");
    let scene = dir.join("doubling.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 40, width: 40, height: 30 }\n\
         max_depth: 40\n\
         adaptive_threshold: 0\n\
         lights: [ { point: [0, 5, -5], intensity: 1 } ]\n\
         materials:\n  \
           glass: { color: 1, kr: 0.5, kt: 0.5, ior: 1.5 }\n  \
           mirror: { color: 1, kr: 1 }\n\
         objects:\n  \
           - { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: glass }\n  \
           - { name: shell, sphere: { center: [0, 0, 0], radius: 10 }, material: mirror }\n",
    )
    .unwrap();
    let mut app = open(scene.to_str().unwrap(), ColorMode::TrueColor, (160, 48));
    update(&mut app, Msg::Pick(20, 15));
    let depth = app.tree.depth();
    let rays = |d: u32| {
        let scene = app.file.scene.as_ref().unwrap();
        let ray = scene.camera.pixel_ray(20, 15);
        let mut tracer = Tracer::new(scene).with_depth(d);
        tracer.radiance(&ray);
        tracer.stats.rays()
    };
    assert!((FREE_DEPTH..40).contains(&depth), "depth {depth}");
    assert!(depth == FREE_DEPTH || rays(depth) <= TREE_BUDGET);
    assert!(rays(depth + 1) > TREE_BUDGET);
    assert_eq!(app.tree.depth_cut_from(), Some(40));
    assert_eq!(app.tree.stats().rays(), rays(depth));
    assert!(screen(&app).contains(&format!("depth {depth} of 40 (preview {FREE_DEPTH})")));
    // The preview traces every pixel: it stays at FREE_DEPTH, where a pixel's tree has some
    // thousands of rays, not the picked tree's hundred thousand.
    assert_eq!(app.preview.depth, Some(FREE_DEPTH));
    press(&mut app, KeyCode::Char('+'));
    assert_eq!(app.tree.depth(), depth);
    assert!(screen(&app).contains(&format!("over {TREE_BUDGET} rays")));
    // One level shallower is one level up from the tree shown.
    press(&mut app, KeyCode::Char('-'));
    assert_eq!(app.tree.depth(), depth - 1);
    assert_eq!(app.tree.depth_cut_from(), None);
}
