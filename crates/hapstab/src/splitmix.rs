//! SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
//! OOPSLA 2014): the seeded uniform streams of the sampled analyses (robust K_max over a box,
//! populations of operators). A stream per sample index keeps a draw independent of the
//! threads that compute it.

/// A SplitMix64 state.
pub(crate) struct SplitMix(pub(crate) u64);

impl SplitMix {
    /// The stream of sample `i` of the draw seeded `seed`.
    pub(crate) fn stream(seed: u64, i: usize) -> Self {
        SplitMix(seed ^ (i as u64).wrapping_mul(0xD1B5_4A32_D192_ED03))
    }

    /// The next uniform in [0, 1) (53 bits).
    pub(crate) fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `n` uniforms in [0, 1).
    pub(crate) fn point(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next_f64()).collect()
    }
}
