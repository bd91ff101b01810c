//! A pass's barriers come from the shaders it binds (issue 31): a texture sampled in the vertex
//! stage is waited for at the vertex stage, without the pass saying so, and a declaration that
//! disagrees with the shaders is refused at creation with one line naming the pipeline or
//! pass, the binding and the stage. The shaders are test-only (shaders/test/): a vertex shader
//! that samples a texture, and a fragment shader that samples nothing.

mod common;

use common::{assert_validation_clean, gpu_context, test_image as image};
use vkocean::gpu::oneshot::run_once;
use vkocean::gpu::{
    check_bindings, vk, Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GraphicsDesc,
    Image, Load, Order, Pipeline, PipelineLayout, Sampler, Target,
};
use vkocean::shaders;

const FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

/// The test pipeline, its texture visible to `visible` in the set layout.
fn pipeline(
    ctx: &std::sync::Arc<Context>,
    visible: vk::ShaderStageFlags,
) -> (
    DescriptorSetLayout,
    Result<Pipeline, vkocean::gpu::GpuError>,
) {
    made(ctx, visible, Pipeline::graphics)
}

type Make = fn(
    &std::sync::Arc<Context>,
    &PipelineLayout,
    &GraphicsDesc,
) -> Result<Pipeline, vkocean::gpu::GpuError>;

/// The test pipeline as `make` makes it (at once or on first use).
fn made(
    ctx: &std::sync::Arc<Context>,
    visible: vk::ShaderStageFlags,
    make: Make,
) -> (
    DescriptorSetLayout,
    Result<Pipeline, vkocean::gpu::GpuError>,
) {
    let set_layout = DescriptorSetLayout::new(
        ctx,
        "test texture layout",
        &[(0, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, visible)],
    )
    .unwrap();
    let layout = PipelineLayout::new(ctx, "test layout", &[&set_layout], None).unwrap();
    let pipeline = make(
        ctx,
        &layout,
        &GraphicsDesc {
            name: "samples in vertex",
            stages: &[
                (
                    vk::ShaderStageFlags::VERTEX,
                    shaders::TEST_SAMPLED_IN_VERTEX_VERT,
                ),
                (vk::ShaderStageFlags::FRAGMENT, shaders::TEST_CONSTANT_FRAG),
            ],
            colour_formats: &[FORMAT],
            ..Default::default()
        },
    );
    (set_layout, pipeline)
}

/// The texture the test pipeline's vertex shader samples, a target to draw into, a sampler.
fn images(ctx: &std::sync::Arc<Context>) -> (Image, Image, Sampler) {
    let sampled = vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED;
    let texture = image(ctx, "vertex texture", sampled);
    let target = image(ctx, "test target", vk::ImageUsageFlags::COLOR_ATTACHMENT);
    let sampler =
        Sampler::linear(ctx, "test sampler", vk::SamplerAddressMode::CLAMP_TO_EDGE).unwrap();
    (texture, target, sampler)
}

#[test]
fn a_texture_sampled_in_the_vertex_stage_is_waited_for_there() {
    let ctx = gpu_context();
    let (texture, target, sampler) = images(&ctx);
    let (set_layout, pipeline) = pipeline(&ctx, vk::ShaderStageFlags::VERTEX);
    let pipeline = pipeline.unwrap();
    // Nothing says "vertex" below: the stage comes from the vertex shader's SPIR-V.
    let bind = Bind::Sampled(&texture, &sampler, Order::Tracked);
    let set = BoundSet::new(&ctx, &set_layout, "test texture set", &[(0, bind)]).unwrap();
    let sets = [&set];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets,
    };
    check_bindings("vertex reader", &[draw]).unwrap();

    ctx.capture_frame_graph();
    run_once(&ctx, "derived barrier test", |rec| {
        // The texture is written (a cleared colour attachment) ...
        let clear = Load::Clear(vk::ClearValue {
            color: vk::ClearColorValue {
                float32: [0.5, 0.0, 0.0, 1.0],
            },
        });
        rec.rendering("writer", &[Target::new(&texture, clear)], None, &[])
            .record(|| {});
        // ... then sampled by the vertex shader of the next pass's draw.
        let target = [Target::new(&target, Load::DontCare)];
        let scope = rec.rendering("vertex reader", &target, None, &[draw]);
        scope.record(|| {
            rec.bind(&draw);
            rec.draw(3, 1);
        });
    })
    .unwrap();
    let graph = ctx.take_frame_graph().expect("the capture's graph");
    let reader = graph
        .submissions
        .iter()
        .flat_map(|s| &s.passes)
        .find(|p| p.name == "vertex reader")
        .expect("the reading pass in the graph");
    let read = reader
        .reads
        .iter()
        .find(|r| r.resource == "vertex texture")
        .expect("the texture among the pass's reads");
    let vertex = vk::PipelineStageFlags2::VERTEX_SHADER;
    assert!(read.stages.contains(vertex), "read at {:?}", read.stages);
    let (after, before) = read.barrier.expect("a barrier before the read");
    assert!(
        before.stage.contains(vertex),
        "the barrier waits at {:?}, not at the vertex stage",
        before.stage
    );
    assert!(
        after
            .stage
            .contains(vk::PipelineStageFlags2::COLOR_ATTACHMENT_OUTPUT),
        "the barrier waits for {:?}, not the colour write",
        after.stage
    );
    assert_eq!(read.layout, Some(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL));
    drop((set, pipeline, set_layout, sampler, texture, target));
    // Synchronization validation checks the same barrier independently.
    assert_validation_clean(ctx);
}

