//! Rendered checks: every windowed example's screenshot exists and shows a scene, not a blank,
//! black or UI-only frame. CI renders the examples under Xvfb and Mesa's lavapipe into
//! `$WINDFALL_SCREENSHOTS` (see `.ci/run`) and then runs
//! `cargo test --test it -- --ignored screenshots::`; without a renderer the check is skipped, but
//! the checker itself is tested on synthetic frames every run.

use std::collections::HashMap;
use std::fs::File;
use std::path::{Path, PathBuf};

/// The screenshots CI takes: the showcase's four scenes, every topic example (the curtain and the
/// GPU-swayed grass among them), and a newcomer's game (the
/// README's quick start in a fresh project, `.ci/newcomer.py`). The showcase's leaves scene must
/// also show its storm, its flag its red and its gallery the motions' trails (see
/// [`showcase_reason`]); the examples what they are about (see [`content_reason`]).
const EXPECTED: [&str; 17] = [
    "showcase_leaves.png",
    "showcase_coin.png",
    "showcase_flag.png",
    "showcase_gallery.png",
    "example_falling_leaves.png",
    "example_leaf_cloud.png",
    "example_coin_in_water.png",
    "example_flag.png",
    "example_curtain.png",
    "example_wind_settings.png",
    "example_wind_sources.png",
    "example_grass.png",
    "example_avian_body.png",
    "example_physical_flag.png",
    "example_inspector.png",
    "example_interaction.png",
    "newcomer.png",
];

/// Shares of the frame's pixels that are flag red (the default cloth fabric) and cloth blue (the
/// default physical cloth).
fn fabric_shares(frame: &Frame) -> (f64, f64) {
    let n = frame.rgb.len() as f64;
    let red = frame.rgb.iter().filter(|p| {
        let [r, g, b] = p.map(f64::from);
        r > 90.0 && r > 2.0 * g && r > 2.0 * b
    });
    let blue = frame.rgb.iter().filter(|p| {
        let [r, g, b] = p.map(f64::from);
        b > 80.0 && b > 1.5 * r && b > 1.2 * g
    });
    (red.count() as f64 / n, blue.count() as f64 / n)
}

/// Leaves anywhere in the frame: runs of autumn-coloured pixels (red, orange, yellow or brown:
/// red above green above blue by a margin) per 1000 pixels. Green ground and blue sky give none.
fn leaf_specks(frame: &Frame) -> f64 {
    let w = frame.width;
    let mut runs = 0usize;
    for row in frame.rgb.chunks(w) {
        let mut previous = false;
        for p in row {
            let [r, g, b] = p.map(i32::from);
            let autumn = r > g + 10 && r > b + 40;
            runs += usize::from(autumn && !previous);
            previous = autumn;
        }
    }
    1000.0 * runs as f64 / frame.rgb.len().max(1) as f64
}

/// Why an example's (or the newcomer's) frame does not show what it is about: a flag (red), a
/// physical cloth (blue), leaves (autumn specks) or grass.
fn content_reason(name: &str, frame: &Frame) -> Option<String> {
    let (_, blue) = fabric_shares(frame);
    let specks = leaf_specks(frame);
    let wants = |topics: &[&str]| topics.iter().any(|t| name.contains(t));
    let mut missing = Vec::new();
    if wants(&["_flag", "curtain", "inspector", "interaction", "newcomer"]) {
        missing.extend(red_flag_reason(frame));
    }
    if wants(&["physical_flag", "interaction", "newcomer"]) && blue < 0.002 {
        missing.push(format!(
            "no blue physical cloth: {:.2} % blue",
            blue * 100.0
        ));
    }
    if wants(&[
        "falling_leaves",
        "leaf_cloud",
        "wind_settings",
        "wind_sources",
        "interaction",
        "newcomer",
    ]) && specks < 0.3
    {
        missing.push(format!(
            "no leaves: {specks:.2} autumn specks per 1000 pixels (≥ 0.3)"
        ));
    }
    if wants(&["grass", "interaction"]) {
        missing.extend(grass_reason(frame));
    }
    (!missing.is_empty()).then(|| missing.join("; "))
}

/// Why a frame shows no red flag (the default cloth fabric): under 0.2 % red.
fn red_flag_reason(frame: &Frame) -> Option<String> {
    let (red, _) = fabric_shares(frame);
    (red < 0.002).then(|| format!("no red flag: {:.2} % red", red * 100.0))
}

