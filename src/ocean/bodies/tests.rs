//! The physics checks of issue 35, on analytic surfaces (the GPU's height queries feed the same
//! code in a run; tests/queries.rs checks those against the CPU reference).

use super::*;

/// Still water: height 0, at rest.
fn still(_: usize, _: [f64; 2], _: f64) -> [f64; 2] {
    [0.0, 0.0]
}

fn cube(relative_density: f64, y: f64) -> BodyDesc {
    BodyDesc {
        shape: Shape::Box([0.5, 0.5, 0.5]),
        relative_density,
        position: [3.0, y, -2.0],
        heading_deg: 20.0,
    }
}

/// Runs `fleet` to `seconds` on `water`, returning each step's first body's (time, height).
fn run(
    fleet: &mut Fleet,
    seconds: f64,
    water: &mut dyn FnMut(usize, [f64; 2], f64) -> [f64; 2],
) -> Vec<(f64, f64)> {
    let mut track = Vec::new();
    let frame = 1.0 / 60.0;
    fleet.advance(0.0, water);
    let mut t = 0.0;
    while t < seconds {
        t += frame;
        fleet.advance(t, water);
        track.push((t, fleet.bodies[0].position.y));
    }
    track
}

#[test]
fn a_box_of_half_the_waters_density_floats_half_under() {
    // A 2 × 0.5 × 2 m box of relative density 0.5 dropped from 0.3 m above its floating
    // height: after 30 s its centre is at the waterline (half its height under), within 2 % of
    // the height. (A cube would roll over: between relative densities 0.21 and 0.79 a cube is
    // unstable upright, its metacentre below its centre of gravity, and floats edge up.)
    for density in [0.5, 0.25, 0.75] {
        let slab = BodyDesc {
            shape: Shape::Box([1.0, 0.25, 1.0]),
            ..cube(density, 0.3)
        };
        let mut fleet = Fleet::new(&[slab]);
        run(&mut fleet, 30.0, &mut still);
        let b = &fleet.bodies[0];
        // The draft is density × height; the centre sits half a height above the keel.
        let draft = (0.25 - b.position.y) / 0.5;
        eprintln!("density {density}: draft {draft:.4} of the height");
        assert!(
            (draft - density).abs() < 0.02,
            "density {density}: draft {draft:.4} of the height, expected {density} (±0.02)"
        );
        assert!(b.velocity.length() < 1e-3, "still moving: {:?}", b.velocity);
        let tilt = (b.orientation * DVec3::Y)
            .angle_between(DVec3::Y)
            .to_degrees();
        assert!(tilt < 0.5, "tilted {tilt:.2}°");
    }
}