#[test]
fn a_layout_that_hides_the_texture_from_the_stage_reading_it_is_refused() {
    let ctx = gpu_context();
    let (set_layout, pipeline) = pipeline(&ctx, vk::ShaderStageFlags::FRAGMENT);
    let error = pipeline
        .err()
        .expect("refused at pipeline creation")
        .to_string();
    for part in ["samples in vertex", "set 0 binding 0", "VERTEX", "FRAGMENT"] {
        assert!(error.contains(part), "{part:?} not in: {error}");
    }
    assert_eq!(error.lines().count(), 1, "one line: {error}");
    drop(set_layout);
    assert_validation_clean(ctx);
}

#[test]
fn a_texture_read_outside_its_semaphore_waits_stages_is_refused() {
    let ctx = gpu_context();
    let texture = image(&ctx, "waited texture", vk::ImageUsageFlags::SAMPLED);
    let sampler =
        Sampler::linear(&ctx, "test sampler", vk::SamplerAddressMode::CLAMP_TO_EDGE).unwrap();
    let (set_layout, pipeline) = pipeline(&ctx, vk::ShaderStageFlags::VERTEX);
    let pipeline = pipeline.unwrap();
    // Ordered by a wait at the fragment stage only, but read by the vertex shader.
    let wait = Order::Wait {
        by: "a test semaphore's wait",
        stages: vk::PipelineStageFlags2::FRAGMENT_SHADER,
    };
    let bind = Bind::Sampled(&texture, &sampler, wait);
    let set = BoundSet::new(&ctx, &set_layout, "waited set", &[(0, bind)]).unwrap();
    let sets = [&set];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets,
    };
    let error = check_bindings("early reader", &[draw])
        .expect_err("refused at creation")
        .to_string();
    for part in [
        "early reader",
        "waited texture",
        "set 0 binding 0",
        "VERTEX_SHADER",
        "a test semaphore's wait",
    ] {
        assert!(error.contains(part), "{part:?} not in: {error}");
    }
    // Covered by the wait: accepted.
    let covering = Order::Wait {
        by: "a test semaphore's wait",
        stages: vk::PipelineStageFlags2::VERTEX_SHADER | vk::PipelineStageFlags2::FRAGMENT_SHADER,
    };
    let bind = Bind::Sampled(&texture, &sampler, covering);
    let set2 = BoundSet::new(&ctx, &set_layout, "covered set", &[(0, bind)]).unwrap();
    let sets2 = [&set2];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets2,
    };
    check_bindings("early reader", &[draw]).unwrap();
    drop((set, set2, pipeline, set_layout, sampler, texture));
    assert_validation_clean(ctx);
}

#[test]
fn a_set_written_with_another_type_than_its_layout_is_refused() {
    let ctx = gpu_context();
    let texture = image(&ctx, "mistyped texture", vk::ImageUsageFlags::STORAGE);
    let (set_layout, _) = pipeline(&ctx, vk::ShaderStageFlags::VERTEX);
    let bind = Bind::StorageImage(&texture, Order::Tracked);
    let error = BoundSet::new(&ctx, &set_layout, "mistyped set", &[(0, bind)])
        .err()
        .expect("refused")
        .to_string();
    assert!(error.contains("binding 0"), "{error}");
    drop((set_layout, texture));
    assert_validation_clean(ctx);
}

