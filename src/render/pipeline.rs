//! How a technique's pipelines are made from its WGSL file, the same way for the renderer, its
//! hot reload and `lectern check`: naga parses and validates the (include-expanded) source, the
//! technique's builder describes each pipeline against the renderer's real bind-group and
//! vertex layouts, [`super::interface`] compares each description with the shader (a mismatch
//! is reported at the shader's own line), and wgpu creates the module and pipelines inside a
//! validation error scope (anything else wgpu rejects is reported for the file).

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use crate::diag::Diagnostic;
use crate::reload::{self, LastGood};

use super::caps::RenderCaps;
use super::frame::{ShadowFilter, WaterNormals};
use super::layouts::{Layout, Layouts};
use super::shaders::{self, Checked};
use super::{caustics, debug, fish, interface, pbr, shadow, sky, tonemap, water};

/// Everything a technique's builder needs besides its shader module.
pub struct Ctx<'a> {
    pub device: &'a wgpu::Device,
    pub layouts: &'a Layouts,
    pub output_format: wgpu::TextureFormat,
    /// the formats of every target but the output, and the 8-bit encodings
    pub caps: &'a RenderCaps,
    /// the checked shader being built, for the interface check
    shader: &'a Checked,
    /// interface mismatches found while building
    problems: RefCell<Vec<Diagnostic>>,
}

/// Depth state of a pipeline: write, compare, bias.
pub type Depth = (bool, wgpu::CompareFunction, wgpu::DepthBiasState);

pub const NO_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 0,
    slope_scale: 0.0,
    clamp: 0.0,
};

pub const OPAQUE_DEPTH: Option<Depth> = Some((true, wgpu::CompareFunction::Less, NO_BIAS));

/// One render pipeline as a technique describes it.
#[derive(Clone)]
pub struct PipelineDesc<'a> {
    pub label: &'static str,
    /// bind groups 0, 1, … in order
    pub groups: &'a [&'a Layout],
    pub vs: &'static str,
    pub fs: Option<&'static str>,
    pub buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub color: Option<wgpu::TextureFormat>,
    pub depth: Option<Depth>,
    pub cull: Option<wgpu::Face>,
}

impl Ctx<'_> {
    /// Checks `d` against the shader, then creates it (inside the caller's error scope).
    pub fn pipeline(&self, module: &wgpu::ShaderModule, d: PipelineDesc) -> wgpu::RenderPipeline {
        self.pipeline_with(module, d, &[], true)
    }

    /// A pipeline that draws into the output target (`d.color` is the output format): its
    /// shader includes srgb.wgsl, whose `TARGET_IS_SRGB` is set from that format.
    pub fn output_pipeline(
        &self,
        module: &wgpu::ShaderModule,
        d: PipelineDesc,
    ) -> wgpu::RenderPipeline {
        let srgb = if self.output_format.is_srgb() {
            1.0
        } else {
            0.0
        };
        self.pipeline_with(module, d, &[("TARGET_IS_SRGB", srgb)], true)
    }

    /// A lit pipeline once per [`ShadowFilter`] (`SHADOW_PCF_RADIUS` in common.wgsl), so the
    /// quality setting can switch between them from one frame to the next.
    pub fn lit_pipelines(
        &self,
        module: &wgpu::ShaderModule,
        d: PipelineDesc,
    ) -> PerShadowFilter<wgpu::RenderPipeline> {
        PerShadowFilter(ShadowFilter::ALL.map(|f| {
            let radius = [("SHADOW_PCF_RADIUS", f.pcf_radius_texels())];
            // one interface check: the variants differ only in a constant
            self.pipeline_with(module, d.clone(), &radius, f == ShadowFilter::ALL[0])
        }))
    }

    /// The water's pipelines: one per [`ShadowFilter`] and [`WaterNormals`]
    /// (`WATER_VERTEX_WAVES` in common.wgsl).
    pub fn water_pipelines(
        &self,
        module: &wgpu::ShaderModule,
        d: PipelineDesc,
    ) -> PerShadowFilter<[wgpu::RenderPipeline; 3]> {
        PerShadowFilter(ShadowFilter::ALL.map(|f| {
            WaterNormals::ALL.map(|w| {
                let constants = [
                    ("SHADOW_PCF_RADIUS", f.pcf_radius_texels()),
                    ("WATER_VERTEX_WAVES", w.vertex_waves()),
                ];
                let first = f == ShadowFilter::ALL[0] && w == WaterNormals::ALL[0];
                self.pipeline_with(module, d.clone(), &constants, first)
            })
        }))
    }

    /// Creates `d` with those of `constants` the shader declares (a shader edited to drop
    /// one still builds, with the declaration's default if it keeps it).
    pub fn pipeline_with(
        &self,
        module: &wgpu::ShaderModule,
        d: PipelineDesc,
        constants: &[(&str, f64)],
        check_interface: bool,
    ) -> wgpu::RenderPipeline {
        let declared = |name: &str| {
            self.shader
                .module
                .overrides
                .iter()
                .any(|(_, o)| o.name.as_deref() == Some(name))
        };
        // every pipeline gets the target encodings its shader declares (encoding.wgsl)
        let encoding = self.caps.encoding.constants();
        let constants: Vec<(&str, f64)> = (constants.iter().chain(&encoding))
            .copied()
            .filter(|(name, _)| declared(name))
            .collect();
        let options = wgpu::PipelineCompilationOptions {
            constants: &constants,
            ..Default::default()
        };
        if check_interface {
            self.problems
                .borrow_mut()
                .extend(interface::check(self.shader, &d));
        }
        let groups: Vec<Option<&wgpu::BindGroupLayout>> =
            d.groups.iter().map(|g| Some(&g.layout)).collect();
        let layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(d.label),
                bind_group_layouts: &groups,
                immediate_size: 0,
            });
        let targets = [d.color.map(|format| wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })];
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(d.label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(d.vs),
                    compilation_options: options.clone(),
                    buffers: d.buffers,
                },
                fragment: d.fs.map(|fs| wgpu::FragmentState {
                    module,
                    entry_point: Some(fs),
                    compilation_options: options.clone(),
                    targets: &targets,
                }),
                primitive: wgpu::PrimitiveState {
                    cull_mode: d.cull,
                    ..Default::default()
                },
                depth_stencil: d
                    .depth
                    .map(|(write, compare, bias)| wgpu::DepthStencilState {
                        format: self.caps.depth_format,
                        depth_write_enabled: Some(write),
                        depth_compare: Some(compare),
                        stencil: Default::default(),
                        bias,
                    }),
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            })
    }
}

