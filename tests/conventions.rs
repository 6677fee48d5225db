//! The conventions of command-line tools: help for every option with examples, completions and
//! a man page, JSON with the version for every result, images to stdout, colour only where
//! wanted.

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

use clap::CommandFactory;

fn raytree_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_raytree"));
    cmd.args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("NO_COLOR")
        .env_remove("CLICOLOR_FORCE")
        .env_remove("COLORTERM")
        .env("RAYTREE_DATA", scratch("data"))
        .stdin(Stdio::null());
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("runs")
}

fn raytree(args: &[&str]) -> Output {
    raytree_env(args, &[])
}

fn ok(o: &Output) -> String {
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raytree-conventions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A 16 × 12 scene: a lit ball.
fn small_scene() -> String {
    let path = scratch("small.yaml");
    std::fs::write(
        &path,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 16, height: 12 }\n\
         ambient: 0.2\nlights: [ { point: [2, 3, -4] } ]\n\
         materials: { m: { color: [1, 0.5, 0.25], ka: 1, kd: 0.8, ks: 0.3 } }\n\
         objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1.5 }, material: m } ]\n",
    )
    .unwrap();
    path.to_string_lossy().into_owned()
}

/// Every command under `cmd` (itself included), with its path of names.
fn commands(cmd: &clap::Command, path: String, out: &mut Vec<(String, clap::Command)>) {
    out.push((path.clone(), cmd.clone()));
    for sub in cmd.get_subcommands() {
        commands(sub, format!("{path} {}", sub.get_name()), out);
    }
}

#[test]
fn every_argument_has_help_and_every_command_examples() {
    let mut all = vec![];
    commands(&raytree::cli::Cli::command(), "raytree".into(), &mut all);
    assert!(all.len() > 12, "{} commands", all.len());
    let mut missing = vec![];
    for (path, cmd) in &all {
        for arg in cmd.get_arguments() {
            let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
            if help.trim().is_empty() {
                missing.push(format!("{path} {}", arg.get_id()));
            }
        }
        if path != "raytree" {
            let after = cmd
                .get_after_help()
                .map(|h| h.to_string())
                .unwrap_or_default();
            if !after.starts_with("Examples:") || after.lines().count() < 2 {
                missing.push(format!("{path}: no examples"));
            }
            if cmd.get_about().is_none() {
                missing.push(format!("{path}: no description"));
            }
        }
    }
    assert!(missing.is_empty(), "without help: {missing:#?}");
}

#[test]
fn render_help_names_the_image_formats() {
    let help = ok(&raytree(&["render", "--help"]));
    for format in ["PNG", "PPM", "EXR"] {
        assert!(help.contains(format), "{format} in {help}");
    }
    assert!(help.contains("Examples:"), "{help}");
}

