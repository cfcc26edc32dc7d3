//! Does a shader fit the pipeline the renderer builds from it? The checks wgpu makes at
//! pipeline creation (entry points, each used binding against the bind-group layouts, each
//! vertex input against the vertex buffers), made first on naga's module so that a mismatch is
//! reported at the shader's own file:line:col — the binding's declaration, the entry point's
//! name, the `@location` of the vertex input — instead of as a message for the whole file.

use naga::{AddressSpace, Binding, ImageClass, ImageDimension, ScalarKind, ShaderStage, TypeInner};

use crate::diag::Diagnostic;

use super::pipeline::PipelineDesc;
use super::shaders::Checked;

/// Every mismatch between the shader and the pipeline description `d`.
pub fn check(shader: &Checked, d: &PipelineDesc) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let stages = [
        (ShaderStage::Vertex, Some(d.vs)),
        (ShaderStage::Fragment, d.fs),
    ];
    for (stage, name) in stages {
        let Some(name) = name else { continue };
        let found = shader
            .module
            .entry_points
            .iter()
            .position(|ep| ep.stage == stage && ep.name == name);
        match found {
            None => out.push(missing_entry_point(shader, d.label, stage, name)),
            Some(index) => {
                out.extend(bindings(shader, d, index, stage));
                if stage == ShaderStage::Vertex {
                    out.extend(vertex_inputs(shader, d, index));
                }
            }
        }
    }
    out
}

fn stage_attr(stage: ShaderStage) -> &'static str {
    match stage {
        ShaderStage::Vertex => "@vertex",
        ShaderStage::Fragment => "@fragment",
        _ => "@compute",
    }
}

/// Byte offset of the name in `fn NAME(` of each entry point of `stage`, with the name.
fn entry_point_names(text: &str, stage: ShaderStage) -> Vec<(usize, String)> {
    let attr = stage_attr(stage);
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(at) = text[from..].find(attr).map(|i| i + from) {
        from = at + attr.len();
        let Some(fn_at) = text[from..].find("fn ").map(|i| i + from + 3) else {
            break;
        };
        let name: String = text[fn_at..]
            .trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let start = fn_at + (text[fn_at..].len() - text[fn_at..].trim_start().len());
        out.push((start, name));
    }
    out
}

fn missing_entry_point(
    shader: &Checked,
    label: &str,
    stage: ShaderStage,
    name: &str,
) -> Diagnostic {
    let attr = stage_attr(stage);
    let candidates = entry_point_names(&shader.src.text, stage);
    let message = |found: &str| {
        format!(
            "pipeline `{label}` needs a {attr} entry point named `{name}`{found} (the renderer \
             builds it with that name)"
        )
    };
    match candidates.first() {
        Some((offset, other)) => {
            shader.diag_at_offset(*offset, message(&format!("; this one is `{other}`")))
        }
        None => Diagnostic::whole_file(&shader.src.path, message(&format!("; there is no {attr}"))),
    }
}

