//! Drawing helpers of `railcontact report`: the one palette (a fixed colour per normal model, used
//! by every figure), the embedded font, rendering a figure to SVG and PNG, a legend strip, a
//! colour map and the small geometric helpers the figures share.
//!
//! Text: plotters' `ab_glyph` font backend with DejaVu Sans compiled into the binary
//! (`assets/fonts/DejaVuSans.ttf`, licence next to it), so PNGs render their text on machines
//! without any system font; SVGs name the family `sans-serif` and leave the glyphs to the viewer.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use railcontact::normal::NormalModel;
use std::path::{Path, PathBuf};

/// Font family every text of the figures uses (registered by [`register_font`]).
pub const FONT: &str = "sans-serif";

/// DejaVu Sans, embedded.
static FONT_DATA: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/fonts/DejaVuSans.ttf"
));

/// Registers the embedded font as [`FONT`] (normal and bold). Call once before drawing.
pub fn register_font() -> Result<(), String> {
    for style in [FontStyle::Normal, FontStyle::Bold] {
        plotters::style::register_font(FONT, style, FONT_DATA)
            .map_err(|_| "the embedded font assets/fonts/DejaVuSans.ttf is not readable")?;
    }
    Ok(())
}

/// Colour of CONTACT's exact solution in every figure.
pub const REFERENCE_COLOUR: RGBColor = RGBColor(0, 0, 0);
/// Colour of auxiliary curves (the raw geometric curvature B).
pub const AUX_COLOUR: RGBColor = RGBColor(140, 140, 140);

/// The palette: one colour per normal model, the same in every figure (Okabe–Ito colours,
/// distinguishable with the common colour-vision deficiencies).
pub const PALETTE: [(NormalModel, RGBColor); 7] = [
    (NormalModel::Hertz, RGBColor(230, 159, 0)),
    (NormalModel::Linder, RGBColor(86, 180, 233)),
    (NormalModel::KikPiotrowski, RGBColor(0, 158, 115)),
    (NormalModel::StripesB, RGBColor(204, 121, 167)),
    (NormalModel::StripesAB, RGBColor(213, 94, 0)),
    (NormalModel::Analyn, RGBColor(0, 114, 178)),
    (NormalModel::CoupledStrips, RGBColor(240, 228, 66)),
];

/// The colour of `model` in [`PALETTE`].
pub fn model_colour(model: NormalModel) -> RGBColor {
    PALETTE
        .iter()
        .find(|(m, _)| *m == model)
        .map_or(AUX_COLOUR, |(_, c)| *c)
}

/// Display name of a normal model with its `normalModel` code, e.g. "6 ANALYN".
pub fn model_label(model: NormalModel) -> String {
    let name = match model {
        NormalModel::Hertz => "Hertz",
        NormalModel::Linder => "Linder",
        NormalModel::KikPiotrowski => "Kik–Piotrowski",
        NormalModel::StripesB => "STRIPES-B",
        NormalModel::StripesAB => "STRIPES-A&B",
        NormalModel::Analyn => "ANALYN",
        NormalModel::CoupledStrips => "coupled strips",
    };
    format!("{} {name}", model.code())
}

/// How a curve is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LineKind {
    Solid,
    Dashed,
    Dotted,
    /// No line (markers only).
    None,
}

/// Marker at the data points of a curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Marker {
    None,
    Circle,
    Triangle,
    Square,
    Cross,
}

/// The look of one curve (also its legend entry).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    pub colour: RGBColor,
    pub line: LineKind,
    pub marker: Marker,
    /// Line width [px].
    pub width: u32,
}

impl Look {
    pub fn solid(colour: RGBColor, width: u32) -> Self {
        Self {
            colour,
            line: LineKind::Solid,
            marker: Marker::None,
            width,
        }
    }

    pub fn with(self, line: LineKind, marker: Marker) -> Self {
        Self {
            line,
            marker,
            ..self
        }
    }
}

