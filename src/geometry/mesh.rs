//! Triangle meshes: many triangles as one object, with their own BVH (seed 002: "the cost comes
//! from ray–triangle intersections, reduced by a BVH") and smooth shading by interpolating the
//! vertex normals with the hit's barycentric coordinates; texture coordinates (OBJ `vt`) are
//! blended with the same weights.

use std::fmt;
use std::path::Path;

use glam::{DVec2, DVec3};

use super::{Ray, Triangle};
use crate::accel::bvh::Visits;
use crate::accel::{Aabb, Bvh};

/// A triangle mesh (from an OBJ file) with its own BVH over the triangles; the shape of scene
/// `mesh` objects.
pub struct Mesh {
    /// Vertex positions, object space.
    pub positions: Vec<DVec3>,
    /// One per position, or empty for flat shading.
    pub normals: Vec<DVec3>,
    /// Texture coordinates (u, v), one per position, or empty.
    pub texcoords: Vec<DVec2>,
    /// Triangles as three indices into `positions` (and into `normals` and `texcoords` when
    /// present).
    pub triangles: Vec<[u32; 3]>,
    bvh: Bvh,
    bounds: Aabb,
}

/// The heap bytes of a mesh (see `Mesh::memory`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshMemory {
    /// Positions, and the normals and texture coordinates when it has them.
    pub vertices: usize,
    /// The three vertex indices of each triangle.
    pub triangles: usize,
    /// The BVH over the triangles: nodes and item indices.
    pub bvh: usize,
}

impl MeshMemory {
    /// All of it.
    pub fn total(&self) -> usize {
        self.vertices + self.triangles + self.bvh
    }
}

impl fmt::Debug for Mesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "Mesh({} vertices, {} triangles)",
            self.positions.len(),
            self.triangles.len()
        )
    }
}

impl PartialEq for Mesh {
    fn eq(&self, other: &Mesh) -> bool {
        std::ptr::eq(self, other)
    }
}

