//! The sea against the ocean literature: each row a quantity, the paper's value, ours and the
//! tolerance it is held to. The literature's formulas are written out here independently of
//! `spectrum.rs` and `shore.rs` (the unit tests there use them too); tests/accuracy.rs adds the GPU's rows
//! (whitecaps), asserts every row and prints README's "Physical accuracy" table.

use std::f64::consts::PI;

use super::moments::{SeaMoments, DEEP_WATER_M};
use super::shore::{shoaling, shore_waves};
use super::spectrum::{
    donelan_banner, donelan_banner_beta, frequency_spectrum, peak_omega, SeaState, SpectrumKind, G,
};

/// One line of the table.
#[derive(Clone, Debug)]
pub struct Row {
    pub quantity: String,
    /// The source and its value, as text.
    pub literature: String,
    pub literature_value: f64,
    pub ours: f64,
    /// Largest accepted |ours/literature − 1| (relative), or the bound's description.
    pub tolerance: Tolerance,
}

#[derive(Clone, Copy, Debug)]
pub enum Tolerance {
    /// |ours / literature − 1| ≤ this.
    Relative(f64),
    /// literature / this ≤ ours ≤ literature · this.
    Factor(f64),
    /// ours < this.
    Below(f64),
}

impl Row {
    pub fn holds(&self) -> bool {
        match self.tolerance {
            Tolerance::Relative(r) => (self.ours / self.literature_value - 1.0).abs() <= r,
            Tolerance::Factor(f) => {
                self.ours >= self.literature_value / f && self.ours <= self.literature_value * f
            }
            Tolerance::Below(b) => self.ours < b,
        }
    }

    /// The row in README's table: quantity | literature | ours | tolerance.
    pub fn markdown(&self, digits: usize) -> String {
        let tolerance = match self.tolerance {
            Tolerance::Relative(r) => format!("±{} %", r * 100.0),
            Tolerance::Factor(f) => format!("×{f}"),
            Tolerance::Below(b) => format!("< {b}"),
        };
        format!(
            "| {} | {} | {:.*} | {} |",
            self.quantity, self.literature, digits, self.ours, tolerance
        )
    }
}

/// Banner's (1990) spreading width β = 10^(−0.4 + 0.8393 r^−1.134) above r = ω/ω_p = 1.6,
/// since exp(−0.567 ln r²) = r^−1.134 (REFERENCES.md; Horvath 2015).
pub fn banner_beta(r: f64) -> f64 {
    10f64.powf(-0.4 + 0.8393 * r.powf(-1.134))
}

/// Significant wave height 4√m0 (m) and peak period 2π/ω_p (s) of `sea`'s frequency spectrum,
/// from a midpoint sum over 0 < ω < 20 rad/s (the tail above holds < 0.1 % of m0 for U10 ≥ 3 m/s)
/// and the largest sample.
pub fn height_and_peak_period(sea: &SeaState) -> (f64, f64) {
    let (n, top) = (400_000, 20.0);
    let dw = top / n as f64;
    let (mut m0, mut peak) = (0.0, (0.0, 0.0));
    for i in 0..n {
        let w = (i as f64 + 0.5) * dw;
        let s = frequency_spectrum(sea, w);
        m0 += s * dw;
        if s > peak.1 {
            peak = (w, s);
        }
    }
    (4.0 * m0.sqrt(), 2.0 * PI / peak.0)
}

/// The fully developed sea of Pierson & Moskowitz (1964): Hs = 0.21 U19.5²/g, ω_p = 0.877 g/U19.5,
/// U19.5 = 1.026 U10. Returns (Hs m, T_p s).
pub fn pierson_moskowitz_literature(u10: f64) -> (f64, f64) {
    let u195 = 1.026 * u10;
    (0.21 * u195 * u195 / G, 2.0 * PI * u195 / (0.877 * G))
}

/// JONSWAP (Hasselmann et al. 1973): Hs = 1.6·10⁻³ X^½ U10²/g and ω_p = 22 (g²/(U10 F))^⅓,
/// capped by the fully developed sea of Pierson & Moskowitz (1964). Returns (Hs m, T_p s).
pub fn jonswap_literature(u10: f64, fetch_km: f64) -> (f64, f64) {
    let f = fetch_km * 1000.0;
    let x = G * f / (u10 * u10);
    let (hs_pm, tp_pm) = pierson_moskowitz_literature(u10);
    let hs = (1.6e-3 * x.sqrt() * u10 * u10 / G).min(hs_pm);
    let tp = (2.0 * PI / (22.0 * (G * G / (u10 * f)).cbrt())).min(tp_pm);
    (hs, tp)
}

