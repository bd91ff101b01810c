//! Rigid bodies that float (`--bodies N`): boxes, small boat hulls and buoys, each a set of
//! voxels in its own frame, moved by a fixed step that does not depend on the frame rate.
//!
//! The water reaches a body through its *columns*: the voxels above one point of its plan share
//! that point's surface height and vertical velocity, which the GPU's height queries answer
//! (`Simulation::ask`, a frame or two late, carried to the step's time with ∂h/∂t; the CPU
//! tests give analytic surfaces). Per voxel, per step:
//! - buoyancy: ρ_w g V f upward at the voxel's centre, f its submerged share (the water's height
//!   against the voxel's world-vertical extent; exact for a level box);
//! - drag on the voxel's velocity relative to the water's vertical motion (the horizontal
//!   orbital velocity is not queried): linear, ρ_w V f · `LINEAR_DAMPING_PER_S` · v (the wave
//!   radiation that damps a floating body's heave, a choice: a 1 m box in still water comes to
//!   rest within about ten heave periods), and quadratic, ½ ρ_w C_d A f |v| v with Hoerner's
//!   cube C_d = 1.05 (Hoerner 1965, *Fluid-Dynamic Drag*, 3-16) and A the voxel's share of the
//!   body's (N V)^(2/3);
//! - gravity on the body's mass.
//!
//! Added mass: the water a body accelerates with it. A sphere carries half its displaced mass,
//! exactly in potential flow (Lamb 1932, *Hydrodynamics*, §92: C_a = ½); every body here takes
//! ½ ρ_w V_submerged on its translation and its inertia scaled alike. It keeps light bodies
//! (wood, foam) from reacting to the waves faster than they do, and the explicit step stable.
//!
//! Not modelled: bodies touching each other or the sea floor (they pass through), the water's
//! horizontal orbital velocity and the waves a body makes (its wake is a separate model).

use glam::{DMat3, DQuat, DVec3};

use super::simulation::Answers;
use super::wake::{self, Boat};

/// Density of sea water (kg/m³).
pub const WATER_DENSITY: f64 = 1025.0;
/// Gravity (m/s²), as the spectra's.
pub const GRAVITY: f64 = super::spectrum::G;
/// The physics step (s): fixed, the frame's time is cut into as many as fit.
pub const STEP_S: f64 = 1.0 / 120.0;
/// Added-mass coefficient: a sphere's (Lamb 1932, §92).
pub const ADDED_MASS: f64 = 0.5;
/// Hoerner's drag coefficient of a cube (1965).
pub const DRAG_COEFFICIENT: f64 = 1.05;
/// Linear (radiation) damping rate (1/s) per unit submerged mass: a choice (see above).
pub const LINEAR_DAMPING_PER_S: f64 = 1.0;
/// Answers older than this are not carried forward (s): the bodies wait for new ones.
pub const MAX_ANSWER_AGE_S: f64 = 0.5;
/// Most steps one `advance` takes (a stalled frame does not run the physics for seconds).
pub const MAX_STEPS: usize = 30;

/// A body's shape in its own frame (x forward, y up, z to the side), voxelized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A box of half extents (x, y, z) (m).
    Box([f64; 3]),
    /// A small boat: length, beam and depth (m); the bow's front third tapers to a point in plan.
    Hull([f64; 3]),
    /// An upright cylinder of radius and height (m).
    Buoy([f64; 2]),
}

/// A body as placed: shape, density relative to the water's, where and how it starts.
#[derive(Clone, Copy, Debug)]
pub struct BodyDesc {
    pub shape: Shape,
    /// Density over the water's (0.5 floats half under, above 1 sinks).
    pub relative_density: f64,
    pub position: [f64; 3],
    /// Rotation about the vertical (degrees).
    pub heading_deg: f64,
}

/// One voxel: its centre in the body's frame, its column.
#[derive(Clone, Copy, Debug)]
struct Voxel {
    centre: DVec3,
    column: usize,
}