impl Mesh {
    /// Builds the mesh and its BVH, dropping degenerate (zero-area) triangles; returns how many
    /// were dropped.
    pub fn new(
        positions: Vec<DVec3>,
        normals: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
    ) -> (Mesh, usize) {
        let before = triangles.len();
        let triangles: Vec<[u32; 3]> = triangles
            .into_iter()
            .filter(|t| {
                let [a, b, c] = t.map(|i| positions[i as usize]);
                Triangle { a, b, c }.normal() != DVec3::ZERO
            })
            .collect();
        let dropped = before - triangles.len();
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| positions[i as usize]);
                Aabb::point(a).grow(b).grow(c)
            })
            .collect();
        let bounds = boxes.iter().fold(Aabb::empty(), |acc, b| acc.union(b));
        let bvh = Bvh::build_over_triangles(&boxes);
        let mut normals = if normals.len() == positions.len() {
            normals
        } else {
            vec![]
        };
        // Loaders grow these by pushing: keep only what the mesh uses.
        let (mut positions, mut triangles) = (positions, triangles);
        positions.shrink_to_fit();
        normals.shrink_to_fit();
        triangles.shrink_to_fit();
        (
            Mesh {
                positions,
                normals,
                texcoords: vec![],
                triangles,
                bvh,
                bounds,
            },
            dropped,
        )
    }

    /// The mesh with texture coordinates, one per position (others are ignored).
    pub fn with_texcoords(mut self, texcoords: Vec<DVec2>) -> Mesh {
        if texcoords.len() == self.positions.len() {
            self.texcoords = texcoords;
        }
        self
    }

    /// The texture coordinates at p on triangle `face`: its vertices' blended by the
    /// barycentric coordinates, uv = λ1·uv1 + λ2·uv2 + λ3·uv3; without them, the triangle's
    /// own (λ2, λ3).
    pub fn uv(&self, p: DVec3, face: u32) -> DVec2 {
        let l = self.triangle(face).barycentric(p);
        if self.texcoords.is_empty() {
            return DVec2::new(l.y, l.z);
        }
        let [a, b, c] = self.triangles[face as usize].map(|v| self.texcoords[v as usize]);
        l.x * a + l.y * b + l.z * c
    }

    /// Triangle number `i`, with its vertex positions (panics when `i` is out of range).
    pub fn triangle(&self, i: u32) -> Triangle {
        let [a, b, c] = self.triangles[i as usize].map(|v| self.positions[v as usize]);
        Triangle { a, b, c }
    }

    /// The bytes the mesh holds on the heap, part by part.
    pub fn memory(&self) -> MeshMemory {
        fn bytes<T>(v: &Vec<T>) -> usize {
            v.capacity() * std::mem::size_of::<T>()
        }
        MeshMemory {
            vertices: bytes(&self.positions) + bytes(&self.normals) + bytes(&self.texcoords),
            triangles: bytes(&self.triangles),
            bvh: self.bvh.heap_bytes(),
        }
    }

    /// The object-space box around all triangles.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The nearest triangle hit with t_min < t < t_max: (t, triangle).
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> (Option<(f64, u32)>, Visits) {
        let mut best = None;
        let visits = self
            .bvh
            .closest(ray.origin, ray.dir, t_min, t_max, |i, limit| {
                let h = self.triangle(i).intersect(ray)?;
                (h.t > t_min && h.t < limit).then(|| {
                    best = Some((h.t, i));
                    h.t
                })
            });
        (best, visits)
    }

    /// The same as `hit`, testing every triangle (to measure what the BVH saves).
    pub fn hit_brute(&self, ray: &Ray, t_min: f64, t_max: f64) -> (Option<(f64, u32)>, Visits) {
        let mut best: Option<(f64, u32)> = None;
        for i in 0..self.triangles.len() as u32 {
            if let Some(h) = self.triangle(i).intersect(ray) {
                if h.t > t_min && h.t < best.map_or(t_max, |b| b.0) {
                    best = Some((h.t, i));
                }
            }
        }
        (
            best,
            Visits {
                nodes: 0,
                items: self.triangles.len() as u64,
            },
        )
    }

    /// Every crossing of the ray's line with the surface, in order (for segment-list views).
    pub fn crossings(&self, ray: &Ray) -> Vec<(f64, u32)> {
        let mut all = vec![];
        self.bvh.closest(
            ray.origin,
            ray.dir,
            f64::NEG_INFINITY,
            f64::INFINITY,
            |i, _| {
                if let Some(h) = self.triangle(i).intersect(ray) {
                    all.push((h.t, i));
                }
                None
            },
        );
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        // A ray through a shared edge or vertex may be reported by every triangle that meets
        // there (the watertight test never misses, but can answer twice): one crossing.
        all.dedup_by(|b, a| (b.0 - a.0).abs() <= 1e-12 * a.0.abs().max(1.0));
        all
    }

    /// The shading normal at p on triangle `face`: the vertex normals blended by the
    /// barycentric coordinates n = λ1·n1 + λ2·n2 + λ3·n3 (seed 002), or the flat normal.
    pub fn normal(&self, p: DVec3, face: u32) -> DVec3 {
        let tri = self.triangle(face);
        if self.normals.is_empty() {
            return tri.normal();
        }
        let l = tri.barycentric(p);
        let [a, b, c] = self.triangles[face as usize].map(|v| self.normals[v as usize]);
        (l.x * a + l.y * b + l.z * c)
            .try_normalize()
            .unwrap_or_else(|| tri.normal())
    }

    /// A unit icosphere: an icosahedron with each face split into 4, `subdivisions` times
    /// (20·4^k triangles), vertices pushed onto the sphere; `smooth`: its normals are the
    /// positions (else each triangle is flat).
    pub fn icosphere(subdivisions: u32, smooth: bool) -> Mesh {
        let g = (1.0 + 5f64.sqrt()) / 2.0;
        let mut positions: Vec<DVec3> = [
            (-1.0, g, 0.0),
            (1.0, g, 0.0),
            (-1.0, -g, 0.0),
            (1.0, -g, 0.0),
            (0.0, -1.0, g),
            (0.0, 1.0, g),
            (0.0, -1.0, -g),
            (0.0, 1.0, -g),
            (g, 0.0, -1.0),
            (g, 0.0, 1.0),
            (-g, 0.0, -1.0),
            (-g, 0.0, 1.0),
        ]
        .iter()
        .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
        .collect();
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            // Shared edges get one midpoint, so the mesh stays watertight.
            let mut midpoints = std::collections::HashMap::new();
            let mut mid = |a: u32, b: u32, positions: &mut Vec<DVec3>| {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    positions.push((positions[a as usize] + positions[b as usize]).normalize());
                    positions.len() as u32 - 1
                })
            };
            triangles = triangles
                .iter()
                .flat_map(|&[a, b, c]| {
                    let (ab, bc, ca) = (
                        mid(a, b, &mut positions),
                        mid(b, c, &mut positions),
                        mid(c, a, &mut positions),
                    );
                    [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
                })
                .collect();
        }
        let normals = if smooth { positions.clone() } else { vec![] };
        Mesh::new(positions, normals, triangles).0
    }

    /// Loads a Wavefront OBJ file (all its objects, triangulated); `smooth` keeps its vertex
    /// normals. The file and its triangles are budgeted before they are read and built; the
    /// second value is the number of degenerate (zero-area) triangles dropped.
    pub fn load_obj(
        path: &Path,
        smooth: bool,
        budget: &ObjBudget,
    ) -> Result<(Mesh, usize), String> {
        use crate::files::ReadError;
        let shown = path.display();
        let bytes = crate::files::read_bounded(path, budget.max_bytes).map_err(|e| match e {
            ReadError::Directory => format!("{shown}: is a directory, not a mesh file"),
            ReadError::TooLarge { budget: b } => format!(
                "{shown}: larger than the budget of {} for mesh files ({})",
                crate::files::bytes(b),
                budget.raise
            ),
            e => format!("{shown}: {e}"),
        })?;
        // A UTF-8 byte-order mark (as some Windows editors write) is not part of the first line.
        let text = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
        // The parser takes `#` as a comment only at the start of a line; files put them after
        // statements too.
        let text = &*without_comments(text);
        let triangles = face_triangles(text);
        if triangles > budget.max_triangles {
            return Err(format!(
                "{shown}: {triangles} triangles bring the scene over its budget of {} triangles ({})",
                budget.total, budget.raise
            ));
        }
        if let Err(e) = check_obj(text) {
            return Err(format!("{shown}:{}:{}: {}", e.line, e.column, e.message));
        }
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        // Materials come from the scene file, not from the OBJ's `mtllib`.
        let (models, _) = tobj::load_obj_buf(&mut &text[..], &options, |_| {
            Ok((vec![], Default::default()))
        })
        .map_err(|e| format!("{shown}: {e}"))?;
        let (mut positions, mut normals, mut triangles) = (vec![], vec![], vec![]);
        let mut texcoords = vec![];
        for m in models {
            let base = positions.len() as u32;
            let p = &m.mesh.positions;
            positions.extend(p.chunks_exact(3).map(|v| DVec3::new(v[0], v[1], v[2])));
            if smooth && m.mesh.normals.len() == p.len() {
                normals.resize(base as usize, DVec3::ZERO);
                normals.extend(
                    m.mesh
                        .normals
                        .chunks_exact(3)
                        .map(|v| DVec3::new(v[0], v[1], v[2])),
                );
            }
            if m.mesh.texcoords.len() / 2 == p.len() / 3 {
                texcoords.extend(
                    m.mesh
                        .texcoords
                        .chunks_exact(2)
                        .map(|t| DVec2::new(t[0], t[1])),
                );
            }
            triangles.extend(
                m.mesh
                    .indices
                    .chunks_exact(3)
                    .map(|t| [base + t[0], base + t[1], base + t[2]]),
            );
        }
        if triangles.is_empty() {
            return Err(format!("{shown}: the OBJ file has no triangles"));
        }
        // An object of the file without `vn` lines stays flat beside smooth ones: its vertices'
        // normals are zero, and a triangle whose blended normal is zero is shaded by its own
        // (`normal`).
        if !normals.is_empty() {
            normals.resize(positions.len(), DVec3::ZERO);
        }
        let (mesh, dropped) = Mesh::new(positions, normals, triangles);
        Ok((mesh.with_texcoords(texcoords), dropped))
    }
}

