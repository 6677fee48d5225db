//! Texture coordinates: where a point of a surface lands on a flat image, (u, v) in the unit
//! square, u across and v up (v = 0 is the bottom row of an image).
//!
//! Four projections take a point p (in the space a texture is placed in) to (u, v), with the
//! conventions of The Ray Tracer Challenge (chapter "Texture mapping"):
//!
//! - spherical: θ = atan2(x, z), φ = acos(y/|p|); u = 1 − (θ/2π + ½), v = 1 − φ/π. u runs once
//!   round the y axis (the seam is where z < 0 and x = 0), v from the south pole (0) to the
//!   north pole (1).
//! - planar: u = x − ⌊x⌋, v = z − ⌊z⌋: unit tiles over the xz plane.
//! - cylindrical: u as spherical, v = y − ⌊y⌋: one image per unit of height round the y axis.
//! - cube: the face of the cube [−1, 1]³ that p's largest coordinate points to, (u, v) on that
//!   face, and the six faces unfolded into a cross four faces wide and three high (below). The
//!   book lays the faces out to be read from inside the cube, as a sky box is; raytree's world
//!   is left-handed like the book's, so seen from outside each face reads mirrored. A box's own
//!   (u, v) mirrors the point in z first, which turns the cross inside out: every face then
//!   reads left to right from outside.
//!
//! A point on a seam (u = 1 after rounding, or −0 turning atan2 round) wraps to u = 0, so the
//! same point always gets the same coordinates. Each shape also has its own (u, v): the
//! projection that fits it, placed on it (`Shape::uv`).

use glam::{DVec2, DVec3};
use std::f64::consts::PI;

use super::floor::floor;
use super::{cylinder, Shape};

/// Which texture coordinates of a surface run from one edge of the image to the other, as v
/// does on a sphere from pole to pole, rather than round and round (u round a sphere) or on
/// without end (a plane's): an image does not wrap round those edges. On a face of the cube
/// cross, the image ends at the edges of the face's own cell: its neighbours in the cross are
/// blank or, for most edges, not its neighbours on the cube.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Edges {
    /// u ends at the image's left and right edges.
    pub u: bool,
    /// v ends at the image's bottom and top edges.
    pub v: bool,
    /// The face of the cube cross the point lies on, whose cell ends the image both ways.
    pub cell: Option<CubeFace>,
}

impl Edges {
    /// Neither coordinate ends: the image repeats both ways.
    pub const NONE: Edges = Edges {
        u: false,
        v: false,
        cell: None,
    };
    /// v ends (pole to pole, base to top), u goes round.
    pub const V: Edges = Edges {
        u: false,
        v: true,
        cell: None,
    };
    /// Both end: a disc or a triangle filling the unit square.
    pub const BOTH: Edges = Edges {
        u: true,
        v: true,
        cell: None,
    };

    /// The cell of `face` in the cube cross: the image ends at its four edges.
    pub fn cell(face: CubeFace) -> Edges {
        Edges {
            u: true,
            v: true,
            cell: Some(face),
        }
    }
}

/// x − ⌊x⌋, in [0, 1) (a value that rounds to 1 wraps to 0).
pub fn wrap(x: f64) -> f64 {
    let f = x - floor(x);
    if f >= 1.0 {
        0.0
    } else {
        f
    }
}

/// u of the angle round the y axis: 0 on the −z axis, ¼ on +x, ½ on +z, ¾ on −x.
fn around_y(x: f64, z: f64) -> f64 {
    let theta = x.atan2(z);
    wrap(1.0 - (theta / (2.0 * PI) + 0.5))
}

/// Spherical projection about the origin (only the direction of p matters). At a pole
/// (x = z = 0) u is ½.
pub fn spherical(p: DVec3) -> DVec2 {
    let r = p.length();
    if r == 0.0 {
        return DVec2::new(0.5, 0.5);
    }
    let phi = (p.y / r).clamp(-1.0, 1.0).acos();
    DVec2::new(around_y(p.x, p.z), 1.0 - phi / PI)
}

/// Planar projection onto the xz plane, unit tiles.
pub fn planar(p: DVec3) -> DVec2 {
    DVec2::new(wrap(p.x), wrap(p.z))
}

/// Cylindrical projection round the y axis, one unit of height per image.
pub fn cylindrical(p: DVec3) -> DVec2 {
    DVec2::new(around_y(p.x, p.z), wrap(p.y))
}

