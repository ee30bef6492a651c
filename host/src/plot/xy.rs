//! x-y plots: several named series (lines, markers or dashed reference curves) on linear or
//! logarithmic axes, with a legend and optional ringed highlight points.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axis::Axis;
use super::{draw_title, font, render, Draw, PlotError};

/// Size of a saved x-y plot in pixels.
pub const XY_SIZE: (u32, u32) = (1000, 700);

/// Series colours, in order (Tableau 10, distinguishable by most colour-blind readers).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
];

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    /// A solid line through the points.
    #[default]
    Line,
    /// A filled circle at each point.
    Markers,
    /// A solid line with a filled circle at each point.
    LineMarkers,
    /// A dashed line, for analytic or reference curves.
    Dashed,
}

/// One named set of points.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend text (no legend entry when empty).
    pub name: String,
    /// The points (x, y), in drawing order; unplottable points break the line.
    pub points: Vec<(f64, f64)>,
    /// How the points are drawn.
    pub style: SeriesStyle,
}

/// An x-y plot, saved as a 1000x700 PNG or SVG by [`XyPlot::save`].
///
/// Axis ranges come from the data (with a small margin; whole decades on log axes). Non-finite
/// values are ignored, and so are non-positive values on a log axis.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct XyPlot {
    /// Title above the plot (none when empty).
    pub title: String,
    /// x axis label, with units.
    pub x_label: String,
    /// y axis label, with units.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// The series, coloured in [`PALETTE`] order.
    pub series: Vec<Series>,
    /// Points to mark with a ring (for example a Pareto front).
    pub highlight: Vec<(f64, f64)>,
    /// Legend text for the rings.
    pub highlight_label: Option<String>,
}

impl XyPlot {
    /// Writes the plot to `path`: PNG for `.png`, SVG for `.svg`.
    pub fn save(&self, path: &Path) -> Result<(), PlotError> {
        render(self, path, XY_SIZE)
    }