/// An RGB frame.
struct Frame {
    width: usize,
    height: usize,
    rgb: Vec<[u8; 3]>,
}

fn load(path: &Path) -> Result<Frame, String> {
    let file = File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let mut buffer = vec![0; reader.output_buffer_size().ok_or("PNG too large")?];
    let info = reader.next_frame(&mut buffer).map_err(|e| e.to_string())?;
    let channels = info.color_type.samples();
    let rgb = buffer[..info.buffer_size()]
        .chunks(channels)
        .map(|p| match channels {
            1 | 2 => [p[0]; 3],
            _ => [p[0], p[1], p[2]],
        })
        .collect();
    Ok(Frame {
        width: info.width as usize,
        height: info.height as usize,
        rgb,
    })
}

/// Shares of the pixels by colour, quantised to 16 levels per channel, largest first.
fn colour_shares<'a>(pixels: impl Iterator<Item = &'a [u8; 3]>) -> Vec<f64> {
    let mut counts: HashMap<[u8; 3], usize> = HashMap::new();
    let mut total = 0usize;
    for p in pixels {
        *counts.entry(p.map(|c| c >> 4)).or_default() += 1;
        total += 1;
    }
    let mut shares: Vec<f64> = counts
        .values()
        .map(|&c| c as f64 / total.max(1) as f64)
        .collect();
    shares.sort_by(|a, b| b.total_cmp(a));
    shares
}

/// Shares of colours in the part of `frame` where `keep(x, y)`.
fn region_shares(frame: &Frame, keep: impl Fn(usize, usize) -> bool) -> Vec<f64> {
    let w = frame.width;
    colour_shares(
        frame
            .rgb
            .iter()
            .enumerate()
            .filter(|(i, _)| keep(i % w, i / w))
            .map(|(_, p)| p),
    )
}

/// Why `frame` is not a rendered scene, or `None` if it is one: not black, no colour covering
/// most of it, at least three colours that each cover 2 % (sky, ground, objects), and a
/// lower-left quadrant (clear of the text at the top and the panel on the right) that is not
/// one colour: before the 3-D pipelines are ready, that part shows only the clear colour.
fn blank_reason(frame: &Frame) -> Option<String> {
    scene_reason(frame, 3).or_else(|| {
        let (w, h) = (frame.width, frame.height);
        let corner = region_shares(frame, |x, y| x < w / 2 && y > h / 2);
        (corner[0] > 0.9).then(|| {
            format!(
                "one colour covers {:.0} % of the lower-left quadrant: no scene behind the UI",
                corner[0] * 100.0
            )
        })
    })
}

/// Why `frame` is not a rendered scene, without the showcase's lower-left rule (an example's
/// ground may fill that quadrant): not black, no colour over 80 %, `colours` colours of 2 % or
/// more (the showcase's scenes have three; an example may be sky and ground and what it shows,
/// which its content check looks for).
fn scene_reason(frame: &Frame, colours: usize) -> Option<String> {
    let n = frame.rgb.len() as f64;
    let luminance: f64 = frame
        .rgb
        .iter()
        .map(|p| p.iter().map(|&c| f64::from(c)).sum::<f64>() / 765.0)
        .sum::<f64>()
        / n;
    if luminance < 0.08 {
        return Some(format!("black: mean luminance {luminance:.3}"));
    }
    let shares = colour_shares(frame.rgb.iter());
    if shares[0] > 0.8 {
        return Some(format!("one colour covers {:.0} %", shares[0] * 100.0));
    }
    let visible = shares.iter().filter(|&&s| s >= 0.02).count();
    (visible < colours).then(|| format!("only {visible} colours cover 2 % or more"))
}

/// The grass of a meadow view (the grass example's): the bottom third of the left half (clear of the panel) is mostly
/// green and full of blades, i.e. fine detail between neighbouring pixels (mean |Δ luminance|),
/// where a bare ground plane would be smooth. Returns (green share, detail).
fn grass_measures(frame: &Frame) -> (f64, f64) {
    let (w, h) = (frame.width, frame.height);
    let (mut green, mut detail, mut n) = (0usize, 0.0f64, 0usize);
    let lum = |p: &[u8; 3]| p.iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0;
    for y in (2 * h / 3)..h {
        for x in 0..(w / 2 - 1) {
            let p = &frame.rgb[y * w + x];
            if p[1] > p[0] && p[1] > p[2] {
                green += 1;
            }
            detail += (lum(p) - lum(&frame.rgb[y * w + x + 1])).abs();
            n += 1;
        }
    }
    (green as f64 / n as f64, detail / n as f64)
}