/// One legend entry: a sample of the look and its label.
#[derive(Debug, Clone)]
pub struct LegendEntry {
    pub label: String,
    pub look: Look,
}

impl LegendEntry {
    pub fn line(label: impl Into<String>, look: Look) -> Self {
        Self {
            label: label.into(),
            look,
        }
    }
}

/// A figure that can draw itself on any plotters backend.
pub trait Figure {
    /// File name without extension.
    fn name(&self) -> &str;
    /// Size in pixels (PNG) and user units (SVG).
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Turns a plotters error into the report's error text.
pub fn fail(e: impl std::fmt::Display) -> String {
    format!("drawing failed: {e}")
}

/// Writes `figure` as `<dir>/<name>.svg` and `<dir>/<name>.png`; returns both paths.
pub fn render<F: Figure>(figure: &F, dir: &Path) -> Result<[PathBuf; 2], String> {
    let svg = dir.join(format!("{}.svg", figure.name()));
    let png = dir.join(format!("{}.png", figure.name()));
    let size = figure.size();
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        figure.draw(&root)?;
        root.present()
            .map_err(|e| format!("{}: cannot write the figure: {e}", svg.display()))?;
    }
    let mut pixels = vec![0u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        figure.draw(&root)?;
        root.present().map_err(fail)?;
    }
    write_png(&png, &pixels, size)
        .map_err(|e| format!("{}: cannot write the figure: {e}", png.display()))?;
    Ok([svg, png])
}

/// Writes RGB `pixels` of `size` as an indexed-colour PNG with the best compression (see
/// [`palette`]).
fn write_png(path: &Path, pixels: &[u8], size: (u32, u32)) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(|e| e.to_string())?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size.0, size.1);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Best);
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    let (palette, indices) = palette(pixels);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_palette(palette);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer
        .write_image_data(&indices)
        .map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())
}

/// Most colours of an indexed PNG.
const PALETTE_SIZE: usize = 256;

/// The palette (RGB triples) and per-pixel indices of an RGB image: its colours if there are at
/// most [`PALETTE_SIZE`], else its most frequent ones with every other colour (anti-aliasing
/// shades) mapped to the nearest of them. The figures' flat colours are kept exactly; the
/// figures are drawn with few enough of them (the traction colour map has discrete levels).
fn palette(pixels: &[u8]) -> (Vec<u8>, Vec<u8>) {
    let mut counts = std::collections::HashMap::<[u8; 3], usize>::new();
    for px in pixels.chunks_exact(3) {
        *counts.entry([px[0], px[1], px[2]]).or_default() += 1;
    }
    let mut colours: Vec<([u8; 3], usize)> = counts.into_iter().collect();
    // Most frequent first; ties by colour, so the output is deterministic.
    colours.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let kept: Vec<[u8; 3]> = colours.iter().take(PALETTE_SIZE).map(|c| c.0).collect();
    let distance = |a: [u8; 3], b: [u8; 3]| -> i32 {
        (0..3)
            .map(|k| (i32::from(a[k]) - i32::from(b[k])).pow(2))
            .sum()
    };
    let index: std::collections::HashMap<[u8; 3], u8> = colours
        .iter()
        .map(|&(c, _)| {
            let nearest = (0..kept.len())
                .min_by_key(|&i| distance(c, kept[i]))
                .unwrap_or(0);
            (c, nearest as u8)
        })
        .collect();
    let indices = pixels
        .chunks_exact(3)
        .map(|px| index.get(&[px[0], px[1], px[2]]).copied().unwrap_or(0))
        .collect();
    (kept.concat(), indices)
}

/// Draws `title` centred in a strip of `height` px at the top of `area`; returns the rest.
pub fn title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    height: u32,
) -> Result<DrawingArea<DB, Shift>, String> {
    let (top, rest) = area.split_vertically(height);
    let (w, h) = top.dim_in_pixel();
    let style = TextStyle::from((FONT, 20).into_font().style(FontStyle::Bold))
        .pos(Pos::new(HPos::Center, VPos::Center));
    top.draw(&Text::new(
        text.to_string(),
        (w as i32 / 2, h as i32 / 2),
        style,
    ))
    .map_err(fail)?;
    Ok(rest)
}

