//! The frame graph: what one frame's submissions wait for and signal, and what each pass reads
//! and writes, at which stages, with which accesses, in which layouts. Recorded as the frame is
//! (`Context::capture_frame_graph` arms it; `Recorder::uses`, `Recorder::rendering` and the
//! queue submissions write it), so it is the table the barriers were made from, not a
//! description beside them. `--frame-graph PATH` writes it as JSON, or as a Graphviz picture
//! when PATH ends in `.dot`.

use std::fmt::Write as _;

use ash::vk;
use serde_json::{json, Value};

use super::track::Access;

/// `ordered_by` of a read of what the host wrote before the submission (uniforms, tables):
/// listed in the JSON, left out of the picture.
pub const HOST_WRITES: &str = "the host's writes before the submission";

/// One use of a resource by a pass.
#[derive(Clone, Debug)]
pub struct UseRecord {
    pub resource: String,
    pub stages: vk::PipelineStageFlags2,
    pub access: vk::AccessFlags2,
    /// The image's layout during the use (`None` for buffers).
    pub layout: Option<vk::ImageLayout>,
    /// The barrier recorded before it: (waited-for stages and accesses, this use's).
    pub barrier: Option<(Access, Access)>,
    /// What orders it when no barrier of this queue does (a semaphore wait).
    pub ordered_by: Option<String>,
}

/// A pass: its name and its uses, reads and writes apart.
#[derive(Clone, Debug, Default)]
pub struct PassRecord {
    pub name: String,
    pub reads: Vec<UseRecord>,
    pub writes: Vec<UseRecord>,
}

/// A semaphore a submission waits for or signals.
#[derive(Clone, Debug)]
pub struct SemaphoreRecord {
    pub semaphore: String,
    /// The timeline value (0 for a binary semaphore).
    pub value: u64,
    pub stages: vk::PipelineStageFlags2,
}

/// One `vkQueueSubmit2`.
#[derive(Clone, Debug)]
pub struct SubmissionRecord {
    pub name: String,
    pub queue: &'static str,
    pub queue_family: u32,
    pub waits: Vec<SemaphoreRecord>,
    pub signals: Vec<SemaphoreRecord>,
    pub passes: Vec<PassRecord>,
}

/// A recorded frame.
#[derive(Clone, Debug, Default)]
pub struct FrameGraph {
    pub submissions: Vec<SubmissionRecord>,
}

/// The frame graph being recorded: the passes of the command buffer not yet submitted.
#[derive(Default)]
pub(super) struct Journal {
    pub graph: FrameGraph,
    /// The next submission's name (its command buffer's first label).
    pub label: Option<String>,
    pub passes: Vec<PassRecord>,
}

impl Journal {
    pub fn label(&mut self, name: &str) {
        if self.label.is_none() {
            self.label = Some(name.to_string());
        }
    }

    pub fn pass(&mut self, name: &str) {
        if self.passes.last().is_none_or(|p| p.name != name) {
            self.passes.push(PassRecord {
                name: name.to_string(),
                ..PassRecord::default()
            });
        }
    }

    pub fn record(&mut self, record: UseRecord, writes: bool) {
        if self.passes.is_empty() {
            self.pass("(outside any pass)");
        }
        let pass = self.passes.last_mut().expect("a pass");
        if writes {
            pass.writes.push(record);
        } else {
            pass.reads.push(record);
        }
    }

    pub fn use_record(
        resource: &str,
        access: Access,
        layout: Option<vk::ImageLayout>,
        barrier: Option<(Access, Access)>,
        ordered_by: Option<&str>,
    ) -> UseRecord {
        UseRecord {
            resource: resource.to_string(),
            stages: access.stage,
            access: access.access,
            layout,
            barrier,
            ordered_by: ordered_by.map(str::to_string),
        }
    }

