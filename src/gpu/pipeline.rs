//! Pipeline layouts and pipelines (graphics for dynamic rendering, compute), built from the
//! SPIR-V that build.rs embeds (`crate::shaders`).

use std::cell::{Cell, RefCell};
use std::rc::Rc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::descriptors::DescriptorSetLayout;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::reflect::{Interface, Kind};

/// A pipeline layout: descriptor set layouts + one push-constant range. A shared handle: each
/// pipeline made with it keeps it alive.
#[derive(Clone)]
pub struct PipelineLayout(Rc<LayoutCore>);

pub(super) struct LayoutCore {
    ctx: Arc<Context>,
    pub(super) raw: vk::PipelineLayout,
    /// Stages and size of the push-constant range (size 0: none).
    pub(super) push: (vk::ShaderStageFlags, u32),
    /// Each set's bindings: (binding, type, stages).
    sets: Vec<Vec<(u32, vk::DescriptorType, vk::ShaderStageFlags)>>,
}

impl PipelineLayout {
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        sets: &[&DescriptorSetLayout],
        push_constants: Option<(vk::ShaderStageFlags, u32)>,
    ) -> GpuResult<Self> {
        let set_layouts: Vec<_> = sets.iter().map(|s| s.raw).collect();
        let ranges: Vec<_> = push_constants
            .map(|(stages, size)| vk::PushConstantRange {
                stage_flags: stages,
                offset: 0,
                size,
            })
            .into_iter()
            .collect();
        let info = vk::PipelineLayoutCreateInfo::default()
            .set_layouts(&set_layouts)
            .push_constant_ranges(&ranges);
        // SAFETY: valid create info on a live device; the set layouts are live.
        let raw = unsafe { ctx.device.create_pipeline_layout(&info, None) }
            .vk("vkCreatePipelineLayout")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Self(Rc::new(LayoutCore {
            ctx: ctx.clone(),
            raw,
            push: push_constants.unwrap_or_default(),
            sets: sets.iter().map(|s| s.bindings.clone()).collect(),
        })))
    }

    pub(super) fn raw(&self) -> vk::PipelineLayout {
        self.0.raw
    }

    pub(super) fn push(&self) -> (vk::ShaderStageFlags, u32) {
        self.0.push
    }

    /// Set `index`'s bindings, if the layout has that set.
    pub(super) fn set(
        &self,
        index: usize,
    ) -> Option<&[(u32, vk::DescriptorType, vk::ShaderStageFlags)]> {
        self.0.sets.get(index).map(Vec::as_slice)
    }

    /// Checks that every descriptor the shaders use is declared by the layout, with a
    /// matching type and visible to the stages that use it.
    fn check(&self, pipeline: &str, interface: &Interface) -> GpuResult<()> {
        for (&(set, binding), used) in &interface.bindings {
            let declared = self
                .0
                .sets
                .get(set as usize)
                .and_then(|s| s.iter().find(|b| b.0 == binding));
            let Some(&(_, ty, stages)) = declared else {
                return Err(GpuError::Interface(format!(
                    "pipeline {pipeline}: its shaders use set {set} binding {binding} ({:?}, {:?}), which its layout does not declare",
                    used.kind, used.stages
                )));
            };
            if !kind_matches(used.kind, ty) {
                return Err(GpuError::Interface(format!(
                    "pipeline {pipeline}: set {set} binding {binding} is a {:?} in the shaders but {ty:?} in the layout",
                    used.kind
                )));
            }
            if !stages.contains(used.stages) {
                return Err(GpuError::Interface(format!(
                    "pipeline {pipeline}: set {set} binding {binding} is used in {:?}, but the layout makes it visible to {stages:?} only",
                    used.stages
                )));
            }
        }
        Ok(())
    }
}

