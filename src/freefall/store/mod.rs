//! The fall store: every fall of a [`LeafCloud`](crate::freefall::LeafCloud), or every
//! [`FallingObject`](crate::freefall::FallingObject) of an app, kept as a structure of arrays
//! in blocks of the lane width, stepped by one driver.
//!
//! | part | what | touched |
//! |---|---|---|
//! | [`Hot`](block::Hot) columns | control points, orientations, carry, drift, f(t), the piece's clock and offset, the heading, the piece compiled (1/T, its words, its database row), flags, the tier's span | every step of the fall, lane by lane |
//! | [`ConstantStorage`](block::Constants) | U, 1/ℓ, the ground, W, levels of detail | splatted for a cloud; a column for objects |
//! | [`Cold`](cold::Cold) | generator, chain, motion and sojourn, the piece itself, blends, release fade, easing | when a piece ends, a motion changes, a fall lands or is let go |
//!
//! **Levels of detail in bands.** A fall's tier (1, 2 or 4: stepped every fixed step, every
//! second or every fourth) and its phase (which of those steps, from its handle) put it in one of
//! seven bands, each a dense run of blocks. A step takes the three bands due on it and nothing
//! else: no record of a fall that waits is read. A fall's tier is measured again from its new
//! position each time it is stepped, and it moves band when that changes (the step after).
//!
//! **One driver** ([`driver`]): the wind of a block read in one batch of lanes; one lane pass
//! over the block's falls whose piece goes on; the others (a piece ends, the chain steps, a
//! swing is searched, a blend, a landing) one at a time through the same kernels ([`slot`]).
//!
//! **Determinism.** A fall's bits depend on its own state and the wind where it is: nothing of
//! another lane, block, band, thread or store enters its arithmetic, which is plain IEEE-754 in
//! a fixed order (`crate::math`). Which band, block or lane it sits in changes no bit.

pub(crate) mod air;
pub(crate) mod block;
pub(crate) mod clock;
pub(crate) mod cold;
pub(crate) mod driver;
pub(crate) mod kernel;
pub(crate) mod path;
pub(crate) mod pose;
pub(crate) mod slot;
pub(crate) mod step;
pub(crate) mod view;

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use self::block::{Block, ConstantStorage, W};
use self::clock::FallClock;
use self::cold::Cold;
use self::cold::FallStart;
use self::slot::Slot;
use crate::freefall::model::FallModel;

/// How many bands: tier 1; tier 2 at phases 0 and 1; tier 4 at phases 0 to 3.
pub(crate) const BANDS: usize = 7;

/// The band of a fall of tier `tier` (1, 2 or 4) with handle `handle`.
pub(crate) fn band_of(tier: u32, handle: u32) -> usize {
    match tier {
        0 | 1 => 0,
        2 => 1 + (handle % 2) as usize,
        _ => 3 + (handle % 4) as usize,
    }
}

/// The bands due on fixed step `steps` (a fall of tier n is due when steps + handle is a
/// multiple of n).
pub(crate) fn due_bands(steps: u64) -> [usize; 3] {
    [
        0,
        1 + ((2 - steps % 2) % 2) as usize,
        3 + ((4 - steps % 4) % 4) as usize,
    ]
}

/// A dense run of falls: `len` of them in blocks of [`W`], their cold state beside.
#[derive(Debug)]
pub(crate) struct Band<K: ConstantStorage> {
    pub blocks: Vec<Block<K>>,
    pub cold: Vec<Cold>,
}

/// A clone keeps the room the band has grown to, so that it steps as the original does: a band
/// cloned to its length would reallocate (and copy whole) on the first fall that moves into it.
impl<K: ConstantStorage> Clone for Band<K> {
    fn clone(&self) -> Self {
        let mut blocks = Vec::with_capacity(self.blocks.capacity());
        blocks.extend_from_slice(&self.blocks);
        let mut cold = Vec::with_capacity(self.cold.capacity());
        cold.extend_from_slice(&self.cold);
        Self { blocks, cold }
    }
}

