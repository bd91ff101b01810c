//! [`Clock`]: simulation time from a run's progress (frames × `--dt`, or wall seconds), scaled
//! by `--time-scale` and paused by the overlay. A change of scale continues from the time
//! reached, so the waves never jump.

/// Simulation time as a function of progress.
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    /// Simulation time at progress `base_at`.
    base_s: f64,
    base_at: f64,
    scale: f64,
    paused: bool,
}

impl Clock {
    /// Time `start_s` at progress 0, advancing `scale` seconds per unit of progress.
    pub fn new(start_s: f64, scale: f64) -> Clock {
        Clock {
            base_s: start_s,
            base_at: 0.0,
            scale,
            paused: false,
        }
    }

    /// The simulation time at `progress` (frames × dt, or wall seconds since the start).
    pub fn at(&self, progress: f64) -> f64 {
        if self.paused {
            self.base_s
        } else {
            self.base_s + (progress - self.base_at) * self.scale
        }
    }

    /// From `progress` on, advance at `scale` (stopped while `paused`).
    pub fn set(&mut self, progress: f64, scale: f64, paused: bool) {
        if scale == self.scale && paused == self.paused {
            return;
        }
        self.base_s = self.at(progress);
        self.base_at = progress;
        self.scale = scale;
        self.paused = paused;
    }
}

#[cfg(test)]
mod tests {
    use super::Clock;

    #[test]
    fn a_change_of_scale_continues_from_the_time_reached() {
        let mut c = Clock::new(10.0, 1.0);
        assert_eq!(c.at(2.0), 12.0);
        c.set(2.0, 3.0, false);
        assert_eq!(c.at(2.0), 12.0);
        assert_eq!(c.at(4.0), 18.0);
        c.set(4.0, 3.0, true);
        assert_eq!(c.at(9.0), 18.0);
        c.set(9.0, 3.0, false);
        assert_eq!(c.at(10.0), 21.0);
    }
}
