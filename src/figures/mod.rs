//! Every chart the program draws, as PNG files: the blocks they share (the bundled font,
//! the canvas, the axes frame, the colours, the legend and its keys, error bars) and one
//! module per kind of figure. The figures take plain numbers and tables, so that any
//! command can draw them and none of them reads a command's own types.
//!
//! * [`profiles`]: profiles against z, one panel per quantity (`saltus run`, `compare`,
//!   `calibrate`, `diagnose`);
//! * [`closures`]: closure curves against one swept input (`saltus closure plot`);
//! * [`phases`]: a periodic run's phase averages (`saltus run`);
//! * [`transport`]: qs* against the Shields number with fits and bedload laws
//!   (`saltus sweep`);
//! * [`precision`]: error against cost (`saltus compare` with a `[reference]`);
//! * [`likelihood`]: profile likelihoods of fitted constants (`saltus calibrate`).

use std::path::Path;
use std::sync::OnceLock;

use anyhow::bail;
use plotters::coord::Shift;
use plotters::element::{ErrorBar, ErrorBarOrientV};
use plotters::prelude::*;

pub mod closures;
pub mod likelihood;
pub mod phases;
pub mod precision;
pub mod profiles;
pub mod transport;

/// The drawing area of a figure, or of one of its panels.
pub type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Register the bundled font once (plotters draws text with ab_glyph, no system fonts).
/// Safe to call from several threads; only the first call registers.
pub fn register_font() -> anyhow::Result<()> {
    static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        bail!("bundled font is invalid")
    }
}

/// Line colours, in order.
pub const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// The `i`-th colour of [`COLORS`], round again past the last.
pub fn color(i: usize) -> RGBColor {
    COLORS[i % COLORS.len()]
}

/// A white canvas of `size` pixels that draws into `png`, the font registered.
pub fn canvas(png: &Path, size: (u32, u32)) -> anyhow::Result<Area<'_>> {
    register_font()?;
    let root = BitMapBackend::new(png, size).into_drawing_area();
    root.fill(&WHITE)?;
    Ok(root)
}

/// Most decades a logarithmic axis spans: the axis's key points are counted from the
/// ratio of its ends, which must stay far from overflow.
const MAX_DECADES: i32 = 200;

/// The ends of a logarithmic axis over the values `lo..hi`, widened by `factor` each
/// side, inside the positive normal numbers and at most 200 decades apart
/// (the lower end raised): a value near 1e308 or 1e-308 would otherwise give an infinite
/// or zero end, or a ratio of the ends that overflows, on which the axis's key points
/// never end.
pub fn log_span(lo: f64, hi: f64, factor: f64) -> (f64, f64) {
    let inside = |v: f64| v.clamp(f64::MIN_POSITIVE, f64::MAX / 16.0);
    let (a, b) = (inside(lo / factor), inside(hi * factor));
    let a = a.max(b / 10f64.powi(MAX_DECADES));
    if b > a {
        (a, b)
    } else {
        (a, a * 4.0)
    }
}

/// The ends of a linear axis over `lo..hi`, padded by `pad` of the span each side, with
/// finite ends and a finite span (values beyond +-1e307 are drawn at the frame).
pub fn linear_span(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    const END: f64 = 1e307;
    let (lo, hi) = (lo.clamp(-END, END), hi.clamp(-END, END));
    let width = (hi - lo) * pad;
    (lo - width, hi + width)
}

/// The sizes around a chart's axes: caption font, margin, label areas below and left.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// caption font size
    pub caption: u32,
    /// margin around the chart
    pub margin: u32,
    /// height of the x labels' area
    pub x_area: u32,
    /// width of the y labels' area
    pub y_area: u32,
}

/// The frame of a figure with one chart.
pub const PAGE: Frame = Frame { caption: 22, margin: 15, x_area: 45, y_area: 70 };

/// The frame of one of several panels side by side.
pub const PANEL: Frame = Frame { caption: 18, margin: 12, x_area: 42, y_area: 62 };

impl Frame {
    /// A chart builder on `area` with this frame and `caption` above it.
    pub fn on<'a, 'b>(&self, area: &'a Area<'b>, caption: &str) -> ChartBuilder<'a, 'b, BitMapBackend<'b>> {
        let mut b = ChartBuilder::on(area);
        b.caption(caption, ("sans-serif", self.caption))
            .margin(self.margin)
            .x_label_area_size(self.x_area)
            .y_label_area_size(self.y_area);
        b
    }
}

/// A pixel of the canvas, where legend keys are drawn.
type Pixel = (i32, i32);

/// The legend key of a line: a 20-pixel stroke.
pub fn line_key(color: RGBColor, width: u32) -> impl Fn(Pixel) -> PathElement<Pixel> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(width))
}

/// The legend key of circle symbols of radius `size`.
pub fn circle_key(style: ShapeStyle, size: i32) -> impl Fn(Pixel) -> Circle<Pixel, i32> {
    move |(x, y)| Circle::new((x + 10, y), size, style)
}

/// The legend key of triangle symbols.
pub fn triangle_key(style: ShapeStyle, size: i32) -> impl Fn(Pixel) -> TriangleMarker<Pixel, i32> {
    move |(x, y)| TriangleMarker::new((x + 10, y), size, style)
}

/// The legend key of cross symbols.
pub fn cross_key(style: ShapeStyle, size: i32) -> impl Fn(Pixel) -> Cross<Pixel, i32> {
    move |(x, y)| Cross::new((x + 10, y), size, style)
}

/// Draw the legend of the labelled series of `chart` at `position`, in a framed box that
/// lets the curves behind it show through, with labels of `font` pixels.
pub fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    font: u32,
) -> anyhow::Result<()>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", font))
        .draw()?;
    Ok(())
}

/// Vertical error bars from y - e to y + e at each (x, y, e) with e > 0, cut to the y
/// range `(y0, y1)` of the axis (a log axis has no room for y - e <= 0).
pub fn error_bars(
    bars: impl IntoIterator<Item = (f64, f64, f64)>,
    (y0, y1): (f64, f64),
    style: ShapeStyle,
) -> impl Iterator<Item = ErrorBar<f64, f64, ErrorBarOrientV<f64, f64>>> {
    bars.into_iter()
        .filter(|(x, y, e)| *e > 0.0 && x.is_finite() && y.is_finite() && e.is_finite())
        .map(move |(x, y, e)| ErrorBar::new_vertical(x, (y - e).max(y0), y, (y + e).min(y1), style, 6))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_spans_keep_finite_ordered_ends() {
        for (lo, hi) in [(1e-308, 1e308), (f64::MIN_POSITIVE, f64::MAX), (5e-324, 5e-324), (1.0, 1.0), (0.1, 10.0)] {
            let (a, b) = log_span(lo, hi, 2.0);
            assert!(a.is_normal() && b.is_normal() && 0.0 < a && a < b, "{lo} {hi}: {a} {b}");
            assert!((b / a).log10() <= f64::from(MAX_DECADES) + 1e-9, "{lo} {hi}: {a} {b}");
        }
        assert_eq!(log_span(0.1, 10.0, 2.0), (0.05, 20.0));
        for (lo, hi) in [(-f64::MAX, f64::MAX), (-1e308, 0.0), (0.0, 1.0)] {
            let (a, b) = linear_span(lo, hi, 0.05);
            assert!(a.is_finite() && b.is_finite() && (b - a).is_finite() && a < b, "{lo} {hi}: {a} {b}");
        }
        assert_eq!(linear_span(0.0, 1.0, 0.05), (-0.05, 1.05));
    }
}
