//! The scene generator of docs/scenes.md: xorshift64*, reproduced bit for bit so that rapier and Rebound build
//! identical scenes from the same seeds.
//!
//! ```text
//! next: s ^= s >> 12; s ^= s << 25; s ^= s >> 27; return s · 0x2545F4914F6CDD1D (wrapping)
//! U(lo, hi) = lo + (hi − lo)·((next >> 40) / 2^24)   in f32
//! ```

/// xorshift64* with a 64-bit state.
#[derive(Debug, Clone)]
pub struct XorShift64Star {
    state: u64,
}

impl XorShift64Star {
    /// A generator seeded with `seed`. Zero is a fixed point of xorshift, so a zero seed is replaced by 1
    /// (as in Rebound's copy of the generator); the scenes only use non-zero seeds.
    pub const fn new(seed: u64) -> Self {
        Self {
            state: if seed == 0 { 1 } else { seed },
        }
    }

    /// The next 64-bit output.
    pub fn next_u64(&mut self) -> u64 {
        let mut s = self.state;
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        self.state = s;
        s.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// `U(lo, hi)`: a uniform `f32` in `[lo, hi)` built from the top 24 bits of the next output.
    pub fn uniform(&mut self, lo: f32, hi: f32) -> f32 {
        // The top 24 bits fit an f32 mantissa exactly, and 2^24 is a power of two: both conversions are exact.
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * unit
    }
}

#[cfg(test)]
mod tests {
    use super::XorShift64Star;

    #[test]
    fn first_output_matches_the_recurrence_by_hand() {
        // seed 1: s = 1 ^ (1 >> 12) = 1; s ^= 1 << 25 → 0x2000001; s ^= s >> 27 → 0x2000001.
        let mut g = XorShift64Star::new(1);
        assert_eq!(
            g.next_u64(),
            0x0200_0001_u64.wrapping_mul(0x2545_F491_4F6C_DD1D)
        );
    }

    #[test]
    fn uniform_stays_in_range() {
        let mut g = XorShift64Star::new(0xBA11_5EED_0000_0001);
        for _ in 0..10_000 {
            let u = g.uniform(-0.04, 0.04);
            assert!((-0.04..0.04).contains(&u), "{u}");
        }
    }
}