/// Layout of a legend strip `width` px wide: each entry's anchor (sample start, row centre) and
/// the strip's height [px].
fn legend_layout(width: u32, entries: &[LegendEntry]) -> (Vec<(i32, i32)>, u32) {
    let font = (FONT, LEGEND_FONT).into_font();
    let (mut x, mut y) = (10i32, LEGEND_ROW / 2 + 2);
    let mut anchors = Vec::with_capacity(entries.len());
    for e in entries {
        let text_w = font
            .box_size(&e.label)
            .map_or(8 * e.label.chars().count() as u32, |b| b.0) as i32;
        let entry_w = LEGEND_SAMPLE + 6 + text_w + 22;
        if x > 10 && x + entry_w > width as i32 {
            x = 10;
            y += LEGEND_ROW;
        }
        anchors.push((x, y));
        x += entry_w;
    }
    (anchors, (y + LEGEND_ROW / 2 + 4) as u32)
}

/// Legend text size [px], row height [px] and sample length [px].
const LEGEND_FONT: u32 = 15;
const LEGEND_ROW: i32 = 22;
const LEGEND_SAMPLE: i32 = 34;

/// Splits `area` into the rest and a legend strip at its bottom holding `entries` (as many
/// rows as they need), draws the legend and returns the rest.
pub fn with_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
) -> Result<DrawingArea<DB, Shift>, String> {
    let (w, h) = area.dim_in_pixel();
    let (_, height) = legend_layout(w, entries);
    let (rest, strip) = area.split_vertically(h.saturating_sub(height));
    legend(&strip, entries)?;
    Ok(rest)
}

/// Height a legend of `entries` needs in a strip `width` px wide [px].
pub fn legend_height(width: u32, entries: &[LegendEntry]) -> u32 {
    legend_layout(width, entries).1
}

/// Draws a legend strip: the entries left to right, wrapped onto as many rows as needed.
pub fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
) -> Result<(), String> {
    let (w, _) = area.dim_in_pixel();
    let (anchors, _) = legend_layout(w, entries);
    let font = (FONT, LEGEND_FONT).into_font();
    for (e, &(x, y)) in entries.iter().zip(&anchors) {
        draw_sample(area, e.look, (x, y), LEGEND_SAMPLE)?;
        area.draw(&Text::new(
            e.label.clone(),
            (x + LEGEND_SAMPLE + 6, y),
            TextStyle::from(font.clone()).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(fail)?;
    }
    Ok(())
}

/// A short sample of a curve's look at `(x, y)` (pixels), `length` px long.
fn draw_sample<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    look: Look,
    (x, y): (i32, i32),
    length: i32,
) -> Result<(), String> {
    let style = look.colour.stroke_width(look.width);
    let ends = [(x, y), (x + length, y)];
    match look.line {
        LineKind::Solid => area
            .draw(&PathElement::new(ends.to_vec(), style))
            .map_err(fail)?,
        LineKind::Dashed => {
            for k in 0..3 {
                let x0 = x + k * 13;
                area.draw(&PathElement::new(vec![(x0, y), (x0 + 8, y)], style))
                    .map_err(fail)?;
            }
        }
        LineKind::Dotted => {
            for k in 0..5 {
                area.draw(&Circle::new((x + 3 + k * 7, y), 1, look.colour.filled()))
                    .map_err(fail)?;
            }
        }
        LineKind::None => {}
    }
    marker_at(area, look, (x + length / 2, y))
}

/// Draws the marker of `look` at `c` (in `area`'s own coordinates).
fn marker_at<DB: DrawingBackend, CT: CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    look: Look,
    c: CT::From,
) -> Result<(), String> {
    let style = look.colour.stroke_width(2);
    let r = 4;
    let at = EmptyElement::at(c);
    match look.marker {
        Marker::None => Ok(()),
        Marker::Circle => area.draw(&(at + Circle::new((0, 0), r, style))),
        Marker::Triangle => area.draw(&(at + TriangleMarker::new((0, 0), r + 1, style))),
        Marker::Square => area.draw(&(at + Rectangle::new([(-r, -r), (r, r)], style))),
        Marker::Cross => area.draw(&(at + Cross::new((0, 0), r, style))),
    }
    .map_err(fail)
}

