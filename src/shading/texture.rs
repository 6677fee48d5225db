//! Image textures: a picture wrapped onto a surface. A mapping gives every point of the surface
//! its (u, v) in the unit square (`crate::geometry::uv`); the image is read there with bilinear
//! filtering, in linear intensities (an 8- or 16-bit image's sRGB values are decoded when it is
//! loaded, so texture colours enter the lecture's formulas as any other colour does).

use std::fmt;
use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use serde::Deserialize;

use super::pattern::PatternPoint;
use crate::geometry::floor::floor;
use crate::geometry::uv::{cube, cylindrical, planar, spherical, wrap, CubeFace, Edges};

/// How a point of a surface gets its (u, v).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mapping {
    /// Projected from the point in the pattern's space, round its origin.
    Spherical,
    /// Projected onto its xz plane, in unit tiles.
    Planar,
    /// Projected round its y axis, one unit of height per image.
    Cylindrical,
    /// Projected onto the cube [−1, 1]³, the faces unfolded into a cross.
    Cube,
    /// The surface's own (u, v) (`Shape::uv`: a mesh's `vt`), placed by the pattern's
    /// transform.
    #[default]
    Uv,
}

impl Mapping {
    /// (u, v) of a point already in the pattern's space.
    pub fn uv(self, at: &PatternPoint) -> DVec2 {
        match self {
            Mapping::Spherical => spherical(at.point),
            Mapping::Planar => planar(at.point),
            Mapping::Cylindrical => cylindrical(at.point),
            Mapping::Cube => cube(at.point),
            Mapping::Uv => at.uv,
        }
    }

    /// Which of its coordinates end at an image's edges: v from pole to pole (spherical) and
    /// across the cube's cross; none of the planar and cylindrical projections' (one image per
    /// unit tile or unit of height); the surface's own for `uv`.
    pub fn edges(self, at: &PatternPoint) -> Edges {
        match self {
            Mapping::Spherical => Edges::V,
            Mapping::Cube => Edges::cell(CubeFace::of(at.point)),
            Mapping::Planar | Mapping::Cylindrical => Edges::NONE,
            Mapping::Uv => at.edges,
        }
    }

    /// The mapping as a scene file writes it: `spherical`, `planar`, `cylindrical`, `cube` or
    /// `uv`.
    pub fn name(self) -> &'static str {
        match self {
            Mapping::Spherical => "spherical",
            Mapping::Planar => "planar",
            Mapping::Cylindrical => "cylindrical",
            Mapping::Cube => "cube",
            Mapping::Uv => "uv",
        }
    }
}

/// A picture in linear RGB, row 0 at the top.
pub struct Image {
    /// The file as the scene names it.
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    texels: Vec<[f32; 3]>,
}

impl fmt::Debug for Image {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Image({}, {}×{})", self.name, self.width, self.height)
    }
}

impl PartialEq for Image {
    fn eq(&self, other: &Image) -> bool {
        self.name == other.name && self.width == other.width && self.texels == other.texels
    }
}

/// sRGB-encoded value in [0, 1] to linear intensity (the sRGB standard's curve).
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// An image texture not loaded. The message names the file as the scene wrote it.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file cannot be opened or read.
    #[error("cannot read `{name}`: {source}")]
    Read {
        /// The file as the scene wrote it.
        name: String,
        /// The file's path.
        path: PathBuf,
        /// The system's reason.
        source: std::io::Error,
    },
    /// The path names a folder, a device, a pipe or a socket.
    #[error("cannot read `{name}`: not a regular file")]
    NotRegular {
        /// The file as the scene wrote it.
        name: String,
        /// The file's path.
        path: PathBuf,
    },
    /// The file is not a PNG or EXR image that decodes.
    #[error("cannot read `{name}`: {}", decode_reason(.source))]
    Decode {
        /// The file as the scene wrote it.
        name: String,
        /// The file's path.
        path: PathBuf,
        /// The decoder's reason.
        source: image::ImageError,
    },
    /// The image has no pixels.
    #[error("cannot read `{name}`: the image is empty")]
    Empty {
        /// The file as the scene wrote it.
        name: String,
        /// The file's path.
        path: PathBuf,
    },
    /// A texel of a floating-point image is infinite or NaN: no colour.
    #[error(
        "`{name}`: the texel at column {x}, row {y} (from the top left) is {value}, not a colour"
    )]
    NotFinite {
        /// The file as the scene wrote it.
        name: String,
        /// The file's path.
        path: PathBuf,
        /// Its column.
        x: u32,
        /// Its row.
        y: u32,
        /// The channel's value: inf, -inf or NaN.
        value: f32,
    },
}