/// Whether a shader's descriptor kind is the layout's descriptor type.
fn kind_matches(kind: Kind, ty: vk::DescriptorType) -> bool {
    use vk::DescriptorType as T;
    match kind {
        Kind::UniformBuffer => ty == T::UNIFORM_BUFFER,
        Kind::StorageBuffer => ty == T::STORAGE_BUFFER,
        // OpTypeSampledImage: combined only; an OpTypeImage alone: either (Vulkan spec,
        // "Shader Resource and Descriptor Type Correspondence").
        Kind::CombinedImageSampler => ty == T::COMBINED_IMAGE_SAMPLER,
        Kind::SampledImage => ty == T::COMBINED_IMAGE_SAMPLER || ty == T::SAMPLED_IMAGE,
        Kind::StorageImage => ty == T::STORAGE_IMAGE,
        Kind::UniformTexelBuffer => ty == T::UNIFORM_TEXEL_BUFFER,
        Kind::StorageTexelBuffer => ty == T::STORAGE_TEXEL_BUFFER,
        Kind::Sampler => ty == T::SAMPLER,
    }
}

impl Drop for LayoutCore {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::PipelineLayout(self.raw));
    }
}

/// A shader module, alive only while pipelines are created from it.
struct ShaderModule<'a> {
    ctx: &'a Context,
    raw: vk::ShaderModule,
}

impl<'a> ShaderModule<'a> {
    fn new(ctx: &'a Context, name: &str, spirv: &[u8]) -> GpuResult<Self> {
        let words = ash::util::read_spv(&mut std::io::Cursor::new(spirv))
            .map_err(|e| GpuError::Unsupported(format!("shader {name}: invalid SPIR-V: {e}")))?;
        let info = vk::ShaderModuleCreateInfo::default().code(&words);
        // SAFETY: `words` is SPIR-V produced by glslc at build time.
        let raw =
            unsafe { ctx.device.create_shader_module(&info, None) }.vk("vkCreateShaderModule")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Self { ctx, raw })
    }
}

impl Drop for ShaderModule<'_> {
    fn drop(&mut self) {
        // SAFETY: modules are only referenced during pipeline creation, which has returned.
        unsafe { self.ctx.device.destroy_shader_module(self.raw, None) };
        self.ctx.count_destroyed(1);
    }
}

/// Specialization constants `constant_id = 0, 1, …`, each 32 bits.
struct Specialization {
    entries: Vec<vk::SpecializationMapEntry>,
    data: Vec<u8>,
}

impl Specialization {
    fn new(constants: &[u32]) -> Specialization {
        Specialization {
            entries: (0..constants.len() as u32)
                .map(|i| vk::SpecializationMapEntry {
                    constant_id: i,
                    offset: i * 4,
                    size: 4,
                })
                .collect(),
            data: constants.iter().flat_map(|c| c.to_ne_bytes()).collect(),
        }
    }

    fn info(&self) -> vk::SpecializationInfo<'_> {
        vk::SpecializationInfo::default()
            .map_entries(&self.entries)
            .data(&self.data)
    }
}

/// Fixed-function state of a graphics pipeline (viewport and scissor are dynamic).
#[derive(Clone, Debug)]
pub struct GraphicsDesc<'a> {
    pub name: &'a str,
    /// (stage, SPIR-V) for each shader stage.
    pub stages: &'a [(vk::ShaderStageFlags, &'a [u8])],
    pub colour_formats: &'a [vk::Format],
    pub depth_format: Option<vk::Format>,
    /// Depth test with this compare op (`None`: no test).
    pub depth_compare: Option<vk::CompareOp>,
    pub depth_write: bool,
    pub cull: vk::CullModeFlags,
    pub topology: vk::PrimitiveTopology,
    /// Control points per patch (tessellation pipelines).
    pub patch_control_points: u32,
    pub polygon_mode: vk::PolygonMode,
    /// Blend premultiplied colour over the attachment (out = src + (1 − src.a)·dst), for
    /// translucent draws (the spray); else the draw replaces what is there.
    pub blend_over: bool,
    /// `constants[i]` specializes `constant_id = i` in every stage (32-bit values).
    pub constants: &'a [u32],
}