/// A rigid body's state and its voxels.
#[derive(Clone, Debug)]
pub struct Body {
    pub desc: BodyDesc,
    pub position: DVec3,
    pub orientation: DQuat,
    pub velocity: DVec3,
    pub angular_velocity: DVec3,
    /// `--boat`: the course that drives it (its engine holds its speed against the drag, a
    /// rudder its heading); the water still lifts, tilts and drags it vertically.
    pub driven: Option<Boat>,
    mass: f64,
    /// Inertia about the centre of mass, body frame.
    inertia: DMat3,
    voxels: Vec<Voxel>,
    /// The centre of mass in the shape's frame (its offset from the shape's centre).
    centroid: DVec3,
    /// The columns' centres in the body's frame (y = 0).
    columns: Vec<DVec3>,
    voxel_size: DVec3,
}

/// Voxels per side along a body's length: one every half metre, 2 to 8.
fn cells(extent_m: f64) -> usize {
    ((extent_m / 0.5).ceil() as usize).clamp(2, 8)
}

/// Voxel layers in the vertical.
const LAYERS: usize = 3;
/// A buoy's bottom layer's mass over a layer above's.
const BALLAST: f64 = 10.0;

impl Body {
    pub fn new(desc: BodyDesc) -> Body {
        let (size, inside): (DVec3, Box<dyn Fn(DVec3) -> bool>) = match desc.shape {
            Shape::Box(h) => (DVec3::from(h) * 2.0, Box::new(|_| true)),
            Shape::Hull([l, b, d]) => (
                DVec3::new(l, d, b),
                Box::new(move |p: DVec3| {
                    // The bow's third: the half-beam shrinks linearly to 0 at x = l/2.
                    let bow = (l / 2.0 - p.x) / (l / 3.0);
                    p.z.abs() <= b / 2.0 * bow.clamp(0.0, 1.0) + 1e-9
                }),
            ),
            Shape::Buoy([r, h]) => (
                DVec3::new(2.0 * r, h, 2.0 * r),
                Box::new(move |p: DVec3| p.x * p.x + p.z * p.z <= r * r),
            ),
        };
        let (nx, nz) = (cells(size.x), cells(size.z));
        let cell = DVec3::new(
            size.x / nx as f64,
            size.y / LAYERS as f64,
            size.z / nz as f64,
        );
        let mut columns = Vec::new();
        let mut voxels = Vec::new();
        for ix in 0..nx {
            for iz in 0..nz {
                let x = -size.x / 2.0 + (ix as f64 + 0.5) * cell.x;
                let z = -size.z / 2.0 + (iz as f64 + 0.5) * cell.z;
                if !inside(DVec3::new(x, 0.0, z)) {
                    continue;
                }
                for iy in 0..LAYERS {
                    let y = -size.y / 2.0 + (iy as f64 + 0.5) * cell.y;
                    voxels.push(Voxel {
                        centre: DVec3::new(x, y, z),
                        column: columns.len(),
                    });
                }
                columns.push(DVec3::new(x, 0.0, z));
            }
        }
        // Mass properties from the voxels: each a uniform box about its centre, of its share
        // of the mass. A buoy carries ballast: its bottom layer BALLAST times a layer above's
        // mass (a tall buoy of uniform density capsizes: its metacentre lies below its centre
        // of gravity).
        let volume = cell.x * cell.y * cell.z;
        // Weighed in the shape's frame, before the voxels are moved to the mass centre's.
        let weights: Vec<f64> = voxels
            .iter()
            .map(|v| match desc.shape {
                Shape::Buoy(_) if v.centre.y < -size.y / 2.0 + cell.y => BALLAST,
                _ => 1.0,
            })
            .collect();
        let total: f64 = weights.iter().sum();
        let mass = desc.relative_density * WATER_DENSITY * volume * voxels.len() as f64;
        let mut centre = DVec3::ZERO;
        for (v, w) in voxels.iter().zip(&weights) {
            centre += v.centre * *w;
        }
        centre /= total.max(1e-9);
        for v in &mut voxels {
            v.centre -= centre;
        }
        for c in &mut columns {
            *c -= DVec3::new(centre.x, 0.0, centre.z);
        }
        let own = DVec3::new(
            cell.y * cell.y + cell.z * cell.z,
            cell.x * cell.x + cell.z * cell.z,
            cell.x * cell.x + cell.y * cell.y,
        ) / 12.0;
        let mut inertia = DMat3::ZERO;
        for (v, w) in voxels.iter().zip(&weights) {
            let m = mass * w / total;
            let r = v.centre;
            let parallel = DMat3::from_diagonal(DVec3::splat(r.length_squared()))
                - DMat3::from_cols(r * r.x, r * r.y, r * r.z);
            inertia += (parallel + DMat3::from_diagonal(own)) * m;
        }
        let orientation = DQuat::from_rotation_y(desc.heading_deg.to_radians());
        Body {
            desc,
            position: DVec3::from(desc.position) + orientation * centre,
            orientation,
            velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
            driven: None,
            mass,
            inertia,
            voxels,
            centroid: centre,
            columns,
            voxel_size: cell,
        }
    }