/// The cartesian chart type of every panel.
pub type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Axis ranges and labels of a panel.
#[derive(Debug, Clone)]
pub struct Axes {
    pub x: (f64, f64),
    pub y: (f64, f64),
    pub x_label: String,
    pub y_label: String,
}

/// A panel with a caption, labelled axes and a light grid.
pub fn panel<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    axes: &Axes,
) -> Result<Chart<'a, DB>, String> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 16))
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(58)
        .build_cartesian_2d(axes.x.0..axes.x.1, axes.y.0..axes.y.1)
        .map_err(fail)?;
    chart
        .configure_mesh()
        .x_desc(axes.x_label.as_str())
        .y_desc(axes.y_label.as_str())
        .axis_desc_style((FONT, 15))
        .label_style((FONT, 13))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_labels(8)
        .y_labels(6)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(fail)?;
    Ok(chart)
}

/// An axis tick label: the value rounded to 1e−9 in its shortest form, never "-0".
pub fn tick(v: f64) -> String {
    let r = (v * 1e9).round() / 1e9 + 0.0;
    format!("{r}").replace('-', "−")
}

/// Draws a curve through `points` (data coordinates) with `look`.
pub fn curve<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    points: &[(f64, f64)],
    look: Look,
) -> Result<(), String> {
    let style = look.colour.stroke_width(look.width);
    let pts = points.to_vec();
    match look.line {
        LineKind::Solid => {
            chart
                .draw_series(LineSeries::new(pts, style))
                .map_err(fail)?;
        }
        LineKind::Dashed => {
            chart
                .draw_series(DashedLineSeries::new(pts, 8, 5, style))
                .map_err(fail)?;
        }
        LineKind::Dotted => {
            let colour = look.colour;
            chart
                .draw_series(DottedLineSeries::new(pts, 0, 6, move |c| {
                    Circle::new(c, 1, colour.filled())
                }))
                .map_err(fail)?;
        }
        LineKind::None => {}
    }
    if look.marker != Marker::None {
        let area = chart.plotting_area();
        for &p in points {
            marker_at(area, look, p)?;
        }
    }
    Ok(())
}

/// A closed outline through `points` (data coordinates).
pub fn outline<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    points: &[(f64, f64)],
    look: Look,
) -> Result<(), String> {
    let mut closed = points.to_vec();
    if let Some(&first) = points.first() {
        closed.push(first);
    }
    curve(chart, &closed, look)
}

/// A filled polygon (data coordinates).
pub fn filled<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    points: &[(f64, f64)],
    colour: RGBAColor,
) -> Result<(), String> {
    chart
        .draw_series(std::iter::once(Polygon::new(
            points.to_vec(),
            colour.filled(),
        )))
        .map_err(fail)?;
    Ok(())
}

