//! `--frame-graph`: the frame as recorded, the table a synchronization question is checked
//! against (issue 31). The water pass lists the sky cube among its reads at the stage its
//! vertex routine samples it in, tessellation evaluation for the tessellated water and vertex
//! for the clipmap (the hazard the review found: it was declared for fragment shaders only),
//! and every image the pass's shaders sample appears with its stages.

mod common;

use common::{clean_run, entries, run, scratch, stderr};
use serde_json::Value;

fn names(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap_or(&Vec::new())
        .iter()
        .filter_map(|s| s.as_str().map(str::to_string))
        .collect()
}

const TESE: &str = "VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT";
const VERTEX: &str = "VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT";
const FRAGMENT: &str = "VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT";

/// Each water geometry and the stage its vertices are displaced and lit in.
const GEOMETRIES: [(&str, &str); 2] = [("tessellated", TESE), ("clipmap", VERTEX)];

fn graph(args: &[&str], name: &str) -> Value {
    let dir = scratch(name);
    let path = dir.join("fg.json");
    let mut all = vec!["--headless", "--validation", "--size", "320x180"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--frame-graph", path.to_str().unwrap()]);
    clean_run(&run(&all), "a frame graph run");
    serde_json::from_slice(&std::fs::read(&path).unwrap()).expect("valid JSON")
}

/// The passes named `name` in the graph (one per submission that has it).
fn passes<'a>(g: &'a Value, name: &str) -> Vec<&'a Value> {
    g["submissions"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|s| s["passes"].as_array().unwrap())
        .filter(|p| p["name"] == name)
        .collect()
}

fn read<'a>(pass: &'a Value, resource: &str) -> &'a Value {
    pass["reads"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["resource"] == resource)
        .unwrap_or_else(|| panic!("{resource} not among the reads of {}", pass["name"]))
}

#[test]
fn the_water_reads_the_sky_cube_where_its_shaders_sample_it() {
    for (geometry, stage) in GEOMETRIES {
        water_reads(geometry, stage);
    }
}