/// What an OBJ file may hold: bytes, and triangles (what is left of the scene's budget).
#[derive(Clone, Copy, Debug)]
pub struct ObjBudget {
    /// Largest OBJ file to read, in bytes.
    pub max_bytes: u64,
    /// Most triangles the file may make (what is left of the scene's budget).
    pub max_triangles: u64,
    /// The scene's whole triangle budget (for the message).
    pub total: u64,
    /// How to raise the budgets (for the message).
    pub raise: &'static str,
}

/// A mistake in an OBJ file, at a line and column from 1.
#[derive(Debug, PartialEq)]
struct ObjMistake {
    line: usize,
    column: usize,
    message: String,
}

/// The largest magnitude of an OBJ number: the scene's own bound.
const MAX_OBJ_NUMBER: f64 = super::MAX_MAGNITUDE;

/// Checks what the OBJ parser would refuse without a line, or accept though it is wrong: the
/// numbers of `v`, `vn` and `vt` lines and the vertices and indices of `f` lines. The text is
/// `without_comments`.
fn check_obj(text: &[u8]) -> Result<(), ObjMistake> {
    let lines = || {
        text.split(|&b| b == b'\n')
            .enumerate()
            .map(|(i, line)| (i + 1, line))
    };
    // An index may name an element written later in the file (the parser resolves them once
    // it has read it all); one counted back (negative) names one written before.
    let mut total = [0usize; 3];
    for (_, line) in lines() {
        if let Some(kind) = element_kind(words(line).next().map(|(_, w)| w)) {
            total[kind] += 1;
        }
    }
    let mut so_far = [0usize; 3];
    for (number, line) in lines() {
        let at = |offset: usize, message: String| ObjMistake {
            line: number,
            column: String::from_utf8_lossy(&line[..offset]).chars().count() + 1,
            message,
        };
        if let Err(e) = std::str::from_utf8(line) {
            let message = "not UTF-8 text (save the file as UTF-8)".to_string();
            return Err(at(e.valid_up_to(), message));
        }
        let mut ws = words(line);
        let Some((_, keyword)) = ws.next() else {
            continue;
        };
        if let Some(kind) = element_kind(Some(keyword)) {
            so_far[kind] += 1;
            let needs = [3, 2, 3][kind];
            let mut count = 0;
            for (offset, word) in ws {
                check_obj_number(word).map_err(|m| at(offset, m))?;
                count += 1;
            }
            if count < needs {
                return Err(at(
                    0,
                    format!(
                        "a `{}` line needs {needs} numbers, this one has {count}",
                        String::from_utf8_lossy(keyword)
                    ),
                ));
            }
        } else if keyword == b"f" {
            let corners = words(line).count() - 1;
            if corners < 3 {
                return Err(at(
                    0,
                    format!("a face needs at least 3 vertices, this one has {corners}"),
                ));
            }
            for (offset, word) in ws {
                let mut part_offset = offset;
                for (kind, part) in word.split(|&b| b == b'/').enumerate() {
                    if kind < 3 && !(part.is_empty() && kind > 0) {
                        check_obj_index(part, kind, so_far[kind], total[kind])
                            .map_err(|m| at(part_offset, m))?;
                    }
                    part_offset += part.len() + 1;
                }
            }
        }
    }
    Ok(())
}