/// Why a meadow shows no grass, if it does not.
fn grass_reason(frame: &Frame) -> Option<String> {
    let (green, detail) = grass_measures(frame);
    (green < 0.5 || detail < 8.0).then(|| {
        format!("no grass blades: {green:.2} green, mean |Δ luminance| {detail:.1} (≥ 0.5, ≥ 8)")
    })
}

/// The storm of the leaves scene: specks of leaf colour (red above blue) in the sky right of the
/// trunk, below the header text and the inspector panel (which now cover the upper sky), counted
/// as runs of warm pixels per 1000 pixels. In CI's 640 × 360 frames, taken 4 s into the scene on
/// the examples' recording clock, the storm's cloud gives 11.2 there (many small leaves far off);
/// the other scenes 0–5 (the measure is checked on the leaves scene only). Before that clock the
/// moment followed the software renderer's speed and the storm measured 4.9–7.
fn storm_specks(frame: &Frame) -> f64 {
    let (w, h) = (frame.width, frame.height);
    let (mut runs, mut n) = (0usize, 0usize);
    for y in (h * 58 / 100)..(h * 85 / 100) {
        let mut previous = false;
        for x in (w * 35 / 100)..(w * 95 / 100) {
            let p = frame.rgb[y * w + x];
            let warm = i32::from(p[0]) > i32::from(p[2]) + 25;
            runs += usize::from(warm && !previous);
            previous = warm;
            n += 1;
        }
    }
    1000.0 * runs as f64 / n.max(1) as f64
}

/// The gallery's trails: how many of twelve 30° hue sectors the thin coloured lines of the band
/// between the header and the shelf fill, each with at least 0.02 % of the band. A pixel counts
/// when it is strongly coloured (max − min channel over 90) and the pixels three to its left and
/// right are not: a trail one or two pixels wide does, a flag's stripe (a broad area) does not
/// (nor does a trail's nearly horizontal stretch; the gallery's trails run mostly downwards).
/// The six motions' trails (blue, green, orange, red, cyan, purple) fill 6 sectors in CI's
/// 640 × 360 frame; the flag scene (broad stripes, stray edges) 3, the leaves scene 3, the white
/// room, black text and a grey panel none.
fn trail_hues(frame: &Frame) -> usize {
    let (w, h) = (frame.width, frame.height);
    let hue_of = |p: [u8; 3]| {
        let [r, g, b] = p.map(f64::from);
        let (max, min) = (r.max(g).max(b), r.min(g).min(b));
        (max - min > 90.0).then(|| {
            if max == r {
                60.0 * ((g - b) / (max - min)).rem_euclid(6.0)
            } else if max == g {
                60.0 * ((b - r) / (max - min) + 2.0)
            } else {
                60.0 * ((r - g) / (max - min) + 4.0)
            }
        })
    };
    let mut sectors = [0usize; 12];
    let mut n = 0usize;
    for y in (h * 30 / 100)..(h * 68 / 100) {
        for x in 3..w - 3 {
            n += 1;
            let at = |x: usize| frame.rgb[y * w + x];
            if let Some(hue) = hue_of(at(x))
                && hue_of(at(x - 3)).is_none()
                && hue_of(at(x + 3)).is_none()
            {
                // Sectors centred on 0°, 30°, …: pure hues (the trails' blue is 240°, red 0°)
                // sit in a sector's middle, not on an edge between two.
                sectors[((hue + 15.0) / 30.0) as usize % 12] += 1;
            }
        }
    }
    let least = n as f64 * 0.0002;
    sectors.iter().filter(|&&c| c as f64 >= least).count()
}

/// Why a showcase scene's frame does not show that scene: a blank
/// frame; the leaves without their storm; the flag without its red; the gallery without trails
/// of at least five colours.
fn showcase_reason(name: &str, frame: &Frame) -> Option<String> {
    blank_reason(frame).or_else(|| {
        if name.contains("leaves") {
            storm_reason(frame)
        } else if name.contains("flag") {
            red_flag_reason(frame)
        } else if name.contains("gallery") {
            let hues = trail_hues(frame);
            (hues < 5).then(|| format!("trails of {hues} colours (≥ 5)"))
        } else {
            None
        }
    })
}

