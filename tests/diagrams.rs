//! Ray diagrams: the `raytree diagram` figure (its rays drawn where the JSON tree says they
//! are, in their colours, once resvg has drawn it), `inspect --format dot` (one node per ray),
//! the BVH boxes a ray's search visits, and the labels of `render --depth-strip`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use glam::{DVec2, DVec3};
use raytree::diagram::figure::Figure;
use raytree::diagram::{raster, Drawing, SegKind, ViewChoice};
use raytree::geometry::Ray;
use raytree::scene::{Limits, Search};
use raytree::stats::Stats;
use raytree::trace::Tracer;
use serde_json::Value;

const L08: &str = "lessons/08-pixel-intensity/scene.yaml";

fn raytree(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .output()
        .expect("raytree runs")
}

fn temp(name: &str) -> PathBuf {
    let dir = Path::new("target/diagram-tests");
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    p
}

fn vec3(v: &Value) -> DVec3 {
    let a: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    DVec3::new(a[0], a[1], a[2])
}

/// Every node of a JSON tree with a hit: (kind, origin, hit point), parents first.
fn hit_rays(node: &Value, out: &mut Vec<(String, DVec3, DVec3)>) {
    if let Some(h) = node["hit"].as_object() {
        out.push((
            node["kind"].as_str().unwrap().to_string(),
            vec3(&node["origin"]),
            vec3(&h["point"]),
        ));
    }
    for c in node["children"].as_array().unwrap() {
        hit_rays(c, out);
    }
}

fn count_nodes(node: &Value) -> usize {
    1 + node["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(count_nodes)
        .sum::<usize>()
}

/// Whether a pixel within `reach` of (x, y) has about the colour `rgb` (lines are
/// antialiased, so their edges are blends).
fn colour_near(img: &(u32, u32, Vec<u8>), at: DVec2, rgb: [u8; 3], reach: i64) -> bool {
    let (w, h, px) = img;
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (x, y) = (at.x.round() as i64 + dx, at.y.round() as i64 + dy);
            if x < 0 || y < 0 || x >= *w as i64 || y >= *h as i64 {
                continue;
            }
            let i = 4 * (y as usize * *w as usize + x as usize);
            let close = (0..3).all(|c| (px[i + c] as i32 - rgb[c] as i32).abs() <= 24);
            if close {
                return true;
            }
        }
    }
    false
}

