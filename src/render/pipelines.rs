//! Bind group layouts (fixed, made once) and the render pipelines (made from `shaders/`, remade
//! on hot reload). A shader is parsed and validated by naga first; then its module and
//! pipelines are created inside a wgpu error scope, and on any error the old ones stay.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::diag::Diagnostic;

use super::mesh::Vertex;
use super::shaders;

pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
pub const CUBE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

pub struct Layouts {
    pub empty: wgpu::BindGroupLayout,
    pub frame: wgpu::BindGroupLayout,
    pub shadow_frame: wgpu::BindGroupLayout,
    pub material: wgpu::BindGroupLayout,
    pub object: wgpu::BindGroupLayout,
    pub water_inputs: wgpu::BindGroupLayout,
    pub sky_params: wgpu::BindGroupLayout,
    pub prefilter: wgpu::BindGroupLayout,
    pub tonemap: wgpu::BindGroupLayout,
    pub debug: wgpu::BindGroupLayout,
}

fn uniform(binding: u32, vis: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: vis,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture(
    binding: u32,
    dim: wgpu::TextureViewDimension,
    sample: wgpu::TextureSampleType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: sample,
            view_dimension: dim,
            multisampled: false,
        },
        count: None,
    }
}

fn sampler(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

impl Layouts {
    pub fn new(device: &wgpu::Device) -> Self {
        use wgpu::{
            SamplerBindingType as S, ShaderStages as V, TextureSampleType as T,
            TextureViewDimension as D,
        };
        let vf = V::VERTEX | V::FRAGMENT;
        let float = T::Float { filterable: true };
        let make = |label: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        Self {
            empty: make("empty", &[]),
            frame: make(
                "frame",
                &[
                    uniform(0, vf),
                    texture(1, D::Cube, float),
                    sampler(2, S::Filtering),
                    texture(3, D::D2, T::Depth),
                    sampler(4, S::Comparison),
                ],
            ),
            shadow_frame: make("shadow frame", &[uniform(0, vf)]),
            material: make(
                "material",
                &[
                    uniform(0, vf),
                    texture(1, D::D2, float),
                    sampler(2, S::Filtering),
                ],
            ),
            object: make("object", &[uniform(0, vf)]),
            water_inputs: make(
                "water inputs",
                &[
                    texture(0, D::D2, float),
                    texture(1, D::D2, T::Depth),
                    sampler(2, S::Filtering),
                ],
            ),
            sky_params: make("sky params", &[uniform(0, vf)]),
            prefilter: make(
                "prefilter",
                &[
                    uniform(0, vf),
                    texture(1, D::Cube, float),
                    sampler(2, S::Filtering),
                ],
            ),
            tonemap: make(
                "tonemap",
                &[
                    uniform(0, vf),
                    texture(1, D::D2, T::Float { filterable: false }),
                ],
            ),
            debug: make(
                "debug",
                &[
                    uniform(0, vf),
                    texture(1, D::D2, T::Depth),
                    texture(2, D::Cube, float),
                    sampler(3, S::Filtering),
                ],
            ),
        }
    }
}

/// Everything a pipeline builder needs besides the shader module.
pub struct Ctx<'a> {
    pub device: &'a wgpu::Device,
    pub layouts: &'a Layouts,
    pub output_format: wgpu::TextureFormat,
}