    /// Mass (kg).
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// World xz of each column now (where the water is asked about).
    pub fn column_points(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.columns.iter().map(|c| {
            let p = self.position + self.orientation * *c;
            [p.x, p.z]
        })
    }

    /// Columns: how many points the body asks the water about.
    pub fn column_count(&self) -> usize {
        self.columns.len()
    }

    /// The body as the bodies' vertex shader draws it (shaders/terrain/bodies.vert): (position,
    /// shape: 0 box, 1 hull, 2 buoy), its orientation (x, y, z, w), its size (m; box and hull:
    /// x along, y up, z across; buoy: radius, height).
    pub fn instance(&self) -> [[f32; 4]; 3] {
        let r = self.orientation;
        let p = self.shape_centre();
        let (shape, size) = match self.desc.shape {
            Shape::Box(h) => (0.0, [2.0 * h[0], 2.0 * h[1], 2.0 * h[2]]),
            Shape::Hull([l, b, d]) => (1.0, [l, d, b]),
            Shape::Buoy([radius, h]) => (2.0, [radius, h, radius]),
        };
        [
            [p.x as f32, p.y as f32, p.z as f32, shape],
            [r.x as f32, r.y as f32, r.z as f32, r.w as f32],
            [size[0] as f32, size[1] as f32, size[2] as f32, 0.0],
        ]
    }

    /// A boat driven along `boat`'s course: the hull whose pressure makes its wake
    /// (`wake::HULL_LENGTH_M` by `wake::HULL_BEAM_M`, 1.2 m deep, a third of the water's
    /// density), where the course has it at `t_s`.
    pub fn driven_boat(boat: &Boat, t_s: f64) -> Body {
        let p = boat.position(t_s);
        let mut body = Body::new(BodyDesc {
            shape: Shape::Hull([wake::HULL_LENGTH_M, wake::HULL_BEAM_M, 1.2]),
            relative_density: 0.35,
            position: [p[0], 0.0, p[1]],
            // Rotations about +y turn +x toward −z; the course turns it toward +z.
            heading_deg: -boat.heading_deg,
        });
        body.driven = Some(*boat);
        body.drive(t_s);
        body
    }

    /// The driven body's horizontal velocity (zero for the others).
    fn driven_velocity(&self) -> DVec3 {
        self.driven.map_or(DVec3::ZERO, |b| {
            let u = b.course();
            DVec3::new(u[0], 0.0, u[1]) * b.speed_m_s
        })
    }

    /// Puts a driven body where its course has it at `t_s`, at its speed, not turning about
    /// the vertical.
    fn drive(&mut self, t_s: f64) {
        if let Some(b) = self.driven {
            let p = b.position(t_s);
            let v = self.driven_velocity();
            (self.position.x, self.position.z) = (p[0], p[1]);
            (self.velocity.x, self.velocity.z) = (v.x, v.z);
            self.angular_velocity.y = 0.0;
        }
    }

    /// Where the shape's centre is (m): the body's position is its centre of mass.
    pub fn shape_centre(&self) -> DVec3 {
        self.position - self.orientation * self.centroid
    }

