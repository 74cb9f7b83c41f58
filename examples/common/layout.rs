//! The layout check of Bevy UI text (the native examples' captions; the showcase draws its text
//! with egui and checks it itself): at every screenshot the harness measures every text node
//! laid out on screen and fails the run if two overlap or one runs out of the window.

use bevy::prelude::*;
use bevy::window::PrimaryWindow;

use super::harness::{CheckLayout, LayoutFailures};

pub(super) fn plugin(app: &mut App) {
    app.add_systems(Last, check_layout);
}

/// One text node as laid out: its rectangle in logical pixels and its first words.
struct Placed {
    rect: Rect,
    text: String,
}

fn check_layout(
    mut requests: MessageReader<CheckLayout>,
    window: Single<&Window, With<PrimaryWindow>>,
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
        if placed.is_empty() {
            continue; // no UI text (the showcase draws its own with egui and checks it there)
        }
        let problems = overlaps(&placed, window.size());
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

/// What overlaps: text with text, text with the window's edge (one pixel of slack for rounding).
fn overlaps(placed: &[Placed], window: Vec2) -> Vec<String> {
    let inset = |r: Rect| r.inflate(-1.0);
    let mut problems = Vec::new();
    for (i, a) in placed.iter().enumerate() {
        for b in &placed[i + 1..] {
            if !inset(a.rect).intersect(inset(b.rect)).is_empty() {
                problems.push(format!("\"{}\" overlaps \"{}\"", a.text, b.text));
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
