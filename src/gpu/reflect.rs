//! What a shader reads and writes, from its SPIR-V: each descriptor (set, binding) its entry
//! point statically uses, of which kind, read or written, in which stage. Pipelines keep the
//! union over their stages ([`Interface`]); a pass's barriers are derived from it
//! (`pass.rs`), so a shader that starts sampling an image in another stage moves the
//! barrier with it.
//!
//! A small reader of the SPIR-V 1.6 binary (Khronos, "SPIR-V Specification", 2.3 "Physical
//! Layout", 3 "Binary Form"): the header, then instructions of `wordcount << 16 | opcode`.
//! A variable is *used* when an instruction of a function reachable from the entry point
//! loads, stores, accesses or passes it (glslang keeps descriptors a shader declares but never
//! touches, e.g. the frame set's images in a shader that includes frame.glsl for its uniforms).

use std::collections::{BTreeMap, HashMap, HashSet};

use ash::vk;

const MAGIC: u32 = 0x0723_0203;

// Opcodes (SPIR-V spec, 3.52 "Instructions").
const OP_ENTRY_POINT: u16 = 15;
const OP_TYPE_IMAGE: u16 = 25;
const OP_TYPE_SAMPLER: u16 = 26;
const OP_TYPE_SAMPLED_IMAGE: u16 = 27;
const OP_TYPE_ARRAY: u16 = 28;
const OP_TYPE_RUNTIME_ARRAY: u16 = 29;
const OP_TYPE_STRUCT: u16 = 30;
const OP_TYPE_POINTER: u16 = 32;
const OP_FUNCTION: u16 = 54;
const OP_FUNCTION_END: u16 = 56;
const OP_FUNCTION_CALL: u16 = 57;
const OP_VARIABLE: u16 = 59;
const OP_IMAGE_TEXEL_POINTER: u16 = 60;
const OP_LOAD: u16 = 61;
const OP_STORE: u16 = 62;
const OP_COPY_MEMORY: u16 = 63;
const OP_COPY_MEMORY_SIZED: u16 = 64;
const OP_COPY_OBJECT: u16 = 83;
const OP_ATOMIC_FLAG_TEST_AND_SET: u16 = 318;
const OP_ATOMIC_FLAG_CLEAR: u16 = 319;
const OP_ACCESS_CHAIN: u16 = 65;
const OP_IN_BOUNDS_ACCESS_CHAIN: u16 = 66;
const OP_PTR_ACCESS_CHAIN: u16 = 67;
const OP_ARRAY_LENGTH: u16 = 68;
const OP_DECORATE: u16 = 71;
const OP_MEMBER_DECORATE: u16 = 72;
const OP_ATOMIC_STORE: u16 = 228;
/// OpAtomicLoad (227) to OpAtomicXor (242): the pointer is operand 3 (228, a store, has it at 1).
const OP_ATOMICS: std::ops::RangeInclusive<u16> = 227..=242;

// Decorations (3.20).
const DECORATION_BLOCK: u32 = 2;
const DECORATION_BUFFER_BLOCK: u32 = 3;
const DECORATION_NON_WRITABLE: u32 = 24;
const DECORATION_NON_READABLE: u32 = 25;
const DECORATION_BINDING: u32 = 33;
const DECORATION_DESCRIPTOR_SET: u32 = 34;

// Storage classes (3.7).
const STORAGE_UNIFORM_CONSTANT: u32 = 0;
const STORAGE_UNIFORM: u32 = 2;
const STORAGE_STORAGE_BUFFER: u32 = 12;

/// What kind of descriptor a shader declares at a binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    /// A uniform block.
    UniformBuffer,
    /// A storage block (`buffer`).
    StorageBuffer,
    /// An image combined with its sampler (`sampler2D`: OpTypeSampledImage).
    CombinedImageSampler,
    /// A sampled image alone (`texture2D`).
    SampledImage,
    /// A storage image (`image2D`).
    StorageImage,
    /// `samplerBuffer` / `textureBuffer`.
    UniformTexelBuffer,
    /// `imageBuffer`.
    StorageTexelBuffer,
    /// A sampler alone.
    Sampler,
}

