//! Every mistake a user can make in a scene file gives one line naming file:line:col.

use raytree::scene::{parse, Limits};

const CAMERA: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\n";

/// (scene text, expected "line:column", message fragment)
const CASES: &[(&str, &str, &str)] = &[
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 40, widht: 3 }", "1:57", "unknown field `widht`"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nbackground: red", "2:1", "number or a list"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: 1 }, material: glass }", "4:68", "unknown material `glass`"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: -1 }, material: m }", "4:53", "sphere radius must be > 0"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nlights:\n  - { direction: [0, 0, 0] }", "3:18", "zero vector"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], up: [0, 0, 0] }", "1:52", "zero vector"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nlights:\n  - { direction: [0, 1e-200, 0] }", "3:18", "light direction is too short to have a direction"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], up: [0, 0, 1] }", "1:52", "parallel to the view direction"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials:\n  glass: { ior: 0 }", "3:17", "ior must be between 0.01 and 100"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials:\n  glass: { ior: 1e-16 }", "3:17", "ior must be between 0.01 and 100"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials:\n  glass: { ior: 1000 }", "3:17", "ior must be between 0.01 and 100"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, .nan] }", "1:44", "non-finite"),
    ("background: 1", "1:1", "missing `camera`"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 0 }", "1:53", "fov must be between 0 and 180"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 100000, height: 100000 }", "1:55", "budget"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmax_depth: 1000", "2:12", "max_depth must be between 1 and 64"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: a, sphere: { center: [0, 0, 0], radius: 1 }, material: m }\n  - { name: a, sphere: { center: [0, 0, 0], radius: 1 }, material: m }", "5:5", "duplicate object name `a`"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: a, material: m }", "4:5", "no shape"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: t, triangle: [[0, 0, 0], [1, 1, 1], [2, 2, 2]], material: m }", "4:26", "degenerate triangle"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - name: u\n    union: [ { sphere: { center: [0, 0, 0], radius: 1 } } ]\n    material: m", "4:5", "at least two children"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: b, box: { min: [1, 0, 0], max: [0, 1, 1] }, material: m }", "4:28", "box min must be smaller"),
    ("camera: { eye: [0, 0, -5], u: [1, 0, 0], v: [0, 1, 0], w: [0, 0, 1], f: 1, window: [1, 1, 1, -1] }", "1:84", "zero width"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\ncamera: { eye: [0, 0, -5], look_at: [0, 0, 0] }", "2:1", "duplicate"),
    ("camera: [1, 2", "1:9", "expected a mapping"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, -.inf] }", "1:44", "non-finite"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 1e999] }", "1:44", "expected a number within floating point's range here, got `1e999`"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nambient: \"abc\"", "2:1", "number or a list"),
    // Extreme numbers are shown short, not in hundreds of digits.
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 1e50 }", "1:53", "180 degrees (exclusive), got 1e50"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: -1e-300 } }", "2:23", "kd must be ≥ 0, got -1e-300"),
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: -0.25 } }", "2:23", "kd must be ≥ 0, got -0.25"),
    // A triangle is no more collinear for being large (its cross product's length squared is 10⁶⁴⁰).
    ("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: t, triangle: [[-1e80, -1e80, 5], [1e80, -1e80, 5], [0, 1e80, 5]], material: m }\n  - { name: t, sphere: { center: [0, 0, 0], radius: 1 }, material: m }", "5:5", "duplicate object name `t`"),
];

#[test]
fn bad_scenes_name_line_and_column() {
    let mut failures = vec![];
    for (text, at, fragment) in CASES {
        match parse(text, "bad.yaml", None, &Limits::default()) {
            Ok(_) => failures.push(format!("accepted: {text}")),
            Err(e) => {
                let shown = e.to_string();
                let ok = shown.starts_with(&format!("bad.yaml:{at}: "))
                    && shown.contains(fragment)
                    && !shown.contains('\n');
                if !ok {
                    failures.push(format!(
                        "{text:?}\n  got: {shown}\n  want bad.yaml:{at}: …{fragment}…"
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_good_scene_parses() {
    let text = format!("{CAMERA}materials: {{ m: {{ kd: 1 }} }}\nobjects: [ {{ name: s, sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }} ]");
    parse(&text, "good.yaml", None, &Limits::default()).unwrap();
}

/// A large file's object list parses in pieces on several threads (`scene/split.rs`); its
/// mistakes are still reported where they are, and the last of its mistakes too (in the last
/// piece), whatever the thread count.
#[test]
fn a_mistake_deep_in_a_large_file_names_its_line_and_column() {
    let mut text = format!("{CAMERA}materials: {{ m: {{ kd: 1 }} }}\nobjects:\n");
    for i in 0..4000 {
        text +=
            &format!("  - {{ sphere: {{ center: [{i}, 0, 0], radius: 0.25 }}, material: m }}\n");
    }
    assert!(text.len() > 128 * 1024, "large enough to be cut");
    // (item, its mistake, what is reported where): the compiler points at a bad number, the
    // parser at an unknown key.
    for (i, mistake, pointed_at) in [
        (3, "radius: -0.25", "-0.25"),
        (2500, "radius: -0.25", "-0.25"),
        (3999, "radious: 0.25", "radious"),
    ] {
        let at = format!("center: [{i}, 0, 0], ");
        let spoiled = text.replacen(&format!("{at}radius: 0.25"), &format!("{at}{mistake}"), 1);
        let line = 4 + i;
        let shown = spoiled.lines().nth(line - 1).unwrap();
        assert!(shown.contains(mistake));
        let column = shown.find(pointed_at).unwrap() + 1;
        for threads in [1, 2, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let e = pool
                .install(|| parse(&spoiled, "big.yaml", None, &Limits::default()))
                .err()
                .unwrap_or_else(|| panic!("{mistake} at {i} accepted"));
            assert_eq!(
                (e.line, e.column),
                (line as u64, column as u64),
                "{threads} threads: {e}"
            );
        }
    }
}