/// Kitaigorodskii's depth factor as Bouws et al. (1985) give it (Thompson & Vincent's fit):
/// ω_h = ω √(h/g); Φ = ω_h²/2 (ω_h ≤ 1), 1 − (2 − ω_h)²/2 (1 < ω_h < 2), 1 (ω_h ≥ 2).
pub fn bouws_phi(omega: f64, depth_m: f64) -> f64 {
    let wh = omega * (depth_m / G).sqrt();
    match wh {
        w if w <= 1.0 => w * w / 2.0,
        w if w < 2.0 => 1.0 - (2.0 - w) * (2.0 - w) / 2.0,
        _ => 1.0,
    }
}

/// Hs of `sea`'s deep-water spectrum times Bouws et al.'s Φ at `depth_m` (m).
pub fn tma_literature_height(sea: &SeaState, depth_m: f64) -> f64 {
    let (n, top) = (400_000, 20.0);
    let dw = top / n as f64;
    let m0: f64 = (0..n)
        .map(|i| {
            let w = (i as f64 + 0.5) * dw;
            frequency_spectrum(sea, w) * bouws_phi(w, depth_m) * dw
        })
        .sum();
    4.0 * m0.sqrt()
}

/// Share of the Pierson–Moskowitz sea's energy at 2.5 ≤ ω/ω_p ≤ 4 that travels within 90° of
/// the wind: (the code's spreading, Banner's β written out here).
pub fn downwind_share() -> (f64, f64) {
    let sea = SeaState {
        spectrum: SpectrumKind::PiersonMoskowitz,
        ..SeaState::default()
    };
    let wp = peak_omega(&sea);
    let (nw, nt) = (300, 2000);
    let (mut down, mut total, mut expected_down, mut expected_total) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..nw {
        let r = 2.5 + 1.5 * (i as f64 + 0.5) / nw as f64;
        let s = frequency_spectrum(&sea, r * wp);
        // The code's D integrated over the downwind half-plane (midpoint rule).
        let half: f64 = (0..nt)
            .map(|j| {
                let theta = -PI / 2.0 + PI * (j as f64 + 0.5) / nt as f64;
                donelan_banner(r * wp, wp, theta) * PI / nt as f64
            })
            .sum();
        down += s * half;
        total += s;
        // For one ω the share is tanh(βπ/2)/tanh(βπ) (the integral of the sech² spreading).
        let beta = banner_beta(r);
        let weight = r.powi(-5) * (-1.25 / r.powi(4)).exp();
        expected_down += weight * (beta * PI / 2.0).tanh() / (beta * PI).tanh();
        expected_total += weight;
    }
    (down / total, expected_down / expected_total)
}

/// The CPU-side rows: spreading, Pierson–Moskowitz, JONSWAP, TMA.
pub fn spectrum_rows() -> Vec<Row> {
    let mut rows = Vec::new();
    for r in [2.5, 4.0] {
        rows.push(Row {
            quantity: format!("spreading width β at ω/ω_p = {r}"),
            literature: format!("Banner (1990): {:.3}", banner_beta(r)),
            literature_value: banner_beta(r),
            ours: donelan_banner_beta(r),
            tolerance: Tolerance::Relative(0.002),
        });
    }
    let (share, _) = downwind_share();
    rows.push(Row {
        quantity: "downwind energy share, ω/ω_p 2.5–4".into(),
        literature: "Banner (1990) via Horvath (2015): 0.82".into(),
        literature_value: 0.82,
        ours: share,
        tolerance: Tolerance::Relative(0.02),
    });
    let pm = SeaState {
        spectrum: SpectrumKind::PiersonMoskowitz,
        ..SeaState::default()
    };
    let (hs, tp) = height_and_peak_period(&pm);
    let (hs_pm, tp_pm) = pierson_moskowitz_literature(pm.wind_speed_m_s);
    rows.push(Row {
        quantity: "Pierson–Moskowitz Hs, U10 = 10 m/s (m)".into(),
        literature: format!("0.21 U19.5²/g: {hs_pm:.3}"),
        literature_value: hs_pm,
        ours: hs,
        tolerance: Tolerance::Relative(0.02),
    });
    rows.push(Row {
        quantity: "Pierson–Moskowitz T_p, U10 = 10 m/s (s)".into(),
        literature: format!("2π U19.5/(0.877 g): {tp_pm:.3}"),
        literature_value: tp_pm,
        ours: tp,
        tolerance: Tolerance::Relative(0.02),
    });
    let sea = SeaState::default();
    let (hs, _) = height_and_peak_period(&sea);
    let (hs_lit, _) = jonswap_literature(sea.wind_speed_m_s, sea.fetch_km);
    rows.push(Row {
        quantity: "JONSWAP Hs, 10 m/s over 100 km (m)".into(),
        literature: format!("Hasselmann et al. (1973) growth law: {hs_lit:.3}"),
        literature_value: hs_lit,
        ours: hs,
        tolerance: Tolerance::Relative(0.02),
    });
    // The worst ratio over the wind/fetch grid, as a ratio to 1.
    let mut worst = 1.0f64;
    for u10 in [5.0, 10.0, 15.0, 25.0] {
        for fetch_km in [10.0, 30.0, 100.0, 300.0, 1000.0] {
            let sea = SeaState {
                wind_speed_m_s: u10,
                fetch_km,
                ..SeaState::default()
            };
            let ratio = height_and_peak_period(&sea).0 / jonswap_literature(u10, fetch_km).0;
            if (ratio - 1.0).abs() > (worst - 1.0).abs() {
                worst = ratio;
            }
        }
    }
    rows.push(Row {
        quantity: "JONSWAP Hs / growth law (capped at PM), worst of U10 5–25 m/s × F 10–1000 km"
            .into(),
        literature: "1".into(),
        literature_value: 1.0,
        ours: worst,
        tolerance: Tolerance::Relative(0.02),
    });
    for depth in [10.0, 5.0] {
        let shallow = SeaState {
            depth_m: Some(depth),
            ..SeaState::default()
        };
        let lit = tma_literature_height(&SeaState::default(), depth);
        rows.push(Row {
            quantity: format!("TMA Hs at {depth} m depth, default sea (m)"),
            literature: format!("JONSWAP × Bouws et al. (1985) Φ: {lit:.3}"),
            literature_value: lit,
            ours: height_and_peak_period(&shallow).0,
            tolerance: Tolerance::Relative(0.005),
        });
    }
    rows
}