#[test]
#[should_panic(expected = "did not declare")]
fn a_draw_its_scope_did_not_declare_is_refused() {
    let ctx = gpu_context();
    let texture = image(&ctx, "undeclared texture", vk::ImageUsageFlags::SAMPLED);
    let target = image(&ctx, "test target", vk::ImageUsageFlags::COLOR_ATTACHMENT);
    let sampler =
        Sampler::linear(&ctx, "test sampler", vk::SamplerAddressMode::CLAMP_TO_EDGE).unwrap();
    let (set_layout, pipeline) = pipeline(&ctx, vk::ShaderStageFlags::VERTEX);
    let pipeline = pipeline.unwrap();
    let bind = Bind::Sampled(&texture, &sampler, Order::Tracked);
    let set = BoundSet::new(&ctx, &set_layout, "undeclared set", &[(0, bind)]).unwrap();
    let sets = [&set];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets,
    };
    let _ = run_once(&ctx, "undeclared draw", |rec| {
        // The scope declares no draws, so no barrier covers the texture: the draw is refused.
        let target = [Target::new(&target, Load::DontCare)];
        rec.rendering("undeclared", &target, None, &[]).record(|| {
            rec.bind(&draw);
            rec.draw(3, 1);
        });
    });
}

#[test]
#[should_panic(expected = "in a submission without waits")]
fn a_read_ordered_by_a_wait_in_a_submission_without_waits_is_refused() {
    let ctx = gpu_context();
    let texture = image(&ctx, "waited texture", vk::ImageUsageFlags::SAMPLED);
    let target = image(&ctx, "test target", vk::ImageUsageFlags::COLOR_ATTACHMENT);
    let sampler =
        Sampler::linear(&ctx, "test sampler", vk::SamplerAddressMode::CLAMP_TO_EDGE).unwrap();
    let (set_layout, pipeline) = pipeline(&ctx, vk::ShaderStageFlags::VERTEX);
    let pipeline = pipeline.unwrap();
    let wait = Order::Wait {
        by: "compute timeline",
        stages: vk::PipelineStageFlags2::VERTEX_SHADER,
    };
    let bind = Bind::Sampled(&texture, &sampler, wait);
    let set = BoundSet::new(&ctx, &set_layout, "waited set", &[(0, bind)]).unwrap();
    let sets = [&set];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets,
    };
    // A one-shot waits for nothing: the read has no wait to rely on.
    let _ = run_once(&ctx, "read without its wait", |rec| {
        let target = [Target::new(&target, Load::DontCare)];
        let _ = rec.rendering("early reader", &target, None, &[draw]);
    });
}

#[test]
fn a_pipeline_made_on_first_use_is_made_by_the_first_draw_with_it_and_only_then() {
    let ctx = gpu_context();
    let (texture, target, sampler) = images(&ctx);
    let visible = vk::ShaderStageFlags::VERTEX;
    let (set_layout, pipeline) = made(&ctx, visible, Pipeline::graphics_on_first_use);
    let pipeline = pipeline.unwrap();
    let bind = Bind::Sampled(&texture, &sampler, Order::Tracked);
    let set = BoundSet::new(&ctx, &set_layout, "test texture set", &[(0, bind)]).unwrap();
    let sets = [&set];
    let draw = Bindings {
        pipeline: &pipeline,
        sets: &sets,
    };
    // Its interface is read at creation: the checks need no handle.
    check_bindings("vertex reader", &[draw]).unwrap();
    let frame = |with_draw: bool| {
        run_once(&ctx, "first use test", |rec| {
            let clear = Load::Clear(vk::ClearValue {
                color: vk::ClearColorValue {
                    float32: [0.5, 0.0, 0.0, 1.0],
                },
            });
            rec.rendering("writer", &[Target::new(&texture, clear)], None, &[])
                .record(|| {});
            let target = [Target::new(&target, Load::DontCare)];
            let draws: &[Bindings] = if with_draw { &[draw] } else { &[] };
            rec.rendering("vertex reader", &target, None, draws)
                .record(|| {
                    if with_draw {
                        rec.bind(&draw);
                        rec.draw(3, 1);
                    }
                });
        })
        .unwrap();
        ctx.live_objects()
    };
    let before = ctx.live_objects();
    // A frame that declares and draws nothing with it does not make it ...
    assert_eq!(frame(false), before, "made without a draw");
    // ... the first draw makes it: one pipeline (its shader modules live only for the call) ...
    assert_eq!(frame(true), before + 1, "the first draw made no pipeline");
    // ... and later draws use it.
    assert_eq!(frame(true), before + 1, "a second draw made another");
    drop((set, pipeline, set_layout, sampler, texture, target));
    assert_validation_clean(ctx);
}