impl<K: ConstantStorage> Default for Band<K> {
    fn default() -> Self {
        Self {
            blocks: Vec::new(),
            cold: Vec::new(),
        }
    }
}

impl<K: ConstantStorage> Band<K> {
    /// How many falls.
    pub fn len(&self) -> usize {
        self.cold.len()
    }

    /// Fall `s`.
    pub fn slot(&mut self, s: usize) -> Slot<'_, K> {
        Slot {
            block: &mut self.blocks[s / W],
            k: s % W,
            cold: &mut self.cold[s],
        }
    }

    /// Appends a fall whose cold state is `cold` (its lanes to be written); returns its index.
    fn push(&mut self, cold: Cold) -> usize {
        let s = self.cold.len();
        if s.is_multiple_of(W) {
            self.blocks.push(Block::default());
        }
        self.cold.push(cold);
        s
    }

    /// Takes fall `s` out (the last one moves into its place): its lanes (lane 0 of the block
    /// returned), its cold state, and the handle of the fall that moved, if one did.
    fn swap_remove(&mut self, s: usize) -> (Block<K>, Cold, Option<u32>) {
        let last = self.cold.len() - 1;
        let mut taken = Block::default();
        taken.copy_lane(0, &self.blocks[s / W], s % W);
        let moved = (s != last).then(|| {
            let source = self.blocks[last / W];
            self.blocks[s / W].copy_lane(s % W, &source, last % W);
            source.handle[last % W]
        });
        let cold = self.cold.swap_remove(s);
        // The lanes past the end are left as they are: never read as falls.
        if last.is_multiple_of(W) {
            self.blocks.pop();
        }
        (taken, cold, moved)
    }
}

/// Where a handle's fall is: its band and index there (`band` = [`Place::FREE`]: no fall).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Place {
    pub band: u8,
    pub index: u32,
}

impl Place {
    const FREE: u8 = u8::MAX;
}

/// Falls in bands of blocks (see the module docs), each known by a handle that stays the same
/// while it lives.
#[derive(Clone, Debug)]
pub(crate) struct Store<K: ConstantStorage> {
    pub kind: K,
    pub bands: [Band<K>; BANDS],
    places: Vec<Place>,
    /// Handles given back, the lowest first.
    free: BinaryHeap<Reverse<u32>>,
    /// Seconds and fixed steps taken, and the last step's length.
    pub clock: FallClock,
    /// Falls on the ground.
    pub resting: usize,
}

impl<K: ConstantStorage> Store<K> {
    /// An empty store.
    pub fn new(kind: K) -> Self {
        Self {
            kind,
            bands: Default::default(),
            places: Vec::new(),
            free: BinaryHeap::new(),
            clock: FallClock::default(),
            resting: 0,
        }
    }

    /// How many falls.
    pub fn len(&self) -> usize {
        self.places.len() - self.free.len()
    }

    /// One more than the largest handle ever given.
    pub fn handles(&self) -> usize {
        self.places.len()
    }

    /// Lets a new fall go as `start` says; returns its handle (the lowest free one).
    pub fn insert(&mut self, model: &FallModel, start: &FallStart) -> u32 {
        let handle = match self.free.pop() {
            Some(Reverse(h)) => h,
            None => {
                self.places.push(Place {
                    band: Place::FREE,
                    index: 0,
                });
                self.places.len() as u32 - 1
            }
        };
        let s = self.bands[0].push(Cold::blank(start));
        self.places[handle as usize] = Place {
            band: 0,
            index: s as u32,
        };
        let mut slot = self.bands[0].slot(s);
        slot.block.handle[slot.k] = handle;
        slot.release(model, start, self.clock.seconds);
        handle
    }

