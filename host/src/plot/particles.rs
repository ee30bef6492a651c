//! Particle plots: each particle a filled circle at its position, coloured by a field (viridis)
//! with a colour bar; equal aspect ratio. A 1D table (all y and z zero) is drawn as a profile of
//! the field against x instead.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axis::Axis;
use super::fields::{field_label, field_values, particle_spacing};
use super::xy::{Series, SeriesStyle, XyPlot, PALETTE, XY_SIZE};
use super::{draw_title, font, render, viridis, Draw, PlotError};
use crate::output::ParticleTable;

/// Picture width of a 2D particle plot (its height follows the aspect ratio of the particles).
const WIDTH: u32 = 1000;
/// Height of the title band.
const TITLE_H: u32 = 52;
/// Width of the colour bar column on the right.
const BAR_COLUMN: u32 = 170;
/// Width of the colour bar itself.
const BAR_W: u32 = 28;
/// Chart margins (top, bottom, left, right) and the x label area.
const MARGINS: (u32, u32, u32, u32) = (8, 12, 12, 16);
const X_LABEL_AREA: u32 = 64;
/// Colour of particles whose value is not finite.
const NAN_GREY: RGBColor = RGBColor(0xb0, 0xb0, 0xb0);

/// A plot of the particles of a table coloured by one field, saved by [`ParticlePlot::save`].
///
/// `field` is a float column name (`rho`, `eps_p`, ...) or one of
/// [`DERIVED_FIELDS`](super::DERIVED_FIELDS).
#[derive(Debug, Clone, PartialEq)]
pub struct ParticlePlot<'a> {
    /// The particles.
    pub table: &'a ParticleTable,
    /// The field that colours the particles.
    pub field: &'a str,
    /// Title above the plot (none when empty).
    pub title: String,
    /// Which coordinates go along the horizontal and vertical axes: 0 = x, 1 = y, 2 = z.
    pub axes: (usize, usize),
    /// Colour range (lo, hi); the range of the data when `None`.
    pub range: Option<(f64, f64)>,
    /// Draw the particles of this material in black (for example the projectile).
    pub highlight_material: Option<u32>,
}

impl ParticlePlot<'_> {
    /// Writes the plot to `path`: PNG for `.png`, SVG for `.svg`.
    pub fn save(&self, path: &Path) -> Result<(), PlotError> {
        let values = field_values(self.table, self.field)?;
        if self.table.is_empty() {
            return Err(PlotError::NoData("the particle table is empty".into()));
        }
        let (a, b) = self.axes;
        if a == b || a > 2 || b > 2 {
            return Err(PlotError::InvalidAxes(a, b));
        }
        let t = self.table;
        if t.y.iter().chain(&t.z).all(|&v| v == 0.0) {
            let profile = Profile { plot: self, values };
            return render(&profile, path, XY_SIZE);
        }
        let map = Map::new(self, values);
        let size = (WIDTH, map.height);
        render(&map, path, size)
    }

    /// Coordinate column `k` (0 = x, 1 = y, 2 = z).
    fn coord(&self, k: usize) -> &[f64] {
        match k {
            0 => &self.table.x,
            1 => &self.table.y,
            _ => &self.table.z,
        }
    }

    fn is_highlighted(&self, i: usize) -> bool {
        self.highlight_material == Some(self.table.material[i])
    }

    /// The colour range: the given one, else that of the finite values of the particles that
    /// are not highlighted (all particles if every one is).
    fn colour_range(&self, values: &[f64]) -> (f64, f64) {
        if let Some(r) = self.range {
            return r;
        }
        let pick = |skip_highlighted: bool| {
            let finite = (0..values.len())
                .filter(|&i| !(skip_highlighted && self.is_highlighted(i)))
                .map(|i| values[i])
                .filter(|v| v.is_finite());
            finite.fold(None, |acc: Option<(f64, f64)>, v| {
                Some(acc.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v))))
            })
        };
        pick(true).or_else(|| pick(false)).unwrap_or((0.0, 1.0))
    }
}

/// The 1D profile: the field against x.
struct Profile<'p, 'a> {
    plot: &'p ParticlePlot<'a>,
    values: Vec<f64>,
}

