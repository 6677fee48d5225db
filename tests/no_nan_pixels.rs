//! No legal scene gives a NaN or a negative pixel: random scenes of spheres, planes and boxes
//! with random materials and lights, among them lights placed exactly where a primary ray
//! meets a surface (d = 0, where fatt = 1/(c1·d + c2·d²) is infinite and l undefined), with
//! attenuations that vanish at d = 0, box and Gaussian filters, both engines.

use proptest::prelude::*;
use raytree::render::{render_simple, Engine, RenderOptions};
use raytree::scene::{parse, Limits, Scene};
use raytree::trace::Tracer;

fn num() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), (-4.0f64..4.0)]
}

fn coefficient() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(1.0), (0.0f64..1.2)]
}

fn attenuation() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        Just([1.0, 0.0, 0.0]),
        Just([0.0, 1.0, 0.0]),
        Just([0.0, 0.0, 1.0]),
        Just([0.0, 0.5, 0.25]),
        (0.0f64..1.0, 0.0f64..1.0, 0.01f64..1.0).prop_map(|(a, b, c)| [a, b, c]),
    ]
}

/// One object of the scene, as YAML, from a shape kind and numbers.
fn object(i: usize, kind: u8, p: [f64; 3], size: f64, material: usize) -> String {
    let [x, y, z] = p;
    let s = size.abs() + 0.25;
    let shape = match kind % 3 {
        0 => format!("sphere: {{ center: [{x}, {y}, {}], radius: {s} }}", z + 3.0),
        1 => format!(
            "plane: {{ point: [{x}, {y}, {}], normal: [{y}, 1, {x}] }}",
            z + 5.0
        ),
        _ => format!(
            "box: {{ min: [{x}, {y}, {}], max: [{}, {}, {}] }}",
            z + 2.0,
            x + s,
            y + s,
            z + 2.0 + s
        ),
    };
    format!("  - {{ name: o{i}, {shape}, material: m{material} }}\n")
}

#[derive(Debug, Clone)]
struct Spec {
    objects: Vec<(u8, [f64; 3], f64, usize)>,
    materials: Vec<[f64; 7]>,
    lights: Vec<([f64; 3], [f64; 3], f64)>,
    /// Lights placed where the ray of pixel (column, row) first meets a surface.
    on_surface: Vec<((u32, u32), [f64; 3])>,
    sampling: u8,
    spp: u32,
}

fn spec() -> impl Strategy<Value = Spec> {
    (
        prop::collection::vec((any::<u8>(), [num(), num(), num()], num(), 0usize..3), 1..5),
        prop::collection::vec(
            (
                coefficient(),
                coefficient(),
                coefficient(),
                1.0f64..60.0,
                coefficient(),
                coefficient(),
                0.5f64..2.5,
            )
                .prop_map(|(a, b, c, d, e, f, g)| [a, b, c, d, e, f, g]),
            3,
        ),
        prop::collection::vec(([num(), num(), num()], attenuation(), 0.0f64..2.0), 0..3),
        prop::collection::vec(((0u32..9, 0u32..7), attenuation()), 1..3),
        any::<u8>(),
        1u32..5,
    )
        .prop_map(
            |(objects, materials, lights, on_surface, sampling, spp)| Spec {
                objects,
                materials,
                lights,
                on_surface,
                sampling,
                spp,
            },
        )
}

fn yaml(spec: &Spec, placed: &[([f64; 3], [f64; 3])]) -> String {
    // The lecture's window camera: exact numbers, so a pixel's centre ray is exactly known.
    let mut text = String::from(
        "camera: { eye: [0, 0, -10], u: [1, 0, 0], v: [0, 1, 0], w: [0, 0, 1], f: 10,\n\
         \x20         window: [-4, 4, 3, -3], width: 9, height: 7 }\n\
         ambient: 0.1\nbackground: 0.2\nmax_depth: 4\n",
    );
    text += &format!("spp: {}\n", spec.spp);
    text += match spec.sampling % 3 {
        0 => "antialias: grid\n",
        1 => "antialias: jittered\n",
        _ => "antialias: adaptive\n",
    };
    if spec.sampling & 4 != 0 {
        text += "filter: gaussian\n";
    }
    text += "materials:\n";
    for (i, m) in spec.materials.iter().enumerate() {
        text += &format!(
            "  m{i}: {{ color: [1, 0.5, 0.25], ka: {}, kd: {}, ks: {}, shininess: {}, kr: {}, kt: {}, ior: {}, highlight: {} }}\n",
            m[0], m[1], m[2], m[3], m[4], m[5], m[6],
            if i == 1 { "phong" } else { "blinn" }
        );
    }
    text += if spec.lights.is_empty() && placed.is_empty() {
        "lights: []\n"
    } else {
        "lights:\n"
    };
    for (i, (p, a, intensity)) in spec.lights.iter().enumerate() {
        text += &format!(
            "  - {{ name: l{i}, point: [{}, {}, {}], attenuation: [{}, {}, {}], intensity: {intensity} }}\n",
            p[0], p[1], p[2], a[0], a[1], a[2]
        );
    }
    for (i, (p, a)) in placed.iter().enumerate() {
        text += &format!(
            "  - {{ name: on{i}, point: [{}, {}, {}], attenuation: [{}, {}, {}] }}\n",
            p[0], p[1], p[2], a[0], a[1], a[2]
        );
    }
    text += "objects:\n";
    for (i, (kind, p, size, m)) in spec.objects.iter().enumerate() {
        text += &object(i, *kind, *p, *size, *m);
    }
    text
}

fn scene(text: &str) -> Scene {
    parse(text, "random.yaml", None, &Limits::default()).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn no_pixel_is_nan_or_negative(spec in spec()) {
        // First without the placed lights, to find where the chosen pixels' rays meet a surface.
        let bare = scene(&yaml(&spec, &[]));
        let mut placed = vec![];
        for &((x, y), a) in &spec.on_surface {
            let tree = Tracer::new(&bare).inspect(&bare.camera.pixel_ray(x, y));
            if let Some(hit) = &tree.hit {
                placed.push((hit.point.to_array(), a));
            }
        }
        let text = yaml(&spec, &placed);
        let s = scene(&text);
        for engine in [Engine::Fast, Engine::Core] {
            let options = RenderOptions { engine, ..RenderOptions::of(&s) };
            let (image, _) = render_simple(&s, options);
            for (i, p) in image.pixels.iter().enumerate() {
                prop_assert!(
                    p.is_finite() && p.min_element() >= 0.0,
                    "pixel {} is {p} ({engine:?}):\n{text}", i
                );
            }
        }
    }
}
