//! What the strategies take from a job: its tables turned into each strategy's
//! parameter struct (angles from degrees to radians here, at the input edge).

use super::{Direction, Job};
use swarf_path::params::{Finish, IsoParams, ParamDir, RasterParams};
use swarf_path::roughing::RoughingParams;
use swarf_path::steep_shallow::SteepShallowParams;
use swarf_path::waterline::{Milling, WaterlineParams};
use swarf_rest::RegionParams;

impl Job {
    /// The feed direction angle in radians.
    pub fn angle_rad(&self) -> f64 {
        self.strategy.angle.to_radians()
    }

    /// What every strategy takes from the job: tool, tolerance, zigzag, feeds,
    /// linking.
    pub fn finish(&self) -> Finish {
        Finish {
            tool: self.tool,
            tolerance: self.strategy.tolerance,
            zigzag: self.strategy.zigzag,
            feeds: self.feeds,
            linking: self.linking,
        }
    }

    /// The parameters of the iso strategies.
    pub fn iso_params(&self) -> IsoParams {
        let s = &self.strategy;
        IsoParams {
            finish: self.finish(),
            scallop: s.scallop,
            stepover: s.stepover,
            direction: self.param_dir(),
            angle: self.angle_rad(),
            start: s.start,
        }
    }

    /// The parameter the iso passes follow (u unless `direction = "v"`).
    pub fn param_dir(&self) -> ParamDir {
        match self.strategy.direction {
            Some(Direction::V) => ParamDir::V,
            _ => ParamDir::U,
        }
    }

    /// The milling direction (climb unless `direction = "conventional"`).
    pub fn milling(&self) -> Milling {
        match self.strategy.direction {
            Some(Direction::Conventional) => Milling::Conventional,
            _ => Milling::Climb,
        }
    }

    /// The parameters of the waterline strategy (steep angle 45 and flat angle 15
    /// degrees unless given).
    pub fn waterline_params(&self) -> WaterlineParams {
        let s = &self.strategy;
        WaterlineParams {
            finish: self.finish(),
            scallop: s.scallop,
            level_step: s.level_step,
            steep_angle: s.steep_angle.unwrap_or(45.0).to_radians(),
            flat_angle: s.flat_angle.unwrap_or(15.0).to_radians(),
            adaptive: s.adaptive,
            sampling: s.sampling,
            direction: self.milling(),
            top: None,
            bottom: None,
        }
    }

    /// The parameters of Z-level roughing (module doc of [`swarf_path::roughing`]).
    pub fn roughing_params(&self) -> RoughingParams {
        let s = &self.strategy;
        let base = RoughingParams::new(self.finish());
        RoughingParams {
            allowance: s.allowance.unwrap_or(base.allowance),
            step_down: s.step_down.unwrap_or(base.step_down),
            max_engagement: s
                .max_engagement
                .map_or(base.max_engagement, f64::to_radians),
            ramp_angle: s.ramp_angle.map_or(base.ramp_angle, f64::to_radians),
            sampling: s.sampling,
            ..base
        }
    }

    /// The parameters of steep-and-shallow finishing (steep angle 40 and flat angle
    /// 15 degrees unless given; the overlap band is `overlap`).
    pub fn steep_shallow_params(&self) -> SteepShallowParams {
        let s = &self.strategy;
        let base = SteepShallowParams::new(self.finish(), s.scallop.unwrap_or(f64::NAN));
        SteepShallowParams {
            steep_angle: s.steep_angle.map_or(base.steep_angle, f64::to_radians),
            flat_angle: s.flat_angle.map_or(base.flat_angle, f64::to_radians),
            overlap: s.overlap,
            angle: self.angle_rad(),
            direction: self.milling(),
            sampling: s.sampling,
            ..base
        }
    }

    /// The parameters of the raster strategy.
    pub fn raster_params(&self) -> RasterParams {
        let s = &self.strategy;
        RasterParams {
            finish: self.finish(),
            scallop: s.scallop,
            stepover: s.stepover,
            angle: self.angle_rad(),
            start: s.start,
            boundary: s.boundary,
            max_ramp: s.max_ramp.map(f64::to_radians),
            max_slope: s.max_slope.map(f64::to_radians),
        }
    }
}

impl Job {
    /// The region parameters of a cleanup job (threshold: the tolerance plus the
    /// scallop height unless given).
    pub fn region_params(&self) -> RegionParams {
        let s = &self.strategy;
        RegionParams {
            threshold: s
                .threshold
                .unwrap_or(s.tolerance + s.scallop.unwrap_or(0.0)),
            merge: s.merge,
            overlap: s.overlap,
            min_area: s.min_area,
            smoothness: s.smoothness,
        }
    }
}