/// A lit pipeline for each [`ShadowFilter`].
pub struct PerShadowFilter<T>([T; 2]);

impl<T> PerShadowFilter<T> {
    pub fn get(&self, filter: ShadowFilter) -> &T {
        match filter {
            ShadowFilter::Pcf3x3 => &self.0[0],
            ShadowFilter::Bilinear => &self.0[1],
        }
    }
}

/// A technique's pipelines, built from one WGSL file (and its includes).
pub trait Technique: Sized {
    /// The file in the shader folder.
    const SHADER: &'static str;
    fn build(ctx: &Ctx, module: &wgpu::ShaderModule) -> Self;
}

/// What the builders share across techniques and rebuilds.
pub struct BuildEnv<'a> {
    pub device: &'a wgpu::Device,
    pub layouts: &'a Layouts,
    pub output_format: wgpu::TextureFormat,
    pub caps: &'a RenderCaps,
}

/// Builds technique `T` from `path`: naga, the interface check, then wgpu inside an error
/// scope. Every problem found, each at its file:line:col where it has one.
pub fn build<T: Technique>(env: &BuildEnv, path: &Path) -> Result<T, Vec<Diagnostic>> {
    let shader = shaders::load_checked(path).map_err(|d| vec![d])?;
    let ctx = Ctx {
        device: env.device,
        layouts: env.layouts,
        output_format: env.output_format,
        caps: env.caps,
        shader: &shader,
        problems: RefCell::new(Vec::new()),
    };
    let scope = env.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = env
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&path.display().to_string()),
            source: wgpu::ShaderSource::Wgsl(shader.src.text.as_str().into()),
        });
    let built = T::build(&ctx, &module);
    let scoped = super::gpu::scope_result(scope.pop());
    let problems = ctx.problems.into_inner();
    if !problems.is_empty() {
        // our own findings carry positions; wgpu's message for the same fault would not
        return Err(problems);
    }
    match scoped {
        None => Ok(built),
        Some(e) => Err(vec![Diagnostic::whole_file(
            path,
            format!("pipeline creation failed: {e}"),
        )]),
    }
}

/// A technique in use: its pipelines in the app's one last-good holder (a rebuild that fails
/// keeps the previous pipelines in use and records its problems), and the files they were built
/// from.
pub struct Live<T> {
    pipelines: LastGood<T>,
    path: PathBuf,
    /// the [`reload::file_key`] of the shader and of each of its includes
    file_keys: Vec<PathBuf>,
}