type Built = Vec<(&'static str, wgpu::RenderPipeline)>;
type Builder = fn(&Ctx, &wgpu::ShaderModule) -> Built;

/// Each shader file and the pipelines made from it.
pub const SHADERS: [(&str, Builder); 8] = [
    ("sky.wgsl", build_sky),
    ("prefilter.wgsl", build_prefilter),
    ("pbr.wgsl", build_pbr),
    ("fish.wgsl", build_fish),
    ("shadow.wgsl", build_shadow),
    ("water.wgsl", build_water),
    ("tonemap.wgsl", build_tonemap),
    ("debug.wgsl", build_debug),
];

pub struct Pipelines {
    dir: PathBuf,
    map: HashMap<&'static str, wgpu::RenderPipeline>,
    /// The newest error of each shader file (cleared when it builds again).
    errors: HashMap<&'static str, Diagnostic>,
    /// Files each shader was built from (itself and its includes).
    files: HashMap<&'static str, Vec<PathBuf>>,
}

impl Pipelines {
    /// Builds every pipeline; fails with the first shader error (nothing to fall back to yet).
    pub fn new(ctx: &Ctx, dir: &Path) -> Result<Self, Diagnostic> {
        let mut p = Self {
            dir: dir.to_path_buf(),
            map: HashMap::new(),
            errors: HashMap::new(),
            files: HashMap::new(),
        };
        for (name, builder) in SHADERS {
            p.build_one(ctx, name, builder);
            if let Some(e) = p.errors.get(name) {
                return Err(e.clone());
            }
        }
        Ok(p)
    }

    fn build_one(&mut self, ctx: &Ctx, name: &'static str, builder: Builder) {
        let path = self.dir.join(name);
        if let Ok(src) = shaders::load(&path) {
            self.files.insert(name, src.files.clone());
        }
        match try_build(ctx, &path, builder) {
            Ok(built) => {
                self.map.extend(built);
                self.errors.remove(name);
            }
            Err(d) => {
                tracing::warn!("{d}");
                self.errors.insert(name, d);
            }
        }
    }

    /// Rebuilds the shaders that use any of `changed`; returns whether any was affected.
    pub fn reload(&mut self, ctx: &Ctx, changed: &[PathBuf]) -> bool {
        let same = |a: &Path, b: &Path| a.file_name() == b.file_name();
        let mut any = false;
        for (name, builder) in SHADERS {
            let deps = self
                .files
                .get(name)
                .cloned()
                .unwrap_or_else(|| vec![self.dir.join(name)]);
            if changed.iter().any(|c| deps.iter().any(|d| same(c, d))) {
                self.build_one(ctx, name, builder);
                any = true;
            }
        }
        any
    }

    pub fn get(&self, key: &str) -> &wgpu::RenderPipeline {
        &self.map[key]
    }

    pub fn errors(&self) -> Vec<&Diagnostic> {
        let mut v: Vec<&Diagnostic> = self.errors.values().collect();
        v.sort_by_key(|d| d.to_string());
        v
    }
}

/// naga parse + validate, then module and pipelines inside a validation error scope.
pub fn try_build(ctx: &Ctx, path: &Path, builder: Builder) -> Result<Built, Diagnostic> {
    let src = shaders::load_checked(path)?;
    let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = ctx
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&path.display().to_string()),
            source: wgpu::ShaderSource::Wgsl(src.text.clone().into()),
        });
    let built = builder(ctx, &module);
    match pollster::block_on(scope.pop()) {
        None => Ok(built),
        Some(e) => Err(Diagnostic::whole_file(
            path,
            format!("pipeline creation failed: {e}"),
        )),
    }
}

fn layout(ctx: &Ctx, groups: &[&wgpu::BindGroupLayout]) -> wgpu::PipelineLayout {
    let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().map(|g| Some(*g)).collect();
    ctx.device
        .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &groups,
            immediate_size: 0,
        })
}

struct Desc<'a> {
    label: &'static str,
    layout: &'a wgpu::PipelineLayout,
    vs: &'static str,
    fs: Option<&'static str>,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    color: Option<wgpu::TextureFormat>,
    depth: Option<(bool, wgpu::CompareFunction, wgpu::DepthBiasState)>,
    cull: Option<wgpu::Face>,
}

fn pipeline(
    ctx: &Ctx,
    module: &wgpu::ShaderModule,
    d: Desc,
) -> (&'static str, wgpu::RenderPipeline) {
    let targets = [d.color.map(|format| wgpu::ColorTargetState {
        format,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    })];
    let p = ctx
        .device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(d.label),
            layout: Some(d.layout),
            vertex: wgpu::VertexState {
                module,
                entry_point: Some(d.vs),
                compilation_options: Default::default(),
                buffers: d.buffers,
            },
            fragment: d.fs.map(|fs| wgpu::FragmentState {
                module,
                entry_point: Some(fs),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            primitive: wgpu::PrimitiveState {
                cull_mode: d.cull,
                ..Default::default()
            },
            depth_stencil: d
                .depth
                .map(|(write, compare, bias)| wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias,
                }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
    (d.label, p)
}

const NO_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 0,
    slope_scale: 0.0,
    clamp: 0.0,
};

fn opaque_depth() -> Option<(bool, wgpu::CompareFunction, wgpu::DepthBiasState)> {
    Some((true, wgpu::CompareFunction::Less, NO_BIAS))
}

fn build_sky(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    let l = &ctx.layouts;
    vec![
        pipeline(
            ctx,
            m,
            Desc {
                label: "sky.cube",
                layout: &layout(ctx, &[&l.empty, &l.sky_params]),
                vs: "vs_fullscreen",
                fs: Some("fs_cube_face"),
                buffers: &[],
                color: Some(CUBE_FORMAT),
                depth: None,
                cull: None,
            },
        ),
        pipeline(
            ctx,
            m,
            Desc {
                label: "sky.background",
                layout: &layout(ctx, &[&l.frame]),
                vs: "vs_fullscreen",
                fs: Some("fs_background"),
                buffers: &[],
                color: Some(HDR_FORMAT),
                depth: Some((false, wgpu::CompareFunction::LessEqual, NO_BIAS)),
                cull: None,
            },
        ),
    ]
}

fn build_prefilter(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "prefilter",
            layout: &layout(ctx, &[&ctx.layouts.prefilter]),
            vs: "vs_fullscreen",
            fs: Some("fs_main"),
            buffers: &[],
            color: Some(CUBE_FORMAT),
            depth: None,
            cull: None,
        },
    )]
}

