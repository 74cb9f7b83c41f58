//! The hostile sweep's shared parts: the values, the case rule and the tally.

use std::cell::Cell;

use bevy::prelude::*;

/// The values every numeric field is tried at.
pub const HOSTILE: [f32; 13] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    -1.0,
    1e-45, // the smallest subnormal
    f32::MIN_POSITIVE,
    1e-30,
    1e30,
    f32::MAX,
    -f32::MAX,
    f32::from_bits(f32::MAX.to_bits() - 1),
];

/// The wind's lean of eq. 15 used where a test does not care.
pub const TILT: bevy_windfall::freefall::WindTilt = bevy_windfall::freefall::WindTilt {
    max_angle: 0.6,
    reference_speed: 4.0,
};

// Per test: each test runs on its own thread.
thread_local! {
    static REFUSED: Cell<usize> = const { Cell::new(0) };
    static ACCEPTED: Cell<usize> = const { Cell::new(0) };
}

/// One case: refused with one of `fields` named, or accepted and `run` (which asserts).
pub fn case<T, E: std::fmt::Display>(
    what: &str,
    value: f32,
    fields: &[&str],
    result: Result<T, E>,
    field_of: impl Fn(&E) -> &'static str,
    run: impl FnOnce(T),
) {
    match result {
        Err(e) => {
            let named = field_of(&e);
            assert!(
                fields.contains(&named),
                "{what} = {value}: refused naming `{named}`, expected one of {fields:?} ({e})"
            );
            REFUSED.set(REFUSED.get() + 1);
        }
        Ok(t) => {
            run(t);
            ACCEPTED.set(ACCEPTED.get() + 1);
        }
    }
}

/// Prints this test's tally.
pub fn report(name: &str) {
    println!(
        "hostile {name}: {} refused with the field named, {} accepted and finite",
        REFUSED.get(),
        ACCEPTED.get()
    );
}

/// Asserts a finite vector.
pub fn finite(v: Vec3, what: &str) {
    assert!(v.is_finite(), "{what}: {v}");
}