    /// One step of `dt` s; `water(column)` gives the surface's (height, ∂h/∂t) above each
    /// column at the step's start.
    fn step(&mut self, dt: f64, water: &[[f64; 2]]) {
        let r = DMat3::from_quat(self.orientation);
        let volume = self.voxel_size.x * self.voxel_size.y * self.voxel_size.z;
        // Each voxel's share of the body's frontal area, (N V)^(2/3) over its N voxels (a
        // voxel's own V^(2/3) would count the inner faces: N^(1/3) times too much).
        let n = self.voxels.len() as f64;
        let area = (n * volume).powf(2.0 / 3.0) / n;
        // The voxel's world-vertical extent: its rotated box's height.
        let extent = r.row(1).abs().dot(self.voxel_size);
        let mut force = DVec3::new(0.0, -self.mass * GRAVITY, 0.0);
        let mut torque = DVec3::ZERO;
        let mut submerged = 0.0;
        for v in &self.voxels {
            let arm = r * v.centre;
            let p = self.position + arm;
            let [mut h, rate] = water[v.column];
            // A driven hull's own pressure holds the water under it down (up to
            // `wake::DRAFT_M`, the wake's static trough, in the height queries too): its
            // columns see the water without that hollow, or the hull would sink into it.
            if let Some(b) = self.driven {
                let at = [self.position.x, self.position.z];
                h += b.pressure(at, [p.x, p.z]) / GRAVITY;
            }
            let f = ((h - (p.y - extent / 2.0)) / extent).clamp(0.0, 1.0);
            if f == 0.0 {
                continue;
            }
            submerged += f * volume;
            let relative = self.velocity + self.angular_velocity.cross(arm)
                - DVec3::new(0.0, rate, 0.0)
                - self.driven_velocity();
            let mut fv = DVec3::new(0.0, WATER_DENSITY * GRAVITY * volume * f, 0.0);
            fv -= relative * (WATER_DENSITY * volume * f * LINEAR_DAMPING_PER_S);
            fv -=
                relative * (0.5 * WATER_DENSITY * DRAG_COEFFICIENT * area * f * relative.length());
            force += fv;
            torque += arm.cross(fv);
        }
        let added = ADDED_MASS * WATER_DENSITY * submerged;
        let scale = (self.mass + added) / self.mass;
        self.velocity += force / (self.mass + added) * dt;
        self.position += self.velocity * dt;
        // Euler's equations in the world frame: I_w = R I Rᵀ.
        let inertia = r * self.inertia * r.transpose() * scale;
        let gyro = self.angular_velocity.cross(inertia * self.angular_velocity);
        self.angular_velocity += inertia.inverse() * (torque - gyro) * dt;
        let w = self.angular_velocity;
        let spin = DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * self.orientation;
        self.orientation = (self.orientation + spin * (0.5 * dt)).normalize();
    }
}

/// Bodies stepped together at a fixed rate.
#[derive(Clone, Debug, Default)]
pub struct Fleet {
    pub bodies: Vec<Body>,
    /// Simulation time the physics has reached (s).
    time_s: Option<f64>,
    /// Steps taken so far.
    pub steps: u64,
}

impl Fleet {
    pub fn new(descs: &[BodyDesc]) -> Fleet {
        Fleet {
            bodies: descs.iter().map(|d| Body::new(*d)).collect(),
            time_s: None,
            steps: 0,
        }
    }

    /// Every body's columns, body after body: the points to ask the water about.
    pub fn query_points(&self) -> Vec<[f64; 2]> {
        self.bodies.iter().flat_map(|b| b.column_points()).collect()
    }

    /// `n` bodies on a grid `spacing_m` apart around `centre` (x, z): a 1.2 × 0.5 × 1 m crate, a 4 m
    /// boat and a 1 m buoy in turn, each turned a little further.
    pub fn scattered(n: usize, centre: [f64; 2], spacing_m: f64) -> Fleet {
        let side = (n as f64).sqrt().ceil().max(1.0) as usize;
        let descs: Vec<BodyDesc> = (0..n)
            .map(|i| {
                let (row, col) = (i / side, i % side);
                let offset = |k: usize| (k as f64 - (side - 1) as f64 / 2.0) * spacing_m;
                let (shape, relative_density) = match i % 3 {
                    0 => (Shape::Box([0.6, 0.25, 0.5]), 0.5),
                    1 => (Shape::Hull([4.0, 1.6, 0.8]), 0.3),
                    _ => (Shape::Buoy([0.5, 1.2]), 0.4),
                };
                BodyDesc {
                    shape,
                    relative_density,
                    position: [centre[0] + offset(col), 0.0, centre[1] + offset(row)],
                    heading_deg: 37.0 * i as f64,
                }
            })
            .collect();
        Fleet::new(&descs)
    }