impl Default for GraphicsDesc<'_> {
    fn default() -> Self {
        GraphicsDesc {
            name: "unnamed pipeline",
            stages: &[],
            colour_formats: &[],
            depth_format: None,
            depth_compare: None,
            depth_write: false,
            cull: vk::CullModeFlags::NONE,
            topology: vk::PrimitiveTopology::TRIANGLE_LIST,
            patch_control_points: 0,
            polygon_mode: vk::PolygonMode::FILL,
            blend_over: false,
            constants: &[],
        }
    }
}

/// A graphics or compute pipeline, its layout, and what its shaders use ([`Interface`], read
/// from their SPIR-V): the passes derive their reads from it.
pub struct Pipeline {
    ctx: Arc<Context>,
    /// Null until made: a pipeline made on first use ([`Pipeline::graphics_on_first_use`])
    /// is made when a recorder first binds it ([`Pipeline::handle`]).
    raw: Cell<vk::Pipeline>,
    /// What a pipeline made on first use is made from (`None` once made, or made at once).
    recipe: RefCell<Option<Recipe>>,
    /// Its identity for a rendering scope's declared draws (the handle may not exist yet).
    pub(super) id: u64,
    pub(super) bind_point: vk::PipelineBindPoint,
    pub(super) layout: PipelineLayout,
    pub(super) name: String,
    pub(super) interface: Interface,
    /// A graphics pipeline's colour and depth formats (`None` for compute).
    pub(super) formats: Option<(Vec<vk::Format>, Option<vk::Format>)>,
}

/// The union of the interfaces of `stages`, checked against `layout`.
fn interface_of(
    layout: &PipelineLayout,
    name: &str,
    stages: &[(vk::ShaderStageFlags, &[u8])],
) -> GpuResult<Interface> {
    let mut interface = Interface::default();
    for (stage, spirv) in stages {
        let one = Interface::of_shader(&format!("{name} {stage:?}"), spirv)
            .map_err(GpuError::Interface)?;
        interface.merge(&one);
    }
    layout.check(name, &interface)?;
    Ok(interface)
}

/// A colour attachment's blending: none (the draw replaces), or premultiplied colour over it.
fn blend_state(over: bool) -> vk::PipelineColorBlendAttachmentState {
    let state = vk::PipelineColorBlendAttachmentState::default()
        .color_write_mask(vk::ColorComponentFlags::RGBA);
    if !over {
        return state;
    }
    let (one, under) = (vk::BlendFactor::ONE, vk::BlendFactor::ONE_MINUS_SRC_ALPHA);
    state
        .blend_enable(true)
        .src_color_blend_factor(one)
        .dst_color_blend_factor(under)
        .color_blend_op(vk::BlendOp::ADD)
        .src_alpha_blend_factor(one)
        .dst_alpha_blend_factor(under)
        .alpha_blend_op(vk::BlendOp::ADD)
}

impl Pipeline {
    /// A graphics pipeline for dynamic rendering into `desc.colour_formats` / `desc.depth_format`.
    pub fn graphics(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        desc: &GraphicsDesc,
    ) -> GpuResult<Pipeline> {
        let pipeline = Pipeline::graphics_on_first_use(ctx, layout, desc)?;
        pipeline.handle()?;
        Ok(pipeline)
    }

    /// A graphics pipeline as [`Pipeline::graphics`] makes it, but made when a recorder first
    /// binds it: its shaders' interface is read and checked against `layout` now, the driver's
    /// compile waits until a frame draws with it. For the variants many runs never draw with
    /// (under the water, at the waterline, wireframe, floating bodies): lavapipe spends about
    /// 0.07–0.35 s of CPU on each scene pipeline, two thirds of a run's start-up. A failure
    /// then is the recording's: [`Recorder`](super::Recorder) skips the draws and the
    /// submission returns the error.
    pub fn graphics_on_first_use(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        desc: &GraphicsDesc,
    ) -> GpuResult<Pipeline> {
        let interface = interface_of(layout, desc.name, desc.stages)?;
        Ok(Pipeline {
            ctx: ctx.clone(),
            raw: Cell::new(vk::Pipeline::null()),
            recipe: RefCell::new(Some(Recipe::of(desc))),
            id: next_id(),
            bind_point: vk::PipelineBindPoint::GRAPHICS,
            layout: layout.clone(),
            name: desc.name.to_string(),
            interface,
            formats: Some((desc.colour_formats.to_vec(), desc.depth_format)),
        })
    }