#[test]
fn a_box_denser_than_water_sinks_at_its_terminal_speed() {
    // A 1 m cube of 1.2 sinks; once under, its speed v settles where the drag holds its net
    // weight: ρ_w V · LINEAR_DAMPING_PER_S · v + ½ ρ_w C_d A v² = 0.2 ρ_w g V (A = 1 m²).
    let mut fleet = Fleet::new(&[cube(1.2, 0.0)]);
    let track = run(&mut fleet, 10.0, &mut still);
    let end = track.last().unwrap().1;
    assert!(
        end < -5.0,
        "a density-1.2 box sank only to {end:.2} m in 10 s"
    );
    let (a, b, c) = (
        0.5 * WATER_DENSITY * DRAG_COEFFICIENT,
        WATER_DENSITY * LINEAR_DAMPING_PER_S,
        -0.2 * WATER_DENSITY * GRAVITY,
    );
    let terminal = (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
    let v = -fleet.bodies[0].velocity.y;
    eprintln!("sinking at {v:.3} m/s, terminal {terminal:.3} m/s");
    assert!(
        (v / terminal - 1.0).abs() < 0.02,
        "sinking at {v:.3} m/s, terminal speed {terminal:.3} m/s (±2 %)"
    );
}

#[test]
fn mass_and_inertia_are_the_shapes() {
    // A box's voxels hold its mass, and its inertia is a solid box's, m (b² + c²) / 12 about
    // each axis, exactly (a voxel's own inertia plus the parallel axes sum to it).
    let b = Body::new(BodyDesc {
        heading_deg: 0.0,
        ..cube(0.5, 0.0)
    });
    let m = 0.5 * WATER_DENSITY;
    assert!((b.mass() - m).abs() < 1e-9 * m);
    for k in 0..3 {
        let i = b.inertia.col(k)[k];
        assert!(
            (i - m / 6.0).abs() < 1e-9 * m,
            "I[{k}] {i} against {}",
            m / 6.0
        );
    }
    // A ballasted buoy: its centre of mass lies below its middle, where the ballast weighs:
    // bottom layer 10 shares, the two above 1 each, at −h/3, 0 and h/3: −9/12 · h/3.
    let buoy = Body::new(BodyDesc {
        shape: Shape::Buoy([0.5, 1.2]),
        relative_density: 0.4,
        position: [0.0; 3],
        heading_deg: 0.0,
    });
    let below = -buoy.centroid.y;
    let expected = 9.0 / 12.0 * 0.4;
    assert!(
        (below - expected).abs() < 1e-9,
        "buoy's mass centre {below} m below its middle, expected {expected}"
    );
    // Its roll inertia about the mass centre is less than a uniform one's about its middle.
    let uniform = buoy.mass() * (1.0 + 1.2 * 1.2) / 12.0;
    assert!(buoy.inertia.col(0)[0] < uniform);
}

#[test]
fn the_most_bodies_fit_the_height_queries() {
    let fleet = Fleet::scattered(crate::shared::MAX_BODIES as usize, [0.0; 2], 8.0);
    let columns = fleet.column_count();
    assert!(
        columns <= crate::ocean::simulation::MAX_QUERIES,
        "{columns} columns over the {} queries a frame",
        crate::ocean::simulation::MAX_QUERIES
    );
}

/// A long-crested sinusoid of amplitude `a` and wavelength `lambda` travelling along x (deep
/// water): (height, ∂h/∂t).
fn swell(a: f64, lambda: f64) -> impl FnMut(usize, [f64; 2], f64) -> [f64; 2] {
    let k = std::f64::consts::TAU / lambda;
    let omega = (GRAVITY * k).sqrt();
    move |_, xz, t| {
        let phase = k * xz[0] - omega * t;
        [a * phase.cos(), a * omega * phase.sin()]
    }
}

/// Heave amplitude of the first body over the last `span` seconds of a `seconds` run.
fn heave_amplitude(track: &[(f64, f64)], span: f64) -> f64 {
    let end = track.last().unwrap().0;
    let tail: Vec<f64> = track
        .iter()
        .filter(|(t, _)| *t > end - span)
        .map(|(_, y)| *y)
        .collect();
    let (lo, hi) = tail
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), &y| (lo.min(y), hi.max(y)));
    (hi - lo) / 2.0
}

#[test]
fn heave_follows_a_long_swell_and_filters_short_waves() {
    // Long swell: λ = 100 m (period 8.0 s), 0.5 m amplitude, under a 2 × 0.5 × 2 m box: the
    // heave follows it (ratio ≈ 1; its natural period, about 1.3 s, is far shorter).
    let slab = BodyDesc {
        shape: Shape::Box([1.0, 0.25, 1.0]),
        ..cube(0.5, 0.0)
    };
    let mut fleet = Fleet::new(&[slab]);
    let track = run(&mut fleet, 60.0, &mut swell(0.5, 100.0));
    let long = heave_amplitude(&track, 16.0) / 0.5;
    // Short waves: λ = 1.5 m under a 4 × 1 × 4 m raft (8 columns a side, 0.5 m apart: three
    // phases per wavelength): the buoyancy averages out, and the waves' 1 s period is shorter
    // than the raft's heave period.
    let raft = BodyDesc {
        shape: Shape::Box([2.0, 0.5, 2.0]),
        heading_deg: 0.0,
        ..cube(0.5, 0.0)
    };
    let mut fleet = Fleet::new(&[raft]);
    let track = run(&mut fleet, 30.0, &mut swell(0.05, 1.5));
    let short = heave_amplitude(&track, 10.0) / 0.05;
    eprintln!("heave / wave amplitude: long swell {long:.3}, short waves {short:.4}");
    assert!(
        (long - 1.0).abs() < 0.1,
        "long swell: heave ratio {long:.3}, expected 1 ± 0.1"
    );
    assert!(
        short < 0.1,
        "short waves: heave ratio {short:.4}, expected < 0.1"
    );
}