/// A deep-water sea of one frequency (an 8 s wave, Hs 1 m) for the shoaling rows.
fn shoaling_sea() -> (SeaMoments, f64) {
    let omega = 2.0 * PI / 8.0;
    let sea = SeaMoments {
        hs_m: 1.0,
        mean_omega: omega,
        depth_m: DEEP_WATER_M,
        slope_variance: [0.0; 4],
        slope_anisotropy: [[0.0; 2]; 4],
        curvature_variance: [0.0; 4],
        short_slope_variance: [0.0; 4],
        slope_mip_gain: [[1.0; 4]; super::moments::MIP_LEVELS],
    };
    (sea, 2.0 * PI * G / (omega * omega)) // and its deep-water wavelength L₀
}

/// Our shoaling coefficient's minimum over depth, and the relative depth d/L₀ where it is
/// (scanned in steps of 0.0005 L₀).
pub fn shoaling_minimum() -> (f64, f64) {
    let (sea, l0) = shoaling_sea();
    (1..1000)
        .map(|i| i as f64 / 2000.0)
        .map(|r| (shoaling(&sea, r * l0), r))
        .fold((f64::MAX, 0.0), |a, b| if b.0 < a.0 { b } else { a })
}

/// Green's law, the shallow-water limit of linear shoaling from deep water: K_s = (4 k₀ d)^−¼
/// (energy flux E·√(g d) = E₀·g/(2ω)).
pub fn green_law(k0d: f64) -> f64 {
    (4.0 * k0d).powf(-0.25)
}

/// Our shoaling coefficient at k₀d.
pub fn shoaling_at(k0d: f64) -> f64 {
    let (sea, l0) = shoaling_sea();
    shoaling(&sea, k0d * l0 / (2.0 * PI))
}

/// The rows of the waves over the shallows (src/ocean/shore.rs).
pub fn shore_rows() -> Vec<Row> {
    let (min_ks, at) = shoaling_minimum();
    let k0d = 1e-3;
    // A 3 m sea over 1 m of water: broken down to the breaker index.
    let (sea, _) = shoaling_sea();
    let surf = shore_waves(&SeaMoments { hs_m: 3.0, ..sea }, 1.0).hs_m;
    vec![
        Row {
            quantity: format!("linear shoaling K_s, minimum (at d/L₀ = {at:.3})"),
            literature: "Dean & Dalrymple (1991): 0.913 at d/L₀ ≈ 0.15".into(),
            literature_value: 0.913,
            ours: min_ks,
            tolerance: Tolerance::Relative(0.002),
        },
        Row {
            quantity: "linear shoaling K_s at k₀d = 10⁻³".into(),
            literature: format!("Green's law (4k₀d)^−¼: {:.3}", green_law(k0d)),
            literature_value: green_law(k0d),
            ours: shoaling_at(k0d),
            tolerance: Tolerance::Relative(0.01),
        },
        Row {
            quantity: "surf zone Hs / depth (3 m sea over 1 m)".into(),
            literature: "McCowan (1894) breaker index: 0.78".into(),
            literature_value: 0.78,
            ours: surf,
            tolerance: Tolerance::Relative(0.001),
        },
    ]
}