impl Draw for Profile<'_, '_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
    where
        DB::ErrorType: 'static,
    {
        let p = self.plot;
        let pts = |hl: bool| -> Vec<(f64, f64)> {
            (0..self.values.len())
                .filter(|&i| p.is_highlighted(i) == hl)
                .map(|i| (p.table.x[i], self.values[i]))
                .collect()
        };
        let series = |name: String, points| Series {
            name,
            points,
            style: SeriesStyle::Markers,
        };
        let (series, colours) = match p.highlight_material {
            Some(m) => (
                vec![
                    series("other materials".into(), pts(false)),
                    series(format!("material {m}"), pts(true)),
                ],
                vec![PALETTE[0], BLACK],
            ),
            None => (vec![series(String::new(), pts(false))], vec![PALETTE[0]]),
        };
        let xy = XyPlot {
            title: p.title.clone(),
            x_label: "x (m)".into(),
            y_label: field_label(p.field),
            series,
            ..XyPlot::default()
        };
        xy.draw_with(root, &colours, p.range)
    }
}

/// The 2D map: particles as circles, equal aspect, with a colour bar.
struct Map<'p, 'a> {
    plot: &'p ParticlePlot<'a>,
    values: Vec<f64>,
    /// Picture height (pixels).
    height: u32,
    /// Estimated particle spacing (m).
    spacing: f64,
    /// Horizontal and vertical axes before the aspect correction.
    axes: (Axis, Axis),
}

impl<'p, 'a> Map<'p, 'a> {
    fn new(plot: &'p ParticlePlot<'a>, values: Vec<f64>) -> Self {
        let (ca, cb) = (plot.coord(plot.axes.0), plot.coord(plot.axes.1));
        let spacing = particle_spacing(plot.table);
        let bounds = |c: &[f64]| {
            let lo = c
                .iter()
                .copied()
                .filter(|v| v.is_finite())
                .fold(f64::INFINITY, f64::min);
            let hi = c
                .iter()
                .copied()
                .filter(|v| v.is_finite())
                .fold(f64::NEG_INFINITY, f64::max);
            Axis::from_values([lo - spacing, hi + spacing], false)
        };
        let axes = (bounds(ca), bounds(cb));
        let (w, h) = (axes.0.hi - axes.0.lo, axes.1.hi - axes.1.lo);
        let plot_w = f64::from(WIDTH - BAR_COLUMN - MARGINS.2 - MARGINS.3 - 100);
        let plot_h = (plot_w * h / w).clamp(320.0, 1000.0);
        let title_h = if plot.title.is_empty() { 12 } else { TITLE_H };
        let height = title_h + MARGINS.0 + plot_h as u32 + X_LABEL_AREA + MARGINS.1;
        Self {
            plot,
            values,
            height,
            spacing,
            axes,
        }
    }
}