/// The text with every comment (from `#` to the end of its line) taken out; borrowed where it
/// has none.
fn without_comments(text: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    if !text.contains(&b'#') {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut kept = Vec::with_capacity(text.len());
    for (i, line) in text.split(|&b| b == b'\n').enumerate() {
        if i > 0 {
            kept.push(b'\n');
        }
        let end = line.iter().position(|&b| b == b'#').unwrap_or(line.len());
        kept.extend_from_slice(&line[..end]);
    }
    std::borrow::Cow::Owned(kept)
}

/// The words of a line with their byte offsets.
fn words(line: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    let mut offset = 0;
    line.split(|b| b.is_ascii_whitespace())
        .filter_map(move |w| {
            let at = offset;
            offset += w.len() + 1;
            (!w.is_empty()).then_some((at, w))
        })
}

/// 0, 1 and 2 for the keywords of positions, texture coordinates and normals: the elements
/// a face's `v/vt/vn` indices name, in that order.
fn element_kind(keyword: Option<&[u8]>) -> Option<usize> {
    match keyword? {
        b"v" => Some(0),
        b"vt" => Some(1),
        b"vn" => Some(2),
        _ => None,
    }
}

fn check_obj_number(word: &[u8]) -> Result<(), String> {
    let shown = String::from_utf8_lossy(word);
    let x: f64 = std::str::from_utf8(word)
        .ok()
        .and_then(|w| w.parse().ok())
        .ok_or_else(|| format!("`{shown}` is not a number"))?;
    if !x.is_finite() {
        Err(format!(
            "non-finite number `{shown}`: every number in a mesh must be finite"
        ))
    } else if x.abs() > MAX_OBJ_NUMBER {
        Err(format!(
            "number {x:e} is too large: numbers must lie within ±1e100"
        ))
    } else {
        Ok(())
    }
}

fn check_obj_index(word: &[u8], kind: usize, so_far: usize, total: usize) -> Result<(), String> {
    let what = ["vertex", "texture coordinate", "normal"][kind];
    let keyword = ["v", "vt", "vn"][kind];
    let shown = String::from_utf8_lossy(word);
    let i: i64 = std::str::from_utf8(word)
        .ok()
        .and_then(|w| w.parse().ok())
        .ok_or_else(|| format!("`{shown}` is not a {what} index"))?;
    let (fine, have) = match i {
        0 => (false, total),
        i if i > 0 => (i as u64 <= total as u64, total),
        i => (i.unsigned_abs() <= so_far as u64, so_far),
    };
    if fine {
        return Ok(());
    }
    let lines = match have {
        1 => format!("1 `{keyword}` line"),
        n => format!("{n} `{keyword}` lines"),
    };
    let counted = if i < 0 { " before this one" } else { "" };
    Err(format!(
        "{what} index {i} is out of range: the file has {lines}{counted} (indices count from 1, or back from −1)"
    ))
}

/// The triangles an OBJ file's faces make (a face of n vertices makes n − 2), counted from
/// the text before it is parsed.
fn face_triangles(text: &[u8]) -> u64 {
    text.split(|&b| b == b'\n')
        .filter_map(|line| {
            line.strip_prefix(b"f")
                .filter(|r| r.first().is_some_and(u8::is_ascii_whitespace))
        })
        .map(|rest| {
            let vertices = rest
                .split(u8::is_ascii_whitespace)
                .filter(|w| !w.is_empty())
                .count() as u64;
            vertices.saturating_sub(2)
        })
        .sum()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A budget no test file comes near.
    pub(crate) const BUDGET: ObjBudget = ObjBudget {
        max_bytes: 1 << 20,
        max_triangles: 1000,
        total: 1000,
        raise: "raise it",
    };

    /// Writes `text` to the OBJ file `name` in this test process's own folder.
    pub(crate) fn obj(name: &str, text: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("raytree-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    /// A byte-order mark before the first vertex must not hide it: the triangle keeps its
    /// three corners where the file puts them.
    #[test]
    fn a_byte_order_mark_does_not_lose_the_first_vertex() {
        let text = b"v 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\n";
        let plain = obj("plain.obj", text);
        let marked = obj("bom.obj", &[b"\xEF\xBB\xBF".as_slice(), text].concat());
        let (a, _) = Mesh::load_obj(&plain, false, &BUDGET).unwrap();
        let (b, _) = Mesh::load_obj(&marked, false, &BUDGET).unwrap();
        assert_eq!(b.positions, a.positions);
        assert_eq!(b.positions[0], DVec3::new(5.0, 0.0, 0.0));
        assert_eq!(b.triangles, vec![[0, 1, 2]]);
    }

    /// An OBJ's numbers are read as a scene's are, in double precision: 100 000 000.5 and 0.1
    /// stay what the file says (single precision has a step of 8 at 10⁸ and reads 0.1 as
    /// 0.100000001490116), and 10⁵⁰, beyond single precision's range, is a number like another.
    #[test]
    fn obj_numbers_are_read_in_double_precision() {
        let text = b"v 100000000.5 0.1 0\nv 100000001.5 0.1 0\nv 100000000.5 1e50 0\nvt 0.1 0.3\n\
                     vt 1 0.3\nvt 0.1 1\nf 1/1 2/2 3/3\n";
        let (m, dropped) = Mesh::load_obj(&obj("precise.obj", text), false, &BUDGET).unwrap();
        assert_eq!(dropped, 0);
        assert_eq!(m.positions[0], DVec3::new(100_000_000.5, 0.1, 0.0));
        assert_eq!(m.positions[1].x, 100_000_001.5);
        assert_eq!(m.positions[2].y, 1e50);
        assert_eq!(m.texcoords[0], DVec2::new(0.1, 0.3));
    }

    /// Where the check points, and a piece of what it says.
    fn mistake(text: &str) -> (usize, usize, String) {
        let e = check_obj(&without_comments(text.as_bytes())).unwrap_err();
        (e.line, e.column, e.message)
    }

    #[test]
    fn obj_mistakes_are_found_with_their_line_and_column() {
        let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let (line, column, m) = mistake(&format!("{tri}f 1/5 2/5 3/5\n"));
        assert_eq!((line, column), (4, 5), "{m}");
        assert!(
            m.contains("texture coordinate index 5") && m.contains("0 `vt` lines"),
            "{m}"
        );
        let (line, column, m) = mistake("v 0 0 0\n# a comment\n  v 1 0 abc\n");
        assert_eq!((line, column), (3, 9), "{m}");
        assert!(m.contains("`abc` is not a number"), "{m}");
        let (line, column, m) = mistake("v 1e300 0 0\n");
        assert_eq!((line, column), (1, 3), "{m}");
        assert!(m.contains("±1e100") && !m.contains("finite"), "{m}");
        let (_, _, m) = mistake("v nan 0 0\n");
        assert!(m.contains("non-finite"), "{m}");
        let (line, column, m) = mistake(&format!("{tri}f 1 2 0\n"));
        assert_eq!((line, column), (4, 7), "{m}");
        // Counted back from the face, −4 is before the first of three vertices.
        let (line, column, m) = mistake(&format!("{tri}f -1 -2 -4\n"));
        assert_eq!((line, column), (4, 9), "{m}");
        assert!(m.contains("3 `v` lines before this one"), "{m}");
        let (line, column, m) = mistake(&format!("{tri}vn 0 0 1\nf 1//1 2//2 3//1\n"));
        assert_eq!((line, column), (5, 11), "{m}");
        assert!(
            m.contains("normal index 2") && m.contains("1 `vn` line"),
            "{m}"
        );
        let (line, column, m) = mistake("v 1 2\n");
        assert_eq!((line, column), (1, 1), "{m}");
        assert!(m.contains("needs 3 numbers"), "{m}");
        for (face, corners) in [("f 1 2", 2), ("f 3 # a triangle", 1), ("f", 0)] {
            let (line, column, m) = mistake(&format!("{tri}{face}\n"));
            assert_eq!((line, column), (4, 1), "{m}");
            assert!(
                m.contains(&format!("at least 3 vertices, this one has {corners}")),
                "{m}"
            );
        }
    }

    /// In a file of several objects, one without normals is flat and the others keep theirs.
    #[test]
    fn an_object_without_normals_leaves_the_others_smooth() {
        let smooth = "o A\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 0.6 0 -0.8\n";
        let flat = "o B\nv 5 5 5\nv 6 5 5\nv 5 6 5\n";
        for (name, text) in [
            (
                "smooth-first.obj",
                format!("{smooth}f 1//1 2//1 3//1\n{flat}f 4 5 6\n"),
            ),
            (
                "flat-first.obj",
                format!("{flat}f 1 2 3\n{smooth}f 4//1 5//1 6//1\n"),
            ),
        ] {
            let (m, _) = Mesh::load_obj(&obj(name, text.as_bytes()), true, &BUDGET).unwrap();
            let face_at = |x: f64| {
                (0..m.triangles.len() as u32)
                    .find(|&f| m.triangle(f).a.x == x)
                    .unwrap()
            };
            let (a, b) = (face_at(-1.0), face_at(5.0));
            let at_a = m.normal(DVec3::new(0.0, -0.5, 0.0), a);
            assert_eq!(at_a, DVec3::new(0.6, 0.0, -0.8), "{name}");
            assert_eq!(m.normal(DVec3::new(5.2, 5.2, 5.0), b), DVec3::Z, "{name}");
        }
    }

    /// A comment may follow a statement on its line, as many exporters write them: the
    /// statement is read up to it.
    #[test]
    fn comments_after_statements_are_comments() {
        let text = b"# a triangle\nv 5 0 0 # first\nv 6 0 0\nv 5 1 0#last\nf 1 2 3 # the face\n";
        let (m, dropped) = Mesh::load_obj(&obj("comments.obj", text), false, &BUDGET).unwrap();
        assert_eq!(dropped, 0);
        assert_eq!(m.triangles.len(), 1);
        assert_eq!(
            m.positions,
            [
                DVec3::new(5.0, 0.0, 0.0),
                DVec3::new(6.0, 0.0, 0.0),
                DVec3::new(5.0, 1.0, 0.0)
            ]
        );
    }

    #[test]
    fn well_formed_obj_files_pass_the_check() {
        for text in [
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            // A face may name vertices written after it, and count back from itself.
            "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n",
            "v 0 0 0 1\nv 1 0 0\r\nv 0 1 0 # corner\nvt 0 0\nvt 1 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1\n",
            "v -1e30 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        ] {
            assert_eq!(check_obj(&without_comments(text.as_bytes())), Ok(()), "{text:?}");
        }
    }

    #[test]
    fn faces_are_counted_against_the_triangle_budget_before_parsing() {
        assert_eq!(
            face_triangles(b"f 1 2 3\nf 1 2 3 4\nfoo\n# f 1 2 3\nf\t1 2 3 4 5"),
            6
        );
        let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        text += &"f 1 2 3\n".repeat(1001);
        let e = Mesh::load_obj(&obj("many.obj", text.as_bytes()), false, &BUDGET).unwrap_err();
        assert!(
            e.contains("1001 triangles") && e.contains("budget of 1000"),
            "{e}"
        );
    }

    #[test]
    fn icosphere_is_watertight_through_edges_and_vertices() {
        let mesh = Mesh::icosphere(2, true);
        assert_eq!(mesh.triangles.len(), 320);
        // Aim at every vertex and every edge midpoint from outside, steeply (a ray grazing a
        // silhouette vertex may legitimately only touch it): the ray must enter and leave.
        let mut targets: Vec<DVec3> = mesh.positions.clone();
        for t in &mesh.triangles {
            for k in 0..3 {
                targets.push(
                    0.5 * (mesh.positions[t[k] as usize] + mesh.positions[t[(k + 1) % 3] as usize]),
                );
            }
        }
        for (i, target) in targets.iter().enumerate() {
            let out = target.normalize();
            let side = out
                .cross(if out.y.abs() < 0.9 {
                    DVec3::Y
                } else {
                    DVec3::X
                })
                .normalize();
            let from = 3.0 * out + (0.2 + 0.1 * (i % 5) as f64) * side;
            let ray = Ray::new(from, *target - from);
            let n = mesh.crossings(&ray).len();
            let brute = (0..mesh.triangles.len() as u32)
                .filter(|&k| mesh.triangle(k).intersect(&ray).is_some())
                .count();
            assert!(
                n >= 2,
                "ray {i} at {target} crossed {n} times (brute force {brute}): a leak"
            );
            let (hit, _) = mesh.hit(&ray, 0.0, f64::INFINITY);
            assert!(hit.is_some());
        }
    }

    /// What an icosphere holds, part by part, from Euler's formula: 20·4^k triangles, half as
    /// many vertices plus 2 (V − E + F = 2 with E = 3F/2), a position and a normal (two f64
    /// vectors, 48 bytes) per vertex, three u32 indices per triangle, and the BVH's 32-byte
    /// nodes and item indices; all of it within the 80 bytes per triangle raytree budgets.
    #[test]
    fn an_icosphere_holds_its_parts_and_at_most_80_bytes_a_triangle() {
        let k = 5;
        let mesh = Mesh::icosphere(k, true);
        let triangles = 20 * 4usize.pow(k);
        let vertices = triangles / 2 + 2;
        assert_eq!(mesh.triangles.len(), triangles);
        let memory = mesh.memory();
        assert_eq!(memory.vertices, vertices * 48);
        assert_eq!(memory.triangles, triangles * 12);
        assert_eq!(memory.bvh, mesh.bvh.node_count() * 32 + triangles * 4);
        let per_triangle = memory.total() as f64 / triangles as f64;
        assert!(per_triangle <= 80.0, "{per_triangle} bytes a triangle");
    }
}