/// Why an image file does not decode, in words: a file of another kind is named as such (the
/// decoder's own words quote its extension oddly).
pub fn decode_reason(e: &image::ImageError) -> String {
    match e {
        image::ImageError::Unsupported(_) => {
            "not an image raytree reads: give a PNG or an EXR file".into()
        }
        e => e.to_string(),
    }
}

impl Image {
    /// An image from linear texels, row by row from the top.
    pub fn new(name: &str, width: u32, height: u32, texels: Vec<[f32; 3]>) -> Image {
        assert_eq!(texels.len(), width as usize * height as usize);
        assert!(width > 0 && height > 0);
        Image {
            name: name.into(),
            width,
            height,
            texels,
        }
    }

    /// Reads a PNG (sRGB values, decoded to linear) or an EXR (linear already). `name` is the
    /// file as the scene wrote it.
    pub fn load(path: &Path, name: &str) -> Result<Image, TextureError> {
        let read = |source| TextureError::Read {
            name: name.into(),
            path: path.to_path_buf(),
            source,
        };
        let meta = std::fs::metadata(path).map_err(read)?;
        if !meta.is_file() {
            return Err(TextureError::NotRegular {
                name: name.into(),
                path: path.to_path_buf(),
            });
        }
        let decoded = image::ImageReader::open(path)
            .and_then(|r| r.with_guessed_format())
            .map_err(read)?
            .decode()
            .map_err(|source| TextureError::Decode {
                name: name.into(),
                path: path.to_path_buf(),
                source,
            })?;
        let linear = matches!(
            decoded,
            image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
        );
        let (width, height) = (decoded.width(), decoded.height());
        if width == 0 || height == 0 {
            return Err(TextureError::Empty {
                name: name.into(),
                path: path.to_path_buf(),
            });
        }
        let texels = if linear {
            decoded
                .to_rgb32f()
                .enumerate_pixels()
                .map(|(x, y, p)| match p.0.into_iter().find(|c| !c.is_finite()) {
                    Some(value) => Err(TextureError::NotFinite {
                        name: name.into(),
                        path: path.to_path_buf(),
                        x,
                        y,
                        value,
                    }),
                    // A filtered image's ringing can dip below zero: no light is less than none.
                    None => Ok(p.0.map(|c| c.max(0.0))),
                })
                .collect::<Result<_, _>>()?
        } else if let image::DynamicImage::ImageRgb8(_)
        | image::DynamicImage::ImageRgba8(_)
        | image::DynamicImage::ImageLuma8(_)
        | image::DynamicImage::ImageLumaA8(_) = decoded
        {
            let table: Vec<f32> = (0..256)
                .map(|i| srgb_to_linear(i as f64 / 255.0) as f32)
                .collect();
            decoded
                .to_rgb8()
                .pixels()
                .map(|p| p.0.map(|c| table[c as usize]))
                .collect()
        } else {
            decoded
                .to_rgb16()
                .pixels()
                .map(|p| p.0.map(|c| srgb_to_linear(c as f64 / 65535.0) as f32))
                .collect()
        };
        Ok(Image::new(name, width, height, texels))
    }