impl Draw for Map<'_, '_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>
    where
        DB::ErrorType: 'static,
    {
        let p = self.plot;
        let body = if p.title.is_empty() {
            root.margin(12, 0, 0, 0)
        } else {
            let (band, body) = root.split_vertically(TITLE_H);
            draw_title(&band, &p.title, 28.0)?;
            body
        };
        let (w, _) = body.dim_in_pixel();
        let (left, right) = body.split_horizontally(w - BAR_COLUMN);
        let label_font = font(18.0);
        let widest = |axis: &Axis| {
            let sizes = axis.labels().into_iter();
            let sizes = sizes.filter_map(|l| root.estimate_text_size(&l, &label_font).ok());
            sizes.map(|(w, _)| w).max().unwrap_or(0)
        };
        let builder = || {
            let mut b = ChartBuilder::on(&left);
            b.margin_top(MARGINS.0)
                .margin_bottom(MARGINS.1)
                .margin_left(MARGINS.2)
                .margin_right(MARGINS.3)
                .x_label_area_size(X_LABEL_AREA)
                .y_label_area_size(widest(&self.axes.1) + 46);
            b
        };
        // Measure the plotting area, then widen one axis so a metre is as long in x as in y.
        let probe = builder().build_cartesian_2d(0f64..1f64, 0f64..1f64)?;
        let (pw, ph) = probe.plotting_area().dim_in_pixel();
        let (mut xa, mut ya) = self.axes.clone();
        let scale = ((xa.hi - xa.lo) / f64::from(pw)).max((ya.hi - ya.lo) / f64::from(ph));
        let (cx, cy) = (0.5 * (xa.lo + xa.hi), 0.5 * (ya.lo + ya.hi));
        xa.set_range(
            cx - 0.5 * scale * f64::from(pw),
            cx + 0.5 * scale * f64::from(pw),
        );
        ya.set_range(
            cy - 0.5 * scale * f64::from(ph),
            cy + 0.5 * scale * f64::from(ph),
        );

        let mut chart = builder().build_cartesian_2d(xa.clone(), ya.clone())?;
        let names = ["x (m)", "y (m)", "z (m)"];
        chart
            .configure_mesh()
            .x_desc(names[p.axes.0])
            .y_desc(names[p.axes.1])
            .label_style(label_font.clone())
            .axis_desc_style(font(21.0))
            .bold_line_style(BLACK.mix(0.1))
            .light_line_style(TRANSPARENT)
            .set_all_tick_mark_size(6)
            .draw()?;

        let (lo, hi) = p.colour_range(&self.values);
        let colour = |i: usize| {
            let v = self.values[i];
            if p.is_highlighted(i) {
                BLACK
            } else if v.is_finite() {
                viridis(if hi > lo { (v - lo) / (hi - lo) } else { 0.5 })
            } else {
                NAN_GREY
            }
        };
        // Low values first, highlighted particles last, so both extremes stay visible.
        let mut order: Vec<usize> = (0..self.values.len()).collect();
        let key = |i: usize| (p.is_highlighted(i), self.values[i]);
        order.sort_by(|&i, &j| {
            let (a, b) = (key(i), key(j));
            a.0.cmp(&b.0).then(a.1.total_cmp(&b.1))
        });
        let radius = (0.6 * self.spacing / scale).round().clamp(1.0, 40.0) as u32;
        let (ca, cb) = (p.coord(p.axes.0), p.coord(p.axes.1));
        let dots = order
            .into_iter()
            .filter(|&i| ca[i].is_finite() && cb[i].is_finite())
            .map(|i| Circle::new((ca[i], cb[i]), radius, colour(i).filled()));
        chart.draw_series(dots)?;
        chart.plotting_area().draw(&Rectangle::new(
            [(xa.lo, ya.lo), (xa.hi, ya.hi)],
            BLACK.stroke_width(1),
        ))?;
        colour_bar(&right, (lo, hi), &field_label(p.field))
    }
}

/// A vertical viridis bar for `lo..hi` with ticks and `label`, aligned with the chart's area.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (lo, hi): (f64, f64),
    label: &str,
) -> Result<(), PlotError>
where
    DB::ErrorType: 'static,
{
    let axis = Axis::exact(lo.min(hi), hi.max(lo), false);
    let tick_font = font(17.0);
    let mut bar = ChartBuilder::on(area)
        .margin_top(MARGINS.0)
        .margin_bottom(MARGINS.1 + X_LABEL_AREA)
        .margin_left(6)
        .margin_right(6)
        .right_y_label_area_size(BAR_COLUMN - 12 - BAR_W)
        .build_cartesian_2d(0f64..1f64, axis.clone())?;
    bar.configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .disable_x_axis()
        .set_tick_mark_size(LabelAreaPosition::Right, 6)
        .label_style(tick_font.clone())
        .draw()?;
    const STEPS: usize = 256;
    let (a, b) = (axis.lo, axis.hi);
    let strips = (0..STEPS).map(|k| {
        let (u0, u1) = (k as f64 / STEPS as f64, (k + 1) as f64 / STEPS as f64);
        let (y0, y1) = (a + u0 * (b - a), a + u1 * (b - a));
        let t = (0.5 * (y0 + y1) - lo) / (hi - lo);
        Rectangle::new([(0.0, y0), (1.0, y1)], viridis(t).filled())
    });
    bar.draw_series(strips)?;
    bar.plotting_area()
        .draw(&Rectangle::new([(0.0, a), (1.0, b)], BLACK.stroke_width(1)))?;
    // The label, reading upwards, right of the tick labels.
    let labels = axis.labels();
    let sizes = labels
        .iter()
        .filter_map(|l| area.estimate_text_size(l, &tick_font).ok());
    let widest = sizes.map(|(w, _)| w).max().unwrap_or(0) as i32;
    let (_, h) = area.dim_in_pixel();
    let x = 6 + BAR_W as i32 + 12 + widest + 26;
    let y = (MARGINS.0 as i32 + h as i32 - (MARGINS.1 + X_LABEL_AREA) as i32) / 2;
    let style = font(21.0)
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Center));
    area.draw_text(label, &style, (x, y))?;
    Ok(())
}