    /// All points of the series and the highlights.
    fn all_points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .chain(self.highlight.iter().copied())
    }

    /// Draws onto `root`; series `i` takes `colours[i]` where given, else the palette colour, and
    /// `y_range` (data units) replaces the y range from the data.
    pub(crate) fn draw_with<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        colours: &[RGBColor],
        y_range: Option<(f64, f64)>,
    ) -> Result<(), PlotError>
    where
        DB::ErrorType: 'static,
    {
        let x = Axis::from_values(self.all_points().map(|p| p.0), self.log_x);
        let mut y = Axis::from_values(self.all_points().map(|p| p.1), self.log_y);
        if let Some((lo, hi)) = y_range {
            if let (Some(lo), Some(hi)) = (y.map(lo), y.map(hi)) {
                y.set_range(lo, hi);
            }
        }
        let body = if self.title.is_empty() {
            root.clone()
        } else {
            let (band, body) = root.split_vertically(52);
            draw_title(&band, &self.title, 28.0)?;
            body
        };
        let label_font = font(18.0);
        let widest = y
            .labels()
            .iter()
            .filter_map(|l| root.estimate_text_size(l, &label_font).ok())
            .map(|(w, _)| w)
            .max()
            .unwrap_or(0);
        let mut chart = ChartBuilder::on(&body)
            .margin_top(if self.title.is_empty() { 20 } else { 4 })
            .margin_bottom(12)
            .margin_left(12)
            .margin_right(36)
            .x_label_area_size(64)
            .y_label_area_size(widest + 46)
            .build_cartesian_2d(x.clone(), y.clone())?;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(label_font.clone())
            .axis_desc_style(font(21.0))
            .bold_line_style(BLACK.mix(0.14))
            .light_line_style(BLACK.mix(0.05))
            .axis_style(BLACK.stroke_width(1))
            .set_all_tick_mark_size(6)
            .draw()?;

        let map = |&(px, py): &(f64, f64)| Some((x.map(px)?, y.map(py)?));
        let mut labelled = false;
        for (i, s) in self.series.iter().enumerate() {
            let c = colours
                .get(i)
                .copied()
                .unwrap_or(PALETTE[i % PALETTE.len()]);
            let line = c.stroke_width(2);
            let runs = runs(s.points.iter().map(map));
            if matches!(s.style, SeriesStyle::Line | SeriesStyle::LineMarkers) {
                for run in &runs {
                    chart.draw_series(LineSeries::new(run.iter().copied(), line))?;
                }
            }
            if s.style == SeriesStyle::Dashed {
                for run in &runs {
                    chart.draw_series(DashedLineSeries::new(run.iter().copied(), 10, 6, line))?;
                }
            }
            let r = if s.style == SeriesStyle::Markers {
                3
            } else {
                4
            };
            let markers = matches!(s.style, SeriesStyle::Markers | SeriesStyle::LineMarkers);
            if markers {
                let pts = runs
                    .iter()
                    .flatten()
                    .map(|&p| Circle::new(p, r, c.filled()));
                chart.draw_series(pts)?;
            }
            if s.name.is_empty() {
                continue;
            }
            labelled = true;
            let anchor = chart.draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?;
            let anchor = anchor.label(s.name.as_str());
            match s.style {
                SeriesStyle::Line => {
                    anchor.legend(move |(lx, ly)| PathElement::new([(lx, ly), (lx + 24, ly)], line))
                }
                SeriesStyle::Dashed => anchor.legend(move |(lx, ly)| {
                    EmptyElement::at((lx, ly))
                        + PathElement::new([(0, 0), (9, 0)], line)
                        + PathElement::new([(15, 0), (24, 0)], line)
                }),
                SeriesStyle::Markers => {
                    anchor.legend(move |(lx, ly)| Circle::new((lx + 12, ly), r, c.filled()))
                }
                SeriesStyle::LineMarkers => anchor.legend(move |(lx, ly)| {
                    EmptyElement::at((lx, ly))
                        + PathElement::new([(0, 0), (24, 0)], line)
                        + Circle::new((12, 0), r, c.filled())
                }),
            };
        }

        let ring = BLACK.stroke_width(2);
        let rings = self.highlight.iter().filter_map(map);
        let drawn = chart.draw_series(rings.map(|p| Circle::new(p, 8, ring)))?;
        if let Some(label) = &self.highlight_label {
            labelled = true;
            drawn
                .label(label.as_str())
                .legend(move |(lx, ly)| Circle::new((lx + 12, ly), 7, ring));
        }

        if labelled {
            let mapped: Vec<(f64, f64)> = self.all_points().filter_map(|p| map(&p)).collect();
            chart
                .configure_series_labels()
                .position(legend_corner(&mapped, &x, &y))
                .margin(14)
                .legend_area_size(34)
                .label_font(font(18.0))
                .background_style(WHITE.mix(0.9))
                .border_style(BLACK.mix(0.5))
                .draw()?;
        }
        Ok(())
    }
}

impl Draw for XyPlot {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
    where
        DB::ErrorType: 'static,
    {
        self.draw_with(root, &[], None)
    }
}

/// The maximal runs of consecutive plottable (`Some`) points.
fn runs(points: impl Iterator<Item = Option<(f64, f64)>>) -> Vec<Vec<(f64, f64)>> {
    let mut out = vec![Vec::new()];
    for p in points {
        match p {
            Some(p) => out.last_mut().expect("never empty").push(p),
            None if out.last().is_some_and(|r| !r.is_empty()) => out.push(Vec::new()),
            None => {}
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// The plot corner with the fewest points near it (upper right on ties), for the legend.
fn legend_corner(points: &[(f64, f64)], x: &Axis, y: &Axis) -> SeriesLabelPosition {
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let near = |t: f64, axis: &Axis, high: bool| {
        let u = (t - axis.lo) / (axis.hi - axis.lo);
        if high {
            u > 0.55
        } else {
            u < 0.45
        }
    };
    let count = |right: bool, up: bool| {
        points
            .iter()
            .filter(|p| near(p.0, x, right) && near(p.1, y, up))
            .count()
    };
    let best = corners
        .iter()
        .min_by_key(|(_, right, up)| count(*right, *up))
        .expect("four corners");
    best.0.clone()
}