impl Kind {
    /// Whether shaders can write it (storage descriptors).
    pub fn is_storage(self) -> bool {
        matches!(
            self,
            Kind::StorageBuffer | Kind::StorageImage | Kind::StorageTexelBuffer
        )
    }
}

/// One descriptor a pipeline's shaders use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BindingUse {
    pub kind: Kind,
    /// The stages whose entry points use it.
    pub stages: vk::ShaderStageFlags,
    /// Read (not `writeonly`) and written (a storage descriptor not `readonly`).
    pub reads: bool,
    pub writes: bool,
}

/// Every descriptor (set, binding) the shaders of a pipeline use.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Interface {
    pub bindings: BTreeMap<(u32, u32), BindingUse>,
}

impl Interface {
    /// The descriptors one shader's entry point uses. `name` is for the error.
    pub fn of_shader(name: &str, spirv: &[u8]) -> Result<Interface, String> {
        reflect(spirv).map_err(|e| format!("shader {name}: SPIR-V reflection: {e}"))
    }

    /// The union of two interfaces (a pipeline's stages).
    pub fn merge(&mut self, other: &Interface) {
        for (key, b) in &other.bindings {
            self.bindings
                .entry(*key)
                .and_modify(|a| {
                    a.stages |= b.stages;
                    a.reads |= b.reads;
                    a.writes |= b.writes;
                })
                .or_insert(*b);
        }
    }
}

/// The pipeline stage of a shader stage, for barriers.
pub fn pipeline_stages(stages: vk::ShaderStageFlags) -> vk::PipelineStageFlags2 {
    use vk::PipelineStageFlags2 as P;
    use vk::ShaderStageFlags as S;
    [
        (S::VERTEX, P::VERTEX_SHADER),
        (S::TESSELLATION_CONTROL, P::TESSELLATION_CONTROL_SHADER),
        (
            S::TESSELLATION_EVALUATION,
            P::TESSELLATION_EVALUATION_SHADER,
        ),
        (S::GEOMETRY, P::GEOMETRY_SHADER),
        (S::FRAGMENT, P::FRAGMENT_SHADER),
        (S::COMPUTE, P::COMPUTE_SHADER),
    ]
    .into_iter()
    .filter(|(s, _)| stages.contains(*s))
    .fold(P::NONE, |all, (_, p)| all | p)
}

fn execution_model_stage(model: u32) -> Result<vk::ShaderStageFlags, String> {
    use vk::ShaderStageFlags as S;
    Ok(match model {
        0 => S::VERTEX,
        1 => S::TESSELLATION_CONTROL,
        2 => S::TESSELLATION_EVALUATION,
        3 => S::GEOMETRY,
        4 => S::FRAGMENT,
        5 => S::COMPUTE,
        _ => return Err(format!("unsupported execution model {model}")),
    })
}

/// A type the reader follows from a variable to its descriptor kind.
#[derive(Clone, Copy)]
enum Type {
    Image { buffer_dim: bool, storage: bool },
    Sampler,
    SampledImage { image: u32 },
    Array,
    Struct,
    Pointer { pointee: u32 },
}

