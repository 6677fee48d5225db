//! The fast wing: everything in raytree that exists only for speed.
//!
//! The textbook core (`crate::trace::whitted`, the scene's own `Search`, one routine per shape)
//! is the definition of what raytree computes. This wing is an optimisation of it and nothing
//! else: a pixel's primary rays made four at a time (`camera_rays`), packets of rays traced
//! together (`packet_trace`), searched together through the BVH folded to four children a node
//! (`bvh4`, `bvh_packet`, `hull`) or four at a time in SIMD lanes (`lanes`, `packet_search`;
//! the boxes and spheres a pixel's rays cannot meet known from where each can appear,
//! `footprint`), plain spheres and planes tested without spans and in groups of four (`probe`,
//! `sphere_group`), the usual point lights' terms and shadow rays four surfaces at a time
//! (`light_lanes`), the usual checkers' colours (`checker_lanes`), the usual floor shaded from
//! hit to light without shading records (`plane_lanes`), flat CSG objects read off their
//! primitives' spans (`csg_crossing`) or in lanes (`csg_lanes`, `span_lanes`), and the path
//! tracer for scenes of diffuse surfaces (`diffuse_paths`). The binary's allocator maps large
//! blocks in huge pages (`huge_pages`).
//!
//! The contract: every image the wing renders equals, bit for bit, the image of the core's
//! recursion with the core's search, and so do the counters of rays and of skipped shading
//! (not those of the searches' work: packets of shadow rays try the last blocker toward
//! their light first, and walk the BVH less). `tests/fast_paths.rs`
//! checks it on every lesson and peer scene and with property tests. The core never imports
//! the wing (`tests/architecture.rs`); only the renderer calls it.

mod bvh4;
mod bvh_packet;
mod camera_rays;
mod checker_lanes;
mod csg_crossing;
mod csg_lanes;
mod diffuse_paths;
mod footprint;
#[cfg(target_os = "linux")]
pub mod huge_pages;
mod hull;
mod lanes;
mod light_lanes;
mod light_share;
mod outgoing;
mod packet_search;
mod packet_trace;
mod plane_lanes;
mod probe;
mod search;
mod shadow_cones;
pub mod simd;
mod span_lanes;
mod sphere_group;

pub use bvh_packet::PACKET;
pub use camera_rays::ImagePlane;
pub use diffuse_paths::DiffusePaths;
pub use footprint::{Footprints, Missed};
pub use packet_trace::{trace_packet, SHADED};
pub use probe::{plane_hit, sphere_hit};
pub use search::FastScene;
pub use simd::{level, Level};
pub use sphere_group::SphereGroup;

/// `ArrayVec::push` for a value built where it is pushed: `push` panics with the value when
/// the vector is full, so the value must exist whole before the test, and a large one (a
/// 168-byte task) is built in a stack slot and copied in; here the full vector's value is
/// dropped, and the value is built in its place.
#[inline(always)]
fn push_in_place<T, const N: usize>(v: &mut arrayvec::ArrayVec<T, N>, value: T) {
    if v.try_push(value).is_err() {
        panic!("an ArrayVec of {N} is full");
    }
}
