//! The command line as a user meets it: exit statuses, the JSON contracts, whole outputs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn raytree(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NO_COLOR", "1")
        // A right answer is remembered: in a folder of the test's, not the user's.
        .env(
            "RAYTREE_DATA",
            std::env::temp_dir().join("raytree-cli-data"),
        )
        .output()
        .expect("runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raytree-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

const LESSON_SCENE: &str = "lessons/05-reflection/scene.yaml";

#[test]
fn render_writes_a_png_identical_for_any_thread_count() {
    let (a, b) = (temp("one.png"), temp("two.png"));
    let o1 = raytree(&[
        "render",
        LESSON_SCENE,
        "-o",
        a.to_str().unwrap(),
        "--threads",
        "1",
        "--stats",
    ]);
    assert!(o1.status.success(), "{}", stderr(&o1));
    assert!(stderr(&o1).contains("rays traced"));
    let o2 = raytree(&[
        "render",
        LESSON_SCENE,
        "-o",
        b.to_str().unwrap(),
        "--threads",
        "2",
    ]);
    assert!(o2.status.success());
    let (ia, ib) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert_eq!(ia, ib);
    assert_eq!(&ia[1..4], b"PNG");
}

#[test]
fn a_failed_write_leaves_no_file() {
    let target = temp("no-such-dir").join("out.png");
    let o = raytree(&["render", LESSON_SCENE, "-o", target.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!target.exists());
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
}

#[test]
fn inspect_json_follows_the_contract() {
    let o = raytree(&[
        "inspect",
        "lessons/08-pixel-intensity/scene.yaml",
        "--pixel",
        "30,30",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["pixel"], serde_json::json!([30, 30]));
    let tree = &v["tree"];
    assert_eq!(tree["kind"], "primary");
    assert_eq!(tree["depth"], 0);
    assert_eq!(v["color"], tree["color"]);
    let d: Vec<f64> = serde_json::from_value(tree["direction"].clone()).unwrap();
    assert!(((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - 1.0).abs() < 1e-12);
    for key in [
        "origin",
        "weight",
        "hit",
        "local",
        "color",
        "terminated",
        "children",
    ] {
        assert!(tree.get(key).is_some(), "missing {key}");
    }
    for key in ["object", "t", "point", "normal", "inside"] {
        assert!(tree["hit"].get(key).is_some(), "missing hit.{key}");
    }
    let light = &tree["local"]["lights"][0];
    for key in ["light", "shadow", "diffuse", "specular"] {
        assert!(light.get(key).is_some(), "missing local.lights[0].{key}");
    }
    let kinds: Vec<&str> = tree["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["shadow", "reflection", "refraction"]);
    let shadow = &tree["children"][0];
    assert_eq!(shadow["shadow"], 1.0);
    assert!(shadow["hit"].is_null());
    let c: f64 = serde_json::from_value(tree["color"][0].clone()).unwrap();
    assert!((c - 0.870161).abs() < 1e-6, "the lecture's pixel p: {c}");
}

#[test]
fn inspect_accepts_an_explicit_ray_and_a_depth() {
    let o = raytree(&[
        "inspect",
        "lessons/08-pixel-intensity/scene.yaml",
        "--ray",
        "-2,3.4641016,0:0.5,-0.8660254,0",
        "--depth",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("not traced: max depth"), "{text}");
    assert!(
        text.starts_with("primary (depth 0): hit a, I = 0.439904"),
        "{text}"
    );
}

#[test]
fn csg_json_follows_the_contract() {
    let o = raytree(&[
        "csg",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,0,-10:0,0,1",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["ray"]["direction"], serde_json::json!([0.0, 0.0, 1.0]));
    let objects = v["objects"].as_array().unwrap();
    let diff = objects
        .iter()
        .find(|o| o["node"]["op"] == "difference")
        .expect("a difference");
    let segs = diff["node"]["segments"].as_array().unwrap();
    assert!(!segs.is_empty());
    for key in ["t_in", "t_out", "point_in", "point_out"] {
        assert!(segs[0].get(key).is_some());
    }
    assert_eq!(diff["node"]["children"].as_array().unwrap().len(), 2);
    assert_eq!(diff["node"]["pruned"], false);
}

/// The lists run along the ray's whole line, but only crossings ahead of its origin are hits:
/// `csg` says which, as `inspect` does. Seed 000's spheres: A (centre z = 8, r = 5) spans
/// z ∈ [3, 13], B (z = 9, r = 3) spans z ∈ [6, 12], along the z axis.
#[test]
fn csg_says_what_the_ray_hits_ahead_of_its_origin() {
    let csg = |ray: &str| {
        let o = raytree(&[
            "csg",
            "lessons/10-csg/scene.yaml",
            "--ray",
            ray,
            "--format",
            "json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str::<serde_json::Value>(&stdout(&o)).unwrap()
    };
    let hit_of = |v: &serde_json::Value, name: &str| {
        let objects = v["objects"].as_array().unwrap();
        objects.iter().find(|o| o["object"] == name).unwrap()["hit"].clone()
    };
    // From z = 30 every segment lies behind the origin (A's at t ∈ [−27, −17]): no hit, as
    // inspect finds the background.
    let behind = csg("0,0,30:0,0,1");
    assert!(!behind["objects"].as_array().unwrap().is_empty());
    for o in behind["objects"].as_array().unwrap() {
        assert!(o["hit"].is_null(), "{o}");
    }
    assert!(behind["nearest"].is_null());
    let text = stdout(&raytree(&[
        "csg",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,0,30:0,0,1",
    ]));
    assert!(
        text.contains("not hit: its segments lie behind the ray's origin"),
        "{text}"
    );
    assert!(
        text.contains("the ray hits nothing ahead of its origin"),
        "{text}"
    );
    // A ray that meets no object at all ends its listing with the same last line.
    let away = stdout(&raytree(&[
        "csg",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,50,0:1,0,0",
    ]));
    assert!(away.contains("the ray meets no object"), "{away}");
    assert_eq!(
        away.trim_end().lines().last(),
        Some("nearest hit: none, the ray hits nothing ahead of its origin"),
        "{away}"
    );
    let inspect = stdout(&raytree(&[
        "inspect",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,0,30:0,0,1",
    ]));
    assert!(inspect.contains("background"), "{inspect}");
    // From z = 10, inside A and B: A is left at z = 13 (t = 3), B at z = 12 (t = 2), and A − B
    // is entered again at z = 12: B and A − B are hit first.
    let inside = csg("0,0,10:0,0,1");
    assert_eq!(hit_of(&inside, "A")["t"], 3.0);
    assert_eq!(hit_of(&inside, "B")["t"], 2.0);
    assert_eq!(hit_of(&inside, "AminusB")["t"], 2.0);
    assert_eq!(inside["nearest"]["t"], 2.0);
    assert_eq!(
        inside["nearest"]["point"],
        serde_json::json!([0.0, 0.0, 12.0])
    );
    // The notes' ray from z = −10 meets A first at z = 3, t = 13.
    let notes = csg("0,0,-10:0,0,1");
    assert_eq!(notes["nearest"]["object"], "A");
    assert_eq!(notes["nearest"]["t"], 13.0);
}

/// The command a render suggests for a pixel that is not finite computes that pixel: it
/// carries the render's --depth and image size. kr = kt = 10¹⁰⁰ makes a ray of depth d weigh
/// 10¹⁰⁰ᵈ: finite to the scene's own max_depth 2, past f64's 1.8·10³⁰⁸ from depth 4 on.
#[test]
fn the_replay_of_a_pixel_that_is_not_finite_computes_it() {
    let scene = temp("replay-huge.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
         background: 1\nmax_depth: 2\n\
         materials: { g: { kr: 1e100, kt: 1e100, ior: 1.5 } }\n\
         objects: [ { name: b, sphere: { center: [0, 0, 0], radius: 1 }, material: g } ]\n",
    )
    .unwrap();
    let image = temp("replay-huge.exr");
    let (scene, image) = (scene.to_str().unwrap(), image.to_str().unwrap());
    let args = [
        "render", scene, "-o", image, "--depth", "5", "--width", "40", "--height", "30",
    ];
    let o = raytree(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let (_, command) = err
        .split_once("replay it with: raytree ")
        .expect("a replay command");
    let replay: Vec<&str> = command.split_whitespace().collect();
    assert!(
        command.contains("--depth 5") && command.contains("--width 40"),
        "{command}"
    );
    let shown = stdout(&raytree(&replay));
    let first = shown.lines().next().unwrap_or_default();
    assert!(
        first.ends_with("= ∞") || first.ends_with("= NaN"),
        "{shown}"
    );
}

#[test]
fn check_exit_status_says_right_wrong_or_usage() {
    let right = raytree(&[
        "check",
        "lessons/10-csg",
        "--exercise",
        "b-difference",
        "--answer",
        "13, 16; 22, 23",
    ]);
    assert_eq!(right.status.code(), Some(0), "{}", stdout(&right));
    assert!(stdout(&right).starts_with("right"));
    let wrong = raytree(&[
        "check",
        "lessons/10-csg",
        "--exercise",
        "b-difference",
        "--answer",
        "13, 23",
    ]);
    assert_eq!(wrong.status.code(), Some(1));
    assert!(stdout(&wrong).starts_with("wrong"));
    let usage = raytree(&[
        "check",
        "lessons/10-csg",
        "--exercise",
        "nope",
        "--answer",
        "1",
    ]);
    assert_eq!(usage.status.code(), Some(2));
    let garbage = raytree(&[
        "check",
        "lessons/10-csg",
        "--exercise",
        "b-difference",
        "--answer",
        "abc",
    ]);
    assert_eq!(garbage.status.code(), Some(2));
}

#[test]
fn check_hints_at_the_forgotten_shadow_term() {
    // Lesson 04: at point p the sun is blocked. The answer a student gets by ignoring s is
    // recomputed here with shadow rays switched off, and must draw the shadow hint.
    let lesson = raytree::lessons::Lesson::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/04-shadows"),
    )
    .unwrap();
    let ex = lesson.exercise("local-p").unwrap();
    let w = raytree::lessons::work(&lesson, ex).unwrap();
    assert!(w
        .tree
        .local
        .as_ref()
        .unwrap()
        .lights
        .iter()
        .any(|l| l.shadow == 0.0 && l.n_dot_l > 0.0));
    let options = raytree::trace::TraceOptions {
        max_depth: w.depth,
        shadows: false,
        ..raytree::trace::TraceOptions::of(&w.scene)
    };
    let unshadowed = raytree::trace::Tracer::new(&w.scene)
        .with_options(options)
        .inspect(&w.ray)
        .local
        .unwrap()
        .total()
        .x;
    let o = raytree(&[
        "check",
        "lessons/04-shadows",
        "--exercise",
        "local-p",
        "--answer",
        &format!("{unshadowed}"),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stdout(&o).contains("hint: you left out the shadow term"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn explain_prints_the_derivation() {
    let o = raytree(&[
        "check",
        "lessons/01-camera",
        "--exercise",
        "window-point-00",
        "--explain",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("Δu = (wr − wl)/(nc − 1)"), "{text}");
    assert!(text.contains("answer: -2, 1, 0"), "{text}");
}

#[test]
fn bad_input_exits_2_with_one_line_and_no_panic() {
    let bad = temp("bad.yaml");
    std::fs::write(&bad, "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: 1 }, material: nope }\n").unwrap();
    let cases: Vec<Vec<String>> = vec![
        vec![
            "inspect".into(),
            bad.display().to_string(),
            "--pixel".into(),
            "0,0".into(),
        ],
        vec![
            "render".into(),
            "lessons".into(),
            "-o".into(),
            temp("x.png").display().to_string(),
        ],
        vec![
            "render".into(),
            "no/such/scene.yaml".into(),
            "-o".into(),
            temp("x.png").display().to_string(),
        ],
        vec![
            "inspect".into(),
            LESSON_SCENE.into(),
            "--pixel".into(),
            "100000,0".into(),
        ],
        vec![
            "inspect".into(),
            LESSON_SCENE.into(),
            "--pixel".into(),
            "a,b".into(),
        ],
        vec![
            "inspect".into(),
            LESSON_SCENE.into(),
            "--ray".into(),
            "0,0,0:0,0,0".into(),
        ],
        vec![
            "render".into(),
            LESSON_SCENE.into(),
            "-o".into(),
            temp("x.gif").display().to_string(),
        ],
        vec![
            "render".into(),
            LESSON_SCENE.into(),
            "-o".into(),
            temp("x.png").display().to_string(),
            "--depth".into(),
            "0".into(),
        ],
    ];
    for args in cases {
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = raytree(&refs);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!err.trim().is_empty());
    }
    let o = raytree(&["inspect", bad.to_str().unwrap(), "--pixel", "0,0"]);
    let err = stderr(&o);
    assert!(
        err.contains("bad.yaml:3:68: unknown material `nope`"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1);
}

/// A tall image (1 × 1 000 000 pixels, within the budget) is previewed at most 1000 lines
/// high, a column wide, not rendered 40 × 40 000 000 pixels large.
#[test]
fn a_tall_image_is_previewed_a_thousand_lines_high() {
    let scene = temp("tall.yaml");
    std::fs::write(
        &scene,
        [
            "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 1, height: 1000000 }",
            "materials: { m: { kd: 1 } }",
            "objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m } ]",
        ]
        .join("\n"),
    )
    .unwrap();
    let o = raytree(&[
        "preview",
        scene.to_str().unwrap(),
        "--ascii",
        "--columns",
        "40",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert_eq!(text.lines().count(), 1000);
    assert!(text.lines().all(|l| l.chars().count() == 1), "{text}");
}

#[test]
fn preview_and_lessons_list() {
    let o = raytree(&["preview", LESSON_SCENE, "--columns", "40", "--ascii"]);
    assert!(o.status.success());
    let text = stdout(&o);
    assert!(text.lines().all(|l| l.chars().count() == 40));
    assert!(text.lines().count() >= 10);
    // The narrowest and widest previews are drawn as asked; beyond them, a usage error.
    for columns in ["4", "1000"] {
        let o = raytree(&["preview", LESSON_SCENE, "--columns", columns, "--ascii"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let widths: Vec<String> = stdout(&o)
            .lines()
            .map(|l| l.chars().count().to_string())
            .collect();
        assert!(widths.len() >= 2, "{widths:?}");
        assert!(widths.iter().all(|w| w == columns), "{widths:?}");
    }
    for columns in ["0", "3", "1001"] {
        let o = raytree(&["preview", LESSON_SCENE, "--columns", columns, "--ascii"]);
        assert_eq!(o.status.code(), Some(2), "--columns {columns}");
        assert!(stdout(&o).is_empty());
        assert!(stderr(&o).contains("--columns"), "{}", stderr(&o));
    }
    let o = raytree(&["lessons"]);
    assert!(o.status.success());
    let text = stdout(&o);
    assert!(text.contains("08-pixel-intensity") && text.contains("pixel-p"));
}

/// `--sample K` on a path-traced pixel shows sample K's path: the sixteen samples of lesson
/// 15's pixel, asked for one by one, are sixteen paths whose mean is the pixel's estimate (a
/// box filter), the first four those shown without `--sample`; a K beyond the samples is
/// refused as it is on a Whitted scene.
#[test]
fn a_path_traced_pixel_shows_the_sample_asked_for() {
    let json = |extra: &[&str]| -> serde_json::Value {
        let args = ["inspect", "lessons/15-path-tracing", "--pixel", "10,10"];
        let o = raytree(&[&args[..], extra, &["--format", "json"]].concat());
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str(&stdout(&o)).unwrap()
    };
    let rgb = |x: &serde_json::Value| -> [f64; 3] {
        std::array::from_fn(|i| x[i].as_f64().expect("a number"))
    };
    let all = json(&[]);
    assert_eq!(all["samples"], 16);
    let mut sum = [0.0; 3];
    for k in 1..=16 {
        let one = json(&["--sample", &k.to_string()]);
        let paths = one["paths"].as_array().unwrap();
        assert_eq!(paths.len(), 1, "{one}");
        assert_eq!(paths[0]["sample"], k);
        if k <= 4 {
            assert_eq!(paths[0], all["paths"][k - 1], "sample {k}");
        }
        let value = rgb(&paths[0]["value"]);
        (0..3).for_each(|c| sum[c] += value[c] / 16.0);
    }
    let estimate = rgb(&all["color"]);
    assert!(
        (0..3).all(|c| (sum[c] - estimate[c]).abs() < 1e-9),
        "mean of the samples {sum:?}, estimate {estimate:?}"
    );
    let o = raytree(&[
        "inspect",
        "15-path-tracing",
        "--pixel",
        "10,10",
        "--sample",
        "17",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--sample must be between 1 and 16"),
        "{}",
        stderr(&o)
    );
}

/// A path that leaves lesson 15's box meets no surface: its last vertex says where it left
/// from (its last bounce, or the eye) and in which direction, and that direction goes out through the
/// box's open front (z = 1, |x| and |y| at most 1), the only way out. Text and JSON agree.
#[test]
fn a_path_that_leaves_the_scene_is_shown_leaving_toward_a_direction() {
    let args = ["inspect", "lessons/15-path-tracing", "--pixel", "10,10"];
    let o = raytree(&[&args[..], &["--format", "json"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let vec3 = |x: &serde_json::Value| -> [f64; 3] {
        std::array::from_fn(|i| x[i].as_f64().expect("a number"))
    };
    let mut escapes = 0;
    for p in v["paths"].as_array().unwrap() {
        let vertices = p["vertices"].as_array().unwrap();
        for (k, x) in vertices.iter().enumerate() {
            if x["event"] != "background" {
                assert!(x["toward"].is_null(), "{x}");
                continue;
            }
            escapes += 1;
            let [o, d] = [vec3(&x["point"]), vec3(&x["toward"])];
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((length - 1.0).abs() < 1e-6, "{x}");
            // The primary ray leaves from the eye.
            let last = match k {
                0 => [0.0, 0.0, 3.9],
                _ => vec3(&vertices[k - 1]["point"]),
            };
            assert!((0..3).all(|i| (o[i] - last[i]).abs() < 1e-6), "{x}");
            assert!(d[2] > 0.0, "{x}");
            let t = (1.0 - o[2]) / d[2];
            let (ex, ey) = (o[0] + t * d[0], o[1] + t * d[1]);
            assert!(
                ex.abs() <= 1.0 && ey.abs() <= 1.0,
                "leaves at ({ex}, {ey}): {x}"
            );
        }
    }
    assert!(escapes > 0, "no path of pixel (10, 10) leaves the box: {v}");
    let text = stdout(&raytree(&args));
    let leaving: Vec<&str> = text.lines().filter(|l| l.contains("background")).collect();
    assert_eq!(leaving.len(), escapes, "{text}");
    assert!(
        leaving
            .iter()
            .all(|l| l.contains(" toward (") && !l.contains(" at (")),
        "{text}"
    );
}

/// A path-traced pixel keeps the JSON contract's `tree`: the Whitted reading of its centre
/// ray, from lesson 15's eye at (0, 0, 3.9), the same tree `--ray` gives for that ray. An
/// explicit ray is read the Whitted way too: straight back from the eye along −z it meets
/// the back wall's face z = −1 at t = 4.9, normal (0, 0, 1). Graphviz draws the reading.
#[test]
fn a_path_traced_scene_is_inspected_with_its_whitted_reading() {
    let pixel = ["inspect", "15-path-tracing", "--pixel", "30,30"];
    let o = raytree(&[&pixel[..], &["--format", "json"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["integrator"], "path");
    let tree = &v["tree"];
    assert_eq!(tree["kind"], "primary");
    assert_eq!(tree["depth"], 0);
    let at = |x: &serde_json::Value| -> Vec<f64> {
        (0..3).map(|i| x[i].as_f64().expect("a number")).collect()
    };
    assert_eq!(at(&tree["origin"]), [0.0, 0.0, 3.9]);
    let d = at(&tree["direction"]);
    let ray = format!("0,0,3.9:{},{},{}", d[0], d[1], d[2]);
    let o = raytree(&[
        "inspect",
        "15-path-tracing",
        "--ray",
        &ray,
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let by_ray: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(by_ray["tree"]["color"], tree["color"]);
    assert_eq!(by_ray["integrator"], "path");

    let o = raytree(&[
        "inspect",
        "15-path-tracing",
        "--ray",
        "0,0,3.9:0,0,-1",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let hit = &v["tree"]["hit"];
    assert_eq!(hit["object"], "back");
    assert!((hit["t"].as_f64().unwrap() - 4.9).abs() < 1e-12, "{hit}");
    assert_eq!(at(&hit["normal"]), [0.0, 0.0, 1.0]);
    let text = stdout(&raytree(&[
        "inspect",
        "15-path-tracing",
        "--ray",
        "0,0,3.9:0,0,-1",
    ]));
    assert!(
        text.starts_with("the Whitted reading of this ray"),
        "{text}"
    );

    let o = raytree(&[&pixel[..], &["--format", "dot"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("digraph"), "{}", stdout(&o));
    assert!(stdout(&o).contains("Whitted reading of its centre ray"));
}

#[test]
fn inspect_a_path_traced_pixel_shows_sampled_paths_and_the_estimate() {
    let o = raytree(&[
        "inspect",
        "lessons/examples/cornell.yaml",
        "--pixel",
        "128,60",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["integrator"], "path");
    assert_eq!(v["samples"], 64);
    let paths = v["paths"].as_array().unwrap();
    assert_eq!(paths.len(), 4);
    for p in paths {
        let vertices = p["vertices"].as_array().unwrap();
        assert!(!vertices.is_empty());
        // Each path's value is the sum of what its vertices added.
        let added: f64 = vertices
            .iter()
            .map(|x| x["added"][0].as_f64().unwrap())
            .sum();
        assert!((added - p["value"][0].as_f64().unwrap()).abs() < 1e-9);
    }
}

#[test]
fn bench_threads_prints_both_speed_ups_and_refuses_one_thread() {
    let o = raytree(&["bench", "threads", LESSON_SCENE, "--runs", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 5, "{out}");
    for (line, name) in [(1, "scene"), (2, "arithmetic")] {
        let fields: Vec<&str> = lines[line].split_whitespace().collect();
        assert_eq!(fields[0], name, "{out}");
        // Seconds on one thread and on N, then the speed-up: all positive numbers.
        let seconds: Vec<f64> = fields[1..3].iter().map(|f| f.parse().unwrap()).collect();
        assert!(seconds.iter().all(|&s| s > 0.0), "{out}");
        let speed_up: f64 = fields[3].trim_end_matches('×').parse().unwrap();
        assert!(speed_up > 0.0, "{out}");
    }
    assert!(lines[3].starts_with("rays per second:"), "{out}");
    assert!(lines[4].contains("% of the arithmetic's"), "{out}");

    let one = raytree(&["bench", "threads", LESSON_SCENE, "--threads", "1"]);
    assert_eq!(one.status.code(), Some(2));
    assert!(stderr(&one).contains("--threads"), "{}", stderr(&one));
}

#[test]
fn bench_explorer_times_depth_keys_picks_and_reloads_per_scene() {
    let o = raytree(&[
        "bench",
        "explorer",
        "08-pixel-intensity",
        "benches/peers/whitted.yaml",
        "--runs",
        "3",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert!(v["raytree_version"].is_string());
    assert_eq!(v["terminal"], serde_json::json!([160, 48]));
    let scenes = v["scenes"].as_array().unwrap();
    let names: Vec<&str> = scenes
        .iter()
        .map(|s| s["scene"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["08-pixel-intensity", "whitted.yaml"]);
    for s in scenes {
        let (w, h) = (
            s["preview"][0].as_u64().unwrap(),
            s["preview"][1].as_u64().unwrap(),
        );
        assert!(w > 0 && h > 0 && w <= 160 && h <= 96, "{s}");
        let full = s["full_ms"].as_f64().unwrap();
        assert!(full > 0.0, "{s}");
        // The draft comes first: the full preview's wait includes it.
        if let Some(draft) = s["draft_ms"].as_f64() {
            assert!(draft > 0.0 && draft <= full, "{s}");
        }
        assert!(s["pick_ms"].as_f64().unwrap() >= 0.0, "{s}");
        assert!(s["reload_ms"].as_f64().unwrap() > 0.0, "{s}");
    }
    // The scene file has no lesson beside it: its preview gets the wider pane.
    assert!(scenes[1]["preview"][0].as_u64() > scenes[0]["preview"][0].as_u64());

    let small = raytree(&["bench", "explorer", "--size", "10x10"]);
    assert_eq!(small.status.code(), Some(2));
    assert!(
        stderr(&small).contains("COLUMNSxROWS"),
        "{}",
        stderr(&small)
    );
}

/// A lesson's folder stands for its scene.yaml wherever a command takes a scene, as `explore`
/// takes it; a folder without one is still refused with a clear error.
#[test]
fn a_lessons_folder_stands_for_its_scene() {
    let folder = raytree(&["inspect", "lessons/05-reflection", "--pixel", "20,15"]);
    let file = raytree(&["inspect", LESSON_SCENE, "--pixel", "20,15"]);
    assert!(folder.status.success(), "{}", stderr(&folder));
    assert!(stdout(&folder).contains("primary"), "{}", stdout(&folder));
    assert_eq!(stdout(&folder), stdout(&file));
    let none = raytree(&[
        "render",
        "lessons",
        "-o",
        temp("none.png").to_str().unwrap(),
    ]);
    assert_eq!(none.status.code(), Some(2));
    assert!(
        stderr(&none).contains("lessons:1:1: is a directory, not a scene file"),
        "{}",
        stderr(&none)
    );
}

/// A corridor of two facing mirrors as deep as a scene may ask (64 levels), rendered by the
/// command's own workers: every sample's ray bounces 63 times (63 reflection rays, 64 shadow
/// rays toward the light between the mirrors, the 64th reflection cut off), and the render
/// finishes on their stacks.
#[test]
fn render_goes_64_levels_deep() {
    let image = temp("corridor.ppm");
    let o = raytree(&[
        "render",
        "tests/scenes/mirror-corridor.yaml",
        "-o",
        image.to_str().unwrap(),
        "--stats",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let samples = 16 * 12 * 16;
    assert_eq!(v["stats"]["primary_rays"], samples);
    assert_eq!(v["stats"]["reflection_rays"], 63 * samples);
    assert_eq!(v["stats"]["shadow_rays"], 64 * samples);
    assert_eq!(v["stats"]["max_depth_cutoffs"], samples);
}

/// Every row of `render --stats` ends in the same column, whatever characters its label has
/// (`n·l ≤ 0` is 7 characters of 11 bytes) and however long it is.
#[test]
fn the_stats_table_ends_every_row_in_the_same_column() {
    let out = temp("stats.png");
    let o = raytree(&[
        "render",
        "lessons/06-refraction",
        "-o",
        out.to_str().unwrap(),
        "--stats",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    // The first line says what was rendered; the table follows.
    let rows: Vec<&str> = err.lines().skip(1).collect();
    for label in [
        "skipped: shadow rays, light behind (n·l ≤ 0)",
        "skipped: shadow rays inside convex solids",
        "rays per second",
        "primitives tested per ray",
    ] {
        assert!(rows.iter().any(|r| r.starts_with(label)), "{label}:\n{err}");
    }
    let end = rows[0].chars().count();
    for row in &rows {
        assert_eq!(row.chars().count(), end, "{row:?}:\n{err}");
    }
}

/// A figure `--stats` prints, as a number: the value at the end of the line `name` begins.
fn stat(stats: &str, name: &str) -> f64 {
    let line = stats
        .lines()
        .find(|l| l.starts_with(name))
        .unwrap_or_else(|| panic!("no {name} in {stats}"));
    line.split_whitespace().last().unwrap().parse().unwrap()
}

/// A number as a README writes it, thin groups of thousands apart: "120 311" is 120311.
fn quoted(s: &str) -> f64 {
    s.replace([' ', '\u{a0}'], "").parse().unwrap()
}

/// The text of `readme` between `before` and `after`.
fn between<'a>(readme: &'a str, before: &str, after: &str) -> &'a str {
    let rest =
        &readme[readme.find(before).unwrap_or_else(|| panic!("no {before}")) + before.len()..];
    rest[..rest.find(after).unwrap_or_else(|| panic!("no {after}"))].trim()
}

/// The `--stats` of the first `raytree render … --stats` command of `readme` that does not
/// turn the BVH off, run as the student is told to run it.
fn stats_of_readme_command(readme: &str) -> String {
    let command = readme
        .lines()
        .map(str::trim)
        .find(|l| {
            l.starts_with("raytree render") && l.contains("--stats") && !l.contains("--accel none")
        })
        .expect("a render command");
    let out = temp("readme-stats.png");
    let mut args: Vec<&str> = command.split_whitespace().skip(1).collect();
    let o = args.iter().position(|a| *a == "-o").unwrap();
    let out = out.to_str().unwrap().to_string();
    args[o + 1] = &out;
    let r = raytree(&args);
    assert!(r.status.success(), "{command}: {}", stderr(&r));
    stderr(&r)
}

/// The work a BVH saves, as lessons 11 and 12 quote it, is what the command they give prints:
/// the counts are exact, so each figure in the text must equal the printed one.
#[test]
fn the_lessons_bvh_counts_are_what_their_commands_print() {
    let readme = std::fs::read_to_string("lessons/12-acceleration/README.md").unwrap();
    let stats = stats_of_readme_command(&readme);
    let per_ray = between(&readme, "| spheres tested per ray |", "|");
    let in_all = between(&readme, "| spheres tested in all |", "|");
    let nodes = between(&readme, "| BVH nodes visited per ray |", "|");
    assert_eq!(
        quoted(per_ray),
        stat(&stats, "primitives tested per ray"),
        "{stats}"
    );
    assert_eq!(
        quoted(in_all),
        stat(&stats, "objects/primitives tested"),
        "{stats}"
    );
    assert_eq!(quoted(nodes), stat(&stats, "BVH nodes per ray"), "{stats}");

    let readme = std::fs::read_to_string("lessons/11-triangles/README.md").unwrap();
    let stats = stats_of_readme_command(&readme);
    let search = between(&readme, "| search |", "\n");
    let tests = between(search, "| ", " ray-primitive tests");
    let nodes = between(search, "ray-primitive tests and", "BVH nodes");
    let per_ray = between(
        &readme,
        "pays a search per ray (",
        "\nprimitives tested per ray",
    );
    assert_eq!(
        quoted(tests),
        stat(&stats, "objects/primitives tested"),
        "{stats}"
    );
    assert_eq!(quoted(nodes), stat(&stats, "BVH nodes visited"), "{stats}");
    assert_eq!(
        quoted(per_ray),
        stat(&stats, "primitives tested per ray"),
        "{stats}"
    );
}

/// A lesson name that is neither a folder nor a lesson gets the same answer from `lessons`
/// and `lessons validate` as from `check`: no such lesson, and where to find the list; a
/// scene named that way, "no such file, nor a lesson of that name".
#[test]
fn an_unknown_lesson_name_is_said_to_be_one() {
    for args in [
        &["lessons", "99-nope"][..],
        &["lessons", "validate", "99-nope"],
        &["check", "99-nope", "--exercise", "x", "--answer", "1"],
    ] {
        let o = raytree(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let e = stderr(&o);
        assert!(
            e.contains("no lesson `99-nope`") && e.contains("`raytree lessons` lists them"),
            "{args:?}: {e}"
        );
    }
    let o = raytree(&["inspect", "99-nope", "--pixel", "1,1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("99-nope:1:1: no such file, nor a lesson of that name"),
        "{}",
        stderr(&o)
    );
}

/// Lesson 12's `bench scaling` table quotes, beside its times, the BVH's work: nodes visited
/// and primitives tested per ray, and a mesh's bytes per triangle. Those are counts, the same
/// on every machine, so every sphere row and every mesh row the test measures must be what
/// the command prints, to the table's one decimal; and the sentence built on the sphere rows
/// must quote their first and last nodes per ray, and the step per ×10 in N between them.
/// (Brute force is left out: it changes only the times.)
#[test]
fn the_lessons_bvh_scaling_counts_are_what_bench_scaling_prints() {
    let o = raytree(&[
        "bench",
        "scaling",
        "--max-spheres",
        "100000",
        "--max-brute",
        "10",
        "--max-brute-triangles",
        "0",
        "--max-subdivisions",
        "3",
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let printed = json["rows"].as_array().unwrap();
    let readme = std::fs::read_to_string("lessons/12-acceleration/README.md").unwrap();
    let table = between(&readme, "bytes/tri\n", "\n\n");
    let mut spheres = vec![];
    let mut checked = 0;
    for line in table.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let (kind, n) = (fields[0], quoted(fields[1]));
        // nodes/ray and prims/ray end a sphere row; a mesh row has its bytes/tri after them.
        let counts = match kind {
            "spheres" => &fields[fields.len() - 2..],
            "mesh" => &fields[fields.len() - 3..],
            _ => panic!("a row of neither spheres nor a mesh: {line}"),
        };
        if kind == "spheres" {
            spheres.push((n, counts[0]));
        }
        // Lesson 12: below 16 bounded objects no BVH is built, so 10 spheres have only a
        // brute-force time; a mesh is one object with a BVH of its own.
        let built = !(kind == "spheres" && n < 16.0);
        let printed_row = printed
            .iter()
            .find(|r| r["kind"] == kind && r["n"].as_f64() == Some(n));
        if let Some(row) = printed_row {
            assert_eq!(row["bvh_built"], built, "{row}");
            assert_eq!(row["bvh_ns_per_ray"].is_f64(), built, "{row}");
            assert!(row["brute_ns_per_ray"].is_f64() || built, "{row}");
            assert_eq!(line.contains("(no BVH)"), !built, "{line}");
        }
        let Some(row) = printed
            .iter()
            .find(|r| r["kind"] == kind && r["n"].as_f64() == Some(n))
        else {
            // A mesh too large for a quick test.
            assert!(kind == "mesh" && n > 1280.0, "no row {line}");
            continue;
        };
        let mut columns = vec![
            ("nodes/ray", counts[0], &row["nodes_per_ray"]),
            ("prims/ray", counts[1], &row["primitives_per_ray"]),
        ];
        if kind == "mesh" {
            columns.push(("bytes/tri", counts[2], &row["bytes_per_triangle"]));
        }
        for (column, quoted, value) in columns {
            assert_eq!(
                quoted,
                format!("{:.1}", value.as_f64().unwrap()),
                "{kind} {n}: {column}\n{row}"
            );
        }
        checked += 1;
    }
    assert_eq!(checked, printed.len(), "{table}");
    assert_eq!(spheres.len(), 5, "{table}");

    let text = flowing(&readme);
    let (first, last) = (spheres[1], spheres[4]);
    let from = between(&text, "the nodes visited per ray grow from ", " to ");
    let to = between(&text, &format!("grow from {from} to "), ":");
    let step = between(&text, &format!("{to}: about +"), " for every × 10");
    assert_eq!((from, to), (first.1, last.1), "{text}");
    let decades = (last.0 / first.0).log10();
    let per_decade = (quoted(last.1) - quoted(first.1)) / decades;
    assert!(rounds_to(step, per_decade), "+{step} per ×10: {per_decade}");
}

/// A README's text with every run of whitespace one space: a figure is found whatever the
/// line breaks around it.
fn flowing(readme: &str) -> String {
    readme.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Whether `quoted`, a figure as a README writes it, is `printed` rounded to the digits it
/// shows: "0.119" for 0.119423, not "0.14".
fn rounds_to(quoted: &str, printed: f64) -> bool {
    let decimals = quoted.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    (quoted.parse::<f64>().unwrap() - printed).abs() <= 0.5 * 10f64.powi(-decimals) + 1e-12
}

/// Lesson 15's worked glow-roulette quotes what `check --explain` prints for the exercise's
/// paths: their number, their standard deviation, the mean's standard error and the mean,
/// each to the digits the text gives. The tolerance the text and the question name is the
/// one `check` applies, and the number of standard errors they call it is that tolerance over
/// the printed standard error, rounded. The biased answer it says is rejected is.
#[test]
fn the_lessons_glow_roulette_figures_are_what_check_explain_prints() {
    let readme = std::fs::read_to_string("lessons/15-path-tracing/README.md").unwrap();
    let text = flowing(&readme);
    let text = between(&text, "With max_depth 64", "**Answer (glow-roulette):**");
    let check = |answer: &str| {
        raytree(&[
            "check",
            "lessons/15-path-tracing",
            "--exercise",
            "glow-roulette",
            "--answer",
            answer,
            "--explain",
        ])
    };
    let o = check("0.4");
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let explain = stdout(&o);
    let printed = |before: &str, after: &str| -> f64 {
        between(&explain, before, after)
            .parse()
            .unwrap_or_else(|e| panic!("{before}: {e}\n{explain}"))
    };
    let paths = between(&explain, "pixel = the mean of the ", " values");
    let mean = printed(&format!("the mean of the {paths} values = "), "\n");
    let s = printed("standard deviation s = ", ";");
    let error = printed("s/√N = ", " ");
    assert!((error - s / quoted(paths).sqrt()).abs() < 1e-6, "{explain}");

    let quoted_paths = between(text, "(the ", " paths of the exercise show");
    let quoted_s = between(text, "paths of the exercise show ", ")");
    let quoted_error = between(text, &format!("/√{paths} ≈ "), ":");
    let quoted_mean = between(text, "raytree's estimate is ", ". ");
    assert_eq!(quoted_paths, paths, "{text}");
    for (what, quoted, printed) in [
        ("standard deviation", quoted_s, s),
        ("standard error", quoted_error, error),
        ("mean", quoted_mean, mean),
    ] {
        assert!(
            rounds_to(quoted, printed),
            "the README's {what} {quoted}, `check --explain` {printed}:\n{text}"
        );
    }
    // The tolerance `check` applied, as the README and the question name it, in standard
    // errors.
    let tolerance = between(&explain, "tolerance ±", ")");
    let question = between(&explain, "glow-roulette: ", "\n");
    for (accepts, words) in [
        (
            between(text, "The exercise accepts ±", ","),
            between(text, "accepts ±", " standard errors"),
        ),
        (
            between(question, "Tolerance ", ","),
            between(question, "Tolerance ", " standard errors"),
        ),
    ] {
        assert_eq!(accepts, tolerance, "{text}\n{question}");
        let count = words.rsplit(' ').next().unwrap();
        let count = ["three", "four", "five", "six"]
            .iter()
            .position(|w| *w == count)
            .unwrap_or_else(|| panic!("{words} standard errors")) as f64
            + 3.0;
        assert_eq!(
            (quoted(accepts) / error).round(),
            count,
            "±{accepts} is {} standard errors of {error}",
            quoted(accepts) / error
        );
    }
    let biased = text.rsplit("and rejects ").next().unwrap();
    let biased = biased.trim_end_matches('.');
    assert_eq!(check(biased).status.code(), Some(1), "{biased} is rejected");
}

#[test]
fn a_path_traced_render_refuses_grid_and_jittered_and_names_its_sampling() {
    const PATH: &str = "lessons/15-path-tracing";
    let out = temp("path.png");
    let small = ["--width", "8", "--height", "8", "--spp", "4"];
    for aa in ["grid", "jittered"] {
        let mut args = vec!["render", PATH, "-o", out.to_str().unwrap(), "--aa", aa];
        args.extend(small);
        let o = raytree(&args);
        assert_eq!(o.status.code(), Some(2), "{aa}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains(&format!("--aa {aa} is not for a path-traced scene"))
                && err.contains("Sobol net"),
            "{err}"
        );
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    // The header names the samples' actual placement: a Sobol net, or adaptive when asked.
    let mut args = vec!["render", PATH, "-o", out.to_str().unwrap(), "--stats"];
    args.extend(small);
    let o = raytree(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let header = stderr(&o).lines().next().unwrap_or_default().to_string();
    assert!(header.contains("4 spp (sobol)"), "{header}");
    args.extend(["--format", "json"]);
    let o = raytree(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["antialias"], "sobol");
    let mut args = vec!["render", PATH, "-o", out.to_str().unwrap(), "--stats"];
    args.extend(small);
    args.extend(["--aa", "adaptive"]);
    let o = raytree(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("4 spp (adaptive)"), "{}", stderr(&o));
    // A Whitted scene still takes jittered sampling, and says so.
    let o = raytree(&[
        "render",
        LESSON_SCENE,
        "-o",
        out.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "4",
        "--aa",
        "jittered",
        "--stats",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("4 spp (jittered)"), "{}", stderr(&o));
}

#[test]
fn flags_that_would_be_ignored_are_refused() {
    let strip = temp("strip.png");
    let o = raytree(&[
        "render",
        "lessons/07-recursion-depth",
        "-o",
        strip.to_str().unwrap(),
        "--depth-strip",
        "3",
        "--depth",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--depth does not go with --depth-strip"),
        "{}",
        stderr(&o)
    );
    assert!(!strip.exists());
    let exr = temp("linear.exr");
    for gamma in ["linear", "srgb"] {
        let o = raytree(&[
            "render",
            LESSON_SCENE,
            "-o",
            exr.to_str().unwrap(),
            "--gamma",
            gamma,
        ]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("--gamma is for 8-bit images (PNG, PPM): an EXR holds linear"),
            "{}",
            stderr(&o)
        );
        assert!(!exr.exists());
    }
    // Where they mean something, both are taken.
    let png = temp("linear.png");
    let o = raytree(&[
        "render",
        LESSON_SCENE,
        "-o",
        png.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "8",
        "--gamma",
        "linear",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = raytree(&[
        "render",
        LESSON_SCENE,
        "-o",
        exr.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "8",
        "--depth",
        "2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_lesson_that_is_none_is_said_to_be_none() {
    let expected = "raytree: no lesson `99-nope`: not a folder here and not a lesson in lessons (`raytree lessons` lists them)\n";
    let answers = temp("answers.csv");
    std::fs::write(&answers, "s1,x,1\n").unwrap();
    let hw = temp("hw-none");
    for args in [
        vec!["check", "99-nope", "--exercise", "x", "--answer", "1"],
        vec!["grade", "99-nope", "--answers", answers.to_str().unwrap()],
        vec![
            "homework",
            "99-nope",
            "--student",
            "s1",
            "-o",
            hw.to_str().unwrap(),
        ],
        vec!["explore", "99-nope"],
    ] {
        let o = raytree(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert_eq!(stderr(&o), expected, "{args:?}");
    }
    // With no lessons folder to look in, the built-in lessons are where the name is sought.
    let nowhere = temp("nowhere");
    std::fs::create_dir_all(&nowhere).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(["check", "99-nope", "--exercise", "x", "--answer", "1"])
        .current_dir(&nowhere)
        .env_remove("RAYTREE_LESSONS")
        .env("XDG_CACHE_HOME", temp("cache"))
        .env("RAYTREE_DATA", temp("data"))
        .output()
        .expect("runs");
    assert_eq!(
        stderr(&o),
        "raytree: no lesson `99-nope`: not a folder here and not a built-in lesson (`raytree lessons` lists them)\n"
    );
    // A lesson that exists is still found by its name.
    let o = raytree(&[
        "check",
        "08-pixel-intensity",
        "--exercise",
        "nope",
        "--answer",
        "1",
    ]);
    assert!(
        stderr(&o).contains("has no exercise `nope`"),
        "{}",
        stderr(&o)
    );
}

/// `--sample K` picks one of a pixel's samples: with a ray given by hand there are none, and
/// the flag is refused as a usage error rather than ignored.
#[test]
fn a_sample_of_a_ray_given_by_hand_is_a_usage_error() {
    let o = raytree(&[
        "inspect",
        "lessons/05-reflection/scene.yaml",
        "--ray",
        "0,0,-10:0,0,1",
        "--sample",
        "99",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stdout(&o));
    let err = stderr(&o);
    assert!(err.contains("--sample") && err.contains("--ray"), "{err}");
}

/// A sphere in the middle of a square image is previewed symmetric top to bottom, at odd
/// widths too: the preview has an even number of pixel rows, two to a line.
#[test]
fn a_centred_sphere_is_previewed_symmetric_top_to_bottom() {
    let scene = temp("centred-ball.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 40, height: 40 }
ambient: 1
max_depth: 1
materials:
  m: { color: 1, ka: 1 }
objects:
  - { name: ball, sphere: { center: [0, 0, 0], radius: 2 }, material: m }
",
    )
    .unwrap();
    for columns in ["5", "11", "20", "21", "41"] {
        let args = [
            "preview",
            scene.to_str().unwrap(),
            "--ascii",
            "--columns",
            columns,
        ];
        let o = raytree(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = stdout(&o);
        let lines: Vec<&str> = text.lines().collect();
        // Each line's shape: where the ball is drawn (any character but a blank).
        let shape = |l: &str| -> Vec<bool> { l.chars().map(|c| c != ' ').collect() };
        let down: Vec<Vec<bool>> = lines.iter().map(|l| shape(l)).collect();
        let up: Vec<Vec<bool>> = lines.iter().rev().map(|l| shape(l)).collect();
        assert_eq!(down, up, "--columns {columns}:\n{text}");
        assert!(
            down.iter().flatten().any(|&b| b),
            "--columns {columns}: no ball\n{text}"
        );
    }
}