/// The faces of the cube [−1, 1]³.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CubeFace {
    /// The face at x = −1.
    Left,
    /// The face at x = +1.
    Right,
    /// The face at z = +1.
    Front,
    /// The face at z = −1.
    Back,
    /// The face at y = +1.
    Up,
    /// The face at y = −1.
    Down,
}

impl CubeFace {
    /// The face p's largest coordinate (in size) points to; a tie goes to x, then y.
    pub fn of(p: DVec3) -> CubeFace {
        let a = p.abs();
        let largest = a.max_element();
        if largest == a.x {
            if p.x > 0.0 {
                CubeFace::Right
            } else {
                CubeFace::Left
            }
        } else if largest == a.y {
            if p.y > 0.0 {
                CubeFace::Up
            } else {
                CubeFace::Down
            }
        } else if p.z > 0.0 {
            CubeFace::Front
        } else {
            CubeFace::Back
        }
    }

    /// (u, v) of p on this face, each in [0, 1): the face seen from outside, v up (for the
    /// top and bottom faces, v towards −z and +z).
    pub fn uv(self, p: DVec3) -> DVec2 {
        let half = |x: f64| wrap((x + 1.0) / 2.0);
        let (u, v) = match self {
            CubeFace::Front => (half(p.x), half(p.y)),
            CubeFace::Back => (half(-p.x), half(p.y)),
            CubeFace::Left => (half(p.z), half(p.y)),
            CubeFace::Right => (half(-p.z), half(p.y)),
            CubeFace::Up => (half(p.x), half(-p.z)),
            CubeFace::Down => (half(p.x), half(p.z)),
        };
        DVec2::new(u, v)
    }

    /// Where the face sits in the unfolded cross, in face widths from the image's bottom left:
    ///
    /// ```text
    ///         up
    ///  left  front  right  back
    ///        down
    /// ```
    /// Neighbouring faces of the cross share their edge on the cube too.
    pub fn cell(self) -> (f64, f64) {
        match self {
            CubeFace::Left => (0.0, 1.0),
            CubeFace::Front => (1.0, 1.0),
            CubeFace::Right => (2.0, 1.0),
            CubeFace::Back => (3.0, 1.0),
            CubeFace::Up => (1.0, 2.0),
            CubeFace::Down => (1.0, 0.0),
        }
    }

    /// (u, v) on the face placed in the unfolded cross.
    pub fn unfolded(self, face_uv: DVec2) -> DVec2 {
        let (col, row) = self.cell();
        DVec2::new((col + face_uv.x) / 4.0, (row + face_uv.y) / 3.0)
    }
}

/// Cube projection: the face p points to, unfolded into the cross.
pub fn cube(p: DVec3) -> DVec2 {
    let face = CubeFace::of(p);
    face.unfolded(face.uv(p))
}

// --- Each shape's own (u, v) ---

impl Shape {
    /// The shape's own (u, v) at a point p of its surface (in the shape's space) on `face`:
    ///
    /// - sphere: the spherical projection about its centre;
    /// - plane: the distances from its `point` along two axes, u along n × y (x for a floor), v
    ///   along u × n (z for a floor, up for a wall); not wrapped into the unit square, so that a
    ///   pattern's transform can set the size of its tiles (an image repeats every unit);
    /// - box: the cube projection of the face hit, seen from outside (the point mirrored in z,
    ///   so that the cross's middle face is the one towards −z, which a camera at −z sees),
    ///   unfolded into the cross;
    /// - cylinder and cone: u round the axis (as the cylindrical projection round an upright
    ///   axis: 0 towards −z), v along it, 0 at the base and 1 at the top or apex; a cap's disc
    ///   fills the unit square, seen from outside (as a box's top and bottom faces are);
    /// - triangle: (λ2, λ3), so a = (0, 0), b = (1, 0), c = (0, 1);
    /// - mesh: its vertices' texture coordinates (OBJ `vt`) blended with the barycentric
    ///   coordinates, or the triangle's own (λ2, λ3) without them.
    pub fn uv(&self, p: DVec3, face: u32) -> DVec2 {
        match self {
            Shape::Sphere(s) => spherical(p - s.center),
            Shape::Plane(s) => {
                let (eu, ev) = plane_axes(s.normal);
                let w = p - s.point;
                DVec2::new(w.dot(eu), w.dot(ev))
            }
            Shape::Box(b) => {
                let q = (p - 0.5 * (b.min + b.max)) / (0.5 * (b.max - b.min));
                // Mirrored in z: the face at z = −1 (face 4) is read as the cube's front.
                let q = DVec3::new(q.x, q.y, -q.z);
                let face = box_face(face);
                face.unfolded(face.uv(q))
            }
            Shape::Cylinder(c) | Shape::OpenCylinder(c) => {
                let a = c.axis();
                let h = (c.top - c.base).length();
                round_axis(p - c.base, a, c.radius, face as u8, |s| s / h)
            }
            Shape::Cone(c) | Shape::OpenCone(c) => {
                // Measured from the base towards the apex.
                let a = -c.axis();
                let h = (c.base - c.apex).length();
                round_axis(p - c.base, a, c.radius, face as u8, |s| s / h)
            }
            Shape::Triangle(t) => {
                let l = t.barycentric(p);
                DVec2::new(l.y, l.z)
            }
            Shape::Mesh(m) => m.uv(p, face),
        }
    }

