//! What a view shows of each object: its outline, as the orthographic projection of the solid
//! draws it. A sphere is a circle (an ellipse once scaled unevenly); boxes, cylinders, cones,
//! triangles and meshes are the convex hull of their projected corners or rims (exact for the
//! convex solids, the bounding outline of a mesh); a plane, which no outline holds, is the line
//! it cuts through the plane of the drawing (nothing when it faces the viewer); a CSG object is
//! drawn by its leaves.

use glam::{DMat3, DVec2, DVec3};

use super::view::View;
use crate::geometry::{Shape, Transform};
use crate::scene::{Leaf, Scene};

/// A shape in the drawing's plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Outline {
    /// A closed polygon: a silhouette.
    Polygon(Vec<DVec2>),
    /// A line without end through `point` along `dir`: a plane cut by the drawing's plane.
    Line {
        /// A point of the line, in the view's plane.
        point: DVec2,
        /// The line's direction, in the view's plane.
        dir: DVec2,
    },
}

/// One primitive's outline.
#[derive(Clone, Debug, PartialEq)]
pub struct LeafOutline {
    /// The object's name.
    pub object: String,
    /// The leaf's name (the object's own for a plain object).
    pub leaf: String,
    /// The shape drawn.
    pub outline: Outline,
}

impl Outline {
    /// The point a label is placed by: the polygon's top, the line's point.
    pub fn anchor(&self) -> DVec2 {
        match self {
            // The top, and of points as high (a sheet seen edge-on) the leftmost.
            Outline::Polygon(p) => {
                let top = p.iter().map(|q| q.y).fold(f64::NEG_INFINITY, f64::max);
                let size = self.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length());
                p.iter()
                    .copied()
                    .filter(|q| q.y >= top - 1e-3 * size)
                    .min_by(|a, b| a.x.total_cmp(&b.x))
                    .unwrap_or(DVec2::ZERO)
            }
            Outline::Line { point, .. } => *point,
        }
    }

    /// The polygon's bounding rectangle (none for a line).
    pub fn bounds(&self) -> Option<(DVec2, DVec2)> {
        match self {
            Outline::Polygon(p) if !p.is_empty() => Some(
                p.iter()
                    .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), q| {
                        (lo.min(*q), hi.max(*q))
                    }),
            ),
            _ => None,
        }
    }
}

/// Points on a circle's rim: a polygon with this many sides.
const RIM: usize = 72;

/// The outline of every primitive in `view`; planes are cut at `section` along the axis the
/// view drops.
pub fn outlines(scene: &Scene, view: View, section: f64) -> Vec<LeafOutline> {
    scene
        .leaves
        .iter()
        .filter_map(|l| {
            Some(LeafOutline {
                object: scene.objects.get(l.object as usize)?.name.clone(),
                leaf: l.name.clone(),
                outline: leaf_outline(l, view, section)?,
            })
        })
        .collect()
}

/// The outline of one primitive, if the view shows one.
pub fn leaf_outline(l: &Leaf, view: View, section: f64) -> Option<Outline> {
    let tf = l.transform.as_deref();
    let world = |p: DVec3| tf.map_or(p, |t| t.point_to_world(p));
    let flat = |pts: Vec<DVec3>| {
        Outline::Polygon(hull(
            pts.into_iter().map(|p| view.project(world(p))).collect(),
        ))
    };
    Some(match &l.shape {
        Shape::Sphere(s) => ellipse(s.center, s.radius, tf, view),
        Shape::Box(b) => {
            let corners = (0..8)
                .map(|i| {
                    DVec3::new(
                        if i & 1 == 0 { b.min.x } else { b.max.x },
                        if i & 2 == 0 { b.min.y } else { b.max.y },
                        if i & 4 == 0 { b.min.z } else { b.max.z },
                    )
                })
                .collect();
            flat(corners)
        }
        Shape::Cylinder(c) | Shape::OpenCylinder(c) => {
            let mut pts = rim(c.base, c.top - c.base, c.radius);
            pts.extend(rim(c.top, c.top - c.base, c.radius));
            flat(pts)
        }
        Shape::Cone(c) | Shape::OpenCone(c) => {
            let mut pts = rim(c.base, c.base - c.apex, c.radius);
            pts.push(c.apex);
            flat(pts)
        }
        Shape::Triangle(t) => flat(vec![t.a, t.b, t.c]),
        Shape::Mesh(m) => flat(m.positions.clone()),
        Shape::Plane(p) => {
            let (point, normal) = match tf {
                Some(t) => (t.point_to_world(p.point), t.normal_to_world(p.normal)),
                None => (p.point, p.normal),
            };
            plane_line(point, normal, view, section)?
        }
    })
}