/// What kind of binding a shader global is, in words, and whether a layout entry provides it.
fn binding_fits(
    shader: &Checked,
    var: &naga::GlobalVariable,
    ty: &wgpu::BindingType,
) -> Result<(), String> {
    let inner = &shader.module.types[var.ty].inner;
    let want = match (var.space, inner) {
        (AddressSpace::Uniform, _) => match ty {
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                min_binding_size,
                ..
            } => {
                let size = inner.size(shader.module.to_ctx()) as u64;
                return match min_binding_size {
                    Some(have) if have.get() < size => Err(format!(
                        "this uniform is {size} bytes, the renderer binds {} bytes",
                        have.get()
                    )),
                    _ => Ok(()),
                };
            }
            _ => "a uniform buffer",
        },
        (AddressSpace::Storage { .. }, _) => match ty {
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { .. },
                ..
            } => return Ok(()),
            _ => "a storage buffer",
        },
        (_, TypeInner::Sampler { comparison }) => match (ty, comparison) {
            (wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison), true) => {
                return Ok(());
            }
            (wgpu::BindingType::Sampler(s), false)
                if *s != wgpu::SamplerBindingType::Comparison =>
            {
                return Ok(());
            }
            (_, true) => "a comparison sampler",
            (_, false) => "a filtering sampler",
        },
        (
            _,
            TypeInner::Image {
                dim,
                arrayed,
                class,
            },
        ) => {
            let view = match (dim, arrayed) {
                (ImageDimension::D1, _) => wgpu::TextureViewDimension::D1,
                (ImageDimension::D2, false) => wgpu::TextureViewDimension::D2,
                (ImageDimension::D2, true) => wgpu::TextureViewDimension::D2Array,
                (ImageDimension::D3, _) => wgpu::TextureViewDimension::D3,
                (ImageDimension::Cube, false) => wgpu::TextureViewDimension::Cube,
                (ImageDimension::Cube, true) => wgpu::TextureViewDimension::CubeArray,
            };
            if let wgpu::BindingType::Texture {
                sample_type,
                view_dimension,
                ..
            } = ty
            {
                let kind_fits = matches!(
                    (class, sample_type),
                    (ImageClass::Depth { .. }, wgpu::TextureSampleType::Depth)
                        | (
                            ImageClass::Sampled {
                                kind: ScalarKind::Float,
                                ..
                            },
                            wgpu::TextureSampleType::Float { .. },
                        )
                        | (
                            ImageClass::Sampled {
                                kind: ScalarKind::Sint,
                                ..
                            },
                            wgpu::TextureSampleType::Sint,
                        )
                        | (
                            ImageClass::Sampled {
                                kind: ScalarKind::Uint,
                                ..
                            },
                            wgpu::TextureSampleType::Uint,
                        )
                );
                if kind_fits && *view_dimension == view {
                    return Ok(());
                }
                return Err(format!(
                    "this is a {view:?} {} texture, the renderer binds a {view_dimension:?} \
                     {sample_type:?} one",
                    match class {
                        ImageClass::Depth { .. } => "depth",
                        _ => "sampled",
                    }
                ));
            }
            "a texture"
        }
        _ => "a resource",
    };
    Err(format!(
        "this is {want}, the renderer binds {}",
        kind_of(ty)
    ))
}

fn kind_of(ty: &wgpu::BindingType) -> &'static str {
    match ty {
        wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            ..
        } => "a uniform buffer",
        wgpu::BindingType::Buffer { .. } => "a storage buffer",
        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison) => "a comparison sampler",
        wgpu::BindingType::Sampler(_) => "a sampler",
        wgpu::BindingType::Texture { .. } => "a texture",
        _ => "another kind of resource",
    }
}

/// Each global the entry point uses must be in the layout of its group, of a fitting kind,
/// visible to the stage.
fn bindings(shader: &Checked, d: &PipelineDesc, ep: usize, stage: ShaderStage) -> Vec<Diagnostic> {
    let uses = shader.info.get_entry_point(ep);
    let visible = match stage {
        ShaderStage::Vertex => wgpu::ShaderStages::VERTEX,
        ShaderStage::Fragment => wgpu::ShaderStages::FRAGMENT,
        _ => wgpu::ShaderStages::COMPUTE,
    };
    let mut out = Vec::new();
    for (handle, var) in shader.module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        if uses[handle].is_empty() {
            continue;
        }
        let at = shader
            .module
            .global_variables
            .get_span(handle)
            .to_range()
            .map_or(0, |r| r.start);
        let name = var.name.as_deref().unwrap_or("?");
        let (group, binding) = (rb.group, rb.binding);
        let problem = match d.groups.get(group as usize) {
            None => Some(format!(
                "`{name}` is in @group({group}), but pipeline `{}` has bind groups 0..{}",
                d.label,
                d.groups.len()
            )),
            Some(layout) => match layout.entries.iter().find(|e| e.binding == binding) {
                None => Some(format!(
                    "`{name}` is @group({group}) @binding({binding}), but the renderer's \
                     `{}` bind group (group {group} of pipeline `{}`) has bindings {}",
                    layout.label,
                    d.label,
                    list(layout.entries.iter().map(|e| e.binding))
                )),
                Some(entry) => match binding_fits(shader, var, &entry.ty) {
                    Err(why) => Some(format!(
                        "`{name}` (@group({group}) @binding({binding})): {why}"
                    )),
                    Ok(()) if !entry.visibility.contains(visible) => Some(format!(
                        "`{name}` (@group({group}) @binding({binding})) is used by the {} \
                         stage, which the renderer's layout does not make it visible to",
                        stage_attr(stage)
                    )),
                    Ok(()) => None,
                },
            },
        };
        if let Some(p) = problem {
            out.push(shader.diag_at_offset(at, p));
        }
    }
    out
}