/// One frame: the sky cube is rendered in graphics 1 and first sampled by the water in
/// graphics 2, in `vertex_stage` (where `geometry` displaces and lights its vertices) and in
/// the fragment shader.
fn water_reads(geometry: &str, vertex_stage: &str) {
    let g = graph(
        &["--geometry", geometry],
        &format!("frame-graph-first-{geometry}"),
    );
    let submissions = g["submissions"].as_array().unwrap();
    let water = passes(&g, "water");
    assert_eq!(water.len(), 1, "one water pass");
    let water = water[0];
    let cube = read(water, "sky cube");
    let stages = names(&cube["stages"]);
    assert!(
        stages.iter().any(|s| s == vertex_stage) && stages.iter().any(|s| s == FRAGMENT),
        "{geometry}: sky cube read at {stages:?}"
    );
    // The reflection pass's sky moved it to SHADER_READ_ONLY_OPTIMAL for fragment shaders only
    // (a barrier after the cube's rendering, whose layout transition is its last write): the
    // water's barrier waits for that transition (and, chained through it, the rendering) at
    // the vertex routine's stage too.
    let before = names(&cube["barrier"]["before"]["stages"]);
    assert!(
        before.iter().any(|s| s == vertex_stage),
        "{geometry}: barrier before {before:?}"
    );
    let after = names(&cube["barrier"]["after"]["stages"]);
    assert_eq!(after, [FRAGMENT], "the barrier waits for {after:?}");
    assert_eq!(cube["layout"], "VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL");

    // Every image the water's shaders sample, with its stages: the simulation's ordered by the
    // compute timeline's wait (in GENERAL), the others by barriers.
    for (resource, stage) in [
        ("reflection colour", FRAGMENT),
        ("reflection sky", FRAGMENT),
        ("refraction colour", FRAGMENT),
        ("refraction depth", FRAGMENT),
        ("dudv map", FRAGMENT),
        ("ocean displacement slot 0", vertex_stage),
        ("ocean normals+foam slot 0", FRAGMENT),
    ] {
        let r = read(water, resource);
        assert!(
            names(&r["stages"]).iter().any(|s| s == stage),
            "{geometry}: {resource} read at {:?}",
            r["stages"]
        );
        assert_eq!(r["access"][0], "VK_ACCESS_2_SHADER_SAMPLED_READ_BIT");
    }
    // The reflection's sky and distances are drawn from its depth (after the reflection pass
    // wrote it) and the sky cube.
    let distance = passes(&g, "reflection distance");
    assert_eq!(distance.len(), 1, "one reflection distance pass");
    let depth = read(distance[0], "reflection depth");
    assert_eq!(names(&depth["stages"]), [FRAGMENT]);
    assert_eq!(depth["access"][0], "VK_ACCESS_2_SHADER_SAMPLED_READ_BIT");
    let cube = read(distance[0], "sky cube");
    assert_eq!(names(&cube["stages"]), [FRAGMENT]);
    let displacement = read(water, "ocean displacement slot 0");
    assert_eq!(displacement["ordered_by"], "compute timeline");
    assert_eq!(displacement["layout"], "VK_IMAGE_LAYOUT_GENERAL");

    // The submission with the water waits for the compute timeline at the value the compute
    // submission signals, at every stage that samples the simulation images.
    let with_water = submissions
        .iter()
        .find(|s| {
            s["passes"]
                .as_array()
                .unwrap()
                .iter()
                .any(|p| p["name"] == "water")
        })
        .unwrap();
    let wait = with_water["waits"]
        .as_array()
        .unwrap()
        .iter()
        .find(|w| w["semaphore"] == "compute timeline")
        .expect("a wait for the compute timeline");
    assert!(names(&wait["stages"]).iter().any(|s| s == vertex_stage));
    let signalled = submissions.iter().any(|s| {
        s["signals"]
            .as_array()
            .unwrap()
            .iter()
            .any(|x| x["semaphore"] == "compute timeline" && x["value"] == wait["value"])
    });
    assert!(signalled, "no submission signals {wait}");
    // Three submissions: graphics 1, compute, graphics 2.
    assert_eq!(
        submissions.len(),
        3,
        "{:?}",
        submissions.iter().map(|s| &s["name"]).collect::<Vec<_>>()
    );
}

#[test]
fn a_later_frame_needs_no_barrier_for_the_cube_and_the_dot_picture_draws_it() {
    let g = graph(
        &["--frames", "2", "--geometry", "tessellated"],
        "frame-graph-second",
    );
    let water = passes(&g, "water")[0];
    let cube = read(water, "sky cube");
    assert!(names(&cube["stages"]).iter().any(|s| s == TESE));
    assert!(
        cube.get("barrier").is_none(),
        "frame 0's barrier already made the cube visible there: {cube}"
    );
    // The sky cube is not re-rendered (the sun did not move).
    assert!(passes(&g, "sky cube").is_empty());

    let dir = scratch("frame-graph-dot");
    let dot = dir.join("fg.dot");
    clean_run(
        &run(&[
            "--headless",
            "--validation",
            "--size",
            "320x180",
            "--frames",
            "2",
            "--geometry",
            "tessellated",
            "--frame-graph",
            dot.to_str().unwrap(),
        ]),
        "a .dot frame graph",
    );
    let text = std::fs::read_to_string(&dot).unwrap();
    assert!(text.starts_with("digraph frame {"), "{text}");
    assert!(text.contains("label=\"water\""));
    assert!(text.contains("sky cube @ tessellation_evaluation_shader|fragment_shader"));
    assert!(text.trim_end().ends_with('}'));
}

#[test]
fn bad_frame_graph_paths_are_refused_before_rendering() {
    let dir = scratch("frame-graph-bad");
    let txt = dir.join("fg.txt");
    let out = run(&["--headless", "--frame-graph", txt.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("must end in .json or .dot"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let out = run(&["--headless", "--frame-graph", "/nonexistent-dir/fg.json"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("cannot write --frame-graph"));
    assert!(entries(&dir).is_empty(), "left behind: {:?}", entries(&dir));
}
