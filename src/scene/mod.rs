//! Scenes: the YAML file format, its compilation into the runtime `Scene`, the hit search over
//! its objects, and errors that name file, line and column.
//!
//! A `Scene` is the description a student wrote (camera, lights, materials, objects and the
//! settings of the recursion), validated and with transforms inverted and bounds computed, plus
//! two things derived from it: the `Features` it uses and the `SearchIndex` its rays are
//! searched through.

mod builder;
mod camera;
mod compile;
mod error;
mod features;
mod flow;
pub(crate) mod format;
mod hit;
mod load;
mod objects;
mod search;
mod segments;
mod settings;
mod simple_items;
mod split;

use std::path::PathBuf;

use glam::DVec3;

pub use builder::{MaterialDesc, SceneBuilder};
pub(crate) use camera::{plane_x, plane_y};
pub use camera::{Camera, Projection};
pub use compile::Limits;
pub use error::{Pos, SceneError};
pub use features::Features;
pub use format::Integrator;
pub use hit::{Hit, Interaction, TANGENT_COSINE};
pub use load::{load, parse};
pub use objects::{Geometry, Group, Leaf, Object};
pub use search::{Accel, Search, SearchIndex, Visited};
pub use settings::{Antialias, Filter, StopRules, DEFAULT_THRESHOLD};

use crate::shading::{Light, Material};

/// A compiled scene: camera, lights, materials, objects, the recursion's settings and the search
/// structures, ready to trace.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The file the scene was read from, if any.
    pub source: Option<PathBuf>,
    /// The other files the scene read, each once: its texture images, then its meshes. With
    /// `source`, every file its image depends on.
    pub inputs: Vec<PathBuf>,

    // What is seen, and from where.
    /// The eye and the image.
    pub camera: Camera,
    /// Intensity of rays that hit nothing.
    pub background: DVec3,
    /// Ambient light Ia of the local model's ka·Ia·O term.
    pub ambient: DVec3,
    /// The light sources.
    pub lights: Vec<Light>,
    /// The materials, indexed by `Leaf::material`.
    pub materials: Vec<Material>,
    /// Every primitive: the plain objects and the leaves of CSG trees.
    pub leaves: Vec<Leaf>,
    /// The objects of the scene file (a primitive, a CSG tree or a group each), in file order.
    pub objects: Vec<Object>,

    // How the recursion runs.
    /// Rays per path, primary included: 1 traces primary rays only.
    pub max_depth: u32,
    /// A secondary ray whose weight (the product of kr and kt along its path) falls below
    /// this is not traced.
    pub adaptive_threshold: f64,
    /// Offset of secondary-ray origins; None = automatic, scaled to the hit point.
    pub shadow_bias: Option<f64>,
    /// I_r and I_t divided by c0 + c1·d + c2·d² (d = length of the child ray), when set.
    pub secondary_attenuation: Option<[f64; 3]>,
    /// The notes' other stop rules (a light hit, a diffuse surface), when the scene names them.
    pub stop_rules: StopRules,
    /// CSG bounding boxes and pruning (on; off only to measure what they save).
    pub csg_pruning: bool,

    // How the image is sampled.
    /// Samples (primary rays) per pixel.
    pub spp: u32,
    /// Whitted's recursion or the path tracer.
    pub integrator: Integrator,
    /// Where a pixel's primary rays go (`spp` of them).
    pub antialias: Antialias,
    /// The reconstruction filter of jittered (Monte Carlo) sampling.
    pub filter: Filter,

    // Derived from all of the above.
    /// What the scene uses, derived from its materials, lights and objects.
    pub features: Features,
    /// The objects arranged for the nearest-hit search (BVH or brute force).
    pub index: SearchIndex,

    /// What is legal but probably not meant (a mesh of degenerate triangles only), with where
    /// in the file it is: the command line prints these, the scene loads anyway.
    pub warnings: Vec<(error::Pos, String)>,
}

impl Scene {
    /// The scene with its features found and its search index built, once its description is
    /// complete.
    pub fn prepared(mut self) -> Scene {
        // Neither depends on the other: on two threads where there are two.
        let (features, index) = rayon::join(
            || Features::of(&self),
            || SearchIndex::build(&self, Accel::Bvh),
        );
        self.features = features;
        self.index = index;
        self
    }

    /// Material number `index` (panics when it is out of range).
    pub fn material(&self, index: u32) -> &Material {
        &self.materials[index as usize]
    }

    /// The index of the object named `name`, if there is one.
    pub fn object_index(&self, name: &str) -> Option<u32> {
        self.objects
            .iter()
            .position(|o| o.name == name)
            .map(|i| i as u32)
    }
}