fn list(items: impl Iterator<Item = u32>) -> String {
    let v: Vec<String> = items.map(|i| i.to_string()).collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

/// (kind, components) a vertex format gives the shader: `Float32x3` is three floats.
fn format_gives(f: wgpu::VertexFormat) -> (ScalarKind, u32) {
    let name = format!("{f:?}");
    let n = name
        .rsplit_once('x')
        .and_then(|(_, n)| n.parse().ok())
        .unwrap_or(1);
    let kind = if name.starts_with("Uint") {
        ScalarKind::Uint
    } else if name.starts_with("Sint") {
        ScalarKind::Sint
    } else {
        ScalarKind::Float
    };
    (kind, n)
}

/// (kind, components) of a shader input type.
fn type_takes(inner: &TypeInner) -> Option<(ScalarKind, u32)> {
    match inner {
        TypeInner::Scalar(s) => Some((s.kind, 1)),
        TypeInner::Vector { size, scalar } => Some((scalar.kind, *size as u32)),
        _ => None,
    }
}

fn type_name(kind: ScalarKind, n: u32) -> String {
    let k = match kind {
        ScalarKind::Float => "f",
        ScalarKind::Sint => "i",
        ScalarKind::Uint => "u",
        _ => "?",
    };
    if n == 1 {
        format!("{k}32")
    } else {
        format!("vec{n}{k}")
    }
}

/// Each `@location` input of the vertex entry point must come from a vertex attribute of a
/// fitting format.
fn vertex_inputs(shader: &Checked, d: &PipelineDesc, ep: usize) -> Vec<Diagnostic> {
    let module = &shader.module;
    let entry = &module.entry_points[ep];
    let mut inputs: Vec<(
        u32,
        naga::Handle<naga::Type>,
        Option<naga::Handle<naga::Type>>,
    )> = Vec::new();
    for arg in &entry.function.arguments {
        match (&arg.binding, &module.types[arg.ty].inner) {
            (Some(Binding::Location { location, .. }), _) => inputs.push((*location, arg.ty, None)),
            (None, TypeInner::Struct { members, .. }) => {
                for m in members {
                    if let Some(Binding::Location { location, .. }) = m.binding {
                        inputs.push((location, m.ty, Some(arg.ty)));
                    }
                }
            }
            _ => {}
        }
    }
    let attributes: Vec<&wgpu::VertexAttribute> = d
        .buffers
        .iter()
        .flatten()
        .flat_map(|b| b.attributes.iter())
        .collect();
    let mut out = Vec::new();
    for (location, ty, in_struct) in inputs {
        let problem = match attributes.iter().find(|a| a.shader_location == location) {
            None => Some(format!(
                "vertex input @location({location}) is not in pipeline `{}`'s vertex buffers \
                 (they give locations {})",
                d.label,
                list(attributes.iter().map(|a| a.shader_location))
            )),
            Some(a) => {
                let (kind, n) = format_gives(a.format);
                match type_takes(&module.types[ty].inner) {
                    Some((k, m)) if k == kind && m <= n => None,
                    Some((k, m)) => Some(format!(
                        "vertex input @location({location}) is {}, but the vertex buffer gives \
                         {:?} ({})",
                        type_name(k, m),
                        a.format,
                        type_name(kind, n)
                    )),
                    None => Some(format!(
                        "vertex input @location({location}) is not a number or vector"
                    )),
                }
            }
        };
        if let Some(p) = problem {
            let at = location_offset(shader, entry, location, in_struct);
            out.push(shader.diag_at_offset(at, p));
        }
    }
    out
}

/// Byte offset of `@location(N)` in the struct that declares it, else in the entry point's
/// parameter list.
fn location_offset(
    shader: &Checked,
    entry: &naga::EntryPoint,
    location: u32,
    in_struct: Option<naga::Handle<naga::Type>>,
) -> usize {
    let text = &shader.src.text;
    let needle = format!("@location({location})");
    let region = match in_struct.and_then(|t| shader.module.types.get_span(t).to_range()) {
        Some(r) => r,
        None => entry_point_names(text, entry.stage)
            .into_iter()
            .find(|(_, n)| *n == entry.name)
            .map(|(at, _)| at..text[at..].find('{').map_or(text.len(), |i| at + i))
            .unwrap_or(0..text.len()),
    };
    let region = region.start.min(text.len())..region.end.min(text.len());
    text[region.clone()]
        .find(&needle)
        .map_or(region.start, |i| region.start + i)
}