    /// The pipeline's handle, made now if it is made on first use and was not yet.
    pub(super) fn handle(&self) -> GpuResult<vk::Pipeline> {
        if self.raw.get() == vk::Pipeline::null() {
            let raw = {
                let recipe = self.recipe.borrow();
                let recipe = recipe
                    .as_ref()
                    .expect("a pipeline without a handle has a recipe");
                let stages: Vec<_> = recipe.stages.iter().map(|(s, v)| (*s, &v[..])).collect();
                let desc = GraphicsDesc {
                    name: &recipe.name,
                    stages: &stages,
                    colour_formats: &recipe.colour_formats,
                    constants: &recipe.constants,
                    ..recipe.fixed.clone()
                };
                make_graphics(&self.ctx, &self.layout, &desc)
                    .map_err(|e| GpuError::Unsupported(format!("pipeline {}: {e}", recipe.name)))?
            };
            self.raw.set(raw);
            // Made: the recipe is no longer needed (after a failure it stays, to try again).
            self.recipe.borrow_mut().take();
        }
        Ok(self.raw.get())
    }
}

/// A graphics pipeline made on first use: its `GraphicsDesc`, owned (`fixed` holds the
/// fixed-function state; its name, stages, formats and constants are the fields here).
struct Recipe {
    name: String,
    stages: Vec<(vk::ShaderStageFlags, Vec<u8>)>,
    colour_formats: Vec<vk::Format>,
    constants: Vec<u32>,
    fixed: GraphicsDesc<'static>,
}

impl Recipe {
    fn of(desc: &GraphicsDesc) -> Recipe {
        Recipe {
            name: desc.name.to_string(),
            stages: desc.stages.iter().map(|(s, v)| (*s, v.to_vec())).collect(),
            colour_formats: desc.colour_formats.to_vec(),
            constants: desc.constants.to_vec(),
            fixed: GraphicsDesc {
                name: "",
                stages: &[],
                colour_formats: &[],
                depth_format: desc.depth_format,
                depth_compare: desc.depth_compare,
                depth_write: desc.depth_write,
                cull: desc.cull,
                topology: desc.topology,
                patch_control_points: desc.patch_control_points,
                polygon_mode: desc.polygon_mode,
                blend_over: desc.blend_over,
                constants: &[],
            },
        }
    }
}

/// A pipeline's identity, unique in the process.
fn next_id() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