    /// The brightest value of each channel.
    pub fn max(&self) -> DVec3 {
        self.texels.iter().fold(DVec3::ZERO, |m, t| {
            m.max(DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64))
        })
    }

    /// The column and row of the texel at column i, row j of the grid the image repeats in:
    /// wrapped round the image, or, across an edge where the coordinate ends (`edges`), the
    /// edge's own column or row; on a face of the cube cross, the nearest texel of the face's
    /// cell.
    pub fn texel_at(&self, i: i64, j: i64, edges: Edges) -> (usize, usize) {
        if let Some(face) = edges.cell {
            // The cell's texels: those whose centres lie within its quarter of the width and
            // third of the height (column `col` from the left, row `row` from the bottom).
            let (col, row) = face.cell();
            let span = |from: f64, to: f64, n: u32| {
                let first = (from * n as f64 - 0.5).ceil().max(0.0) as i64;
                let last = ((to * n as f64 - 0.5).floor() as i64).min(n as i64 - 1);
                (first, last.max(first))
            };
            let (i0, i1) = span(col / 4.0, (col + 1.0) / 4.0, self.width);
            let (j0, j1) = span((2.0 - row) / 3.0, (3.0 - row) / 3.0, self.height);
            return (i.clamp(i0, i1) as usize, j.clamp(j0, j1) as usize);
        }
        let place = |k: i64, n: u32, ends: bool| {
            if ends {
                k.clamp(0, n as i64 - 1) as usize
            } else {
                k.rem_euclid(n as i64) as usize
            }
        };
        (
            place(i, self.width, edges.u),
            place(j, self.height, edges.v),
        )
    }

    /// The texel in column i, row j (`texel_at`).
    pub fn texel(&self, i: i64, j: i64, edges: Edges) -> DVec3 {
        let (i, j) = self.texel_at(i, j, edges);
        let [r, g, b] = self.texels[j * self.width as usize + i];
        DVec3::new(r as f64, g as f64, b as f64)
    }

    /// Where (u, v) falls among the texel centres: texel (i, j) is centred at
    /// ((i + ½)/width, 1 − (j + ½)/height), so (u, v) lies at column x = u·width − ½ and row
    /// y = (1 − v)·height − ½ of the grid of centres, between columns ⌊x⌋, ⌊x⌋ + 1 and rows ⌊y⌋,
    /// ⌊y⌋ + 1. The image repeats beyond the unit square, in u and in v; a coordinate that ends
    /// at the image's edges (`edges`) reads 1 at the far edge (a pole's v = 1 is the top row's,
    /// not the bottom's of the next copy).
    pub fn footprint(&self, uv: DVec2, edges: Edges) -> Footprint {
        let within = |x: f64, ends: bool| if ends && x == 1.0 { 1.0 } else { wrap(x) };
        let x = within(uv.x, edges.u) * self.width as f64 - 0.5;
        let y = (1.0 - within(uv.y, edges.v)) * self.height as f64 - 0.5;
        let (x0, y0) = (floor(x), floor(y));
        Footprint {
            x,
            y,
            i: x0 as i64,
            j: y0 as i64,
            fx: x - x0,
            fy: y - y0,
        }
    }

    /// The colour at (u, v), bilinearly filtered: the four texels around it blended by its
    /// distances to their centres, first along the rows, then between them. Across an edge
    /// where a coordinate ends (`edges`) the texels are the edge's own: a sphere's poles take
    /// the top and bottom rows, not a blend of both.
    pub fn bilinear(&self, uv: DVec2, edges: Edges) -> DVec3 {
        let f = self.footprint(uv, edges);
        let t = |di: i64, dj: i64| self.texel(f.i + di, f.j + dj, edges);
        let top = t(0, 0).lerp(t(1, 0), f.fx);
        let bottom = t(0, 1).lerp(t(1, 1), f.fx);
        top.lerp(bottom, f.fy)
    }
}