    pub fn submit(
        &mut self,
        queue: (&'static str, u32),
        waits: Vec<SemaphoreRecord>,
        signals: Vec<SemaphoreRecord>,
    ) {
        self.graph.submissions.push(SubmissionRecord {
            name: self.label.take().unwrap_or_else(|| "(unlabelled)".into()),
            queue: queue.0,
            queue_family: queue.1,
            waits,
            signals,
            passes: std::mem::take(&mut self.passes),
        });
    }
}

/// Vulkan's names of the bits of a flags value (`VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT`),
/// from ash's names of its constants.
fn flag_names(debug: String, prefix: &str) -> Vec<String> {
    if debug.is_empty() || debug == "empty" {
        return vec![format!("{prefix}NONE")];
    }
    debug
        .split(" | ")
        .filter(|n| !n.is_empty() && !n.starts_with("0x"))
        .map(|n| {
            if n == "NONE" || n == "empty" {
                return format!("{prefix}NONE");
            }
            match ["_KHR", "_EXT", "_NV", "_AMD"]
                .iter()
                .find(|s| n.ends_with(**s))
            {
                Some(suffix) => format!("{prefix}{}_BIT{suffix}", &n[..n.len() - suffix.len()]),
                None => format!("{prefix}{n}_BIT"),
            }
        })
        .collect()
}

pub fn stage_names(stages: vk::PipelineStageFlags2) -> Vec<String> {
    flag_names(format!("{stages:?}"), "VK_PIPELINE_STAGE_2_")
}

pub fn access_names(access: vk::AccessFlags2) -> Vec<String> {
    flag_names(format!("{access:?}"), "VK_ACCESS_2_")
}

pub fn layout_name(layout: vk::ImageLayout) -> String {
    format!("VK_IMAGE_LAYOUT_{layout:?}")
}

/// Stage names for a picture: `tessellation_evaluation_shader|fragment_shader`.
fn short(stages: vk::PipelineStageFlags2) -> String {
    stage_names(stages)
        .iter()
        .map(|n| {
            n.trim_start_matches("VK_PIPELINE_STAGE_2_")
                .trim_end_matches("_BIT")
                .to_lowercase()
        })
        .collect::<Vec<_>>()
        .join("|")
}

/// A name inside a Graphviz string.
fn quote(s: &str) -> String {
    s.replace('"', "'")
}

impl FrameGraph {
    /// `{"submissions": [{"name", "queue", "queue_family", "waits", "signals", "passes":
    /// [{"name", "reads", "writes"}]}]}`, flags as arrays of Vulkan names.
    pub fn to_json(&self) -> Value {
        let semaphore = |s: &SemaphoreRecord| json!({"semaphore": s.semaphore, "value": s.value, "stages": stage_names(s.stages)});
        let access =
            |a: &Access| json!({"stages": stage_names(a.stage), "access": access_names(a.access)});
        let one_use = |u: &UseRecord| {
            let mut v = json!({
                "resource": u.resource,
                "stages": stage_names(u.stages),
                "access": access_names(u.access),
            });
            if let Some(layout) = u.layout {
                v["layout"] = json!(layout_name(layout));
            }
            if let Some((src, dst)) = &u.barrier {
                v["barrier"] = json!({"after": access(src), "before": access(dst)});
            }
            if let Some(by) = &u.ordered_by {
                v["ordered_by"] = json!(by);
            }
            v
        };
        let submissions: Vec<Value> = self
            .submissions
            .iter()
            .map(|s| {
                json!({
                    "name": s.name,
                    "queue": s.queue,
                    "queue_family": s.queue_family,
                    "waits": s.waits.iter().map(semaphore).collect::<Vec<_>>(),
                    "signals": s.signals.iter().map(semaphore).collect::<Vec<_>>(),
                    "passes": s.passes.iter().map(|p| json!({
                        "name": p.name,
                        "reads": p.reads.iter().map(one_use).collect::<Vec<_>>(),
                        "writes": p.writes.iter().map(one_use).collect::<Vec<_>>(),
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        json!({ "submissions": submissions })
    }

    /// A Graphviz digraph: each submission a cluster of its passes, in order; an edge from the
    /// pass that last wrote a resource to each pass that then uses it, labelled with the
    /// resource and the reading stages; semaphores as edges between submissions.
    pub fn to_dot(&self) -> String {
        let mut out = String::from(
            "digraph frame {\n  rankdir=TB;\n  node [shape=box, style=rounded, fontname=\"Helvetica\"];\n  edge [fontname=\"Helvetica\", fontsize=10];\n",
        );
        let mut writer: std::collections::HashMap<String, String> = Default::default();
        let mut signalled: std::collections::HashMap<(String, u64), String> = Default::default();
        for (si, s) in self.submissions.iter().enumerate() {
            let _ = writeln!(
                out,
                "  subgraph cluster_{si} {{\n    label=\"{} ({} queue, family {})\";\n    style=dashed;",
                quote(&s.name),
                s.queue,
                s.queue_family
            );
            let first = format!("s{si}_start");
            let _ = writeln!(out, "    {first} [label=\"submit\", shape=point];");
            for (pi, p) in s.passes.iter().enumerate() {
                let _ = writeln!(out, "    s{si}p{pi} [label=\"{}\"];", quote(&p.name));
            }
            out.push_str("  }\n");
            for w in &s.waits {
                let from = signalled
                    .get(&(w.semaphore.clone(), w.value))
                    .cloned()
                    .unwrap_or_else(|| {
                        let id = format!(
                            "ext_{}",
                            w.semaphore.replace(|c: char| !c.is_alphanumeric(), "_")
                        );
                        let _ = writeln!(
                            out,
                            "  {id} [label=\"{}\", shape=ellipse];",
                            quote(&w.semaphore)
                        );
                        id
                    });
                let _ = writeln!(
                    out,
                    "  {from} -> {first} [style=bold, color=blue, label=\"{} = {} at {}\"];",
                    quote(&w.semaphore),
                    w.value,
                    short(w.stages)
                );
            }
            for (pi, p) in s.passes.iter().enumerate() {
                let node = format!("s{si}p{pi}");
                let drawn = p.reads.iter().chain(&p.writes);
                for u in drawn.filter(|u| u.ordered_by.as_deref() != Some(HOST_WRITES)) {
                    if !writer.contains_key(&u.resource)
                        && !p.writes.iter().any(|w| w.resource == u.resource)
                    {
                        // Read before any pass of this frame writes it: from an earlier frame
                        // (or an upload), drawn as a node of its own.
                        let id = format!(
                            "res_{}",
                            u.resource.replace(|c: char| !c.is_alphanumeric(), "_")
                        );
                        let _ = writeln!(
                            out,
                            "  {id} [label=\"{}\\n(earlier frame)\", shape=note];",
                            quote(&u.resource)
                        );
                        writer.insert(u.resource.clone(), id);
                    }
                    if let Some(from) = writer.get(&u.resource) {
                        if *from != node {
                            let style = if u.ordered_by.is_some() {
                                ", style=dashed"
                            } else {
                                ""
                            };
                            let _ = writeln!(
                                out,
                                "  {from} -> {node} [label=\"{} @ {}\"{style}];",
                                quote(&u.resource),
                                short(u.stages)
                            );
                        }
                    }
                }
                for u in &p.writes {
                    writer.insert(u.resource.clone(), node.clone());
                }
            }
            let last = s
                .passes
                .len()
                .checked_sub(1)
                .map_or(first.clone(), |pi| format!("s{si}p{pi}"));
            for sig in &s.signals {
                signalled.insert((sig.semaphore.clone(), sig.value), last.clone());
            }
        }
        out.push_str("}\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_have_their_vulkan_names() {
        use vk::PipelineStageFlags2 as P;
        assert_eq!(
            stage_names(P::TESSELLATION_EVALUATION_SHADER | P::FRAGMENT_SHADER),
            [
                "VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT",
                "VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT"
            ]
        );
        assert_eq!(stage_names(P::NONE), ["VK_PIPELINE_STAGE_2_NONE"]);
        assert_eq!(
            access_names(vk::AccessFlags2::SHADER_SAMPLED_READ),
            ["VK_ACCESS_2_SHADER_SAMPLED_READ_BIT"]
        );
        assert_eq!(
            layout_name(vk::ImageLayout::PRESENT_SRC_KHR),
            "VK_IMAGE_LAYOUT_PRESENT_SRC_KHR"
        );
    }
}