    /// Advances to `t_s` on the GPU's newest height queries `answers`, each column's height
    /// carried to the step's time with its ∂h/∂t (`Answers::height_at`). The answers are for
    /// the points this fleet asked a frame or two before, one per column in `query_points`'
    /// order, each moved along the surface's slope to where its column is now; until the first
    /// arrive (or while they are for another set of columns, or older than
    /// `MAX_ANSWER_AGE_S`) the bodies wait.
    pub fn advance_on(&mut self, answers: Option<&Answers>, t_s: f64) {
        for body in &mut self.bodies {
            body.drive(t_s);
        }
        let columns = self.column_count();
        match answers {
            Some(a) if a.surface.len() == columns && t_s - a.time_s <= MAX_ANSWER_AGE_S => {
                self.advance(t_s, &mut |i, xz, t| {
                    // The column has moved since it asked: along the surface's slope there.
                    let s = &a.surface[i];
                    let [ax, az] = a.points[i];
                    // At most 45° (a fold's normal lies nearly flat: its slope means nothing).
                    let ny = s.normal[1].max(1e-3);
                    let slope = [s.normal[0], s.normal[2]].map(|n| (-n / ny).clamp(-1.0, 1.0));
                    let moved = slope[0] * (xz[0] - ax) + slope[1] * (xz[1] - az);
                    [a.height_at(i, t) + moved, s.vertical_velocity_m_s]
                })
            }
            _ => self.time_s = None,
        }
    }

    /// `bodies.json` of `--dump`: a list of the bodies, each with its shape and size, its
    /// shape's centre `position` and its `centre_of_mass` (m), `orientation` (a unit quaternion
    /// x, y, z, w), `velocity` (m/s) and `angular_velocity` (rad/s), world axes.
    pub fn to_json(&self) -> serde_json::Value {
        let bodies: Vec<serde_json::Value> = self
            .bodies
            .iter()
            .map(|b| {
                let (kind, size) = match b.desc.shape {
                    Shape::Box(h) => ("box", vec![2.0 * h[0], 2.0 * h[1], 2.0 * h[2]]),
                    Shape::Hull(s) => ("hull", s.to_vec()),
                    Shape::Buoy(s) => ("buoy", s.to_vec()),
                };
                let q = b.orientation;
                serde_json::json!({
                    "shape": kind,
                    "size_m": size,
                    "relative_density": b.desc.relative_density,
                    "position": b.shape_centre().to_array(),
                    "centre_of_mass": b.position.to_array(),
                    "orientation": [q.x, q.y, q.z, q.w],
                    "velocity": b.velocity.to_array(),
                    "angular_velocity": b.angular_velocity.to_array(),
                    "driven": b.driven.is_some(),
                })
            })
            .collect();
        serde_json::Value::Array(bodies)
    }

    /// Columns in all.
    pub fn column_count(&self) -> usize {
        self.bodies.iter().map(Body::column_count).sum()
    }

    /// Runs the fixed steps from the time reached to `t_s` (at most `MAX_STEPS`; the first
    /// call only starts the clock). `water(i, xz, t)` answers column `i` (in `query_points`'
    /// order) at world `xz` and time `t`: (height, ∂h/∂t).
    pub fn advance(&mut self, t_s: f64, water: &mut dyn FnMut(usize, [f64; 2], f64) -> [f64; 2]) {
        let Some(mut t) = self.time_s else {
            self.time_s = Some(t_s);
            return;
        };
        if t_s < t {
            // The clock went back (a seek): start again from there.
            self.time_s = Some(t_s);
            return;
        }
        let mut taken = 0;
        let mut samples = Vec::new();
        while t + STEP_S <= t_s + 1e-12 && taken < MAX_STEPS {
            let mut first = 0;
            for body in &mut self.bodies {
                samples.clear();
                for (k, xz) in body.column_points().enumerate() {
                    samples.push(water(first + k, xz, t));
                }
                first += body.column_count();
                body.step(STEP_S, &samples);
                body.drive(t + STEP_S);
            }
            t += STEP_S;
            taken += 1;
            self.steps += 1;
        }
        // A stalled frame drops the steps it could not take.
        self.time_s = Some(if taken == MAX_STEPS { t_s } else { t });
    }
}

#[cfg(test)]
mod tests;