/// Where a point falls among an image's texel centres (`Image::footprint`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Column in the grid of texel centres (0 at the first centre): u·width − ½, u wrapped into
    /// [0, 1).
    pub x: f64,
    /// Row in the grid of texel centres (0 at the first centre, at the top): (1 − v)·height − ½,
    /// v wrapped into [0, 1).
    pub y: f64,
    /// Column of the texel at the top left of the four around the point, ⌊x⌋.
    pub i: i64,
    /// Row of that texel, ⌊y⌋.
    pub j: i64,
    /// How far right of that texel's centre, in texels: x − i, in [0, 1).
    pub fx: f64,
    /// How far below that texel's centre, in texels: y − j, in [0, 1).
    pub fy: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2×2 image: red, green on top; blue, white below.
    fn quad() -> Image {
        Image::new(
            "quad",
            2,
            2,
            vec![
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 1.0, 1.0],
            ],
        )
    }

    /// At a texel's centre the filter gives that texel; halfway between two centres, their
    /// mean.
    #[test]
    fn bilinear_filtering_hits_texel_centres_and_blends_between() {
        let img = quad();
        let at = |u, v| img.bilinear(DVec2::new(u, v), Edges::NONE);
        assert_eq!(at(0.25, 0.75), DVec3::X);
        assert_eq!(at(0.75, 0.75), DVec3::Y);
        assert_eq!(at(0.25, 0.25), DVec3::Z);
        assert_eq!(at(0.75, 0.25), DVec3::ONE);
        assert_eq!(at(0.5, 0.75), DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(at(0.5, 0.5), DVec3::new(0.5, 0.5, 0.5));
    }

    /// At the seam u = 0 the left column meets the right one: the image wraps round.
    #[test]
    fn the_seam_blends_the_first_and_last_columns() {
        let img = quad();
        let at = |u, v| img.bilinear(DVec2::new(u, v), Edges::V);
        assert_eq!(at(0.0, 0.75), DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(at(1.0, 0.75), at(0.0, 0.75));
    }

    /// Where v ends at the image's edges (a sphere from pole to pole) the top row is not
    /// blended with the bottom one: at v = 1 (the north pole) and within half a texel of it
    /// the filter reads the top row alone, at v = 0 the bottom row, where a repeating image
    /// blends the two half and half (v = 1 as v = 0, between the last row and the next copy's
    /// first).
    #[test]
    fn an_image_does_not_wrap_round_an_edge_where_v_ends() {
        let img = quad();
        let (ends, repeats) = (Edges::V, Edges::NONE);
        let mid_top = (DVec3::X + DVec3::Y) / 2.0;
        let mid_bottom = (DVec3::Z + DVec3::ONE) / 2.0;
        assert_eq!(img.bilinear(DVec2::new(0.5, 1.0), ends), mid_top);
        assert_eq!(img.bilinear(DVec2::new(0.5, 0.9), ends), mid_top);
        assert_eq!(img.bilinear(DVec2::new(0.5, 0.0), ends), mid_bottom);
        assert_eq!(img.bilinear(DVec2::new(0.5, 0.1), ends), mid_bottom);
        let half = (mid_top + mid_bottom) / 2.0;
        assert_eq!(img.bilinear(DVec2::new(0.5, 1.0), repeats), half);
        assert_eq!(img.bilinear(DVec2::new(0.5, 0.0), repeats), half);
        // Between the rows' centres both blend the same.
        let inside = DVec2::new(0.5, 0.5);
        assert_eq!(img.bilinear(inside, ends), img.bilinear(inside, repeats));
    }

    /// A cube cross of 2 × 2 texels a face, only the up face painted (red) and every other
    /// cell black: at the up face's left and right edges, and at its top, the filter reads the
    /// up face's own texels alone, never the blank cells beside it in the cross (which the
    /// cube's left, right and back faces are not), so the face stays red to its edges. The
    /// front face, whose cell lies below, keeps its own black up to its top edge: each face
    /// is filtered within its cell, as a cube map without seamless filtering is.
    #[test]
    fn a_cube_faces_filter_reads_its_own_cell_only() {
        let red = [1.0, 0.0, 0.0];
        let mut texels = vec![[0.0; 3]; 8 * 6];
        // The up face's cell: column 1 of 4, the top row of 3 (texels 2–3, rows 0–1).
        for (j, i) in [(0, 2), (0, 3), (1, 2), (1, 3)] {
            texels[j * 8 + i] = red;
        }
        let img = Image::new("cross", 8, 6, texels);
        let at = |p: DVec3| {
            let at = PatternPoint::at(p);
            img.bilinear(Mapping::Cube.uv(&at), Mapping::Cube.edges(&at))
        };
        for p in [
            DVec3::new(-0.999, 1.0, 0.0),
            DVec3::new(0.999, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.999),
            DVec3::new(-0.999, 1.0, 0.999),
        ] {
            assert_eq!(at(p), DVec3::X, "up face at {p}");
        }
        assert_eq!(at(DVec3::new(0.0, 0.999, 1.0)), DVec3::ZERO);
        // Without the cell's edges the up face's left edge would blend in the blank cell.
        let uv = Mapping::Cube.uv(&PatternPoint::at(DVec3::new(-0.999, 1.0, 0.0)));
        assert!(img.bilinear(uv, Edges::V).x < 0.6);
    }

    /// The sRGB curve: 0 and 1 stay, mid grey 0.5 (128/255 stored) is 0.2158 of full
    /// intensity, and the linear toe below 0.04045 is c/12.92.
    #[test]
    fn srgb_values_are_decoded_to_linear() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-15);
        assert!((srgb_to_linear(128.0 / 255.0) - 0.215861).abs() < 1e-6);
        assert!((srgb_to_linear(0.04) - 0.04 / 12.92).abs() < 1e-15);
    }
}
