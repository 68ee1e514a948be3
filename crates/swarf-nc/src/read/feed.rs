//! Feed rate modes: from a block's `F` word and the distances its axes travel to the
//! feed of the tool tip over the part, which is what a [`crate::read::Motion`] carries
//! (mm/min, so that the time of a motion is its tip path length over its feed).
//!
//! As LinuxCNC reads them (its G-code reference, "G93, G94, G95: Feed Rate Mode"):
//!
//! - **G94**, units per minute. When any of `X Y Z` move, `F` is the speed along the
//!   `X Y Z` path of the machine (mm/min, or inch/min in G20) and the rotary axes move
//!   in step; when only rotary axes move, `F` is in degrees per minute along the rotary
//!   axes' "pseudo-Cartesian" path `sqrt(dA^2 + dB^2 + dC^2)`. So the block lasts
//!   `T = |dXYZ| / F` or `T = |dABC| / F`. Every G94 sets the feed rate to 0 (an `F` in
//!   the same block then sets it), as `rs274` does.
//! - **G93**, inverse time. `F` on a block means the block takes `T = 1 / F` minutes.
//!   An `F` is required on every G1, G2 and G3 block (modal ones included) and is not
//!   carried over; G0 is unaffected. `F` is in 1/min whatever the length units.
//!
//! The tip feed is then `L / T` with `L` the length of the tip's path over the part
//! (the sum over the pieces of a five-axis move, so that the pieces' times add up to
//! `T`). Where the machine's `X Y Z` map rigidly to the part frame (no rotary motion),
//! G94 gives the tip exactly `F`. A block whose tip does not move over the part (a turn
//! of the tool about its tip) has no length to carry a time: its feed is 0, and a time
//! estimate from motion lengths leaves it out.

use swarf_geom::tol::LENGTH_EPS;

/// How the feed of one motion block is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlockFeed {
    /// A rapid (G0): no feed.
    Rapid,
    /// Units per minute (G94).
    PerMinute {
        /// Along the `X Y Z` path, mm/min.
        linear: f64,
        /// Along the rotary axes when only they move, degrees/min.
        rotary: f64,
    },
    /// Inverse time (G93): the block takes `1 / f` minutes.
    InverseTime(f64),
}

impl BlockFeed {
    /// The feed of the tool tip, mm/min, for a block whose tip travels `tip_length` mm
    /// over the part while the machine's `X Y Z` travel `linear` mm and its rotary axes
    /// `rotary` degrees (the Euclidean norm of their steps); 0 for rapids and for
    /// blocks whose tip does not move (module docs).
    ///
    /// # Units
    /// mm, degrees, mm/min.
    ///
    /// # Example
    /// ```
    /// use swarf_nc::read::feed::BlockFeed;
    /// // G93 F20: a 5 mm block in 1/20 minute is 100 mm/min.
    /// assert_eq!(BlockFeed::InverseTime(20.0).tip_feed(5.0, 5.0, 0.0), 100.0);
    /// // G94 F300 on a pure turn of 30 degrees: 0.1 minute; the tip travels 2 mm.
    /// let f = BlockFeed::PerMinute { linear: 300.0, rotary: 300.0 };
    /// assert!((f.tip_feed(2.0, 0.0, 30.0) - 20.0).abs() < 1e-12);
    /// ```
    pub fn tip_feed(&self, tip_length: f64, linear: f64, rotary: f64) -> f64 {
        let minutes = match *self {
            BlockFeed::Rapid => return 0.0,
            BlockFeed::PerMinute { linear: f, .. } if rotary == 0.0 => return f,
            BlockFeed::PerMinute { linear: f, .. } if linear > 0.0 => linear / f,
            BlockFeed::PerMinute { rotary: f, .. } => rotary / f,
            BlockFeed::InverseTime(f) => 1.0 / f,
        };
        if tip_length > LENGTH_EPS && minutes.is_finite() && minutes > 0.0 {
            tip_length / minutes
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn per_minute_without_rotary_motion_is_the_programmed_feed() {
        let f = BlockFeed::PerMinute {
            linear: 250.0,
            rotary: 10.0,
        };
        // A rigid map: whatever the tip length, the feed is F.
        assert_eq!(f.tip_feed(3.0, 3.0, 0.0), 250.0);
        assert_eq!(BlockFeed::Rapid.tip_feed(3.0, 3.0, 1.0), 0.0);
    }

    #[test]
    fn per_minute_with_rotary_motion_times_the_machine_path() {
        let f = BlockFeed::PerMinute {
            linear: 100.0,
            rotary: 100.0 / 25.4,
        };
        // 10 mm of X Y Z at 100 mm/min: 0.1 min; the tip travels 15 mm.
        assert!((f.tip_feed(15.0, 10.0, 45.0) - 150.0).abs() < 1e-12);
        // Only rotary: 45 degrees at 100/25.4 degrees/min (F100 in G20).
        let minutes = 45.0 / (100.0 / 25.4);
        assert!((f.tip_feed(15.0, 0.0, 45.0) - 15.0 / minutes).abs() < 1e-12);
    }

    #[test]
    fn inverse_time_is_length_over_block_time() {
        let f = BlockFeed::InverseTime(4.0);
        assert!((f.tip_feed(7.5, 0.0, 12.0) - 30.0).abs() < 1e-12);
        // A turn about the tip carries no time.
        assert_eq!(f.tip_feed(0.0, 0.0, 12.0), 0.0);
    }
}