/// Why the leaves scene shows no storm, if it does not.
fn storm_reason(frame: &Frame) -> Option<String> {
    let specks = storm_specks(frame);
    (specks < 5.0)
        .then(|| format!("no leaf storm: {specks:.1} leaf specks per 1000 sky pixels (≥ 5)"))
}

/// A synthetic 320 × 180 frame: `f(x, y)` per pixel.
fn synthetic(f: impl Fn(usize, usize) -> [u8; 3]) -> Frame {
    let (width, height) = (320, 180);
    let rgb = (0..width * height)
        .map(|i| f(i % width, i / width))
        .collect();
    Frame { width, height, rgb }
}

#[test]
fn the_checker_rejects_blank_frames_and_accepts_a_scene() {
    let black = synthetic(|_, _| [0, 0, 0]);
    assert!(blank_reason(&black).unwrap().starts_with("black"));
    // A clear colour with a line of text: what a frame looks like before shaders compile.
    let text_only = synthetic(|x, y| {
        if y < 12 && x % 3 == 0 {
            [0, 0, 0]
        } else {
            [40, 42, 48]
        }
    });
    assert!(blank_reason(&text_only).is_some());
    // The clear colour with the header text and the panel over it: UI ready, 3-D not yet.
    let ui_only = synthetic(|x, y| {
        if x > 170 {
            [30, 30, 32]
        } else if y < 40 && x % 3 == 0 {
            [0, 0, 0]
        } else {
            [150, 190, 220]
        }
    });
    assert!(blank_reason(&ui_only).unwrap().contains("lower-left"));
    // Sky over shaded grass with a tree in the middle.
    let scene = synthetic(|x, y| {
        if (140..180).contains(&x) && (40..150).contains(&y) {
            [120, 80, 40]
        } else if y < 90 {
            [150, 190, 220]
        } else {
            [60, 100 + (y as u8 - 90), 50]
        }
    });
    assert_eq!(blank_reason(&scene), None);
    // Only sky.
    let sky = synthetic(|_, _| [150, 190, 220]);
    assert!(blank_reason(&sky).unwrap().contains("one colour"));
    // A smooth green ground is no grass; thin light and dark blades are.
    let ground = synthetic(|x, _| [90, 130 + (x / 40) as u8, 70]);
    assert!(grass_reason(&ground).is_some());
    let blades = synthetic(|x, y| {
        let shade = ((x * 7 + y * 3) % 5) as u8 * 12;
        [60 + shade, 110 + shade, 40]
    });
    assert_eq!(grass_reason(&blades), None);
    // A sky with a few large leaves is no storm; one speckled with small leaves (2 %) is.
    let few = synthetic(|x, y| {
        if (x % 80 < 12) && (110..122).contains(&y) {
            [200, 90, 30]
        } else {
            [150, 190, 220]
        }
    });
    assert!(storm_reason(&few).is_some());
    let storm = synthetic(|x, y| {
        if (x * 13 + y * 7) % 100 < 2 {
            [200, 90, 30]
        } else {
            [150, 190, 220]
        }
    });
    assert_eq!(storm_reason(&storm), None);
}