    /// Lets fall `handle` go again as `start` says (a new fall in its place: its first step at
    /// once). `releases` counts the times it was let go.
    pub fn replace(&mut self, handle: u32, model: &FallModel, start: &FallStart) {
        if self.place(handle).is_none() {
            return;
        }
        if self.landed(handle) {
            self.resting -= 1;
        }
        self.move_to(handle, 0);
        let clock = self.clock.seconds;
        let mut slot = self.slot(handle).expect("a live handle");
        slot.cold.releases += 1;
        slot.release(model, start, clock);
    }

    /// Removes fall `handle` (its handle is given again later).
    pub fn remove(&mut self, handle: u32) {
        let Some(place) = self.place(handle) else {
            return;
        };
        if self.landed(handle) {
            self.resting -= 1;
        }
        let band = &mut self.bands[place.band as usize];
        let (_, _, moved) = band.swap_remove(place.index as usize);
        if let Some(moved) = moved {
            self.places[moved as usize].index = place.index;
        }
        self.places[handle as usize].band = Place::FREE;
        self.free.push(Reverse(handle));
    }

    /// Where fall `handle` is.
    pub fn place(&self, handle: u32) -> Option<Place> {
        self.places
            .get(handle as usize)
            .copied()
            .filter(|p| p.band != Place::FREE)
    }

    /// Fall `handle`, to read and write.
    pub fn slot(&mut self, handle: u32) -> Option<Slot<'_, K>> {
        let place = self.place(handle)?;
        Some(self.bands[place.band as usize].slot(place.index as usize))
    }

    /// Whether fall `handle` is on the ground.
    fn landed(&self, handle: u32) -> bool {
        self.place(handle).is_some_and(|p| {
            let band = &self.bands[p.band as usize];
            let s = p.index as usize;
            band.blocks[s / W].hot.landed[s % W] > 0.5
        })
    }

    /// Moves fall `handle` to band `to` (nothing of it changes but where it is kept).
    pub fn move_to(&mut self, handle: u32, to: usize) {
        let Some(place) = self.place(handle) else {
            return;
        };
        let from = place.band as usize;
        if from == to {
            return;
        }
        let (lanes, cold, moved) = self.bands[from].swap_remove(place.index as usize);
        if let Some(moved) = moved {
            self.places[moved as usize].index = place.index;
        }
        let band = &mut self.bands[to];
        let s = band.push(cold);
        band.blocks[s / W].copy_lane(s % W, &lanes, 0);
        self.places[handle as usize] = Place {
            band: to as u8,
            index: s as u32,
        };
    }

    /// Bytes the falls take (their blocks and cold state; blends, release fades and easings
    /// under way hold a few more on the heap).
    pub fn memory_bytes(&self) -> usize {
        self.bands
            .iter()
            .map(|b| {
                b.blocks.capacity() * std::mem::size_of::<Block<K>>()
                    + b.cold.capacity() * std::mem::size_of::<Cold>()
            })
            .sum::<usize>()
            + self.places.capacity() * std::mem::size_of::<Place>()
    }

    /// A store of fall `handle` alone, as it is now (handle 0, the same clock and constants),
    /// at full detail: it advances on every step. Stepped on from here in the same air, a fall
    /// of a full-detail store follows the same path bit for bit; one that was on a coarser tier
    /// catches up on its first step (over the time since its own last step), as it would on
    /// coming nearer the focus.
    pub fn single(&self, handle: u32) -> Option<Self> {
        let place = self.place(handle)?;
        let band = &self.bands[place.band as usize];
        let s = place.index as usize;
        let mut one = Self::new(self.kind.clone());
        one.clock = self.clock;
        one.places.push(Place { band: 0, index: 0 });
        let target = &mut one.bands[0];
        target.push(band.cold[s].clone());
        target.blocks[0].copy_lane(0, &band.blocks[s / W], s % W);
        target.blocks[0].handle[0] = 0;
        one.resting = usize::from(band.blocks[s / W].hot.landed[s % W] > 0.5);
        Some(one)
    }
}