/// Viridis-like colour map, `t` in [0, 1] (clamped; NaN → 0).
pub fn colour_map(t: f64) -> RGBColor {
    const STOPS: [(u8, u8, u8); 6] = [
        (68, 1, 84),
        (65, 68, 135),
        (42, 120, 142),
        (34, 168, 132),
        (122, 209, 81),
        (253, 231, 37),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let u = t * (STOPS.len() - 1) as f64;
    let i = (u.floor() as usize).min(STOPS.len() - 2);
    let f = u - i as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * f).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Number of discrete levels of the traction colour scale.
pub const COLOUR_LEVELS: usize = 16;

/// The colour of level ⌊t·[`COLOUR_LEVELS`]⌋ (discrete levels read better than a continuum
/// and keep the PNG palette small).
pub fn banded_colour(t: f64) -> RGBColor {
    let n = COLOUR_LEVELS as f64;
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let k = (t * n).floor().min(n - 1.0);
    colour_map((k + 0.5) / n)
}

/// A vertical colour bar for `0..max` in [`COLOUR_LEVELS`] bands in `area`, labelled `label`.
pub fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    max: f64,
    label: &str,
) -> Result<(), String> {
    let axes = Axes {
        x: (0.0, 1.0),
        y: (0.0, max),
        x_label: String::new(),
        y_label: label.to_string(),
    };
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .y_label_area_size(70)
        .build_cartesian_2d(axes.x.0..axes.x.1, axes.y.0..axes.y.1)
        .map_err(fail)?;
    let n = COLOUR_LEVELS;
    chart
        .draw_series((0..n).map(|k| {
            let (y0, y1) = (max * k as f64 / n as f64, max * (k + 1) as f64 / n as f64);
            Rectangle::new(
                [(0.0, y0), (1.0, y1)],
                banded_colour((k as f64 + 0.5) / n as f64).filled(),
            )
        }))
        .map_err(fail)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_x_axis()
        .disable_y_mesh()
        .y_desc(axes.y_label.as_str())
        .axis_desc_style((FONT, 15))
        .label_style((FONT, 13))
        .y_labels(6)
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(fail)?;
    Ok(())
}

/// The range of `values` widened by `pad` of its span on each side (a unit range around a single
/// value; (0, 1) when empty or not finite).
pub fn padded_range(values: impl IntoIterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span <= 0.0 {
        return (lo - 0.5, hi + 0.5);
    }
    (lo - pad * span, hi + pad * span)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palette_has_one_distinct_colour_per_model() {
        for m in NormalModel::ALL {
            assert_eq!(PALETTE.iter().filter(|(p, _)| *p == m).count(), 1);
        }
        for (i, a) in PALETTE.iter().enumerate() {
            for b in &PALETTE[i + 1..] {
                assert_ne!(a.1, b.1);
            }
        }
    }

    #[test]
    fn colour_map_ends_and_clamps() {
        assert_eq!(colour_map(0.0), RGBColor(68, 1, 84));
        assert_eq!(colour_map(1.0), RGBColor(253, 231, 37));
        assert_eq!(colour_map(2.0), colour_map(1.0));
        assert_eq!(colour_map(f64::NAN), colour_map(0.0));
    }

    #[test]
    fn ticks_are_short_and_never_negative_zero() {
        assert_eq!(tick(-0.0), "0");
        assert_eq!(tick(0.30000000000000004), "0.3");
        assert_eq!(tick(-20.0), "−20");
        assert_eq!(tick(0.002), "0.002");
    }

    #[test]
    fn palette_is_exact_for_few_colours_and_nearest_beyond() {
        let pixels = [255, 255, 255, 0, 0, 0, 255, 255, 255];
        let (p, i) = palette(&pixels);
        assert_eq!(p, vec![255, 255, 255, 0, 0, 0]);
        assert_eq!(i, vec![0, 1, 0]);
        // 300 distinct greys: the rarest map to the nearest kept grey.
        let mut many = Vec::new();
        for k in 0..300u32 {
            let g = (k % 256) as u8;
            let repeat = if k < 256 { 2 } else { 1 };
            for _ in 0..repeat {
                many.extend_from_slice(&[g, g, g.wrapping_add((k / 256) as u8)]);
            }
        }
        let (p, i) = palette(&many);
        assert_eq!(p.len(), 3 * PALETTE_SIZE);
        assert_eq!(i.len(), many.len() / 3);
    }

    #[test]
    fn padded_range_handles_degenerate_input() {
        assert_eq!(padded_range([1.0, 3.0], 0.5), (0.0, 4.0));
        assert_eq!(padded_range([2.0], 0.1), (1.5, 2.5));
        assert_eq!(padded_range([f64::NAN], 0.1), (0.0, 1.0));
    }
}
