//! Meshes kept from one compilation of a scene to the next. The explorer compiles a scene again
//! every time its file changes; a teacher moving the camera or a light has not changed the mesh
//! the scene holds. A mesh whose source is unchanged (the same OBJ file with the same length
//! and modification time, read under the same budget, or the same icosphere) is taken as it
//! was built, its BVH included, instead of being read and built again.
//!
//! The cache holds weak references: a mesh lives as long as some scene uses it (the explorer
//! keeps the last good scene on screen while the new one compiles), and not a moment longer.

use std::convert::Infallible;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};
use std::time::SystemTime;

use crate::geometry::{Mesh, ObjBudget};

/// What a mesh is built from: equal sources build equal meshes.
#[derive(Clone, Debug, PartialEq)]
enum Source {
    Obj {
        path: PathBuf,
        len: u64,
        modified: SystemTime,
        smooth: bool,
        /// The budget decides whether the file is refused: a cached mesh stands for the
        /// loader's answer under the same budget only.
        max_bytes: u64,
        max_triangles: u64,
    },
    Icosphere {
        subdivisions: u32,
        smooth: bool,
    },
}

/// A built mesh and the number of degenerate triangles left out of it.
struct Entry {
    source: Source,
    mesh: Weak<Mesh>,
    dropped: usize,
}

static CACHE: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The mesh of an OBJ file, read and built by `Mesh::load_obj` unless a scene still holds the
/// mesh of the same unchanged file. Also the number of degenerate triangles dropped.
pub(super) fn obj(
    path: &Path,
    smooth: bool,
    budget: &ObjBudget,
) -> Result<(Arc<Mesh>, usize), String> {
    // A file whose metadata cannot be read is not cached: the loader reports why.
    let source = std::fs::metadata(path).ok().and_then(|meta| {
        Some(Source::Obj {
            path: std::fs::canonicalize(path).ok()?,
            len: meta.len(),
            modified: meta.modified().ok()?,
            smooth,
            max_bytes: budget.max_bytes,
            max_triangles: budget.max_triangles,
        })
    });
    cached(source, || Mesh::load_obj(path, smooth, budget))
}

/// The icosphere of 20·4^k triangles, with or without its smooth normals.
pub(super) fn icosphere(subdivisions: u32, smooth: bool) -> Arc<Mesh> {
    let source = Source::Icosphere {
        subdivisions,
        smooth,
    };
    let Ok((mesh, _)) = cached(Some(source), || {
        Ok::<_, Infallible>((Mesh::icosphere(subdivisions, smooth), 0))
    });
    mesh
}

/// The live mesh built from `source`, or `build`'s, remembered for the next compilation.
fn cached<E>(
    source: Option<Source>,
    build: impl FnOnce() -> Result<(Mesh, usize), E>,
) -> Result<(Arc<Mesh>, usize), E> {
    let Some(source) = source else {
        return build().map(|(mesh, dropped)| (Arc::new(mesh), dropped));
    };
    if let Some(hit) = lookup(&source) {
        return Ok(hit);
    }
    // Built outside the lock: another scene may compile meanwhile (tests do, in parallel).
    let (mesh, dropped) = build()?;
    let mesh = Arc::new(mesh);
    let mut cache = CACHE.lock().unwrap_or_else(|p| p.into_inner());
    cache.retain(|e| e.mesh.strong_count() > 0 && e.source != source);
    cache.push(Entry {
        source,
        mesh: Arc::downgrade(&mesh),
        dropped,
    });
    Ok((mesh, dropped))
}

fn lookup(source: &Source) -> Option<(Arc<Mesh>, usize)> {
    let cache = CACHE.lock().unwrap_or_else(|p| p.into_inner());
    cache
        .iter()
        .filter(|e| &e.source == source)
        .find_map(|e| Some((e.mesh.upgrade()?, e.dropped)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh_tests::{obj as write_obj, BUDGET};

    #[test]
    fn an_unchanged_file_gives_the_mesh_a_scene_still_holds() {
        let path = write_obj("cached.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let (first, _) = obj(&path, true, &BUDGET).unwrap();
        let (again, _) = obj(&path, true, &BUDGET).unwrap();
        assert!(Arc::ptr_eq(&first, &again), "the same file built twice");

        // Another budget, or flat shading, is another mesh (the loader decides for it).
        let tight = ObjBudget {
            max_triangles: 1,
            ..BUDGET
        };
        assert!(!Arc::ptr_eq(&first, &obj(&path, true, &tight).unwrap().0));
        assert!(!Arc::ptr_eq(&first, &obj(&path, false, &BUDGET).unwrap().0));

        // A changed file (another length) is read again.
        write_obj(
            "cached.obj",
            b"v 0 0 0\nv 2 0 0\nv 0 2 0\nv 2 2 0\nf 1 2 3\nf 2 4 3\n",
        );
        let (changed, _) = obj(&path, true, &BUDGET).unwrap();
        assert_eq!(changed.triangles.len(), 2);

        // No scene holds the mesh any more: it is gone, and built again when asked for.
        let weak = Arc::downgrade(&changed);
        drop(changed);
        assert!(weak.upgrade().is_none(), "the cache kept a mesh alive");
        assert_eq!(obj(&path, true, &BUDGET).unwrap().0.triangles.len(), 2);
    }

    #[test]
    fn a_refused_file_is_refused_again() {
        let path = write_obj(
            "refused.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n",
        );
        let tight = ObjBudget {
            max_triangles: 1,
            ..BUDGET
        };
        let (_held, _) = obj(&path, true, &BUDGET).unwrap();
        assert!(obj(&path, true, &tight).is_err());
        assert!(obj(&path, true, &tight).is_err());
    }

    #[test]
    fn icospheres_are_shared_while_held() {
        let smooth = icosphere(2, true);
        assert!(Arc::ptr_eq(&smooth, &icosphere(2, true)));
        let flat = icosphere(2, false);
        assert!(!Arc::ptr_eq(&smooth, &flat));
        assert!(flat.normals.is_empty() && !smooth.normals.is_empty());
        assert_eq!(flat.triangles, smooth.triangles);
    }
}