impl<T: Technique> Live<T> {
    /// The first build must succeed: there is nothing to fall back to.
    pub fn new(env: &BuildEnv, dir: &Path) -> Result<Self, Diagnostic> {
        let path = dir.join(T::SHADER);
        let current = build::<T>(env, &path).map_err(first)?;
        Ok(Self {
            pipelines: LastGood::new(current),
            file_keys: file_keys_of(&path),
            path,
        })
    }

    /// Rebuilds when any of `changed` is this technique's file or one of its includes (the
    /// same file by [`reload::same_file`]'s rule, not a file of the same name elsewhere).
    pub fn reload(&mut self, env: &BuildEnv, changed: &[PathBuf]) -> bool {
        let changed_keys: Vec<PathBuf> = changed.iter().map(|c| reload::file_key(c)).collect();
        if !changed_keys.iter().any(|c| self.file_keys.contains(c)) {
            return false;
        }
        self.file_keys = file_keys_of(&self.path);
        let built = build::<T>(env, &self.path);
        if let Err(ds) = &built {
            for d in ds {
                tracing::warn!("{d}");
            }
        }
        self.pipelines.update_all(built);
        true
    }

    /// The pipelines in use: the last ones that built.
    pub fn current(&self) -> &T {
        self.pipelines.value()
    }

    /// Bumped on every successful rebuild.
    pub fn generation(&self) -> u64 {
        self.pipelines.generation()
    }

    /// The problems of the newest rebuild, if it failed.
    pub fn errors(&self) -> &[Diagnostic] {
        self.pipelines.errors()
    }
}

fn file_keys_of(path: &Path) -> Vec<PathBuf> {
    files_of(path).iter().map(|f| reload::file_key(f)).collect()
}

fn first(mut ds: Vec<Diagnostic>) -> Diagnostic {
    ds.truncate(1);
    ds.pop()
        .unwrap_or_else(|| Diagnostic::whole_file("shaders", "pipeline creation failed"))
}

/// The files a shader is made of (itself and its includes); itself when it cannot be read.
pub fn files_of(path: &Path) -> Vec<PathBuf> {
    shaders::load(path)
        .map(|s| s.files)
        .unwrap_or_else(|_| vec![path.to_path_buf()])
}

/// Declares the renderer's techniques once: the [`Passes`] holding each one live, and
/// [`check_techniques`] building each one for `lectern check`.
macro_rules! techniques {
    ($($field:ident: $ty:ty),* $(,)?) => {
        /// Every technique's pipelines, live (hot reload keeps the old ones on an error).
        pub struct Passes {
            $(pub $field: Live<$ty>,)*
        }

        impl Passes {
            pub fn new(env: &BuildEnv, dir: &Path) -> Result<Self, Diagnostic> {
                Ok(Self { $($field: Live::new(env, dir)?,)* })
            }

            /// Rebuilds the techniques that use any of `changed`; whether any did.
            pub fn reload(&mut self, env: &BuildEnv, changed: &[PathBuf]) -> bool {
                let mut any = false;
                $(any |= self.$field.reload(env, changed);)*
                any
            }

            pub fn errors(&self) -> Vec<&Diagnostic> {
                let mut v = Vec::new();
                $(v.extend(self.$field.errors());)*
                v
            }
        }

        /// The shader file of each technique, in build order.
        pub const TECHNIQUE_SHADERS: &[&str] = &[$(<$ty as Technique>::SHADER,)*];

        /// Builds, in `dir`, each technique whose files satisfy `wanted`; the problems of each.
        pub fn check_techniques(
            env: &BuildEnv,
            dir: &Path,
            wanted: &dyn Fn(&[PathBuf]) -> bool,
        ) -> Vec<(PathBuf, Vec<Diagnostic>)> {
            let mut out = Vec::new();
            $(
                let path = dir.join(<$ty as Technique>::SHADER);
                if path.exists() && wanted(&files_of(&path)) {
                    let problems = build::<$ty>(env, &path).err().unwrap_or_default();
                    out.push((path, problems));
                }
            )*
            out
        }
    };
}

techniques! {
    sky: sky::SkyPipelines,
    prefilter: sky::PrefilterPipeline,
    pbr: pbr::PbrPipeline,
    fish: fish::FishPipelines,
    shadow: shadow::ShadowPipeline,
    caustics: caustics::CausticsPipeline,
    water: water::WaterPipeline,
    tonemap: tonemap::TonemapPipeline,
    debug: debug::DebugPipeline,
}