fn build_pbr(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    let l = &ctx.layouts;
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "pbr",
            layout: &layout(ctx, &[&l.frame, &l.material, &l.object]),
            vs: "vs_main",
            fs: Some("fs_main"),
            buffers: &[Some(Vertex::layout())],
            color: Some(HDR_FORMAT),
            depth: opaque_depth(),
            cull: Some(wgpu::Face::Back),
        },
    )]
}

/// Per-instance fish data: position + scale, orientation quaternion (x, y, z, w), tail phase.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FishInstanceGpu {
    pub position_scale: [f32; 4],
    pub rotation: [f32; 4],
    pub tail_phase: f32,
}

impl FishInstanceGpu {
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![4 => Float32x4, 5 => Float32x4, 6 => Float32];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Self>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// Slope-scaled depth bias of the shadow casters (in depth-format units and per unit slope).
pub const SHADOW_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 2,
    slope_scale: 2.5,
    clamp: 0.0,
};

fn build_fish(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    let l = &ctx.layouts;
    let buffers = [Some(Vertex::layout()), Some(FishInstanceGpu::layout())];
    vec![
        pipeline(
            ctx,
            m,
            Desc {
                label: "fish",
                layout: &layout(ctx, &[&l.frame, &l.material]),
                vs: "vs_main",
                fs: Some("fs_main"),
                buffers: &buffers,
                color: Some(HDR_FORMAT),
                depth: opaque_depth(),
                cull: None, // the tail fin is seen from both sides
            },
        ),
        pipeline(
            ctx,
            m,
            Desc {
                label: "fish.shadow",
                layout: &layout(ctx, &[&l.shadow_frame]),
                vs: "vs_shadow",
                fs: None,
                buffers: &buffers,
                color: None,
                depth: Some((true, wgpu::CompareFunction::Less, SHADOW_BIAS)),
                cull: None,
            },
        ),
    ]
}

fn build_shadow(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    let l = &ctx.layouts;
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "shadow",
            layout: &layout(ctx, &[&l.shadow_frame, &l.object]),
            vs: "vs_main",
            fs: None,
            buffers: &[Some(Vertex::layout())],
            color: None,
            depth: Some((true, wgpu::CompareFunction::Less, SHADOW_BIAS)),
            cull: None,
        },
    )]
}

pub fn water_vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTR: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x2];
    wgpu::VertexBufferLayout {
        array_stride: 8,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &ATTR,
    }
}

fn build_water(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    let l = &ctx.layouts;
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "water",
            layout: &layout(ctx, &[&l.frame, &l.water_inputs]),
            vs: "vs_main",
            fs: Some("fs_main"),
            buffers: &[Some(water_vertex_layout())],
            color: Some(HDR_FORMAT),
            // reads the opaque depth as a texture in the same pass: test, never write
            depth: Some((false, wgpu::CompareFunction::Less, NO_BIAS)),
            cull: None,
        },
    )]
}

fn build_tonemap(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "tonemap",
            layout: &layout(ctx, &[&ctx.layouts.tonemap]),
            vs: "vs_fullscreen",
            fs: Some("fs_main"),
            buffers: &[],
            color: Some(ctx.output_format),
            depth: None,
            cull: None,
        },
    )]
}

fn build_debug(ctx: &Ctx, m: &wgpu::ShaderModule) -> Built {
    vec![pipeline(
        ctx,
        m,
        Desc {
            label: "debug",
            layout: &layout(ctx, &[&ctx.layouts.debug]),
            vs: "vs_fullscreen",
            fs: Some("fs_main"),
            buffers: &[],
            color: Some(ctx.output_format),
            depth: None,
            cull: None,
        },
    )]
}