// Long: one pass over the instruction stream (each opcode a few lines), then the variables it
// found resolved to descriptors; split, the tables both halves fill would travel between them.
fn reflect(spirv: &[u8]) -> Result<Interface, String> {
    if !spirv.len().is_multiple_of(4) || spirv.len() < 20 {
        return Err(format!("{} bytes is not a SPIR-V module", spirv.len()));
    }
    let words: Vec<u32> = spirv
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    if words[0] != MAGIC {
        return Err(format!("bad magic number {:#x}", words[0]));
    }
    let mut entry: Option<(vk::ShaderStageFlags, u32)> = None;
    let mut types: HashMap<u32, Type> = HashMap::new();
    let mut variables: HashMap<u32, (u32, u32)> = HashMap::new(); // id -> (pointer type, class)
    let mut set_of: HashMap<u32, u32> = HashMap::new();
    let mut binding_of: HashMap<u32, u32> = HashMap::new();
    let mut non_writable: HashSet<u32> = HashSet::new();
    let mut non_readable: HashSet<u32> = HashSet::new();
    let mut buffer_block: HashSet<u32> = HashSet::new();
    // Struct id -> its members decorated NonWritable (`readonly`), NonReadable (`writeonly`).
    let mut readonly_members: HashMap<u32, HashSet<u32>> = HashMap::new();
    let mut writeonly_members: HashMap<u32, HashSet<u32>> = HashMap::new();
    // Arrays of descriptors (one descriptor per binding here).
    let mut arrays: HashSet<u32> = HashSet::new();
    // Function id -> (callees, pointers its instructions use).
    let mut functions: HashMap<u32, (Vec<u32>, Vec<u32>)> = HashMap::new();
    let mut current: Option<u32> = None;
    let mut struct_members: HashMap<u32, usize> = HashMap::new();

    let mut at = 5;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let op = (words[at] & 0xffff) as u16;
        if count == 0 || at + count > words.len() {
            return Err(format!("truncated instruction at word {at}"));
        }
        let w = &words[at..at + count];
        let arg = |i: usize| -> Result<u32, String> {
            w.get(i)
                .copied()
                .ok_or_else(|| format!("opcode {op} at word {at}: operand {i} missing"))
        };
        match op {
            OP_ENTRY_POINT => {
                if entry.is_some() {
                    return Err("more than one entry point".into());
                }
                entry = Some((execution_model_stage(arg(1)?)?, arg(2)?));
            }
            OP_TYPE_IMAGE => {
                // OpTypeImage result, sampled type, dim, depth, arrayed, ms, sampled, format.
                types.insert(
                    arg(1)?,
                    Type::Image {
                        buffer_dim: arg(3)? == 5,
                        storage: arg(7)? == 2,
                    },
                );
            }
            OP_TYPE_SAMPLER => {
                types.insert(arg(1)?, Type::Sampler);
            }
            OP_TYPE_SAMPLED_IMAGE => {
                types.insert(arg(1)?, Type::SampledImage { image: arg(2)? });
            }
            OP_TYPE_ARRAY | OP_TYPE_RUNTIME_ARRAY => {
                types.insert(arg(1)?, Type::Array);
                arrays.insert(arg(1)?);
            }
            OP_TYPE_STRUCT => {
                types.insert(arg(1)?, Type::Struct);
                struct_members.insert(arg(1)?, count - 2);
            }
            OP_TYPE_POINTER => {
                types.insert(arg(1)?, Type::Pointer { pointee: arg(3)? });
            }
            OP_VARIABLE if current.is_none() => {
                variables.insert(arg(2)?, (arg(1)?, arg(3)?));
            }
            OP_DECORATE => {
                let (target, decoration) = (arg(1)?, arg(2)?);
                match decoration {
                    DECORATION_DESCRIPTOR_SET => {
                        set_of.insert(target, arg(3)?);
                    }
                    DECORATION_BINDING => {
                        binding_of.insert(target, arg(3)?);
                    }
                    DECORATION_NON_WRITABLE => {
                        non_writable.insert(target);
                    }
                    DECORATION_NON_READABLE => {
                        non_readable.insert(target);
                    }
                    DECORATION_BUFFER_BLOCK => {
                        buffer_block.insert(target);
                    }
                    DECORATION_BLOCK => {}
                    _ => {}
                }
            }
            OP_MEMBER_DECORATE if arg(3)? == DECORATION_NON_WRITABLE => {
                readonly_members.entry(arg(1)?).or_default().insert(arg(2)?);
            }
            OP_MEMBER_DECORATE if arg(3)? == DECORATION_NON_READABLE => {
                writeonly_members
                    .entry(arg(1)?)
                    .or_default()
                    .insert(arg(2)?);
            }
            OP_FUNCTION => {
                let id = arg(2)?;
                current = Some(id);
                functions.entry(id).or_default();
            }
            OP_FUNCTION_END => current = None,
            _ => {
                if let Some(f) = current {
                    let used: Vec<u32> = match op {
                        OP_LOAD
                        | OP_ACCESS_CHAIN
                        | OP_IN_BOUNDS_ACCESS_CHAIN
                        | OP_PTR_ACCESS_CHAIN
                        | OP_IMAGE_TEXEL_POINTER
                        | OP_ARRAY_LENGTH => vec![arg(3)?],
                        OP_STORE | OP_ATOMIC_STORE | OP_ATOMIC_FLAG_CLEAR => vec![arg(1)?],
                        OP_COPY_MEMORY | OP_COPY_MEMORY_SIZED => vec![arg(1)?, arg(2)?],
                        OP_COPY_OBJECT | OP_ATOMIC_FLAG_TEST_AND_SET => vec![arg(3)?],
                        OP_FUNCTION_CALL => w[4..].to_vec(),
                        _ if OP_ATOMICS.contains(&op) => vec![arg(3)?],
                        _ => Vec::new(),
                    };
                    let entry = functions.entry(f).or_default();
                    if op == OP_FUNCTION_CALL {
                        entry.0.push(arg(3)?);
                    }
                    entry.1.extend(used);
                }
            }
        }
        at += count;
    }
    let (stage, main) = entry.ok_or("no entry point")?;

    // Every pointer used by a function reachable from the entry point.
    let mut used: HashSet<u32> = HashSet::new();
    let mut seen: HashSet<u32> = HashSet::new();
    let mut stack = vec![main];
    while let Some(f) = stack.pop() {
        if !seen.insert(f) {
            continue;
        }
        if let Some((callees, pointers)) = functions.get(&f) {
            used.extend(pointers.iter().copied());
            stack.extend(callees.iter().copied());
        }
    }

    let mut interface = Interface::default();
    for (&var, &(pointer, class)) in &variables {
        if !used.contains(&var) {
            continue;
        }
        let (Some(&set), Some(&binding)) = (set_of.get(&var), binding_of.get(&var)) else {
            continue;
        };
        let Some(Type::Pointer { pointee, .. }) = types.get(&pointer).copied() else {
            return Err(format!(
                "variable {var}: its type {pointer} is not a pointer"
            ));
        };
        // Arrays of descriptors: refused (the layouts here have one descriptor a binding, and
        // a count the layout does not match would be invalid usage). Arrays inside a block
        // (runtime arrays of a storage buffer) are the block's business.
        if arrays.contains(&pointee) {
            return Err(format!(
                "set {set} binding {binding}: an array of descriptors (one descriptor a binding here)"
            ));
        }
        let ty = pointee;
        let kind = match (class, types.get(&ty).copied()) {
            (STORAGE_UNIFORM, Some(Type::Struct)) if buffer_block.contains(&ty) => {
                Kind::StorageBuffer
            }
            (STORAGE_UNIFORM, Some(Type::Struct)) => Kind::UniformBuffer,
            (STORAGE_STORAGE_BUFFER, Some(Type::Struct)) => Kind::StorageBuffer,
            (STORAGE_UNIFORM_CONSTANT, Some(Type::Sampler)) => Kind::Sampler,
            (STORAGE_UNIFORM_CONSTANT, Some(Type::SampledImage { .. })) => {
                Kind::CombinedImageSampler
            }
            (STORAGE_UNIFORM_CONSTANT, Some(Type::Image { buffer_dim, storage })) => {
                match (buffer_dim, storage) {
                    (true, true) => Kind::StorageTexelBuffer,
                    (true, false) => Kind::UniformTexelBuffer,
                    (false, true) => Kind::StorageImage,
                    (false, false) => Kind::SampledImage,
                }
            }
            _ => {
                return Err(format!(
                    "set {set} binding {binding}: a descriptor of an unknown type (storage class {class})"
                ))
            }
        };
        // Combined image samplers over a texel buffer are uniform texel buffers.
        let kind = match (kind, types.get(&ty).copied()) {
            (Kind::CombinedImageSampler, Some(Type::SampledImage { image })) => {
                match types.get(&image).copied() {
                    Some(Type::Image {
                        buffer_dim: true, ..
                    }) => Kind::UniformTexelBuffer,
                    _ => Kind::CombinedImageSampler,
                }
            }
            (k, _) => k,
        };
        // A block is `readonly` (`writeonly`) when the variable or every member says so.
        let all_members = |m: &HashMap<u32, HashSet<u32>>| {
            m.get(&ty)
                .is_some_and(|m| struct_members.get(&ty).is_some_and(|n| m.len() >= *n))
        };
        let readonly = non_writable.contains(&var) || all_members(&readonly_members);
        let writeonly = non_readable.contains(&var) || all_members(&writeonly_members);
        let (reads, writes) = if kind.is_storage() {
            (!writeonly, !readonly)
        } else {
            (true, false)
        };
        let b = BindingUse {
            kind,
            stages: stage,
            reads,
            writes,
        };
        if interface.bindings.insert((set, binding), b).is_some() {
            return Err(format!("set {set} binding {binding} declared twice"));
        }
    }
    Ok(interface)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders;
    use vk::ShaderStageFlags as S;

    fn of(name: &str, spirv: &[u8]) -> Interface {
        Interface::of_shader(name, spirv).unwrap()
    }

    #[test]
    fn the_water_samples_the_sky_cube_in_tessellation_evaluation_and_fragment() {
        let mut water = Interface::default();
        for (name, spirv) in [
            ("water.vert", shaders::SURFACE_WATER_VERT),
            ("water.tesc", shaders::SURFACE_WATER_TESC),
            ("water.tese", shaders::SURFACE_WATER_TESE),
            ("water.frag", shaders::SURFACE_WATER_FRAG),
        ] {
            water.merge(&of(name, spirv));
        }
        let sky_cube = water.bindings[&(0, 3)];
        assert_eq!(sky_cube.kind, Kind::CombinedImageSampler);
        assert!(sky_cube
            .stages
            .contains(S::TESSELLATION_EVALUATION | S::FRAGMENT));
        assert!(!sky_cube.stages.contains(S::VERTEX));
        // The uniforms: a uniform block, read only.
        let uniforms = water.bindings[&(0, 0)];
        assert_eq!(uniforms.kind, Kind::UniformBuffer);
        assert!(uniforms.reads && !uniforms.writes);
        // The reflection (set 1) in the fragment shader only.
        assert_eq!(water.bindings[&(1, 0)].stages, S::FRAGMENT);
        // The ocean displacement where the vertices are displaced.
        assert!(water.bindings[&(0, 1)]
            .stages
            .contains(S::TESSELLATION_EVALUATION));
    }

    #[test]
    fn declared_but_unused_descriptors_are_not_uses() {
        // The fullscreen vertex shader includes nothing it samples.
        assert!(of("fullscreen.vert", shaders::COMMON_FULLSCREEN_VERT)
            .bindings
            .is_empty());
    }

    #[test]
    fn storage_descriptors_say_whether_they_are_read_or_written() {
        let evolve = of("evolve.comp", shaders::OCEAN_EVOLVE_COMP);
        assert!(!evolve.bindings.is_empty());
        for b in evolve.bindings.values() {
            assert_eq!(b.stages, S::COMPUTE);
            assert!(b.kind.is_storage() || b.kind == Kind::UniformTexelBuffer);
        }
        assert!(
            evolve.bindings.values().any(|b| b.writes && !b.reads),
            "evolve writes its output (writeonly): {evolve:?}"
        );
        assert!(
            evolve.bindings.values().any(|b| b.reads && !b.writes),
            "evolve reads h0 (readonly): {evolve:?}"
        );
    }

    #[test]
    fn bad_modules_are_errors_not_panics() {
        assert!(Interface::of_shader("x", &[0; 3]).is_err());
        assert!(Interface::of_shader("x", &[0; 20]).is_err());
        let mut truncated = shaders::SURFACE_WATER_FRAG.to_vec();
        truncated.truncate(truncated.len() - 8);
        // Cut mid-instruction or mid-function: an error or a smaller interface, never a panic.
        let _ = Interface::of_shader("x", &truncated);
    }
}
