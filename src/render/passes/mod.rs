//! One struct per pass, each owning its pipeline and layouts, with `new` and `record`
//! (and `resize` where the pass holds size-dependent descriptors).

pub mod composite;
pub mod sky;
pub mod water;

pub use composite::CompositePass;
pub use sky::SkyPass;
pub use water::WaterPass;