#[test]
fn the_figure_draws_each_ray_where_the_json_tree_puts_it_in_its_colour() {
    let svg = figure_svg(L08, "30,30", "l08.svg");
    assert!(svg.starts_with("<svg"), "{}", &svg[..80.min(svg.len())]);
    let json = raytree(&["inspect", L08, "--pixel", "30,30", "--format", "json"]);
    let doc: Value = serde_json::from_slice(&json.stdout).unwrap();
    let mut rays = vec![];
    hit_rays(&doc["tree"], &mut rays);
    // The exercise's tree: p → a, a → b (reflection), b → d, a → c (refraction).
    let kinds: Vec<&str> = rays.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(kinds, ["primary", "reflection", "reflection", "refraction"]);

    // Where the figure puts world points: the front view (the exercise lies in z = 0) at one
    // scale across and up, framed by the figure.
    let scene = raytree::scene::load(Path::new(L08), &Limits::default()).unwrap();
    let tree = Tracer::new(&scene).inspect(&scene.camera.pixel_ray(30, 30));
    let drawing = Drawing::new(&scene, &tree, &tree, ViewChoice::Auto, Some((30, 30)));
    assert_eq!(drawing.view, raytree::diagram::View::Front);
    let fig = Figure {
        scene: &scene,
        tree: &tree,
        drawing: &drawing,
        title: String::new(),
        width: 1200,
        height: 640,
    };
    let px = |p: DVec3| fig.pixel_of(p);
    let (o, ex, ey) = (px(DVec3::ZERO), px(DVec3::X), px(DVec3::Y));
    assert!(
        (ex - o).y.abs() < 1e-9 && (ey - o).x.abs() < 1e-9,
        "axis-aligned"
    );
    assert!((ex - o).x > 0.0 && (ey - o).y < 0.0, "x to the right, y up");
    assert!(
        ((ex - o).x + (ey - o).y).abs() < 1e-9,
        "the same scale both ways"
    );

    let img = raster::rasterize(&svg).unwrap();
    assert_eq!((img.0, img.1), (1200, 640));
    let colour = |k: &str| match k {
        "primary" => SegKind::Primary.rgb(),
        "reflection" => SegKind::Reflection.rgb(),
        _ => SegKind::Refraction.rgb(),
    };
    for (kind, from, to) in &rays {
        // Along the ray, clear of its ends (where other rays and the hit dots meet).
        for f in [0.3, 0.7] {
            let at = px(*from + (*to - *from) * f);
            assert!(
                colour_near(&img, at, colour(kind), 2),
                "no {kind} colour at {at} ({f} of the way from {from} to {to})"
            );
        }
    }
    // And not everywhere: well clear of every ray, below the refracted ray's end, is paper.
    let c = rays[3].2;
    let blank = px(c + DVec3::new(-1.5, -1.2, 0.0));
    for kind in ["primary", "reflection", "refraction"] {
        assert!(
            !colour_near(&img, blank, colour(kind), 2),
            "{kind} at {blank}"
        );
    }

    // The PNG is the same figure.
    let png_path = temp("l08.png");
    let out = raytree(&[
        "diagram",
        L08,
        "--pixel",
        "30,30",
        "-o",
        png_path.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let png = image::open(&png_path).unwrap().to_rgba8();
    assert_eq!(png.dimensions(), (1200, 640));
    let at = px(rays[0].1 + (rays[0].2 - rays[0].1) * 0.5);
    let png_img = (1200, 640, png.into_raw());
    assert!(colour_near(&png_img, at, SegKind::Primary.rgb(), 2), "{at}");
}

#[test]
fn dot_has_one_node_per_ray_of_the_json_tree() {
    for (scene, pixel) in [
        (L08, "30,30"),
        ("tests/scenes/explorer-mirror.yaml", "20,15"),
        ("lessons/07-recursion-depth/scene.yaml", "80,60"),
    ] {
        let json = raytree(&["inspect", scene, "--pixel", pixel, "--format", "json"]);
        let doc: Value = serde_json::from_slice(&json.stdout).unwrap();
        let dot = raytree(&["inspect", scene, "--pixel", pixel, "--format", "dot"]);
        assert!(dot.status.success());
        let text = String::from_utf8(dot.stdout).unwrap();
        assert!(text.starts_with("digraph ray_tree {"), "{text}");
        let nodes = text
            .lines()
            .filter(|l| l.contains(" [label=") && !l.contains(" -> "))
            .count();
        let edges = text.lines().filter(|l| l.contains(" -> ")).count();
        let n = count_nodes(&doc["tree"]);
        assert_eq!(nodes, n, "{scene}\n{text}");
        assert_eq!(edges, n - 1, "a tree has one edge fewer than nodes");
    }
    // The exercise's coefficients label its edges.
    let dot = raytree(&["inspect", L08, "--pixel", "30,30", "--format", "dot"]);
    let text = String::from_utf8(dot.stdout).unwrap();
    assert!(
        text.contains("[label=\"kr = 0.3\"]") && text.contains("[label=\"kt = 0.3\"]"),
        "{text}"
    );
    assert!(
        text.contains("[label=\"kr = 0.5\"]") && text.contains("[label=\"s = 1\"]"),
        "{text}"
    );
}

#[test]
fn bad_arguments_exit_2_with_one_line_and_a_miss_still_draws() {
    let out_svg = temp("bad.svg");
    let o = out_svg.to_str().unwrap();
    for args in [
        vec!["diagram", L08, "--pixel", "61,0", "-o", o],
        vec![
            "diagram",
            L08,
            "--pixel",
            "3,3",
            "-o",
            "target/diagram-tests/fig.pdf",
        ],
        vec![
            "diagram", L08, "--pixel", "3,3", "--view", "diagonal", "-o", o,
        ],
        vec!["diagram", L08, "--pixel", "3,3", "--width", "5", "-o", o],
    ] {
        let out = raytree(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        if !args.contains(&"--view") {
            assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        }
        assert!(!out_svg.exists(), "{args:?} wrote a figure");
    }
    // A ray into the sky: the ray and the background are drawn.
    let svg = diagram_svg(&[L08, "--ray", "0,5,0:0,1,0", "--view", "side"], "sky.svg");
    assert!(svg.contains("(background)"), "the missed ray is labelled");
    assert!(svg.contains("side view"));
}

#[test]
fn the_boxes_recorded_are_the_search_that_counted_them() {
    let path = "lessons/12-acceleration/many.yaml";
    let scene = raytree::scene::load(Path::new(path), &Limits::default()).unwrap();
    assert!(
        scene.bvh_nodes() > 100,
        "968 spheres are searched through a BVH"
    );
    for ray in [
        Ray::new(DVec3::new(0.0, 0.0, -12.0), DVec3::Z),
        Ray::new(DVec3::new(0.0, 0.0, -12.0), DVec3::new(7.0, 0.0, 24.0)),
        Ray::new(DVec3::new(0.5, 0.0, -12.0), DVec3::Z),
    ] {
        let mut stats = Stats::default();
        let hit = scene.nearest(&ray, 0.0, f64::INFINITY, &mut stats);
        let v = scene.visited_boxes(&ray, f64::INFINITY, false);
        assert_eq!(v.boxes.len() as u64, stats.bvh_nodes_visited);
        assert_eq!(v.objects_tested, stats.primitives_tested);
        assert_eq!(v.hit.map(|h| h.t), hit.map(|h| h.t));
        assert_eq!(v.total, scene.bvh_nodes());
        // The first box is the root, around everything; every box entered is one the ray
        // meets (the slab test, lesson 12).
        assert!(v.boxes[0].1);
        for (b, entered) in &v.boxes {
            if *entered {
                assert!(b.hit(ray.origin, ray.dir.recip(), 0.0, f64::INFINITY));
            }
        }
        // The shadow search: as counted by the blocker search.
        let mut stats = Stats::default();
        scene.blocker(&ray, 0.0, 30.0, &mut stats);
        let v = scene.visited_boxes(&ray, 30.0, true);
        assert_eq!(v.boxes.len() as u64, stats.bvh_nodes_visited);
    }
    // The centre ray hits the first sphere at t = 11.7 (the lesson's worked answer), having
    // entered far fewer boxes than the tree has.
    let v = scene.visited_boxes(
        &Ray::new(DVec3::new(0.0, 0.0, -12.0), DVec3::Z),
        f64::INFINITY,
        false,
    );
    assert!((v.hit.unwrap().t - 11.7).abs() < 1e-9);
    assert!(
        v.boxes.len() * 10 < v.total,
        "{} of {}",
        v.boxes.len(),
        v.total
    );
}

#[test]
fn a_depth_strip_labels_each_frame_with_its_depth() {
    let out_path = temp("strip.png");
    let out = raytree(&[
        "render",
        "lessons/07-recursion-depth/scene.yaml",
        "--depth-strip",
        "3",
        "--width",
        "80",
        "--height",
        "60",
        "-o",
        out_path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&out_path).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    assert_eq!(w, 3 * 80 + 2 * 4);
    let band = h - 60;
    assert!(band >= 10, "a band for the labels above the frames");
    for k in 0..3 {
        // Dark label pixels in each frame's band, and only white elsewhere in it.
        let left = k * 84;
        let dark = (0..band)
            .flat_map(|y| (left..left + 80).map(move |x| (x, y)))
            .filter(|&(x, y)| img.get_pixel(x, y).0 == [0, 0, 0])
            .count();
        assert!(dark > 20, "frame {k} has a label ({dark} dark pixels)");
    }
    // Frame 1 below its band is the depth-1 render.
    let one = temp("one.png");
    raytree(&[
        "render",
        "lessons/07-recursion-depth/scene.yaml",
        "--depth",
        "1",
        "--width",
        "80",
        "--height",
        "60",
        "-o",
        one.to_str().unwrap(),
    ]);
    let one = image::open(&one).unwrap().to_rgb8();
    for (x, y) in [(0, 0), (40, 30), (79, 59)] {
        assert_eq!(img.get_pixel(x, y + band), one.get_pixel(x, y));
    }
}

/// The number an SVG tag's attribute `name` holds.
fn attr(tag: &str, name: &str) -> f64 {
    // (The tag's first attribute follows the element's name and its space.)
    let tag = &format!(" {tag}");
    let from = tag.find(&format!(" {name}=\"")).expect("attribute") + name.len() + 3;
    let to = from + tag[from..].find('"').unwrap();
    tag[from..to].parse().unwrap()
}

/// The names of objects (italic, in the outlines' grey; the normals' `n` are green) and of
/// lights (bold) in an SVG figure, each with the box it covers at about 0.6 em a character.
fn names_drawn(svg: &str) -> Vec<(String, (DVec2, DVec2))> {
    let object = |t: &str| t.contains("font-style=\"italic\"") && t.contains("fill=\"#555555\"");
    let light = |t: &str| t.contains("font-weight=\"bold\"") && t.contains("font-size=\"14\"");
    texts(svg)
        .filter(|(tag, _)| object(tag) || light(tag))
        // The graph's heading is bold too.
        .filter(|(_, name)| name != "ray tree")
        .map(|(tag, name)| {
            let bx = text_box(tag, &name);
            (name, bx)
        })
        .collect()
}

/// Every `<text>` of an SVG figure: its tag (the attributes) and what it says.
fn texts(svg: &str) -> impl Iterator<Item = (&str, String)> {
    svg.split("<text ").skip(1).map(|t| {
        let (tag, rest) = t.split_once('>').unwrap();
        (
            tag,
            rest.split("</text>").next().unwrap().trim().to_string(),
        )
    })
}

/// Every `<line>` of an SVG figure: its ends and its stroke's width.
fn lines_drawn(svg: &str) -> impl Iterator<Item = (DVec2, DVec2, f64)> + '_ {
    svg.split("<line ")
        .skip(1)
        .map(|t| t.split_once('>').unwrap().0)
        .map(|t| {
            (
                DVec2::new(attr(t, "x1"), attr(t, "y1")),
                DVec2::new(attr(t, "x2"), attr(t, "y2")),
                attr(t, "stroke-width"),
            )
        })
}

/// Whether the line from `a` to `b` passes inside the box, tried at 401 points along it.
fn runs_through((min, max): (DVec2, DVec2), a: DVec2, b: DVec2) -> bool {
    (0..=400).any(|k| {
        let q = a + (b - a) * (k as f64 / 400.0);
        q.x > min.x && q.x < max.x && q.y > min.y && q.y < max.y
    })
}

/// The box a text covers, at about 0.6 em a character, placed by its anchor.
fn text_box(tag: &str, s: &str) -> (DVec2, DVec2) {
    let (x, y, size) = (attr(tag, "x"), attr(tag, "y"), attr(tag, "font-size"));
    let width = 0.6 * size * s.chars().count() as f64;
    let x0 = if tag.contains("text-anchor=\"end\"") {
        x - width
    } else if tag.contains("text-anchor=\"middle\"") {
        x - width / 2.0
    } else {
        x
    };
    (DVec2::new(x0, y - size), DVec2::new(x0 + width, y + 2.0))
}

fn apart(a: &(DVec2, DVec2), b: &(DVec2, DVec2)) -> bool {
    a.1.x <= b.0.x || b.1.x <= a.0.x || a.1.y <= b.0.y || b.1.y <= a.0.y
}

fn assert_apart(labels: &[(String, (DVec2, DVec2))]) {
    for (i, (a, ba)) in labels.iter().enumerate() {
        for (b, bb) in &labels[i + 1..] {
            assert!(apart(ba, bb), "{a} at {ba:?} covers {b} at {bb:?}");
        }
    }
}

fn figure_svg(scene: &str, pixel: &str, name: &str) -> String {
    diagram_svg(&[scene, "--pixel", pixel], name)
}

/// The SVG `raytree diagram ARGS -o NAME` writes (in the tests' temporary folder).
fn diagram_svg(args: &[&str], name: &str) -> String {
    let out = temp(name);
    let run = raytree(&[&["diagram"], args, &["-o", out.to_str().unwrap()]].concat());
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read_to_string(&out).unwrap()
}

/// The rectangle the figure is clipped to (its panel).
fn clip_rect(svg: &str) -> (DVec2, DVec2) {
    let from = svg.find("<clipPath").unwrap();
    let tag = svg[from..]
        .split("<rect ")
        .nth(1)
        .unwrap()
        .split_once('>')
        .unwrap()
        .0;
    let (x, y) = (attr(tag, "x"), attr(tag, "y"));
    let (w, h) = (attr(tag, "width"), attr(tag, "height"));
    (DVec2::new(x, y), DVec2::new(x + w, y + h))
}

/// A wall lit by a light far above the eye: pixel 20,15's shadow ray leaves the figure's top.
const FAR_LIGHT: &str =
    "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 60, width: 80, height: 60 }
lights:
  - { name: L, point: [0, 5, -5] }
materials:
  m: { color: 1, kd: 1 }
objects:
  - { name: wall, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }
  - { name: ball, sphere: { center: [0, 0, -12], radius: 2 }, material: m }
";

/// A light off the figure is drawn inside the panel, on the shadow ray that reaches it, where
/// that ray leaves the panel: the student sees the ray arrive at it.
#[test]
fn a_light_off_the_figure_sits_on_its_shadow_ray() {
    let scene = temp("far-light-sun.yaml");
    std::fs::write(&scene, FAR_LIGHT).unwrap();
    let svg = diagram_svg(
        &[
            scene.to_str().unwrap(),
            "--pixel",
            "20,15",
            "--view",
            "front",
        ],
        "far-light-sun.svg",
    );
    let (min, max) = clip_rect(&svg);
    let tag = |element: &str, colour: &str| -> Vec<String> {
        svg.split(&format!("<{element} "))
            .skip(1)
            .map(|t| t.split_once('>').unwrap().0.to_string())
            .filter(|t| t.contains(colour))
            .collect()
    };
    let suns = tag("circle", "fill=\"#f2b705\"");
    assert_eq!(suns.len(), 1, "{suns:?}");
    let sun = DVec2::new(attr(&suns[0], "cx"), attr(&suns[0], "cy"));
    assert!(
        sun.cmpge(min).all() && sun.cmple(max).all(),
        "{sun} outside {min}–{max}"
    );
    assert!(svg.contains("L (off the figure)"));
    // The shadow ray: the thin line in the colour of clear shadow rays (the legend's is 3 wide).
    let rays: Vec<(DVec2, DVec2)> = tag("line", "stroke=\"#e09a00\"")
        .iter()
        .filter(|t| attr(t, "stroke-width") < 2.0 && attr(t, "y2") < min.y)
        .map(|t| {
            let a = DVec2::new(attr(t, "x1"), attr(t, "y1"));
            (a, DVec2::new(attr(t, "x2"), attr(t, "y2")))
        })
        .collect();
    assert_eq!(rays.len(), 1, "one shadow ray runs off the top: {rays:?}");
    let (a, b) = rays[0];
    let along = (b - a).normalize();
    let off = (sun - a).perp_dot(along).abs();
    assert!(
        off < 0.5,
        "the sun at {sun} is {off} px off the ray {a}–{b}"
    );
    // Near the panel's edge, where the ray leaves it.
    let to_top = sun.y - min.y;
    assert!(
        to_top < 0.05 * (max - min).length(),
        "{sun} is {to_top} px below the top"
    );
}

/// A light however far off leaves the figure at the scale of the rays it draws: the ball hit
/// is drawn as wide with its light 10⁶ away as with it 5 away (the shadow ray's length once
/// set the figure's least size, and the ball shrank to a dot).
#[test]
fn a_distant_light_does_not_shrink_the_figure() {
    let width_of_ball = |light: &str| {
        let scene = temp(&format!("distant-{light}.yaml"));
        std::fs::write(
            &scene,
            format!(
                "camera: {{ eye: [0, 0, -5], look_at: [0, 0, 0], width: 40, height: 30 }}\n\
                 lights: [ {{ name: L, point: [{light}, {light}, -{light}] }} ]\n\
                 materials: {{ m: {{ kd: 0.8 }} }}\n\
                 objects: [ {{ name: ball, sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }} ]\n"
            ),
        )
        .unwrap();
        let args = [scene.to_str().unwrap(), "--pixel", "22,17", "--view", "top"];
        let svg = diagram_svg(&args, &format!("distant-{light}.svg"));
        let outline = svg.split("<polygon fill=\"#e4e4e4\"").nth(1).unwrap();
        let (_, points) = outline.split_once("points=\"").unwrap();
        let (points, _) = points.split_once('"').unwrap();
        let xs: Vec<f64> = points
            .split_whitespace()
            .map(|p| p.split_once(',').unwrap().0.parse().unwrap())
            .collect();
        xs.iter().fold(f64::MIN, |a, &b| a.max(b)) - xs.iter().fold(f64::MAX, |a, &b| a.min(b))
    };
    let near = width_of_ball("5");
    assert!(near > 50.0, "the ball is {near} px wide");
    for far in ["1000", "1e6"] {
        let w = width_of_ball(far);
        assert!(
            (w - near).abs() < 0.25 * near,
            "{w} px with the light at {far}, {near} at 5"
        );
    }
}

/// A ray's label and the image plane's name are drawn inside the figure's panel, also where
/// the ray leaves it for a light far off the figure (its label once went along the whole
/// ray, to above the page) and where the image plane reaches the panel's edge.
#[test]
fn ray_labels_and_the_image_planes_name_lie_inside_the_panel() {
    let scene = temp("far-light.yaml");
    std::fs::write(&scene, FAR_LIGHT).unwrap();
    let cases = [
        (scene.to_str().unwrap(), "20,15", "far-light.svg"),
        (
            "lessons/07-recursion-depth/scene.yaml",
            "40,30",
            "l07-front.svg",
        ),
        (
            "lessons/12-acceleration/scene.yaml",
            "40,30",
            "l12-front.svg",
        ),
    ];
    for (scene, pixel, name) in cases {
        let svg = diagram_svg(&[scene, "--pixel", pixel, "--view", "front"], name);
        let (min, max) = clip_rect(&svg);
        let labels: Vec<(String, (DVec2, DVec2))> = texts(&svg)
            .filter(|(tag, said)| {
                // (The title, "… · pixel (x, y) · I = … · …", is above the panel.)
                let ray =
                    said.starts_with("s = ") || said.contains(" I = ") && !said.contains(" · ");
                (ray || said == "image plane") && attr(tag, "x") < max.x
            })
            .map(|(tag, said)| {
                let bx = text_box(tag, &said);
                (said, bx)
            })
            .collect();
        assert!(
            labels.iter().any(|(said, _)| said == "image plane"),
            "{name}"
        );
        assert!(
            labels.iter().any(|(said, _)| said.starts_with("s = ")),
            "{name}: {labels:?}"
        );
        for (said, (lo, hi)) in &labels {
            assert!(
                lo.x >= min.x && lo.y >= min.y && hi.x <= max.x && hi.y <= max.y,
                "{name}: `{said}` at {lo}–{hi}, outside {min}–{max}"
            );
        }
    }
}

/// Lesson 10 holds its CSG exercises as objects made of the same three spheres A, B and C, all
/// in one place: the figure names each sphere once (by the first object, the plain sphere),
/// on top of the silhouettes, and no two names are drawn over each other.
#[test]
fn coinciding_objects_are_named_once_and_names_never_overlap() {
    let svg = figure_svg("lessons/10-csg/scene.yaml", "80,60", "l10.svg");
    // Drawn after every silhouette, so that none is painted over a name.
    let first_name = svg.find("font-size=\"14\" font-style=\"italic\"").unwrap();
    assert!(svg.rfind("<polygon fill=\"#e4e4e4\"").unwrap() < first_name);
    let labels = names_drawn(&svg);
    let names: Vec<&str> = labels.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["A", "B", "C", "L"], "{labels:?}");
    assert_apart(&labels);
}

/// Seen from above, lesson 4's bulb hangs over the ball: the ball's name moves up a line rather
/// than lie under the light's.
#[test]
fn an_objects_name_makes_way_for_a_lights() {
    let labels = names_drawn(&figure_svg("lessons/04-shadows", "40,30", "l04.svg"));
    let names: Vec<&str> = labels.iter().map(|(n, _)| n.as_str()).collect();
    assert!(
        names.contains(&"ball") && names.contains(&"bulb"),
        "{labels:?}"
    );
    assert_apart(&labels);
}

/// A deep tree's graph (lesson 6's slab: eight rows, two total internal reflections on the
/// way) keeps every edge's coefficient in the gap between the boxes it joins: no label is
/// drawn over a box.
#[test]
fn the_graphs_coefficients_lie_between_its_boxes() {
    let svg = figure_svg("lessons/06-refraction", "125,95", "l06-graph.svg");
    // The nodes are the rounded white boxes.
    let boxes: Vec<(DVec2, DVec2)> = svg
        .split("<rect ")
        .skip(1)
        .map(|t| t.split_once('>').unwrap().0)
        .filter(|t| t.contains(" rx=") && t.contains("fill=\"white\""))
        .map(|t| {
            let at = DVec2::new(attr(t, "x"), attr(t, "y"));
            (at, at + DVec2::new(attr(t, "width"), attr(t, "height")))
        })
        .collect();
    let labels: Vec<(String, (DVec2, DVec2))> = texts(&svg)
        .filter(|(tag, _)| tag.contains("fill=\"#444444\""))
        .map(|(tag, label)| (text_box(tag, &label), label))
        .map(|(bx, label)| (label, bx))
        .collect();
    assert!(boxes.len() >= 8, "{boxes:?}");
    assert_eq!(labels.len(), boxes.len() - 1, "a label on every edge");
    assert!(labels.iter().any(|(l, _)| l == "kt = 0.9"), "{labels:?}");
    for (label, bx) in &labels {
        for node in &boxes {
            assert!(
                apart(bx, node),
                "{label} at {bx:?} covers a node at {node:?}"
            );
        }
    }
}

/// Lesson 7's mirror sends the ray straight back past the eye: in the side view the rays run
/// through the eye's dot, so its name goes above it, where no line is drawn through it.
#[test]
fn the_eyes_name_keeps_off_a_ray_that_comes_back_through_the_eye() {
    let svg = diagram_svg(
        &[
            "lessons/07-recursion-depth/scene.yaml",
            "--pixel",
            "80,60",
            "--depth",
            "3",
        ],
        "l07-eye.svg",
    );
    let (tag, _) = texts(&svg)
        .find(|(_, s)| s == "eye")
        .expect("the eye is named");
    let (min, max) = text_box(tag, "eye");
    let lines: Vec<(DVec2, DVec2)> = lines_drawn(&svg).map(|(a, b, _)| (a, b)).collect();
    // The eye's dot (r = 5) has rays drawn through it, level with it, on both sides.
    let dot = svg
        .split("<circle ")
        .skip(1)
        .map(|t| t.split_once('>').unwrap().0)
        .find(|t| attr(t, "r") == 5.0)
        .map(|t| DVec2::new(attr(t, "cx"), attr(t, "cy")))
        .expect("the eye's dot");
    let through_dot = |&&(a, b): &&(DVec2, DVec2)| {
        (a.y - dot.y).abs() < 1.0
            && (b.y - dot.y).abs() < 1.0
            && a.x.min(b.x) <= dot.x
            && a.x.max(b.x) >= dot.x
    };
    assert!(
        lines.iter().filter(through_dot).count() >= 2,
        "{dot} {lines:?}"
    );
    for &(a, b) in &lines {
        assert!(
            !runs_through((min, max), a, b),
            "the line {a} → {b} runs through the eye's name at {min}–{max}"
        );
    }
}

/// In lesson 8's figure of pixel p the two rays that leave for the background (from c and
/// from d) are long, with room beside them: their labels lie across no ray (primary,
/// reflection, refraction: lines 3 and 2.4 px wide), where they would read as that ray's.
/// (d's label was laid across b's ray, beside b, as if b's ray went to the background.)
#[test]
fn the_background_rays_labels_lie_across_no_ray_in_lesson_8() {
    let svg = figure_svg(
        "lessons/08-pixel-intensity/scene.yaml",
        "30,30",
        "l08-labels.svg",
    );
    let rays: Vec<(DVec2, DVec2)> = lines_drawn(&svg)
        .filter(|&(_, _, width)| width == 3.0 || width == 2.4)
        .map(|(a, b, _)| (a, b))
        .collect();
    assert!(rays.len() >= 6, "{rays:?}");
    let labels: Vec<(String, (DVec2, DVec2))> = texts(&svg)
        .filter(|(_, s)| s.ends_with("(background)"))
        .map(|(tag, s)| (s.clone(), text_box(tag, &s)))
        .collect();
    assert_eq!(labels.len(), 2, "{labels:?}");
    for (label, (min, max)) in &labels {
        for &(a, b) in &rays {
            assert!(
                !runs_through((*min, *max), a, b),
                "{label} at {min}–{max} lies across the ray {a} → {b}"
            );
        }
    }
}

/// The far light's name in lesson 8's figure goes where no ray runs through it: beside its
/// arrows on the side the rays leave free. (It was drawn across the shadow ray from d and by
/// the background ray from d.)
#[test]
fn the_far_lights_name_lies_across_no_ray_in_lesson_8() {
    let svg = figure_svg(
        "lessons/08-pixel-intensity/scene.yaml",
        "30,30",
        "l08-light.svg",
    );
    // Primary, secondary and shadow rays: 3, 2.4 and 1.6 px wide (the light's arrows 2.5).
    let rays: Vec<(DVec2, DVec2)> = lines_drawn(&svg)
        .filter(|&(_, _, width)| [3.0, 2.4, 1.6].contains(&width))
        .map(|(a, b, _)| (a, b))
        .collect();
    let (name, (mut min, mut max)) = names_drawn(&svg)
        .into_iter()
        .find(|(name, _)| name == "L (far away)")
        .expect("the light's name");
    // Bold letters: about 0.64 em each, not 0.6 (either way, whichever end is anchored).
    let bold = 0.04 * 14.0 * name.chars().count() as f64;
    (min.x, max.x) = (min.x - bold, max.x + bold);
    for &(a, b) in &rays {
        assert!(
            !runs_through((min, max), a, b),
            "{name} at {min}–{max} lies across the ray {a} → {b}"
        );
    }
}

/// The figures lessons 7 and 8 show are what the commands their READMEs give draw: after a
/// change to the figures, `raytree diagram` writes them again.
#[test]
fn the_lessons_figures_are_what_raytree_draws() {
    for (args, figure) in [
        (
            &["lessons/08-pixel-intensity/scene.yaml", "--pixel", "30,30"][..],
            "lessons/08-pixel-intensity/figure.svg",
        ),
        (
            &[
                "lessons/07-recursion-depth/scene.yaml",
                "--pixel",
                "80,60",
                "--depth",
                "3",
            ][..],
            "lessons/07-recursion-depth/figure-depth-3.svg",
        ),
    ] {
        let drawn = diagram_svg(args, "lesson-figure.svg");
        let name = Path::new(figure).file_name().unwrap().to_str().unwrap();
        let readme = Path::new(figure).with_file_name("README.md");
        let readme = std::fs::read_to_string(readme).unwrap();
        assert!(
            readme.contains(&format!("({name})")),
            "{figure}: shown in its README"
        );
        assert!(
            drawn == std::fs::read_to_string(figure).unwrap(),
            "{figure} is not what `raytree diagram {}` draws now: write it again",
            args.join(" ")
        );
    }
}

/// The title's I is the tree's, the centre ray's: the pixel's value only where the pixel is
/// that one ray. Lesson 08's pixel p (one sample) is the lecture's 0.870161; lesson 13's
/// pixels average a grid of samples, and lesson 15's are path traced, and their titles say
/// that the figure shows the centre ray.
#[test]
fn the_title_says_when_the_centre_ray_is_not_the_pixels_value() {
    let title = |svg: &str| {
        let (_, text) = texts(svg).next().expect("a title");
        text
    };
    let t08 = title(&figure_svg(L08, "30,30", "title-08.svg"));
    assert!(t08.contains("pixel (30, 30) · I = 0.870161"), "{t08}");
    let t13 = title(&figure_svg(
        "lessons/13-antialiasing",
        "1,1",
        "title-13.svg",
    ));
    assert!(
        t13.contains("pixel (1, 1): its centre ray, not the pixel's antialiased value"),
        "{t13}"
    );
    let t15 = title(&figure_svg(
        "lessons/15-path-tracing",
        "10,10",
        "title-15.svg",
    ));
    assert!(
        t15.contains("the Whitted reading of its centre ray, not the path-traced estimate"),
        "{t15}"
    );
}

/// Every point an SVG figure's shapes reach: the ends of its lines, the corners of its
/// rectangles (the white background, given in percent, aside), the extremes of its circles and
/// the points of its polygons.
fn shape_points(svg: &str) -> Vec<(String, DVec2)> {
    let tags = |name: &str| -> Vec<&str> {
        svg.split(&format!("<{name} "))
            .skip(1)
            .map(|t| t.split_once('>').unwrap().0)
            .collect()
    };
    let mut out = vec![];
    for t in tags("line") {
        for (x, y) in [("x1", "y1"), ("x2", "y2")] {
            out.push((format!("line {t}"), DVec2::new(attr(t, x), attr(t, y))));
        }
    }
    for t in tags("rect").into_iter().filter(|t| !t.contains('%')) {
        let at = DVec2::new(attr(t, "x"), attr(t, "y"));
        let size = DVec2::new(attr(t, "width"), attr(t, "height"));
        out.push((format!("rect {t}"), at));
        out.push((format!("rect {t}"), at + size));
    }
    for t in tags("circle") {
        let (c, r) = (DVec2::new(attr(t, "cx"), attr(t, "cy")), attr(t, "r"));
        out.push((format!("circle {t}"), c - DVec2::splat(r)));
        out.push((format!("circle {t}"), c + DVec2::splat(r)));
    }
    for t in tags("polygon") {
        let from = t.find("points=\"").unwrap() + 8;
        let points = &t[from..from + t[from..].find('"').unwrap()];
        for p in points.split(' ') {
            let (x, y) = p.split_once(',').unwrap();
            let p = DVec2::new(x.parse().unwrap(), y.parse().unwrap());
            out.push((format!("polygon {t}"), p));
        }
    }
    out
}

/// The box a text covers, as `text_box` has it, a bold one at 0.64 em a character (the title's
/// and the names' letters are wider).
fn drawn_box(tag: &str, s: &str) -> (DVec2, DVec2) {
    let (min, max) = text_box(tag, s);
    if tag.contains("font-weight=\"bold\"") {
        let size = attr(tag, "font-size");
        let extra = 0.04 * size * s.chars().count() as f64;
        if tag.contains("text-anchor=\"middle\"") {
            (
                min - DVec2::new(extra / 2.0, 0.0),
                max + DVec2::new(extra / 2.0, 0.0),
            )
        } else if tag.contains("text-anchor=\"end\"") {
            (min - DVec2::new(extra, 0.0), max)
        } else {
            (min, max + DVec2::new(extra, 0.0))
        }
    } else {
        (min, max)
    }
}

/// At the narrowest width `raytree diagram` takes, at a middle one (where the legend's last
/// entry once ran off the figure) and at the default, every text (title, legend, the graph's
/// boxes and coefficients) and every shape lies inside the figure, and the section, clipped
/// to its rectangle, lies inside too: on
/// lesson 8's pixel, lesson 6's deep tree through the slab and lesson 13's long title. A
/// narrower figure is refused with a usage error naming the least width.
#[test]
fn nothing_is_drawn_outside_the_figure_at_any_width() {
    let cases = [
        (L08, "30,30"),
        ("lessons/06-refraction", "80,60"),
        ("lessons/06-refraction", "125,95"),
        ("lessons/13-antialiasing", "1,1"),
    ];
    for width in ["400", "600", "1200"] {
        for height in ["200", "640"] {
            for (scene, pixel) in cases {
                let args = [
                    scene, "--pixel", pixel, "--width", width, "--height", height,
                ];
                let svg = diagram_svg(&args, "within.svg");
                // The section is drawn clipped to its rectangle (a <rect> checked below with
                // the other shapes): nothing in it is drawn outside that.
                assert!(svg.contains("<clipPath id=\"section\">"), "{args:?}");
                let (before, rest) = svg
                    .split_once("<g clip-path=\"url(#section)\">")
                    .expect("the section is clipped");
                let svg = format!("{before}{}", rest.split_once("</g>").unwrap().1);
                let (w, h) = (
                    width.parse::<f64>().unwrap(),
                    height.parse::<f64>().unwrap(),
                );
                let inside = |p: DVec2| p.x >= 0.0 && p.y >= 0.0 && p.x <= w && p.y <= h;
                for (tag, s) in texts(&svg) {
                    let (min, max) = drawn_box(tag, &s);
                    assert!(
                        inside(min) && inside(max),
                        "{args:?}: \"{s}\" at {min}–{max} leaves the {w}×{h} figure"
                    );
                }
                for (what, p) in shape_points(&svg) {
                    assert!(inside(p), "{args:?}: {what} reaches {p}, outside {w}×{h}");
                }
            }
        }
    }
    let out = temp("narrow.svg");
    let narrow = raytree(&[
        "diagram",
        L08,
        "--pixel",
        "30,30",
        "--width",
        "399",
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&narrow.stderr);
    assert_eq!(narrow.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--width must be between 400 and 8000"),
        "{err}"
    );
    assert!(!out.exists());
}

/// Lesson 6's slab seen from the side: the rays' labels ("refraction I = …", …) keep off the
/// objects' and the lights' names, and off each other.
#[test]
fn ray_labels_keep_off_the_names() {
    for width in ["1200", "600"] {
        let svg = diagram_svg(
            &[
                "lessons/06-refraction",
                "--pixel",
                "80,60",
                "--width",
                width,
            ],
            "l06-labels.svg",
        );
        // The rays' labels: 12 px, outlined in white, saying an intensity; the title (bold)
        // and the graph's lines (no outline) say one too.
        let rays: Vec<(String, (DVec2, DVec2))> = texts(&svg)
            .filter(|(tag, s)| {
                s.contains("I = ")
                    && tag.contains("font-size=\"12\"")
                    && !tag.contains("font-weight")
                    && !tag.contains("stroke-width=\"0\"")
            })
            .map(|(tag, s)| {
                let bx = text_box(tag, &s);
                (s, bx)
            })
            .collect();
        assert!(
            rays.iter().any(|(s, _)| s.starts_with("refraction I = ")),
            "{width}: {rays:?}"
        );
        let names = names_drawn(&svg);
        assert!(names.iter().any(|(n, _)| n == "slab"), "{width}: {names:?}");
        assert_apart(&[names, rays].concat());
    }
}

/// The section's clip rectangle: its top-left and bottom-right corners.
fn section_clip(svg: &str) -> (DVec2, DVec2) {
    let rect = svg
        .split_once("<clipPath id=\"section\">")
        .expect("the section is clipped")
        .1
        .split_once("<rect ")
        .unwrap()
        .1
        .split_once('>')
        .unwrap()
        .0;
    let at = DVec2::new(attr(rect, "x"), attr(rect, "y"));
    (
        at,
        at + DVec2::new(attr(rect, "width"), attr(rect, "height")),
    )
}

/// A directional light comes in as three arrows from the edge of the section with its name
/// beside them: from whichever side it comes, in any view and at a small figure, the arrows
/// (their round caps too), their heads and the name lie wholly inside the section's clip, so
/// none of them is cut.
#[test]
fn a_directional_lights_arrows_and_name_lie_inside_the_section() {
    let dir = Path::new("target/diagram-tests/sun");
    std::fs::create_dir_all(dir).unwrap();
    let directions = [
        "[1, -2, 1]",
        "[0.5, -1, 0]",
        "[-1, -1, 0]",
        "[3, -1, 0]",
        "[-3, -1, -1]",
        "[1, 1, 1]",
        "[0.2, -1, 3]",
        "[-2, 0.5, -2]",
    ];
    for (i, direction) in directions.into_iter().enumerate() {
        let scene = dir.join(format!("sun-{i}.yaml"));
        std::fs::write(
            &scene,
            format!(
                "camera: {{ eye: [0, 1, -6], look_at: [0, 0.5, 0], fov: 40, width: 160, height: 120 }}\n\
                 lights:\n  - {{ name: sun, direction: {direction}, intensity: 1 }}\n\
                 materials:\n  matte: {{ color: 0.8, kd: 0.7 }}\n\
                 objects:\n  \
                 - {{ name: ball, sphere: {{ center: [0, 1, 0], radius: 1 }}, material: matte }}\n  \
                 - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: matte }}\n"
            ),
        )
        .unwrap();
        let scene = scene.to_str().unwrap();
        for extra in [
            &["--view", "front"][..],
            &["--view", "side"],
            &["--view", "top"],
            &["--view", "front", "--width", "400", "--height", "300"],
        ] {
            let args = [&[scene, "--pixel", "80,75"][..], extra].concat();
            let svg = diagram_svg(&args, "sun.svg");
            let (lo, hi) = section_clip(&svg);
            let inside = |p: DVec2, reach: f64| {
                p.x - reach >= lo.x
                    && p.y - reach >= lo.y
                    && p.x + reach <= hi.x
                    && p.y + reach <= hi.y
            };
            let sun_tags = |name: &str, paint: &str| -> Vec<&str> {
                (svg.split(&format!("<{name} ")).skip(1))
                    .map(|t| t.split_once('>').unwrap().0)
                    .filter(|t| t.contains(&format!("{paint}=\"#f2b705\"")))
                    .collect()
            };
            let arrows = sun_tags("line", "stroke");
            assert_eq!(arrows.len(), 3, "{args:?}: {arrows:?}");
            for t in arrows {
                let cap = attr(t, "stroke-width") / 2.0;
                for (x, y) in [("x1", "y1"), ("x2", "y2")] {
                    let p = DVec2::new(attr(t, x), attr(t, y));
                    assert!(inside(p, cap), "{args:?}: arrow {t} outside {lo}–{hi}");
                }
            }
            let heads = sun_tags("polygon", "fill");
            assert_eq!(heads.len(), 3, "{args:?}: {heads:?}");
            let heads: String = heads.iter().map(|t| format!("<polygon {t}>")).collect();
            for (what, p) in shape_points(&heads) {
                assert!(inside(p, 0.0), "{args:?}: {what} outside {lo}–{hi}");
            }
            let names: Vec<_> = texts(&svg).filter(|(_, s)| s == "sun (far away)").collect();
            assert_eq!(names.len(), 1, "{args:?}");
            let (min, max) = drawn_box(names[0].0, &names[0].1);
            assert!(
                inside(min, 0.0) && inside(max, 0.0),
                "{args:?}: the light's name at {min}–{max} leaves the section {lo}–{hi}"
            );
        }
    }
}

/// A ray seen end on (along the view's axis) projects to a point: the frame keeps the scale
/// of the rays' own length, so the ball it hits is drawn whole at a sensible size (its outline
/// within a few hundred pixels of the figure, not 10¹² across), and the PNG is drawn too.
#[test]
fn a_ray_seen_end_on_keeps_the_drawing_to_scale() {
    let scene = temp("end-on.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 64, height: 48 }\n\
         lights: [ { name: L, point: [0, 0, -5] } ]\nmaterials: { m: { kd: 1 } }\n\
         objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m } ]\n",
    )
    .unwrap();
    for (ray, view) in [
        ("0,0,-5:0,0,1", "front"),
        ("0,5,0:0,-1,0", "top"),
        ("5,0,0:-1,0,0", "side"),
        ("0,0,-5:1e-9,0,1", "front"),
    ] {
        let svg = temp("end-on.svg");
        let png = temp("end-on.png");
        for out in [&svg, &png] {
            let o = raytree(&[
                "diagram",
                scene.to_str().unwrap(),
                "--ray",
                ray,
                "--view",
                view,
                "-o",
                out.to_str().unwrap(),
            ]);
            assert!(
                o.status.success(),
                "{ray} {view}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
        }
        let text = std::fs::read_to_string(&svg).unwrap();
        // Every number of every attribute's value (coordinates, sizes, point lists), colours
        // aside.
        let largest = text
            .split('"')
            .skip(1)
            .step_by(2)
            .filter(|value| !value.starts_with('#'))
            .flat_map(|value| value.split([' ', ',']))
            .filter_map(|w| w.parse::<f64>().ok())
            .fold(0.0, |m: f64, x| m.max(x.abs()));
        assert!(largest < 1e5, "{ray} {view}: a number {largest} in the SVG");
    }
}
