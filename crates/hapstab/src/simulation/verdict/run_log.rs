//! The running statistics of a run: blocks of consecutive samples with their extremes,
//! velocity crossings and contact events, merged pairwise as the run grows.

use super::facts::SampleFacts;
use super::{HYSTERESIS, HYSTERESIS_BLOCKS, INITIAL_BLOCKS, MAX_BLOCKS, MIN_BLOCK_LEN, NO_SAMPLE};

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Extremes {
    pub(super) min: f64,
    pub(super) max: f64,
}

impl Extremes {
    pub(super) const EMPTY: Self = Self {
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
    };

    #[inline(always)]
    pub(super) fn include(&mut self, v: f64) {
        self.min = self.min.min(v);
        self.max = self.max.max(v);
    }

    pub(super) fn merge(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub(super) fn range(&self) -> f64 {
        if self.max >= self.min {
            self.max - self.min
        } else {
            0.0
        }
    }

    pub(super) fn middle(&self) -> f64 {
        0.5 * (self.min + self.max)
    }
}

/// Count and first/last sample index of a kind of event.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Events {
    pub(super) count: usize,
    pub(super) first: usize,
    pub(super) last: usize,
}

impl Events {
    #[inline(always)]
    pub(super) fn add(&mut self, k: usize) {
        if self.count == 0 {
            self.first = k;
        }
        self.last = k;
        self.count += 1;
    }

    pub(super) fn merge(self, o: Self) -> Self {
        match (self.count, o.count) {
            (0, _) => o,
            (_, 0) => self,
            _ => Self {
                count: self.count + o.count,
                first: self.first,
                last: o.last,
            },
        }
    }

    /// Mean interval between the events in samples (needs two).
    pub(super) fn period(&self) -> Option<f64> {
        (self.count >= 2 && self.last > self.first)
            .then(|| (self.last - self.first) as f64 / (self.count - 1) as f64)
    }
}

/// Statistics of consecutive samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Block {
    pub(super) start: usize,
    pub(super) len: usize,
    pub(super) position: Extremes,
    pub(super) velocity: Extremes,
    pub(super) first_position: f64,
    pub(super) last_position: f64,
    pub(super) contact_samples: usize,
    pub(super) linear_samples: usize,
    pub(super) crossings: Events,
    pub(super) contacts: Events,
    pub(super) separations: usize,
}

impl Block {
    pub(super) fn empty(start: usize) -> Self {
        Self {
            start,
            len: 0,
            position: Extremes::EMPTY,
            velocity: Extremes::EMPTY,
            first_position: 0.0,
            last_position: 0.0,
            contact_samples: 0,
            linear_samples: 0,
            crossings: Events::default(),
            contacts: Events::default(),
            separations: 0,
        }
    }

    pub(super) fn merge(self, o: Self) -> Self {
        Self {
            start: self.start,
            len: self.len + o.len,
            position: self.position.merge(o.position),
            velocity: self.velocity.merge(o.velocity),
            first_position: self.first_position,
            last_position: o.last_position,
            contact_samples: self.contact_samples + o.contact_samples,
            linear_samples: self.linear_samples + o.linear_samples,
            crossings: self.crossings.merge(o.crossings),
            contacts: self.contacts.merge(o.contacts),
            separations: self.separations + o.separations,
        }
    }

    pub(super) fn merge_all(blocks: &[Block]) -> Block {
        match blocks.split_first() {
            Some((first, rest)) => rest.iter().fold(*first, |a, b| a.merge(*b)),
            None => Block::empty(0),
        }
    }

    /// Half-range of the velocity.
    pub(super) fn envelope(&self) -> f64 {
        0.5 * self.velocity.range()
    }

    pub(super) fn centre(&self) -> f64 {
        self.start as f64 + 0.5 * self.len as f64
    }
}

/// The running statistics of a run (see the module documentation): fed one sample at a
/// time, allocation-free except when a block closes.
#[derive(Debug, Clone)]
pub struct RunLog {
    block_len: usize,
    blocks: Vec<Block>,
    current: Block,
    pub(super) samples: usize,
    /// Contact on the previous sample: 0 or 1, [`NO_SAMPLE`] before the first sample.
    pub(super) previous_contact: u8,
    below: bool,
    hysteresis: f64,
    pub(super) contacts: usize,
    pub(super) separations: usize,
    pub(super) last_separation: Option<usize>,
}

impl RunLog {
    /// An empty log for a run planned to last `planned` samples (it may run longer).
    pub fn new(planned: usize) -> Self {
        Self {
            block_len: planned.div_ceil(INITIAL_BLOCKS).max(MIN_BLOCK_LEN),
            blocks: Vec::with_capacity(MAX_BLOCKS),
            current: Block::empty(0),
            samples: 0,
            previous_contact: NO_SAMPLE,
            below: false,
            hysteresis: 0.0,
            contacts: 0,
            separations: 0,
            last_separation: None,
        }
    }

    /// Samples logged so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Logs the next sample.
    #[inline(always)]
    pub fn push(&mut self, s: SampleFacts) {
        let k = self.samples;
        self.samples += 1;
        let crossing = if s.velocity < -self.hysteresis {
            self.below = true;
            false
        } else if s.velocity > self.hysteresis && self.below {
            self.below = false;
            true
        } else {
            false
        };
        let contact = u8::from(s.in_contact);
        let event = contact != self.previous_contact && self.previous_contact != NO_SAMPLE;
        self.previous_contact = contact;
        let b = &mut self.current;
        if b.len == 0 {
            b.first_position = s.position;
        }
        b.len += 1;
        b.position.include(s.position);
        b.velocity.include(s.velocity);
        b.last_position = s.position;
        b.contact_samples += usize::from(s.in_contact);
        b.linear_samples += usize::from(s.linear);
        if crossing {
            b.crossings.add(k);
        }
        let full = b.len == self.block_len;
        if event {
            self.contact_event(k, s.in_contact);
        }
        if full {
            self.close_block();
        }
    }

    #[cold]
    #[inline(never)]
    fn contact_event(&mut self, k: usize, in_contact: bool) {
        let b = &mut self.current;
        if in_contact {
            self.contacts += 1;
            b.contacts.add(k);
        } else {
            self.separations += 1;
            b.separations += 1;
            self.last_separation = Some(k);
        }
    }

    #[cold]
    #[inline(never)]
    fn close_block(&mut self) {
        self.blocks.push(self.current);
        self.current = Block::empty(self.samples);
        let recent = &self.blocks[self.blocks.len().saturating_sub(HYSTERESIS_BLOCKS)..];
        self.hysteresis = HYSTERESIS * recent.iter().map(Block::envelope).fold(0.0, f64::max);
        if self.blocks.len() == MAX_BLOCKS {
            self.blocks = self.blocks.chunks(2).map(Block::merge_all).collect();
            self.block_len *= 2;
        }
    }

    /// The closed blocks and the current one (if not empty).
    pub(super) fn all_blocks(&self) -> Vec<Block> {
        let mut v = self.blocks.clone();
        if self.current.len > 0 {
            v.push(self.current);
        }
        v
    }
}