#[test]
#[ignore = "needs the screenshots CI renders; run with -- --ignored"]
fn every_example_screenshot_shows_its_scene() {
    let dir = std::env::var_os("WINDFALL_SCREENSHOTS")
        .map_or_else(|| PathBuf::from("target/screenshots"), PathBuf::from);
    let mut failures = Vec::new();
    for name in EXPECTED {
        let path = dir.join(name);
        match load(&path) {
            Err(e) => failures.push(format!("{name}: {e}")),
            Ok(frame) => {
                let topic = name.starts_with("example_") || name == "newcomer.png";
                let reason = if topic {
                    scene_reason(&frame, 2).or_else(|| content_reason(name, &frame))
                } else {
                    showcase_reason(name, &frame)
                };
                if let Some(reason) = reason {
                    failures.push(format!("{name}: {reason}"));
                }
                let (red, blue) = fabric_shares(&frame);
                println!(
                    "{name}: {:.2} % red, {:.2} % blue, {:.2} leaf specks per 1000 pixels",
                    red * 100.0,
                    blue * 100.0,
                    leaf_specks(&frame)
                );
                let (green, detail) = grass_measures(&frame);
                println!("{name}: grass measures {green:.2} green, detail {detail:.1}");
                println!(
                    "{name}: {:.1} leaf specks per 1000 sky pixels, trails of {} colours",
                    storm_specks(&frame),
                    trail_hues(&frame)
                );
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The showcase as a browser drew it: CI builds it for WebGL2 (`web/build.sh`), opens it in
/// headless Chromium on SwiftShader (`.ci/web.py`), and the tour saves each scene into
/// `$WINDFALL_WEB_SCREENSHOTS`; each must pass the native scene's check.
#[test]
#[ignore = "needs the browser's screenshots CI takes; run with -- --ignored"]
fn every_web_screenshot_shows_its_scene() {
    let dir = std::env::var_os("WINDFALL_WEB_SCREENSHOTS")
        .map_or_else(|| PathBuf::from("target/web-screenshots"), PathBuf::from);
    let failures: Vec<String> = EXPECTED
        .iter()
        .filter(|name| name.starts_with("showcase_"))
        .filter_map(|name| {
            let reason = load(&dir.join(name)).map_or_else(Some, |frame| {
                println!(
                    "web {name}: {:.1} leaf specks per 1000 sky pixels, trails of {} colours",
                    storm_specks(&frame),
                    trail_hues(&frame)
                );
                showcase_reason(name, &frame)
            });
            reason.map(|r| format!("web {name}: {r}"))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The examples' content check: sky and ground alone are refused for the flag, the physical
/// flag and the leaves, and accepted once a red flag, a blue cloth and leaf specks are drawn.
#[test]
fn the_content_check_wants_what_each_example_is_about() {
    let bare = synthetic(|_, y| {
        if y < 90 {
            [150, 190, 220]
        } else {
            [90, 130, 70]
        }
    });
    for name in [
        "example_flag.png",
        "example_physical_flag.png",
        "example_falling_leaves.png",
    ] {
        assert!(content_reason(name, &bare).is_some(), "{name} passed bare");
    }
    let dressed = synthetic(|x, y| match (x, y) {
        (40..80, 40..70) => [200, 30, 25],
        (120..160, 40..70) => [40, 70, 190],
        _ if x % 9 == 0 && y % 7 == 0 => [210, 120, 30],
        _ if y < 90 => [150, 190, 220],
        _ => [90, 130, 70],
    });
    for name in [
        "example_flag.png",
        "example_physical_flag.png",
        "example_falling_leaves.png",
    ] {
        assert_eq!(content_reason(name, &dressed), None, "{name}");
        assert_eq!(scene_reason(&dressed, 2), None, "{name}");
    }
}

/// The gallery check counts the trails' colours: six coloured lines in a white room are six
/// hues; the room with black text and a grey panel none, and broad stripes of colour none.
#[test]
fn the_gallery_check_counts_trail_colours() {
    let colours = [
        [40, 60, 220],
        [40, 170, 60],
        [240, 140, 30],
        [220, 40, 40],
        [30, 190, 210],
        [150, 50, 200],
    ];
    let room = |x: usize, y: usize| {
        if x < 200 && (20..30).contains(&y) {
            [10, 10, 10]
        } else if x > 220 && y < 60 {
            [40, 40, 40]
        } else {
            [235, 232, 225]
        }
    };
    let trails = synthetic(|x, y| {
        let lane = x / 50;
        if lane < 6 && x % 50 == 25 && y < 160 {
            colours[lane]
        } else {
            room(x, y)
        }
    });
    assert_eq!(trail_hues(&trails), 6);
    assert_eq!(trail_hues(&synthetic(room)), 0);
    let stripes = synthetic(|x, y| colours[(y / 30).min(5)].map(|c| if x < 300 { c } else { 235 }));
    assert_eq!(trail_hues(&stripes), 0);
    // A scene (wall, floor, a shelf) without trails is refused for them, and accepted with them.
    let plain = |x: usize, y: usize| {
        if y < 108 {
            room(x, y)
        } else if (130..150).contains(&y) && x < 160 {
            [120, 110, 100]
        } else {
            [170, 170, 165]
        }
    };
    assert_eq!(blank_reason(&synthetic(plain)), None);
    let refused = showcase_reason("showcase_gallery.png", &synthetic(plain)).unwrap();
    assert!(refused.starts_with("trails of 0"), "{refused}");
    let with_trails = synthetic(|x, y| {
        let lane = x / 50;
        if lane < 6 && x % 50 == 25 && (60..100).contains(&y) {
            colours[lane]
        } else {
            plain(x, y)
        }
    });
    assert_eq!(showcase_reason("showcase_gallery.png", &with_trails), None);
}