/// Makes the graphics pipeline `desc` describes (its shader modules live only for the call).
fn make_graphics(
    ctx: &Context,
    layout: &PipelineLayout,
    desc: &GraphicsDesc,
) -> GpuResult<vk::Pipeline> {
    let modules = desc
        .stages
        .iter()
        .map(|(stage, spirv)| ShaderModule::new(ctx, &format!("{} {stage:?}", desc.name), spirv))
        .collect::<GpuResult<Vec<_>>>()?;
    let constants = Specialization::new(desc.constants);
    let specialization = constants.info();
    let stages: Vec<_> = desc
        .stages
        .iter()
        .zip(&modules)
        .map(|((stage, _), module)| {
            vk::PipelineShaderStageCreateInfo::default()
                .specialization_info(&specialization)
                .stage(*stage)
                .module(module.raw)
                .name(c"main")
        })
        .collect();
    let vertex_input = vk::PipelineVertexInputStateCreateInfo::default();
    let input_assembly =
        vk::PipelineInputAssemblyStateCreateInfo::default().topology(desc.topology);
    let tessellation = vk::PipelineTessellationStateCreateInfo::default()
        .patch_control_points(desc.patch_control_points);
    let viewport = vk::PipelineViewportStateCreateInfo::default()
        .viewport_count(1)
        .scissor_count(1);
    let raster = vk::PipelineRasterizationStateCreateInfo::default()
        .polygon_mode(desc.polygon_mode)
        .cull_mode(desc.cull)
        .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
        .line_width(1.0);
    let multisample = vk::PipelineMultisampleStateCreateInfo::default()
        .rasterization_samples(vk::SampleCountFlags::TYPE_1);
    let depth = vk::PipelineDepthStencilStateCreateInfo::default()
        .depth_test_enable(desc.depth_compare.is_some())
        .depth_write_enable(desc.depth_write)
        .depth_compare_op(desc.depth_compare.unwrap_or(vk::CompareOp::ALWAYS));
    let blend_attachments = vec![blend_state(desc.blend_over); desc.colour_formats.len()];
    let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
    let dynamic_states = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
    let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic_states);
    let mut rendering = vk::PipelineRenderingCreateInfo::default()
        .color_attachment_formats(desc.colour_formats)
        .depth_attachment_format(desc.depth_format.unwrap_or(vk::Format::UNDEFINED));
    let mut info = vk::GraphicsPipelineCreateInfo::default()
        .stages(&stages)
        .vertex_input_state(&vertex_input)
        .input_assembly_state(&input_assembly)
        .viewport_state(&viewport)
        .rasterization_state(&raster)
        .multisample_state(&multisample)
        .depth_stencil_state(&depth)
        .color_blend_state(&blend)
        .dynamic_state(&dynamic)
        .layout(layout.raw())
        .push_next(&mut rendering);
    if desc.patch_control_points > 0 {
        info = info.tessellation_state(&tessellation);
    }
    // SAFETY: every pointer in `info` refers to locals alive for the call; modules are live.
    let raw = unsafe {
        ctx.device
            .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
    }
    .map_err(|(_, result)| GpuError::Vk {
        call: "vkCreateGraphicsPipelines",
        result,
    })?[0];
    ctx.count_created(1);
    ctx.name(raw, desc.name);
    Ok(raw)
}

impl Pipeline {
    /// A compute pipeline from one compute shader.
    ///
    /// `constants[i]` specializes `constant_id = i` (32-bit values: uint, int or float bits).
    pub fn compute(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        name: &str,
        spirv: &[u8],
        constants: &[u32],
    ) -> GpuResult<Pipeline> {
        let interface = interface_of(layout, name, &[(vk::ShaderStageFlags::COMPUTE, spirv)])?;
        let module = ShaderModule::new(ctx, name, spirv)?;
        let constants = Specialization::new(constants);
        let specialization = constants.info();
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .specialization_info(&specialization)
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module.raw)
            .name(c"main");
        let info = vk::ComputePipelineCreateInfo::default()
            .stage(stage)
            .layout(layout.raw());
        // SAFETY: as for graphics pipelines.
        let raw = unsafe {
            ctx.device
                .create_compute_pipelines(vk::PipelineCache::null(), &[info], None)
        }
        .map_err(|(_, result)| GpuError::Vk {
            call: "vkCreateComputePipelines",
            result,
        })?[0];
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Pipeline {
            ctx: ctx.clone(),
            raw: Cell::new(raw),
            recipe: RefCell::new(None),
            id: next_id(),
            bind_point: vk::PipelineBindPoint::COMPUTE,
            layout: layout.clone(),
            name: name.to_string(),
            interface,
            formats: None,
        })
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// What its shaders use.
    pub fn interface(&self) -> &Interface {
        &self.interface
    }
}

impl Drop for Pipeline {
    fn drop(&mut self) {
        if self.raw.get() != vk::Pipeline::null() {
            self.ctx.defer(Garbage::Pipeline(self.raw.get()));
        }
    }
}
