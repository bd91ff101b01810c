//! `--dump DIR`: a frame's simulation as files for outside tools (numpy, tools/plot):
//! h0.npy (complex64, K×N×N; FFT model only), displacement.npy and normals.npy (float32,
//! K×N×N×4), spray.npy (float32, P×12, the spray's live particles; with spray), wake.npy
//! (float32, N×N, the wake's height, rows along z; with `--boat`) and params.json, which says
//! what they hold and how they were made.

use std::sync::Arc;

use serde_json::{json, Value};

use super::foam;
use super::gerstner;
use super::simulation::Simulation;
use super::spectrum::{self, G};
use super::stats::npy;
use crate::gpu::Context;

/// The files of slot `slot` (its frame done on the GPU), at simulation time `t`: (name, bytes).
pub fn files(
    sim: &Simulation,
    ctx: &Arc<Context>,
    slot: usize,
    t: f64,
) -> anyhow::Result<Vec<(&'static str, Vec<u8>)>> {
    let (n, k) = (sim.settings.fft_size, sim.cascades.len());
    let (displacement, normals) = sim.read_back(ctx, slot)?;
    let h0 = sim.download_h0(ctx)?;
    let mut files = Vec::new();
    if let Some(h0) = h0 {
        files.push(("h0.npy", npy("<c8", &[k, n, n], &h0)));
    }
    files.push((
        "displacement.npy",
        npy("<f4", &[k, n, n, 4], bytemuck::cast_slice(&displacement)),
    ));
    files.push((
        "normals.npy",
        npy("<f4", &[k, n, n, 4], bytemuck::cast_slice(&normals)),
    ));
    if let Some(particles) = sim.spray_particles(ctx, slot)? {
        let bytes: &[u8] = bytemuck::cast_slice(&particles);
        files.push(("spray.npy", npy("<f4", &[particles.len() / 12, 12], bytes)));
    }
    if let Some(texels) = sim.read_wake(ctx, slot)? {
        let n = super::wake::GRID_N;
        let heights: Vec<f32> = texels.iter().map(|t| t[0]).collect();
        let bytes: &[u8] = bytemuck::cast_slice(&heights);
        files.push(("wake.npy", npy("<f4", &[n, n], bytes)));
    }
    let params = params(sim, t);
    files.push((
        "params.json",
        (serde_json::to_string_pretty(&params)? + "\n").into_bytes(),
    ));
    Ok(files)
}

