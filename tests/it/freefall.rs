//! FallingObject: regime numbers, phase diagram, Markov chain, paths and randomized extremes.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::freefall::*;
use common::paper_coin as coin;

#[test]
fn paper_coin_has_re_3550_and_inertia_1e_2() {
    let r = coin().regime().unwrap();
    assert!(
        (r.reynolds / 3.55e3 - 1.0).abs() < 0.01,
        "Re = {}",
        r.reynolds
    );
    assert!(
        (r.inertia / 1.0e-2 - 1.0).abs() < 0.02,
        "I* = {}",
        r.inertia
    );
    assert!(
        (r.descent_speed - 0.1585).abs() < 1e-3,
        "U = {}",
        r.descent_speed
    );
    assert_eq!(r.main, PrimitiveMotion::Fluttering);
}

#[test]
fn fig_15_objects_fall_in_the_regimes_the_paper_reports() {
    // §5: (a) coin, (b) paper ellipse, (c) leaf, at the paper's (Re, I*).
    assert_eq!(
        PrimitiveMotion::classify(3.55e3, 1.0e-2),
        PrimitiveMotion::Fluttering
    );
    assert_eq!(
        PrimitiveMotion::classify(6.8e3, 2.2e-3),
        PrimitiveMotion::Spiral
    );
    assert_eq!(
        PrimitiveMotion::classify(1.2e4, 6.3e-3),
        PrimitiveMotion::Helix
    );
}

#[test]
fn ellipse_inertia_reduces_to_the_disk_and_grows_with_length() {
    let disk = Regime::new(
        &Shape::Disk {
            diameter: 0.05,
            thickness: 1e-3,
        },
        2400.0,
        &Fluid::WATER,
        9.81,
    )
    .unwrap();
    let round = |major| {
        Regime::new(
            &Shape::Ellipse {
                major,
                minor: 0.05,
                thickness: 1e-3,
            },
            2400.0,
            &Fluid::WATER,
            9.81,
        )
        .unwrap()
    };
    // At L = a the ellipse is the disk.
    let e = round(0.05);
    let expected = std::f32::consts::PI * (2400.0 / 997.0) * 1e-3 / (64.0 * 0.05);
    assert!((e.inertia / expected - 1.0).abs() < 1e-5);
    assert!((round(0.1).inertia / e.inertia - 2.0).abs() < 1e-5);
    assert!((disk.inertia / e.inertia - 1.0).abs() < 1e-6);
}

#[test]
fn every_regime_is_reachable_from_a_physical_object() {
    let cases = [
        // Tiny disk in water: Re < 100.
        (
            Shape::Disk {
                diameter: 0.002,
                thickness: 1e-4,
            },
            2700.0,
            Fluid::WATER,
        ),
        // The coin.
        (
            Shape::Disk {
                diameter: 0.02,
                thickness: 0.0015,
            },
            2700.0,
            Fluid::WATER,
        ),
        // A steel washer in water: I* in the chaotic band.
        (
            Shape::Disk {
                diameter: 0.02,
                thickness: 0.0015,
            },
            7800.0,
            Fluid::WATER,
        ),
        // A card in air.
        (
            Shape::Rectangle {
                length: 0.085,
                width: 0.055,
                thickness: 3e-4,
            },
            700.0,
            Fluid::AIR,
        ),
        // Thin large plastic disks in water (Zhong et al.'s kind).
        (
            Shape::Disk {
                diameter: 0.06,
                thickness: 0.0025,
            },
            2700.0,
            Fluid::WATER,
        ),
        (
            Shape::Disk {
                diameter: 0.06,
                thickness: 0.0025,
            },
            1350.0,
            Fluid::WATER,
        ),
    ];
    let mut seen: Vec<PrimitiveMotion> = cases
        .iter()
        .map(|(shape, density, fluid)| Regime::new(shape, *density, fluid, 9.81).unwrap().main)
        .collect();
    seen.sort();
    seen.dedup();
    assert_eq!(seen, PrimitiveMotion::ALL.to_vec(), "{seen:?}");
}

#[test]
fn lighter_than_fluid_and_bad_sizes_are_typed_errors() {
    let mut cork = coin();
    cork.density = 240.0;
    let e = cork.regime().unwrap_err();
    assert!(matches!(e, FallError::LighterThanFluid { .. }));
    assert_eq!(e.field(), "density");
    let cases: Vec<(FallingObject, &str)> = vec![
        (
            FallingObject {
                density: -1.0,
                ..coin()
            },
            "density",
        ),
        (
            FallingObject {
                gravity: f32::NAN,
                ..coin()
            },
            "gravity",
        ),
        (
            FallingObject {
                deviation: -1.0,
                ..coin()
            },
            "deviation",
        ),
        (
            FallingObject {
                wind_tilt: 10.0,
                ..coin()
            },
            "wind_tilt",
        ),
        (
            FallingObject {
                fluid: Fluid {
                    density: 1.0,
                    kinematic_viscosity: 0.0,
                },
                ..coin()
            },
            "fluid.kinematic_viscosity",
        ),
        (
            FallingObject {
                shape: Shape::Disk {
                    diameter: 0.01,
                    thickness: 0.02,
                },
                ..coin()
            },
            "shape.thickness",
        ),
        (
            FallingObject {
                shape: Shape::Ellipse {
                    major: 0.01,
                    minor: 0.02,
                    thickness: 1e-4,
                },
                ..coin()
            },
            "shape.minor",
        ),
        (
            FallingObject {
                shape: Shape::Rectangle {
                    length: f32::INFINITY,
                    width: 0.02,
                    thickness: 1e-4,
                },
                ..coin()
            },
            "shape.length",
        ),
    ];
    for (object, field) in cases {
        assert_eq!(object.regime().unwrap_err().field(), field, "{object:?}");
    }
}

#[test]
fn bad_markov_matrices_name_their_row() {
    let good = *MarkovChain::default().transitions();
    let start = *MarkovChain::default().initial();
    let mut negative = good;
    negative[2][3] = -0.1;
    negative[2][2] += 0.1;
    let e = MarkovChain::new(start, negative).unwrap_err();
    assert!(
        matches!(e, MarkovError::Negative { .. }) && e.row() == Some(2),
        "{e}"
    );
    let mut sum = good;
    sum[4][5] = 0.5;
    let e = MarkovChain::new(start, sum).unwrap_err();
    assert!(
        matches!(e, MarkovError::RowSum { .. }) && e.row() == Some(4),
        "{e}"
    );
    let mut backward = good;
    backward[3] = [0.2, 0.0, 0.0, 0.55, 0.15, 0.10];
    let e = MarkovChain::new(start, backward).unwrap_err();
    assert!(
        matches!(e, MarkovError::Backward { column: 0, .. }) && e.row() == Some(3),
        "{e}"
    );
    let e = MarkovChain::new([0.5; 6], good).unwrap_err();
    assert_eq!(e.row(), None);
    assert!(MarkovChain::new(start, good).is_ok());
}
