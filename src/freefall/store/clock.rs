//! The clock a fall store runs on, and on which its tiers of detail fall due.

/// The clock a fall store's tiers run on: seconds and fixed steps since it started, and the
/// last step's length.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FallClock {
    pub seconds: f64,
    pub steps: u64,
    pub last_dt: f32,
}

impl FallClock {
    /// One more fixed step of `dt` seconds.
    pub fn tick(&mut self, dt: f32) {
        self.seconds += f64::from(dt);
        self.steps += 1;
        self.last_dt = dt;
    }

    /// Fixed steps from this one to the next on which an object of `tier` with index `index`
    /// is due (1 to `tier`).
    pub fn steps_to_next(&self, tier: u32, index: u32) -> u32 {
        let tier = tier.max(1);
        tier - ((self.steps + u64::from(index)) & u64::from(tier - 1)) as u32
    }
}