#[test]
fn completions_name_the_commands() {
    for shell in ["bash", "zsh", "fish"] {
        let script = ok(&raytree(&["completions", shell]));
        for command in [
            "render",
            "inspect",
            "explore",
            "lessons",
            "bench",
            "completions",
        ] {
            assert!(script.contains(command), "{shell}: {command}");
        }
        // Options too.
        assert!(script.contains("depth-strip"), "{shell}");
    }
    let bad = raytree(&["completions", "tcsh"]);
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn the_man_page_lists_the_commands() {
    let page = ok(&raytree(&["man"]));
    assert!(
        page.starts_with(".ie") || page.contains(".TH raytree"),
        "{page}"
    );
    for command in ["render", "inspect", "explore", "bench", "man"] {
        assert!(page.contains(command), "{command}");
    }
    let dir = scratch("man");
    ok(&raytree(&["man", "-o", dir.to_str().unwrap()]));
    for name in ["raytree.1", "raytree-render.1", "raytree-bench-sweep.1"] {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(text.contains(".TH"), "{name}");
    }
    let render = std::fs::read_to_string(dir.join("raytree-render.1")).unwrap();
    assert!(render.contains("depth\\-strip"), "{render}");
}

/// The document parsed, after checking it carries this build's version.
fn versioned(text: &str) -> serde_json::Value {
    let doc: serde_json::Value =
        serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(doc["raytree_version"], env!("CARGO_PKG_VERSION"), "{text}");
    doc
}

#[test]
fn every_json_document_parses_and_carries_the_version() {
    let l08 = "lessons/08-pixel-intensity/scene.yaml";
    let doc = versioned(&ok(&raytree(&[
        "inspect", l08, "--pixel", "30,30", "--format", "json",
    ])));
    assert_eq!(doc["tree"]["kind"], "primary");
    let doc = versioned(&ok(&raytree(&[
        "csg",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,0,-10:0,0,1",
        "--format",
        "json",
    ])));
    assert!(doc["objects"].is_array());
    let doc = versioned(&ok(&raytree(&["lessons", "--format", "json"])));
    assert!(doc["lessons"].as_array().unwrap().len() >= 16);
    let check = raytree(&[
        "check",
        "lessons/08-pixel-intensity",
        "--exercise",
        "pixel-p",
        "--answer",
        "0.1",
        "--format",
        "json",
    ]);
    assert_eq!(check.status.code(), Some(1));
    let doc = versioned(&String::from_utf8_lossy(&check.stdout));
    assert_eq!(doc["correct"], false);

    let small = small_scene();
    let doc = versioned(&ok(&raytree(&[
        "render",
        &small,
        "-o",
        scratch("stats.png").to_str().unwrap(),
        "--stats",
        "--format",
        "json",
    ])));
    // 16 × 12 pixels, one primary ray each.
    assert_eq!(doc["stats"]["primary_rays"], 192);
    assert_eq!(doc["width"], 16);
    // The peak resident memory of the process: at least the 1 MB any process here maps (Linux
    // reports it; elsewhere null).
    if cfg!(target_os = "linux") {
        assert!(
            doc["peak_memory_bytes"].as_u64().unwrap() > 1 << 20,
            "{doc}"
        );
    } else {
        assert!(doc["peak_memory_bytes"].is_null());
    }
    // The copy of the fast wing the processor runs.
    assert!(
        ["x86-64", "x86-64-v3", "x86-64-v4"].contains(&doc["cpu_level"].as_str().unwrap()),
        "{doc}"
    );

    let reference = scratch("reference.exr");
    ok(&raytree(&[
        "render",
        &small,
        "--spp",
        "16",
        "-o",
        reference.to_str().unwrap(),
    ]));
    let doc = versioned(&ok(&raytree(&[
        "bench",
        "sweep",
        &small,
        "--knob",
        "spp",
        "--values",
        "1,4",
        "--reference",
        reference.to_str().unwrap(),
        "--format",
        "json",
    ])));
    let rows = doc["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[1]["value"], 4.0);
    // 4 primary rays in each of 192 pixels, and a shadow ray from each that meets the ball.
    assert!(rows[1]["rays"].as_u64().unwrap() >= 4 * 192);

    let doc = versioned(&ok(&raytree(&[
        "bench",
        "scaling",
        "--max-spheres",
        "10",
        "--max-brute",
        "10",
        "--max-subdivisions",
        "3",
        "--format",
        "json",
    ])));
    assert_eq!(doc["rows"][0]["kind"], "spheres");
    assert_eq!(doc["rows"][0]["n"], 10);
    assert!(doc["rows"][0]["bytes_per_triangle"].is_null());
    // The 1 280-triangle icosphere: 36 bytes a triangle of vertices and indices, and its BVH.
    assert_eq!(doc["rows"][1]["n"], 1280);
    let bytes = doc["rows"][1]["bytes_per_triangle"].as_f64().unwrap();
    assert!(bytes > 36.0 && bytes <= 80.0, "{bytes}");

    let doc = versioned(&ok(&raytree(&[
        "bench",
        "threads",
        &small,
        "--threads",
        "2",
        "--runs",
        "1",
        "--format",
        "json",
    ])));
    assert_eq!(doc["threads"], 2);
    assert_eq!(doc["runs"].as_array().unwrap().len(), 1);
    // A render of 16 × 12 pixels is far shorter than a measurement: it is repeated.
    assert!(doc["renders_per_figure"].as_u64().unwrap() >= 2, "{doc}");
}

#[test]
fn an_image_goes_to_stdout_with_dash() {
    let small = small_scene();
    let ppm = raytree(&["render", &small, "-o", "-"]);
    let bytes = &ppm.stdout;
    assert!(
        ppm.status.success(),
        "{}",
        String::from_utf8_lossy(&ppm.stderr)
    );
    let header = b"P6\n16 12\n255\n";
    assert_eq!(&bytes[..header.len()], header);
    assert_eq!(bytes.len(), header.len() + 16 * 12 * 3);
    // The same image as written to a file.
    let file = scratch("file.ppm");
    ok(&raytree(&["render", &small, "-o", file.to_str().unwrap()]));
    assert_eq!(&std::fs::read(&file).unwrap(), bytes);

    let png = raytree(&["render", &small, "-o", "-", "--image-format", "png"]);
    assert!(png.status.success());
    let decoded = image::load_from_memory(&png.stdout).unwrap().to_rgb8();
    assert_eq!(decoded.dimensions(), (16, 12));
    assert_eq!(decoded.as_raw()[..], bytes[header.len()..]);

    // --image-format belongs to -o -; stats JSON and an image cannot share stdout.
    let r = raytree(&["render", &small, "-o", "x.png", "--image-format", "png"]);
    assert_eq!(r.status.code(), Some(2));
    let r = raytree(&["render", &small, "-o", "-", "--stats", "--format", "json"]);
    assert_eq!(r.status.code(), Some(2));
    assert!(r.stdout.is_empty());
}

#[test]
fn preview_colours_only_when_wanted() {
    let scene = "lessons/05-reflection/scene.yaml";
    let escapes = |o: &Output| ok(o).contains('\u{1b}');
    // Piped: no escapes unless asked.
    assert!(!escapes(&raytree(&["preview", scene, "--columns", "20"])));
    assert!(escapes(&raytree(&[
        "preview",
        scene,
        "--columns",
        "20",
        "--color",
        "always"
    ])));
    assert!(escapes(&raytree_env(
        &["preview", scene, "--columns", "20"],
        &[("CLICOLOR_FORCE", "1")]
    )));
    assert!(!escapes(&raytree_env(
        &["preview", scene, "--columns", "20"],
        &[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")]
    )));
    assert!(!escapes(&raytree_env(
        &["preview", scene, "--columns", "20", "--color", "never"],
        &[("CLICOLOR_FORCE", "1")]
    )));
    let colour = ok(&raytree(&[
        "preview",
        scene,
        "--columns",
        "20",
        "--color",
        "always",
    ]));
    assert!(colour.contains("\u{1b}[38;5;"), "256 colours by default");
}