#[test]
fn a_thousand_bodies_run_ten_thousand_steps_without_blowing_up() {
    // Boxes, hulls and buoys of 0.3–3 m and densities 0.2–0.9 on a sea of three crossing
    // swells; 10,000 steps (83 s). No NaN; every body stays near the surface and slow.
    let mut state = 7u64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let descs: Vec<BodyDesc> = (0..1000)
        .map(|i| {
            let s = 0.3 + 2.7 * next();
            let shape = match i % 3 {
                0 => Shape::Box([s / 2.0, s / 4.0, s / 3.0]),
                1 => Shape::Hull([s, s / 3.0, s / 5.0]),
                _ => Shape::Buoy([s / 4.0, s / 2.0]),
            };
            BodyDesc {
                shape,
                relative_density: 0.2 + 0.7 * next(),
                position: [200.0 * next(), 0.0, 200.0 * next()],
                heading_deg: 360.0 * next(),
            }
        })
        .collect();
    let waves = [(0.6, 60.0, 0.0), (0.3, 23.0, 1.1), (0.15, 9.0, -0.7)];
    let mut sea = |_: usize, xz: [f64; 2], t: f64| {
        let mut out = [0.0; 2];
        for (a, lambda, dir) in waves {
            let k = std::f64::consts::TAU / lambda;
            let omega = (GRAVITY * k).sqrt();
            let (s, c) = f64::sin_cos(dir);
            let phase = k * (c * xz[0] + s * xz[1]) - omega * t;
            out[0] += a * phase.cos();
            out[1] += a * omega * phase.sin();
        }
        out
    };
    let mut fleet = Fleet::new(&descs);
    assert!(fleet.column_count() <= 20_000);
    fleet.advance(0.0, &mut sea);
    let mut t = 0.0;
    while fleet.steps < 10_000 {
        t += 1.0 / 60.0;
        fleet.advance(t, &mut sea);
    }
    let mut worst_speed = 0.0f64;
    let mut worst_depth = 0.0f64;
    for b in &fleet.bodies {
        assert!(
            b.position.is_finite() && b.velocity.is_finite() && b.orientation.is_finite(),
            "{:?} went non-finite",
            b.desc
        );
        worst_speed = worst_speed.max(b.velocity.length());
        worst_depth = worst_depth.max(b.position.y.abs());
    }
    eprintln!("after 10,000 steps: fastest {worst_speed:.2} m/s, farthest from the mean level {worst_depth:.2} m");
    assert!(worst_speed < 5.0, "a body moves at {worst_speed:.1} m/s");
    assert!(
        worst_depth < 3.0,
        "a body is {worst_depth:.1} m from the mean level"
    );
}

#[test]
fn a_driven_boat_floats_on_the_water_not_in_its_own_trough() {
    // The wake's hull presses the water under it down by up to `wake::DRAFT_M` (1 m), and the
    // height queries answer with that trough in. Driven at 3 m/s over water that is only its
    // own static trough, the hull must float as high as the same hull on still water (within
    // 1 cm), not a trough's depth lower.
    let boat = Boat {
        speed_m_s: 3.0,
        heading_deg: 30.0,
        anchor: [5.0, -7.0],
        anchor_time_s: 0.0,
    };
    let mut driven = Fleet::new(&[]);
    driven.bodies.push(Body::driven_boat(&boat, 0.0));
    let mut trough =
        |_: usize, xz: [f64; 2], t: f64| [-boat.pressure(boat.position(t), xz) / GRAVITY, 0.0];
    let sails = run(&mut driven, 20.0, &mut trough);
    let mut plain = Fleet::new(&[driven.bodies[0].desc]);
    let floats = run(&mut plain, 20.0, &mut still);
    let (y_driven, y_plain) = (sails.last().unwrap().1, floats.last().unwrap().1);
    eprintln!("driven hull {y_driven:.4} m, on still water {y_plain:.4} m");
    assert!(
        (y_driven - y_plain).abs() < 0.01,
        "driven hull at {y_driven:.4} m, the same hull on still water at {y_plain:.4} m"
    );
}
