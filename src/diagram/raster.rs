//! SVG to PNG through resvg: the same figure as pixels, for slides that take no SVG.

use std::sync::{Arc, OnceLock};

use resvg::usvg;

/// The system's fonts, loaded once.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = usvg::fontdb::Database::new();
            db.load_system_fonts();
            // The generic `sans-serif` (all that plotters' SVG names) means Arial to fontdb:
            // point it at a sans-serif face this system has.
            let families: Vec<String> = db
                .faces()
                .filter_map(|f| f.families.first().map(|(name, _)| name.clone()))
                .collect();
            let chosen = [
                "DejaVu Sans",
                "Liberation Sans",
                "Noto Sans",
                "Arial",
                "Helvetica",
            ]
            .iter()
            .find(|name| families.iter().any(|f| f == *name))
            .map(|name| name.to_string())
            .or_else(|| families.first().cloned());
            if let Some(family) = chosen {
                db.set_sans_serif_family(family);
            }
            Arc::new(db)
        })
        .clone()
}

/// Whether any font was found to draw the labels with.
pub fn have_fonts() -> bool {
    !fonts().is_empty()
}

/// A figure not drawn as pixels.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    /// The SVG document does not parse.
    #[error("bad SVG: {0}")]
    Svg(#[source] usvg::Error),
    /// The document's size gives no image to draw into (zero, or too large).
    #[error("cannot draw a {width} × {height} image")]
    Size {
        /// The width in pixels.
        width: u32,
        /// The height in pixels.
        height: u32,
    },
    /// The pixels cannot be encoded as PNG.
    #[error("cannot encode the PNG: {0}")]
    Encode(#[source] Box<dyn std::error::Error + Send + Sync>),
}

fn pixmap(svg: &str) -> Result<resvg::tiny_skia::Pixmap, RasterError> {
    let options = usvg::Options {
        fontdb: fonts(),
        ..Default::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(RasterError::Svg)?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or(RasterError::Size {
            width: size.width(),
            height: size.height(),
        })?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap)
}

/// The RGBA pixels of an SVG document at its own size: (width, height, pixels row by row).
/// The figures are opaque (a white background), so premultiplied alpha changes nothing.
pub fn rasterize(svg: &str) -> Result<(u32, u32, Vec<u8>), RasterError> {
    let p = pixmap(svg)?;
    Ok((p.width(), p.height(), p.take()))
}

/// The SVG document as PNG bytes.
pub fn png(svg: &str) -> Result<Vec<u8>, RasterError> {
    pixmap(svg)?
        .encode_png()
        .map_err(|e| RasterError::Encode(e.into()))
}
