//! On-screen text that fits any window, and the check that it does. Text marked [`FitText`]
//! scales its font with the window (18 px at 1280 × 720, never under 10 px) and wraps short of
//! the panels a scene reports in [`Covered`] (the inspector). At every screenshot the harness
//! measures every text node laid out on screen and fails the run if two overlap, if one runs
//! under a panel or out of the window.

use bevy::prelude::*;
use bevy::window::PrimaryWindow;

/// Screen rectangles (logical pixels, origin top left) that panels cover this frame: text keeps
/// clear of them. The showcase fills it from egui's windows.
#[derive(Resource, Default, Clone, Debug)]
pub struct Covered(pub Vec<Rect>);

/// Text whose font follows the window: `px` at 1280 × 720, scaled with the smaller of the
/// window's width and height ratios, and at least [`FitText::SMALLEST`]. With `wrap`, the node
/// is kept left of the panels in [`Covered`] that reach its height.
#[derive(Component, Clone, Copy, Debug)]
pub struct FitText {
    /// Font size in logical pixels at 1280 × 720.
    pub px: f32,
    /// Wrap the text short of the panels beside it.
    pub wrap: bool,
}

impl FitText {
    /// The smallest font drawn, in logical pixels: readable on a 640 × 360 window.
    pub const SMALLEST: f32 = 10.0;

    /// The font size for a window of `size` logical pixels.
    pub fn size_in(self, size: Vec2) -> f32 {
        let scale = (size.x / 1280.0).min(size.y / 720.0).min(1.0);
        (self.px * scale).max(Self::SMALLEST.min(self.px))
    }
}

/// Asks for a layout check now (the screenshot's name, for the log).
#[derive(Message, Clone, Debug)]
pub struct CheckLayout(pub String);

/// Screenshots whose layout check failed.
#[derive(Resource, Default, Debug)]
pub struct LayoutFailures(pub u32);

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<Covered>()
        .add_message::<CheckLayout>()
        .add_systems(PostUpdate, fit_text.before(bevy::ui::UiSystems::Prepare))
        .add_systems(Last, check_layout);
}

/// A block of black text in the top-left corner, for a scene's live figures and keys.
pub fn info_text() -> impl Bundle {
    (
        Text::new(""),
        TextFont::from_font_size(18.0),
        FitText {
            px: 18.0,
            wrap: true,
        },
        TextColor(Color::BLACK),
        Node {
            position_type: PositionType::Absolute,
            top: px(MARGIN),
            left: px(MARGIN),
            ..default()
        },
    )
}

/// Space kept between text, panels and the window's edges, logical pixels.
const MARGIN: f32 = 10.0;

fn fit_text(
    window: Single<&Window, With<PrimaryWindow>>,
    covered: Res<Covered>,
    mut texts: Query<(&FitText, &mut TextFont, &mut Node)>,
) {
    let size = window.size();
    for (fit, mut font, mut node) in &mut texts {
        let px = fit.size_in(size);
        if !matches!(font.font_size, FontSize::Px(old) if old == px) {
            font.font_size = FontSize::Px(px);
        }
        if fit.wrap {
            let left = match node.left {
                Val::Px(left) => left,
                _ => MARGIN,
            };
            // Left of every panel whose top is in the upper half of the window.
            let right = covered
                .0
                .iter()
                .filter(|r| r.min.y < 0.5 * size.y && r.max.x > left)
                .map(|r| r.min.x)
                .fold(size.x, f32::min);
            let width = px_val((right - left - MARGIN).max(4.0 * px));
            if node.max_width != width {
                node.max_width = width;
            }
        }
    }
}

fn px_val(v: f32) -> Val {
    Val::Px(v.floor())
}

/// One text node as laid out: its rectangle in logical pixels and its first words.
struct Placed {
    rect: Rect,
    text: String,
}

fn check_layout(
    mut requests: MessageReader<CheckLayout>,
    window: Single<&Window, With<PrimaryWindow>>,
    covered: Res<Covered>,
    texts: Query<(
        &Text,
        &ComputedNode,
        &UiGlobalTransform,
        &InheritedVisibility,
    )>,
    mut failures: ResMut<LayoutFailures>,
) {
    for CheckLayout(name) in requests.read() {
        let placed: Vec<Placed> = texts
            .iter()
            .filter(|(text, node, _, visible)| {
                visible.get() && !text.0.trim().is_empty() && node.size().min_element() > 0.0
            })
            .map(|(text, node, transform, _)| {
                let scale = node.inverse_scale_factor();
                let centre = transform.affine().translation * scale;
                let half = 0.5 * node.size() * scale;
                Placed {
                    rect: Rect::from_center_half_size(centre, half),
                    text: text
                        .0
                        .split_whitespace()
                        .take(4)
                        .collect::<Vec<_>>()
                        .join(" "),
                }
            })
            .collect();
        let problems = overlaps(&placed, &covered.0, window.size());
        if problems.is_empty() {
            info!("layout of {name}: {} texts, none overlapping", placed.len());
        } else {
            failures.0 += 1;
            for problem in problems {
                error!("layout of {name} at {}: {problem}", window.size());
            }
        }
    }
}

/// What overlaps: text with text, text with a panel, text with the window's edge (one pixel of
/// slack for rounding).
fn overlaps(placed: &[Placed], covered: &[Rect], window: Vec2) -> Vec<String> {
    let inset = |r: Rect| r.inflate(-1.0);
    let mut problems = Vec::new();
    for (i, a) in placed.iter().enumerate() {
        for b in &placed[i + 1..] {
            if !inset(a.rect).intersect(inset(b.rect)).is_empty() {
                problems.push(format!("\"{}\" overlaps \"{}\"", a.text, b.text));
            }
        }
        for panel in covered {
            if !inset(a.rect).intersect(*panel).is_empty() {
                problems.push(format!("\"{}\" runs under a panel at {panel:?}", a.text));
            }
        }
        let screen = Rect::from_corners(Vec2::ZERO, window);
        if inset(a.rect).union(screen) != screen {
            problems.push(format!(
                "\"{}\" runs out of the window ({:?})",
                a.text, a.rect
            ));
        }
    }
    problems
}
