//! The lessons compiled into the binary: a `raytree` run from a folder without `lessons/` (as an
//! installed one is) lists, checks and exports them; `--lessons DIR` and `RAYTREE_LESSONS` put a
//! teacher's own folder in their place. (`.ci/run` repeats the first with `cargo install`.)

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `raytree ARGS` in `dir`, with the cache and data folders inside `dir` and no lessons set.
fn raytree_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .current_dir(dir)
        .env_remove("RAYTREE_LESSONS")
        .env("RAYTREE_CACHE", dir.join("cache"))
        .env("RAYTREE_DATA", dir.join("data"))
        .env("NO_COLOR", "1")
        .output()
        .expect("runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Every file under `dir`, by its path relative to `dir`, with its bytes.
fn tree(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let bytes = std::fs::read(&p).unwrap();
                out.push((p.strip_prefix(root).unwrap().to_path_buf(), bytes));
            }
        }
    }
    let mut out = vec![];
    walk(dir, dir, &mut out);
    out.sort();
    out
}

fn source_lessons() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

/// The ids of the lessons `raytree lessons … --format json` lists, run in `dir`, and the
/// whole document.
fn listed_lessons(dir: &Path, args: &[&str]) -> (Vec<String>, serde_json::Value) {
    let o = raytree_in(dir, args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let doc: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let ids = doc["lessons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["id"].as_str().expect("every lesson loads").to_string())
        .collect();
    (ids, doc)
}

#[test]
fn away_from_the_sources_the_built_in_lessons_are_listed_and_checked() {
    let tmp = tempfile::tempdir().unwrap();
    let (ids, doc) = listed_lessons(tmp.path(), &["lessons", "--format", "json"]);
    let expected: Vec<String> = {
        let mut v: Vec<String> = std::fs::read_dir(source_lessons())
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.join("exercises.yaml").is_file())
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    assert_eq!(ids, expected);
    // The copy they are read from is the user's cache, not the sources.
    let root = PathBuf::from(doc["root"].as_str().unwrap());
    assert!(root.starts_with(tmp.path().join("cache")), "{root:?}");

    // Lesson 01's README works out the top-left window point as (−2, 1, 0): by the lesson's
    // name, or by its path in the sources.
    for lesson in ["01-camera", "lessons/01-camera"] {
        let o = raytree_in(
            tmp.path(),
            &[
                "check",
                lesson,
                "--exercise",
                "window-point-00",
                "--answer",
                "-2, 1, 0",
            ],
        );
        assert!(
            o.status.success(),
            "{lesson}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // A lesson's name stands for its scene wherever a command takes a scene.
    let named = raytree_in(
        tmp.path(),
        &["inspect", "05-reflection", "--pixel", "20,15"],
    );
    assert!(
        named.status.success(),
        "{}",
        String::from_utf8_lossy(&named.stderr)
    );
    let source = source_lessons().join("05-reflection/scene.yaml");
    let source = source.to_str().unwrap();
    let by_path = raytree_in(tmp.path(), &["inspect", source, "--pixel", "20,15"]);
    assert!(stdout(&named).contains("primary"), "{}", stdout(&named));
    assert_eq!(stdout(&named), stdout(&by_path));
    // One lesson listed by its name, away from the sources as well.
    let (listed, _) = listed_lessons(tmp.path(), &["lessons", "01-camera", "--format", "json"]);
    assert_eq!(listed, ["01-camera"]);
    let wrong = raytree_in(
        tmp.path(),
        &[
            "check",
            "01-camera",
            "--exercise",
            "window-point-00",
            "--answer",
            "2, 1, 0",
        ],
    );
    assert_eq!(wrong.status.code(), Some(1));
}

#[test]
fn lessons_export_writes_the_built_in_lessons_as_they_are_in_the_sources() {
    let tmp = tempfile::tempdir().unwrap();
    let o = raytree_in(tmp.path(), &["lessons", "export", "course"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(tree(&tmp.path().join("course")) == tree(&source_lessons()));
    // A second export would overwrite them: refused, one line, exit 2, nothing changed.
    std::fs::write(tmp.path().join("course/01-camera/README.md"), "mine").unwrap();
    let again = raytree_in(tmp.path(), &["lessons", "export", "course"]);
    assert_eq!(again.status.code(), Some(2));
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        err.contains("not empty") && err.lines().count() == 1,
        "{err}"
    );
    let readme = std::fs::read_to_string(tmp.path().join("course/01-camera/README.md"));
    assert_eq!(readme.unwrap(), "mine");
}

#[test]
fn a_teachers_folder_replaces_the_built_in_lessons() {
    let tmp = tempfile::tempdir().unwrap();
    let mine = tmp.path().join("mine");
    let o = raytree_in(tmp.path(), &["lessons", "export", "all"]);
    assert!(o.status.success());
    std::fs::create_dir(&mine).unwrap();
    std::fs::rename(
        tmp.path().join("all/03-local-illumination"),
        mine.join("3-light"),
    )
    .unwrap();
    let ids = |o: &Output| -> Vec<String> {
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let doc: serde_json::Value = serde_json::from_str(&stdout(o)).unwrap();
        let lessons = doc["lessons"].as_array().unwrap();
        lessons
            .iter()
            .map(|l| l["dir"].as_str().unwrap().to_string())
            .collect()
    };
    let by_flag = raytree_in(
        tmp.path(),
        &["--lessons", "mine", "lessons", "--format", "json"],
    );
    assert_eq!(
        ids(&by_flag),
        vec![Path::new("mine/3-light").display().to_string()]
    );
    let by_env = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(["lessons", "--format", "json"])
        .current_dir(tmp.path())
        .env("RAYTREE_LESSONS", "mine")
        .env("RAYTREE_DATA", tmp.path().join("data"))
        .output()
        .unwrap();
    assert_eq!(ids(&by_env), ids(&by_flag));
}

/// Away from the sources, the commands that take a LESSON take its name too: `homework`
/// writes the same folder as from the lesson's path in the sources, `grade` grades a class
/// against the same values, and `lessons validate` checks that one lesson.
/// README: "Wherever a command takes a SCENE, a lesson's folder or name stands for its
/// scene.yaml". Every such command, run by a lesson's name away from the sources, does what it
/// does with the scene's path; `bench sweep` once read the name as a file for its reference.
#[test]
fn away_from_the_sources_every_command_that_takes_a_scene_takes_a_lessons_name() {
    let tmp = tempfile::tempdir().unwrap();
    let source = source_lessons().join("01-camera/scene.yaml");
    let source = source.to_str().unwrap();
    let commands: [&[&str]; 7] = [
        &["render", "SCENE", "-o", "out.ppm"],
        &["inspect", "SCENE", "--pixel", "2,1"],
        &["csg", "SCENE", "--pixel", "2,1"],
        &["diagram", "SCENE", "--pixel", "2,1", "-o", "fig.svg"],
        &["preview", "SCENE", "--ascii"],
        &[
            "bench", "sweep", "SCENE", "--knob", "spp", "--values", "1,4",
        ],
        &["bench", "threads", "SCENE", "--runs", "1"],
    ];
    for command in commands {
        let runs = ["01-camera", source].map(|scene| {
            let args: Vec<&str> = command
                .iter()
                .map(|&a| if a == "SCENE" { scene } else { a })
                .collect();
            let o = raytree_in(tmp.path(), &args);
            assert!(
                o.status.success(),
                "{args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            o
        });
        // What does not depend on the clock is the same either way.
        if command[0] != "bench" {
            assert_eq!(stdout(&runs[0]), stdout(&runs[1]), "{command:?}");
        }
    }
}

#[test]
fn away_from_the_sources_a_lesson_is_named_for_homework_grading_and_validation() {
    let tmp = tempfile::tempdir().unwrap();
    let source = source_lessons().join("03-local-illumination");
    let source = source.to_str().unwrap();
    for (lesson, out) in [("03-local-illumination", "by-name"), (source, "by-path")] {
        let o = raytree_in(
            tmp.path(),
            &["homework", lesson, "--student", "alice", "-o", out],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let by_name = tree(&tmp.path().join("by-name"));
    assert!(by_name.iter().any(|(f, _)| f == Path::new("scene.yaml")));
    assert!(by_name == tree(&tmp.path().join("by-path")));

    std::fs::write(
        tmp.path().join("class.csv"),
        "alice,diffuse,0.5\nbob,diffuse,0.3\n",
    )
    .unwrap();
    let graded = |lesson: &str| {
        let o = raytree_in(
            tmp.path(),
            &["grade", lesson, "--answers", "class.csv", "--format", "csv"],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        stdout(&o)
    };
    let by_name = graded("03-local-illumination");
    assert_eq!(by_name.lines().filter(|l| l.contains("diffuse")).count(), 2);
    assert_eq!(by_name, graded(source));

    let o = raytree_in(tmp.path(), &["lessons", "validate", "01-camera"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout(&o).starts_with("ok: 1 lesson,"), "{}", stdout(&o));
}

/// The examples every command's `--help` shows name scenes as `lessons/…` paths, as a user
/// reads them in the sources; away from the sources they name the built-in lessons' files.
#[test]
fn away_from_the_sources_the_help_examples_find_their_scenes() {
    let tmp = tempfile::tempdir().unwrap();
    let mut ran = 0;
    for command in ["render", "inspect", "csg", "diagram", "preview"] {
        let help = stdout(&raytree_in(tmp.path(), &[command, "--help"]));
        let examples = help
            .lines()
            .map(str::trim)
            .filter(|l| l.starts_with(&format!("raytree {command} lessons/")))
            // A pipe's other side is not raytree's.
            .map(|l| l.split(" | ").next().unwrap())
            .map(|l| l.split_whitespace().skip(1).collect::<Vec<_>>());
        for args in examples {
            let args: Vec<&str> = args.iter().map(|a| a.trim_matches('"')).collect();
            let o = raytree_in(tmp.path(), &args);
            assert!(
                o.status.success(),
                "{args:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            ran += 1;
        }
    }
    assert!(ran >= 10, "only {ran} examples found");
}

/// A `lessons/` folder in the current folder holding one lesson of a teacher's does not hide
/// the built-in ones: `check 08-pixel-intensity` and `render 08-pixel-intensity` still find the
/// built-in lesson 08, and the folder's own lesson is found too. A folder the user chose
/// (`--lessons`) is the only place looked in.
#[test]
fn a_lessons_folder_in_the_current_folder_does_not_hide_the_built_in_lessons() {
    let tmp = tempfile::tempdir().unwrap();
    let mine = tmp.path().join("lessons/03-mine");
    std::fs::create_dir_all(&mine).unwrap();
    for f in std::fs::read_dir(source_lessons().join("03-local-illumination")).unwrap() {
        let f = f.unwrap();
        std::fs::copy(f.path(), mine.join(f.file_name())).unwrap();
    }
    let check = |lesson: &str, extra: &[&str]| {
        let mut args = extra.to_vec();
        args.extend([
            "check",
            lesson,
            "--exercise",
            "pixel-p",
            "--answer",
            "0.870161",
        ]);
        raytree_in(tmp.path(), &args)
    };
    let o = check("08-pixel-intensity", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = raytree_in(
        tmp.path(),
        &[
            "render",
            "08-pixel-intensity",
            "-o",
            "out.png",
            "--width",
            "8",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = raytree_in(tmp.path(), &["lessons", "validate", "03-mine"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = check("08-pixel-intensity", &["--lessons", "lessons"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("no lesson `08-pixel-intensity`"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A built-in lesson's cached copy edited by hand (the explorer shows its path and reloads it
/// on save) is put back as built on the next run: lesson 08's ambient raised to 0.9 made
/// local-a's answer 0.559904 "right", where the lesson's is 0.439904.
#[test]
fn a_built_in_lesson_edited_in_the_cache_is_put_back() {
    let tmp = tempfile::tempdir().unwrap();
    let (_, doc) = listed_lessons(tmp.path(), &["lessons", "--format", "json"]);
    let scene = PathBuf::from(doc["root"].as_str().unwrap()).join("08-pixel-intensity/scene.yaml");
    let built = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(&scene, built.replace("ambient: 0.3", "ambient: 0.9")).unwrap();
    let check = |answer: &str| {
        raytree_in(
            tmp.path(),
            &[
                "check",
                "08-pixel-intensity",
                "--exercise",
                "local-a",
                "--answer",
                answer,
            ],
        )
        .status
        .code()
    };
    assert_eq!(
        check("0.559904"),
        Some(1),
        "the edited scene's answer is wrong"
    );
    assert_eq!(check("0.439904"), Some(0), "the lesson's answer is right");
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), built);
    // A removed file comes back too.
    std::fs::remove_file(&scene).unwrap();
    assert_eq!(check("0.439904"), Some(0));
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), built);
}

/// In an explorer open on that copy, edited meanwhile, an answer is checked against the
/// changed scene and says so, and is not recorded as the built-in lesson's.
#[test]
fn an_answer_to_an_edited_built_in_lesson_is_not_recorded() {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use raytree::render::preview::ColorMode;
    use raytree::tui::{input, ui, update, App, Msg};

    let tmp = tempfile::tempdir().unwrap();
    // This test binary's own process: the other tests run raytree with their own folders.
    std::env::set_var("RAYTREE_CACHE", tmp.path().join("cache"));
    std::env::set_var("RAYTREE_DATA", tmp.path().join("data"));
    let dir = raytree::lessons::builtin::cached()
        .unwrap()
        .join("08-pixel-intensity");
    let mut app = App::open(Some(&dir), ColorMode::TrueColor).expect("opens");
    update(&mut app, Msg::Resize(160, 48));
    let scene = dir.join("scene.yaml");
    let built = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(&scene, built.replace("ambient: 0.3", "ambient: 0.9")).unwrap();
    update(&mut app, Msg::Tick);
    let mut press = |code: KeyCode| {
        if let Some(msg) = input::key(&app, &KeyEvent::new(code, KeyModifiers::NONE)) {
            update(&mut app, msg);
        }
    };
    press(KeyCode::Char('a'));
    press(KeyCode::Enter);
    for c in "0.559904".chars() {
        press(KeyCode::Char(c));
    }
    press(KeyCode::Enter);
    let text = ui::screen_text(&app, 160, 48);
    assert!(
        text.contains("right") && text.contains("checked against the changed scene.yaml"),
        "{text}"
    );
    let progress = std::fs::read_to_string(tmp.path().join("data/progress.json"));
    assert!(
        progress.as_deref().map_or(true, |p| !p.contains("local-a")),
        "{progress:?}"
    );
}