/// params.json: the settings, the cascades' layout and what the arrays' indices mean.
pub fn params(sim: &Simulation, t: f64) -> Value {
    let s = &sim.settings;
    let common = json!({
        "t": t,
        "spectrum": s.sea.spectrum.name(),
        "wind_speed_m_s": s.sea.wind_speed_m_s,
        "wind_dir_deg": s.sea.wind_dir_deg,
        "fetch_km": s.sea.fetch_km,
        "depth_m": s.sea.depth_m,
        "fft_size": s.fft_size,
        "cascades": sim.cascades.len(),
        "patch_sizes_m": sim.cascades.iter().map(|c| c.patch_m).collect::<Vec<_>>(),
        "k_bands_rad_m": sim.cascades.iter().map(|c| [c.k_min, if c.k_max.is_finite() { c.k_max } else { f64::MAX }]).collect::<Vec<_>>(),
        "choppiness": s.choppiness,
        "seed": s.seed,
        // The surface repeats exactly with this period: every ω is a whole multiple of the
        // quantum (spectrum::REPEAT_PERIOD_S).
        "repeat_period_s": spectrum::REPEAT_PERIOD_S,
        "omega_quantum_rad_s": spectrum::omega_quantum(),
        // foam = max(foam_prev·exp(−dt/decay), clamp((threshold − J_s)·gain, 0, 1)) in layer 0,
        // J_s the whole surface's Jacobian (src/ocean/foam.rs).
        "foam": {
            "threshold": sim.foam_threshold,
            "decay_s": foam::DECAY_S,
            "gain": foam::GAIN,
            "persistence": foam::PERSISTENCE,
            "monahan_fraction": foam::monahan_fraction(s.sea.wind_speed_m_s),
        },
        // Over the island's shallows the water draws these waves scaled by the local depth
        // (src/ocean/shore.rs): shoaling at the mean frequency, breaking at Hs = γ·d.
        "shore": {
            "hs_m": sim.sea_moments.hs_m,
            "mean_omega_rad_s": sim.sea_moments.mean_omega,
            "breaker_index": crate::shared::BREAKER_INDEX,
        },
        // spray.npy's rows (with spray): one puff of drops each (src/ocean/spray.rs).
        "spray": {
            "on": sim.spray().is_some(),
            "columns": ["x_m", "y_m", "z_m", "age_s", "vx_m_s", "vy_m_s", "vz_m_s", "drop_radius_m", "water_below_m", "unused", "unused", "unused"],
            "min_wind_m_s": super::spray::MIN_WIND_M_S,
            "roughness_m": super::spray::roughness_m(s.sea.wind_speed_m_s),
        },
        // The sea surface's mean-square slope (Cox & Munk 1954 at the wind) and what each
        // cascade's waves carry of it (Σ k²E); the sun's glitter takes the rest (water.frag).
        // By direction (`moments::slope_along`): [Σ(k_x² − k_z²)E, Σk_x k_z E] of the whole
        // sea (Cox & Munk's upwind excess) and of each cascade. `short`: what of `resolved`
        // is in waves shorter than 1 m (a natural slick damps them, render/slicks.rs).
        "slopes": {
            "mean_square_slope": sim.mean_square_slope(),
            "resolved": &sim.sea_moments.slope_variance[..sim.cascades.len()],
            "short": &sim.sea_moments.short_slope_variance[..sim.cascades.len()],
            "anisotropy": sim.slope_anisotropy(),
            "resolved_anisotropy": &sim.sea_moments.slope_anisotropy[..sim.cascades.len()],
        },
    });
    let model = match sim.gerstner_waves() {
        None => json!({
            "waves": "fft",
            "g": G,
            "layout": "h0[c, m, n] has k = (2π(n − N/2), 2π(m − N/2)) / L_c; displacement and normals [c, m, n] are at x = n·L_c/N, z = m·L_c/N; normals = (−n_x/n_y, −n_z/n_y, J, foam) of the displaced surface's normal, J the cascade's own; foam in layer 0 only, from the whole surface's Jacobian",
        }),
        Some(waves) => json!({
            "waves": "gerstner",
            "g": gerstner::G_SEED,
            "origin_m": sim.origin_m(),
            "waves_table": waves
                .iter()
                .map(|w| json!({"kx": w.kx, "kz": w.kz, "amplitude": w.amplitude, "phase": w.phase, "steepness": w.steepness}))
                .collect::<Vec<_>>(),
            "layout": "displacement and normals [0, m, n] are at (α, β) = origin_m + (n, m)·window/N; displacement = (x − α, y, z − β, 0)",
        }),
    };
    let mut out = common;
    for (key, value) in model.as_object().into_iter().flatten() {
        out[key] = value.clone();
    }
    if let (Some((origin, spacing)), Some(boat)) = (sim.wake.place_of(), sim.wake.boat()) {
        // wake.npy[j, i] is the wake's height at x = origin_m[0] + i·spacing_m,
        // z = origin_m[1] + j·spacing_m (src/ocean/wake.rs).
        out["wake"] = json!({
            "origin_m": origin,
            "spacing_m": spacing,
            "n": super::wake::GRID_N,
            "model": "eWave (Tessendorf 2014): exact Fourier step with ω = √(g k tanh k d), a Gaussian pressure patch for the hull, an absorbing layer at the edge",
            "boat": {
                "position": boat.position(t),
                "speed_m_s": boat.speed_m_s,
                "heading_deg": boat.heading_deg,
                "course": boat.course(),
                "hull_length_m": super::wake::HULL_LENGTH_M,
                "hull_beam_m": super::wake::HULL_BEAM_M,
                "draft_m": super::wake::DRAFT_M,
                "froude": boat.froude(),
            },
            "sponge_texels": super::wake::SPONGE_TEXELS,
        });
    }
    out
}
