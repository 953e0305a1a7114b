//! Plots and labels with `plotters`: a font registered from the repository (Roboto, a subset
//! committed in examples/fonts/ under the Apache License 2.0), so text draws the same on any
//! machine without fontconfig or system fonts, and a bitmap drawn into our own RGB buffer and
//! written with `png`.

use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{save_indexed, save_rgb8, Result};

/// The font family name the examples draw their text in.
pub const FONT: &str = "sans-serif";

/// Roboto Regular, cut to Latin, Greek, super- and subscripts and a few symbols (27 KB).
static ROBOTO: &[u8] = include_bytes!("../fonts/Roboto-Regular-subset.ttf");

/// Registers the committed font under [`FONT`] (once per process).
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is a valid TrueType file committed with the examples; a failure here is a
        // broken checkout, which the first drawn label would report anyway.
        if plotters::style::register_font(FONT, FontStyle::Normal, ROBOTO).is_err() {
            eprintln!("warning: the font examples/fonts/Roboto-Regular-subset.ttf did not load");
        }
    });
}

/// Colours of successive series (a colour-blind-safe qualitative palette, Okabe & Ito 2008).
pub const SERIES: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

/// Draws a `width`×`height` picture with `draw` on a white background and writes it to
/// `path` as an 8-bit RGB PNG, or an indexed one of 256 colours if `palette`.
pub fn draw_png<F>(path: &Path, width: u32, height: u32, palette: bool, draw: F) -> Result<()>
where
    F: FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<()>,
{
    register_font();
    let mut buffer = vec![255u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root)?;
        root.present()?;
    }
    if palette {
        save_indexed(path, width as usize, height as usize, &buffer)
    } else {
        save_rgb8(path, width as usize, height as usize, &buffer)
    }
}

/// Draws on an existing RGB image (`pixels`, `width`×`height`, row-major) with `draw`.
pub fn draw_on<F>(pixels: &mut [u8], width: u32, height: u32, draw: F) -> Result<()>
where
    F: FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<()>,
{
    register_font();
    let root = BitMapBackend::with_buffer(pixels, (width, height)).into_drawing_area();
    draw(&root)?;
    root.present()?;
    Ok(())
}

/// A "nice" length for a scale bar: 1, 2 or 5 × 10ⁿ metres, the largest not above `at_most`.
pub fn nice_length(at_most: f64) -> f64 {
    let power = 10f64.powf(at_most.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&l| l <= at_most)
        .unwrap_or(power)
}

/// A length in metres as a label: "500 m", "2 km", "0.5 m".
pub fn metres(length: f64) -> String {
    if length >= 1000.0 {
        format!("{} km", trim(length / 1000.0))
    } else {
        format!("{} m", trim(length))
    }
}

fn trim(value: f64) -> String {
    let text = format!("{value:.2}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Draws a scale bar for a map of `metres_per_pixel` at the left of `area`, vertically
/// centred, about a quarter of the map's width (`map_width` pixels) long, with its length and
/// `caption` (e.g. the window's size) to its right: white with a dark outline, so it reads on
/// any background. For a footer under a map, or over the map itself.
pub fn scale_bar(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    metres_per_pixel: f64,
    map_width: u32,
    caption: &str,
) -> Result<()> {
    let (_, height) = area.dim_in_pixel();
    let size = (f64::from(height) * 0.5).clamp(11.0, 18.0);
    let length = nice_length(0.25 * f64::from(map_width) * metres_per_pixel);
    let bar = (length / metres_per_pixel).round() as i32;
    let (x0, y0) = (10, height as i32 / 2);
    let dark = RGBColor(10, 10, 10);
    area.draw(&Rectangle::new(
        [(x0 - 1, y0 - 4), (x0 + bar + 1, y0 + 4)],
        dark.filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(x0, y0 - 3), (x0 + bar, y0 + 3)],
        WHITE.filled(),
    ))?;
    for x in [x0, x0 + bar / 2, x0 + bar] {
        area.draw(&Rectangle::new(
            [(x - 1, y0 - 7), (x, y0 + 7)],
            WHITE.filled(),
        ))?;
    }
    let label = format!("{}   {caption}", metres(length));
    outlined_text(
        area,
        &label,
        (x0 + bar + 10, y0 - (0.55 * size) as i32),
        size,
    )
}

/// Writes `text` at (x, y) in white with a dark outline, `size` pixels high.
pub fn outlined_text(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    text: &str,
    (x, y): (i32, i32),
    size: f64,
) -> Result<()> {
    let style = (FONT, size).into_font();
    let dark = RGBColor(10, 10, 10);
    for (dx, dy) in [(-1, 0), (1, 0), (0, -1), (0, 1), (1, 1)] {
        area.draw(&Text::new(
            text.to_string(),
            (x + dx, y + dy),
            style.color(&dark),
        ))?;
    }
    area.draw(&Text::new(text.to_string(), (x, y), style.color(&WHITE)))?;
    Ok(())
}

/// The legend's sample of a line series drawn in `colour`, 2 px wide: for
/// `.legend(line_swatch(colour))`.
pub fn line_swatch(colour: RGBColor) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
}

/// Draws the chart's legend at `position` in the examples' style: labels of `font_size` px on
/// a translucent white box with a grey border.
pub fn draw_legend<'a, 'b: 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, BitMapBackend<'b>, CT>,
    position: SeriesLabelPosition,
    font_size: f64,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .label_font((FONT, font_size).into_font())
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .draw()?;
    Ok(())
}
