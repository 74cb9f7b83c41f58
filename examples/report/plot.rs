//! Log-log line plots as SVG (plotters).

use std::path::Path;

use plotters::prelude::*;

/// One line of a plot: (x, y) points; points with a non-positive or non-finite coordinate are
/// left out (a log axis cannot show them; the tables keep them).
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        let points = points
            .into_iter()
            .filter(|&(x, y)| x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0)
            .collect();
        Self {
            label: label.into(),
            points,
        }
    }
}

/// A plot with logarithmic axes.
pub struct Plot<'a> {
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub series: Vec<Series>,
}

/// Line colours that read on white.
const COLORS: [RGBColor; 6] = [
    RGBColor(200, 30, 40),
    RGBColor(20, 90, 200),
    RGBColor(30, 150, 60),
    RGBColor(150, 60, 170),
    RGBColor(230, 130, 0),
    RGBColor(40, 40, 40),
];

/// Bounds of all points, widened by a factor on each side.
fn log_bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo.is_finite() && hi > 0.0 {
        // At least a factor 25, so that several labelled ticks (1, 2, 5 × 10^k) are inside.
        let (lo, hi) = (lo / 1.5, hi * 1.5);
        if hi / lo < 25.0 {
            let middle = (lo * hi).sqrt();
            (middle / 5.0, middle * 5.0)
        } else {
            (lo, hi)
        }
    } else {
        (0.1, 10.0)
    }
}

/// A log axis' tick label: 1, 2 and 5 times a power of ten are labelled, the rest left blank
/// so that labels do not run into each other.
fn tick(value: &f64) -> String {
    let label = format!("{value:.0e}");
    if label.starts_with(['1', '2', '5']) {
        label
    } else {
        String::new()
    }
}

/// Writes `plot` to `path` as SVG.
pub fn draw(path: &Path, plot: &Plot) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (720, 440)).into_drawing_area();
    root.fill(&WHITE)?;
    let points = || plot.series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = log_bounds(points().map(|p| p.0));
    let (y0, y1) = log_bounds(points().map(|p| p.1));
    let mut chart = ChartBuilder::on(&root)
        .caption(plot.title, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(plot.x_label)
        .y_desc(plot.y_label)
        .x_labels(12)
        .y_labels(12)
        .light_line_style(BLACK.mix(0.04))
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .draw()?;
    for (i, series) in plot.series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()].to_rgba();
        chart
            .draw_series(LineSeries::new(
                series.points.clone(),
                color.stroke_width(2),
            ))?
            .label(series.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart.draw_series(
            series
                .points
                .iter()
                .map(|&p| Circle::new(p, 3, color.filled())),
        )?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