/// The outline of a sphere carried by a transform: the ellipse {c + A·u : |u| = 1}, where A is
/// the view's 2 × 3 projection of the transform's linear part times the radius.
fn ellipse(center: DVec3, radius: f64, tf: Option<&Transform>, view: View) -> Outline {
    let m = tf.map_or(DMat3::IDENTITY, |t| t.to_world.matrix3) * radius;
    let c = view.project(tf.map_or(center, |t| t.point_to_world(center)));
    // Columns of A: the projections of the images of the axes of the sphere's own space.
    let cols = [
        view.project(m.x_axis),
        view.project(m.y_axis),
        view.project(m.z_axis),
    ];
    // S = A·Aᵀ (2 × 2, symmetric); its eigenvectors are the ellipse's axes, the square roots
    // of its eigenvalues their half-lengths.
    let (a, b, d) = cols.iter().fold((0.0, 0.0, 0.0), |(a, b, d), r| {
        (a + r.x * r.x, b + r.x * r.y, d + r.y * r.y)
    });
    let mean = 0.5 * (a + d);
    let root = (0.25 * (a - d) * (a - d) + b * b).sqrt();
    let (l1, l2) = (mean + root, (mean - root).max(0.0));
    let e1 = if b.abs() > 1e-300 {
        DVec2::new(l1 - d, b).normalize()
    } else if a >= d {
        DVec2::X
    } else {
        DVec2::Y
    };
    let e2 = e1.perp();
    let points = (0..RIM)
        .map(|i| {
            let th = i as f64 / RIM as f64 * std::f64::consts::TAU;
            c + l1.sqrt() * th.cos() * e1 + l2.sqrt() * th.sin() * e2
        })
        .collect();
    Outline::Polygon(points)
}

/// Points on the circle of radius r about `center` perpendicular to `axis`.
fn rim(center: DVec3, axis: DVec3, r: f64) -> Vec<DVec3> {
    let w = axis.normalize_or(DVec3::Y);
    let u = w.any_orthonormal_vector();
    let v = w.cross(u);
    (0..RIM / 2)
        .map(|i| {
            let th = i as f64 / (RIM / 2) as f64 * std::f64::consts::TAU;
            center + r * (th.cos() * u + th.sin() * v)
        })
        .collect()
}

/// The line a plane cuts through the drawing's plane (the view's dropped axis at `section`),
/// or None when the plane is parallel to the drawing.
pub fn plane_line(point: DVec3, normal: DVec3, view: View, section: f64) -> Option<Outline> {
    let n2 = view.project(normal);
    if n2.length() < 1e-9 * normal.length() {
        return None;
    }
    let axis = view.dropped_axis();
    // Points q of the drawing with n2·q + n[axis]·section = n·point.
    let rhs = normal.dot(point) - normal[axis] * section;
    Some(Outline::Line {
        point: n2 * (rhs / n2.length_squared()),
        dir: n2.perp().normalize(),
    })
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain); fewer than three
/// distinct points come back as they are.
pub fn hull(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    pts.retain(|p| p.is_finite());
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<DVec2> = vec![];
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<DVec2> = vec![];
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DAffine3;

    #[test]
    fn a_scaled_sphere_is_an_ellipse_with_the_scaled_half_axes() {
        let tf = Transform::new(DAffine3::from_scale(DVec3::new(3.0, 1.0, 2.0)));
        let Outline::Polygon(p) = ellipse(DVec3::ZERO, 1.0, Some(&tf), View::Front) else {
            panic!("an ellipse is a polygon");
        };
        let max_x = p.iter().map(|q| q.x.abs()).fold(0.0, f64::max);
        let max_y = p.iter().map(|q| q.y.abs()).fold(0.0, f64::max);
        assert!(
            (max_x - 3.0).abs() < 1e-9 && (max_y - 1.0).abs() < 1e-9,
            "{max_x} {max_y}"
        );
        // Seen from above, the z half-axis is 2.
        let Outline::Polygon(p) = ellipse(DVec3::ZERO, 1.0, Some(&tf), View::Top) else {
            panic!();
        };
        let max_z = p.iter().map(|q| q.y.abs()).fold(0.0, f64::max);
        assert!((max_z - 2.0).abs() < 1e-9);
    }

    #[test]
    fn a_floor_is_a_line_from_the_side_and_nothing_from_above() {
        let line = plane_line(DVec3::new(0.0, -1.0, 0.0), DVec3::Y, View::Side, 0.0);
        assert_eq!(
            line,
            Some(Outline::Line {
                point: DVec2::new(0.0, -1.0),
                dir: DVec2::new(-1.0, 0.0),
            })
        );
        assert_eq!(plane_line(DVec3::ZERO, DVec3::Y, View::Top, 0.0), None);
    }

    #[test]
    fn the_hull_of_a_square_and_its_centre_is_the_square() {
        let h = hull(vec![
            DVec2::ZERO,
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 0.5),
            DVec2::ONE,
            DVec2::new(0.0, 1.0),
        ]);
        assert_eq!(h.len(), 4);
        assert!(!h.contains(&DVec2::new(0.5, 0.5)));
    }
}