    /// Which of the coordinates `uv` gives on `face` end at the image's edges: v on a sphere,
    /// on the side of a cylinder or cone and in a box's cross (whose middle row goes round
    /// the box), both on a cap and on a triangle. A plane's run on without end, and a mesh's
    /// `vt` coordinates repeat the image, as OBJ files expect.
    pub fn uv_edges(&self, face: u32) -> Edges {
        match self {
            Shape::Plane(_) | Shape::Mesh(_) => Edges::NONE,
            Shape::Sphere(_) => Edges::V,
            Shape::Box(_) => Edges::cell(box_face(face)),
            Shape::Cylinder(_) | Shape::OpenCylinder(_) | Shape::Cone(_) | Shape::OpenCone(_) => {
                if face == cylinder::SIDE as u32 {
                    Edges::V
                } else {
                    Edges::BOTH
                }
            }
            Shape::Triangle(_) => Edges::BOTH,
        }
    }
}

/// The cube face a box's face is read as: the box is mirrored in z, so that its face at z = −1
/// (face 4), the one a camera at −z sees, is the cross's middle face.
fn box_face(face: u32) -> CubeFace {
    match face {
        0 => CubeFace::Left,
        1 => CubeFace::Right,
        2 => CubeFace::Down,
        3 => CubeFace::Up,
        4 => CubeFace::Front,
        _ => CubeFace::Back,
    }
}

/// u and v axes on a plane with unit normal n: u along n × y (x when n is vertical), v = u × n.
fn plane_axes(n: DVec3) -> (DVec3, DVec3) {
    let across = n.cross(DVec3::Y);
    let eu = if across.length_squared() < 1e-18 {
        DVec3::X
    } else {
        across.normalize()
    };
    (eu, eu.cross(n))
}

/// Two unit vectors (x, z) across the unit axis a, with (x, a, z) turning as (x, y, z) do: for
/// an upright axis, the x and z axes themselves.
fn across_axis(a: DVec3) -> (DVec3, DVec3) {
    let helper = if a.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let z = helper.cross(a).normalize();
    (a.cross(z), z)
}

