//! Figures: x-y line plots ([`XyPlot`]) and particle scatter plots coloured by a field
//! ([`ParticlePlot`]), written as PNG or SVG (chosen by the file extension).
//!
//! Text is drawn with the DejaVu Sans font embedded in the binary (`host/assets/DejaVuSans.ttf`,
//! licence alongside), registered with plotters by [`init_fonts`], so no system font is needed.
//!
//! Files: [`xy`] (x-y plots), [`particles`] (particle plots), [`fields`] (field values, derived
//! fields and units), [`colormap`] (viridis), `axis` (tick placement and labels).

mod axis;
pub mod colormap;
pub mod fields;
pub mod particles;
pub mod runs;
pub mod xy;

#[cfg(test)]
mod tests;

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

pub use self::colormap::viridis;
pub(crate) use self::fields::particle_spacing;
pub use self::fields::{field_label, field_unit, field_values, known_fields, DERIVED_FIELDS};
pub use self::particles::ParticlePlot;
pub use self::xy::{Series, SeriesStyle, XyPlot};

/// The font family name every plot uses (registered by [`init_fonts`]).
pub(crate) const FONT: &str = "sans-serif";

/// The embedded font.
static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Why a plot could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum PlotError {
    /// The path's extension is neither `.png` nor `.svg`.
    UnsupportedFormat(PathBuf),
    /// The field is neither a float column nor a derived field.
    UnknownField {
        /// The requested name.
        field: String,
        /// The names that would have been accepted.
        known: Vec<String>,
    },
    /// The axis indices are not two distinct values in 0..3.
    InvalidAxes(usize, usize),
    /// There is nothing to plot (for example an empty particle table).
    NoData(String),
    /// The embedded font could not be registered.
    Font,
    /// Drawing or writing the file failed.
    Draw(String),
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnsupportedFormat(p) => {
                write!(f, "cannot plot to {}: use a .png or .svg file", p.display())
            }
            Self::UnknownField { field, known } => {
                write!(f, "unknown field `{field}`; known: {}", known.join(", "))
            }
            Self::InvalidAxes(a, b) => {
                write!(
                    f,
                    "invalid plot axes ({a}, {b}): need two distinct of 0, 1, 2"
                )
            }
            Self::NoData(what) => write!(f, "nothing to plot: {what}"),
            Self::Font => write!(f, "the embedded plot font could not be registered"),
            Self::Draw(msg) => write!(f, "plotting failed: {msg}"),
        }
    }
}

impl std::error::Error for PlotError {}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for PlotError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        Self::Draw(e.to_string())
    }
}

/// Whether registering the embedded font succeeded (set once by [`init_fonts`]).
static FONT_OK: OnceLock<bool> = OnceLock::new();

/// Registers the embedded DejaVu Sans as the `sans-serif` family (all styles fall back to it).
///
/// Idempotent and thread-safe; every plot function calls it, so calling it yourself is only
/// needed to use the font in your own plotters code.
pub fn init_fonts() {
    FONT_OK.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, DEJAVU_SANS).is_ok()
    });
}

/// [`init_fonts`], then an error if the font could not be registered.
fn ensure_fonts() -> Result<(), PlotError> {
    init_fonts();
    if FONT_OK.get() == Some(&true) {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// Something that draws itself onto a drawing area of any backend.
pub(crate) trait Draw {
    /// Draws onto `root` (already filled white).
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
    where
        DB::ErrorType: 'static;
}

/// The output formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Png,
    Svg,
}

fn format_of(path: &Path) -> Result<Format, PlotError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(Format::Png),
        Some("svg") => Ok(Format::Svg),
        _ => Err(PlotError::UnsupportedFormat(path.to_path_buf())),
    }
}

/// Renders `item` into a `size` (width, height) picture at `path`, PNG or SVG by extension.
///
/// The picture is drawn in memory and written atomically ([`crate::output::write_atomic`]:
/// a temp file renamed over `path`), so a failed plot leaves no half-written file and a link
/// at `path` is replaced, never written through.
pub(crate) fn render<T: Draw>(item: &T, path: &Path, size: (u32, u32)) -> Result<(), PlotError> {
    ensure_fonts()?;
    let bytes = match format_of(path)? {
        Format::Png => {
            let (w, h) = size;
            let mut rgb = vec![0u8; w as usize * h as usize * 3];
            {
                let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
                root.fill(&WHITE)?;
                item.draw(&root)?;
                root.present()?;
            }
            let mut png = Vec::new();
            use image::ImageEncoder;
            image::codecs::png::PngEncoder::new(&mut png)
                .write_image(&rgb, w, h, image::ColorType::Rgb8)
                .map_err(|e| PlotError::Draw(e.to_string()))?;
            png
        }
        Format::Svg => {
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
                root.fill(&WHITE)?;
                item.draw(&root)?;
                root.present()?;
            }
            svg.into_bytes()
        }
    };
    crate::output::write_atomic(path, &bytes)
        .map_err(|e| PlotError::Draw(format!("{}: {e}", path.display())))
}

/// A text style of the plot font at `size` pixels.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    (FONT, size).into_font().color(&BLACK)
}

/// Draws `title` centred in the band `area`.
pub(crate) fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    size: f64,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    if title.is_empty() {
        return Ok(());
    }
    let (w, h) = area.dim_in_pixel();
    let style = font(size).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Center,
        plotters::style::text_anchor::VPos::Center,
    ));
    area.draw_text(title, &style, (w as i32 / 2, h as i32 / 2))?;
    Ok(())
}