/// (u, v) on a surface round the axis a through the base: u the angle, v = `along`(height) on
/// the side; on a cap (faces 1 and 2) the disc of radius r fills the unit square, u along x and
/// v along z seen from beyond the top cap, v along −z from below the base cap, so that each
/// reads left to right from outside.
fn round_axis(w: DVec3, a: DVec3, r: f64, face: u8, along: impl Fn(f64) -> f64) -> DVec2 {
    let (x, z) = across_axis(a);
    let (wx, wz) = (w.dot(x), w.dot(z));
    if face == cylinder::SIDE {
        return DVec2::new(around_y(wx, wz), along(w.dot(a)).clamp(0.0, 1.0));
    }
    let wz = if face == cylinder::BASE_CAP { -wz } else { wz };
    DVec2::new(
        (0.5 + wx / (2.0 * r)).clamp(0.0, 1.0),
        (0.5 + wz / (2.0 * r)).clamp(0.0, 1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Aabox, Cylinder, Sphere};

    fn close(a: DVec2, u: f64, v: f64) -> bool {
        (a.x - u).abs() < 1e-5 && (a.y - v).abs() < 1e-5
    }

    /// The Ray Tracer Challenge, "Using a spherical mapping on a 3D point" (the poles and the
    /// seam among them).
    #[test]
    fn spherical_mapping_of_the_book() {
        let h = 2f64.sqrt() / 2.0;
        for (p, u, v) in [
            ((0.0, 0.0, -1.0), 0.0, 0.5),
            ((1.0, 0.0, 0.0), 0.25, 0.5),
            ((0.0, 0.0, 1.0), 0.5, 0.5),
            ((-1.0, 0.0, 0.0), 0.75, 0.5),
            ((0.0, 1.0, 0.0), 0.5, 1.0),
            ((0.0, -1.0, 0.0), 0.5, 0.0),
            ((h, h, 0.0), 0.25, 0.75),
        ] {
            let got = spherical(DVec3::from(p));
            assert!(close(got, u, v), "{p:?}: {got}");
        }
    }

    /// On the seam, −0 and +0 give the same u: atan2 says ±π, the wrap says 0 for both.
    #[test]
    fn the_seam_is_one_line() {
        let a = spherical(DVec3::new(0.0, 0.3, -1.0));
        let b = spherical(DVec3::new(-0.0, 0.3, -1.0));
        assert_eq!((a.x, b.x), (0.0, 0.0));
        assert_eq!(a, b);
        // Just either side of it: u just above 0 and just below 1.
        assert!(spherical(DVec3::new(1e-9, 0.0, -1.0)).x < 1e-9);
        assert!(spherical(DVec3::new(-1e-9, 0.0, -1.0)).x > 1.0 - 1e-9);
    }

    /// "Using a planar mapping on a 3D point".
    #[test]
    fn planar_mapping_of_the_book() {
        for (p, u, v) in [
            ((0.25, 0.0, 0.5), 0.25, 0.5),
            ((0.25, 0.0, -0.25), 0.25, 0.75),
            ((0.25, 0.5, -0.25), 0.25, 0.75),
            ((1.25, 0.0, 0.5), 0.25, 0.5),
            ((0.25, 0.0, -1.75), 0.25, 0.25),
            ((1.0, 0.0, -1.0), 0.0, 0.0),
            ((0.0, 0.0, 0.0), 0.0, 0.0),
        ] {
            let got = planar(DVec3::from(p));
            assert!(close(got, u, v), "{p:?}: {got}");
        }
    }

    /// "Using a cylindrical mapping on a 3D point".
    #[test]
    fn cylindrical_mapping_of_the_book() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        for (p, u, v) in [
            ((0.0, 0.0, -1.0), 0.0, 0.0),
            ((0.0, 0.5, -1.0), 0.0, 0.5),
            ((0.0, 1.0, -1.0), 0.0, 0.0),
            ((h, 0.5, -h), 0.125, 0.5),
            ((1.0, 0.5, 0.0), 0.25, 0.5),
            ((h, 0.5, h), 0.375, 0.5),
            ((0.0, -0.25, 1.0), 0.5, 0.75),
            ((-h, 0.5, h), 0.625, 0.5),
            ((-1.0, 1.25, 0.0), 0.75, 0.25),
            ((-h, 0.5, -h), 0.875, 0.5),
        ] {
            let got = cylindrical(DVec3::from(p));
            assert!(close(got, u, v), "{p:?}: {got}");
        }
    }

    /// "Identifying the face of a cube from a point" and the uv of each face.
    #[test]
    fn cube_faces_of_the_book() {
        for (p, face) in [
            ((-1.0, 0.5, -0.25), CubeFace::Left),
            ((1.1, -0.75, 0.8), CubeFace::Right),
            ((0.1, 0.6, 0.9), CubeFace::Front),
            ((-0.7, 0.0, -2.0), CubeFace::Back),
            ((0.5, 1.0, 0.9), CubeFace::Up),
            ((-0.2, -1.3, 1.1), CubeFace::Down),
        ] {
            assert_eq!(CubeFace::of(DVec3::from(p)), face, "{p:?}");
        }
        for (face, p, u, v) in [
            (CubeFace::Front, (-0.5, 0.5, 1.0), 0.25, 0.75),
            (CubeFace::Front, (0.5, -0.5, 1.0), 0.75, 0.25),
            (CubeFace::Back, (0.5, 0.5, -1.0), 0.25, 0.75),
            (CubeFace::Back, (-0.5, -0.5, -1.0), 0.75, 0.25),
            (CubeFace::Left, (-1.0, 0.5, -0.5), 0.25, 0.75),
            (CubeFace::Left, (-1.0, -0.5, 0.5), 0.75, 0.25),
            (CubeFace::Right, (1.0, 0.5, 0.5), 0.25, 0.75),
            (CubeFace::Right, (1.0, -0.5, -0.5), 0.75, 0.25),
            (CubeFace::Up, (-0.5, 1.0, -0.5), 0.25, 0.75),
            (CubeFace::Up, (0.5, 1.0, 0.5), 0.75, 0.25),
            (CubeFace::Down, (-0.5, -1.0, 0.5), 0.25, 0.75),
            (CubeFace::Down, (0.5, -1.0, -0.5), 0.75, 0.25),
        ] {
            let got = face.uv(DVec3::from(p));
            assert!(close(got, u, v), "{face:?} {p:?}: {got}");
        }
    }

    /// The cross: an edge shared on the cube is shared in the image. The front face's right
    /// edge (x = 1) is the right face's left edge, its top edge (y = 1) the top face's bottom.
    #[test]
    fn the_unfolded_cross_keeps_neighbours_together() {
        let p = DVec3::new(1.0, 0.2, 1.0);
        let front = CubeFace::Front.unfolded(CubeFace::Front.uv(DVec3::new(1.0 - 1e-12, 0.2, 1.0)));
        let right = CubeFace::Right.unfolded(CubeFace::Right.uv(p));
        assert!((front - right).length() < 1e-9, "{front} {right}");
        let top_edge = DVec3::new(0.3, 1.0, 1.0);
        let front = CubeFace::Front.unfolded(CubeFace::Front.uv(top_edge - 1e-12 * DVec3::Y));
        let up = CubeFace::Up.unfolded(CubeFace::Up.uv(top_edge - 1e-12 * DVec3::Z));
        assert!((front - up).length() < 1e-9, "{front} {up}");
        assert_eq!(
            cube(DVec3::new(0.0, 0.0, 1.0)),
            DVec2::new(1.5 / 4.0, 1.5 / 3.0)
        );
    }

    /// How (u, v) changes as a point of the surface moves a little to the right and up, as a
    /// viewer outside sees it: looking along −n, with `up` up, right = up × forward (the
    /// look-at camera's left-handed frame).
    fn seen_from_outside(uv: impl Fn(DVec3) -> DVec2, p: DVec3, n: DVec3, up: DVec3) -> DVec2 {
        let right = up.cross(-n);
        let e = 1e-4;
        let across = (uv(p + e * right) - uv(p - e * right)).x;
        let upward = (uv(p + e * up) - uv(p - e * up)).y;
        DVec2::new(across, upward)
    }

    /// Seen from outside, every face of a box and both caps of a cylinder read left to right
    /// and bottom to top, as a sphere does where it faces the viewer: u grows to the right, v
    /// upward (the top faces with +z up, as a camera at −z looking down sees them, the bottom
    /// ones with −z up). The face the book's cube puts in the cross's middle is the one
    /// towards −z.
    #[test]
    fn a_box_and_a_caps_faces_read_left_to_right_from_outside() {
        let ball = Shape::Sphere(Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        });
        let sphere_uv = |p: DVec3| ball.uv(p, 0);
        let at_front = seen_from_outside(
            sphere_uv,
            DVec3::new(0.3, 0.2, -0.9327379),
            DVec3::NEG_Z,
            DVec3::Y,
        );
        assert!(at_front.x > 0.0 && at_front.y > 0.0, "sphere {at_front}");
        let cube = Shape::Box(Aabox {
            min: DVec3::splat(-1.0),
            max: DVec3::ONE,
        });
        let (y, z) = (DVec3::Y, DVec3::Z);
        for (face, n, up) in [
            (0, DVec3::NEG_X, y),
            (1, DVec3::X, y),
            (2, DVec3::NEG_Y, -z),
            (3, DVec3::Y, z),
            (4, DVec3::NEG_Z, y),
            (5, DVec3::Z, y),
        ] {
            // A point off the face's centre, so that no coordinate is on an edge.
            let p = n + (DVec3::ONE - n.abs()) * DVec3::new(0.3, 0.2, 0.1);
            let d = seen_from_outside(|q| cube.uv(q, face), p, n, up);
            assert!(d.x > 0.0 && d.y > 0.0, "box face {face}: {d}");
        }
        assert_eq!(
            cube.uv(DVec3::new(0.0, 0.0, -1.0), 4),
            DVec2::new(1.5 / 4.0, 1.5 / 3.0)
        );
        let can = Shape::Cylinder(Cylinder {
            base: DVec3::ZERO,
            top: DVec3::Y,
            radius: 1.0,
        });
        for (face, n, up) in [
            (cylinder::TOP_CAP, y, z),
            (cylinder::BASE_CAP, DVec3::NEG_Y, -z),
        ] {
            let p = DVec3::new(0.3, if face == cylinder::TOP_CAP { 1.0 } else { 0.0 }, 0.2);
            let d = seen_from_outside(|q| can.uv(q, face as u32), p, n, up);
            assert!(d.x > 0.0 && d.y > 0.0, "cap {face}: {d}");
        }
    }
}
