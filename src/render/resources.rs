//! The scene's GPU resources: materials (uniform + normal map), objects (mesh + transform
//! uniform), the fish mesh with its per-instance buffer, and the water grid.

use std::collections::HashMap;

use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

use crate::scene::{FrameSnapshot, Material, NormalPattern, Object, Scene, Shape};

use super::fish::{FishInstanceGpu, FishMeshes, LodRanges, LodSorter, LodView};
use super::layouts::Layouts;
use super::mesh::{self, GpuMesh};
use super::normal_map;
use super::pbr::{MaterialGpu, ObjectGpu};

pub struct MaterialRes {
    pub uniform: wgpu::Buffer,
    pub bind_group: wgpu::BindGroup,
}

pub struct ObjectRes {
    pub mesh: GpuMesh,
    pub material: usize,
    pub uniform: wgpu::Buffer,
    pub bind_group: wgpu::BindGroup,
    /// index into `Scene::objects`
    pub object_index: usize,
    pub floating: bool,
    pub casts_shadow: bool,
    world_from_object: Mat4,
    world_uv: bool,
    /// what was last uploaded, so a resting object is not rewritten each frame
    uploaded: Option<Mat4>,
}

pub struct SceneResources {
    pub materials: Vec<MaterialRes>,
    pub objects: Vec<ObjectRes>,
    pub fish_meshes: FishMeshes,
    pub fish_material: usize,
    pub fish_instances: wgpu::Buffer,
    pub fish_capacity: usize,
    /// where each level of detail's fish are in `fish_instances` this frame
    pub fish_ranges: LodRanges,
    fish_sorter: LodSorter,
    /// the material constants last uploaded (sliders edit them live)
    uploaded_materials: Vec<Material>,
    pub water_vertices: wgpu::Buffer,
    pub water_indices: wgpu::Buffer,
    pub water_index_count: u32,
    /// every other row and column of the same grid (a quarter of the triangles)
    pub water_indices_coarse: wgpu::Buffer,
    pub water_index_count_coarse: u32,
    /// (size in metres, vertices per side) the water grid was built for
    water_grid_for: u32,
}

fn index_buffer(device: &wgpu::Device, indices: &[u32]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("water grid"),
        contents: bytemuck::cast_slice(indices),
        usage: wgpu::BufferUsages::INDEX,
    })
}

fn normal_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pattern: NormalPattern,
) -> wgpu::TextureView {
    let size = wgpu::Extent3d {
        width: normal_map::SIZE,
        height: normal_map::SIZE,
        depth_or_array_layers: 1,
    };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("normal map"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        // linear: these texels are vectors
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    queue.write_texture(
        texture.as_image_copy(),
        &normal_map::generate(pattern),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * normal_map::SIZE),
            rows_per_image: None,
        },
        size,
    );
    texture.create_view(&Default::default())
}

fn object_mesh(o: &Object) -> (mesh::MeshData, Mat4, bool) {
    match o {
        Object::Seabed {
            size,
            depth,
            resolution,
            relief,
            ..
        } => (
            mesh::terrain(*size, *resolution, -depth, *relief),
            Mat4::IDENTITY,
            true,
        ),
        Object::Rock {
            position,
            radius,
            seed,
            ..
        } => (
            mesh::rock(*radius, *seed),
            Mat4::from_translation(Vec3::from(*position)),
            false,
        ),
        Object::Floating { shape, .. } => {
            let m = match shape {
                Shape::Box { size } => mesh::cuboid(Vec3::from(*size)),
                Shape::Sphere { radius } => mesh::capsule(*radius, 0.0, 16, 24),
                Shape::Capsule { radius, length } => mesh::capsule(*radius, 0.5 * length, 16, 24),
            };
            (m, Mat4::IDENTITY, false)
        }
    }
}

impl SceneResources {
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layouts: &Layouts,
        scene: &Scene,
        repeat: &wgpu::Sampler,
    ) -> Self {
        let mut maps: HashMap<NormalPattern, wgpu::TextureView> = HashMap::new();
        let materials = scene
            .materials
            .iter()
            .map(|m| {
                let view = maps
                    .entry(m.normal_map)
                    .or_insert_with(|| normal_texture(device, queue, m.normal_map))
                    .clone();
                let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(&m.name),
                    contents: bytemuck::bytes_of(&MaterialGpu::from(m)),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&m.name),
                    layout: &layouts.material.layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: uniform.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(&view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::Sampler(repeat),
                        },
                    ],
                });
                MaterialRes {
                    uniform,
                    bind_group,
                }
            })
            .collect();
        let objects = scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let (data, world_from_object, world_uv) = object_mesh(o);
                let uniform = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("object"),
                    size: std::mem::size_of::<ObjectGpu>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("object"),
                    layout: &layouts.object.layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    }],
                });
                ObjectRes {
                    mesh: GpuMesh::upload(device, "object", &data),
                    material: scene.material_index(o.material()).unwrap_or(0),
                    uniform,
                    bind_group,
                    object_index: i,
                    floating: matches!(o, Object::Floating { .. }),
                    casts_shadow: !matches!(o, Object::Seabed { .. }),
                    world_from_object,
                    world_uv,
                    uploaded: None,
                }
            })
            .collect();
        let fish_material = scene
            .material_index("fish_skin")
            .unwrap_or(scene.materials.len() - 1);
        let (grid, indices, coarse) = mesh::water_grid(scene.water.resolution);
        let fish_capacity = scene.school.count.max(1);
        Self {
            materials,
            objects,
            fish_meshes: FishMeshes::new(device),
            fish_material,
            fish_instances: Self::fish_buffer(device, fish_capacity),
            fish_capacity,
            fish_ranges: LodRanges::default(),
            fish_sorter: LodSorter::default(),
            uploaded_materials: scene.materials.clone(),
            water_vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("water grid"),
                contents: bytemuck::cast_slice(&grid),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            water_indices: index_buffer(device, &indices),
            water_index_count: indices.len() as u32,
            water_indices_coarse: index_buffer(device, &coarse),
            water_index_count_coarse: coarse.len() as u32,
            water_grid_for: scene.water.resolution,
        }
    }

    /// Rebuilds the water grid when its resolution was changed live (sliders).
    fn ensure_water_grid(&mut self, device: &wgpu::Device, scene: &Scene) {
        let want = scene.water.resolution.clamp(2, 1024);
        if want == self.water_grid_for {
            return;
        }
        let (grid, indices, coarse) = mesh::water_grid(want);
        self.water_vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("water grid"),
            contents: bytemuck::cast_slice(&grid),
            usage: wgpu::BufferUsages::VERTEX,
        });
        self.water_indices = index_buffer(device, &indices);
        self.water_index_count = indices.len() as u32;
        self.water_indices_coarse = index_buffer(device, &coarse);
        self.water_index_count_coarse = coarse.len() as u32;
        self.water_grid_for = want;
    }

    fn fish_buffer(device: &wgpu::Device, capacity: usize) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("fish instances"),
            size: (capacity * std::mem::size_of::<FishInstanceGpu>()) as u64,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Uploads what changed this frame: materials (sliders edit them live), the transforms of
    /// moving objects, and the fish sorted by level of detail as `view` sees them.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        snap: &FrameSnapshot,
        view: &LodView,
        max_fish: usize,
    ) {
        self.ensure_water_grid(device, scene);
        if self.uploaded_materials != scene.materials {
            for (res, m) in self.materials.iter().zip(&scene.materials) {
                queue.write_buffer(&res.uniform, 0, bytemuck::bytes_of(&MaterialGpu::from(m)));
            }
            self.uploaded_materials.clone_from(&scene.materials);
        }
        for o in &mut self.objects {
            if o.floating
                && let Some(pose) = snap
                    .bodies
                    .iter()
                    .find(|b| b.object_index == o.object_index)
            {
                o.world_from_object =
                    Mat4::from_rotation_translation(pose.orientation, pose.position);
            }
            if o.uploaded == Some(o.world_from_object) {
                continue;
            }
            let data = ObjectGpu {
                world_from_object: o.world_from_object.to_cols_array_2d(),
                world_uv: if o.world_uv { 1.0 } else { 0.0 },
                ambient_occlusion: 1.0,
                _pad: [0.0; 2],
            };
            queue.write_buffer(&o.uniform, 0, bytemuck::bytes_of(&data));
            o.uploaded = Some(o.world_from_object);
        }
        // beyond what one buffer may hold on this adapter (`RenderCaps`), the rest are not drawn
        let fish = &snap.fish[..snap.fish.len().min(max_fish)];
        if fish.len() > self.fish_capacity {
            self.fish_capacity = fish.len().next_power_of_two().min(max_fish);
            self.fish_instances = Self::fish_buffer(device, self.fish_capacity);
        }
        self.fish_ranges = self.fish_sorter.sort(fish, view);
        let sorted = &self.fish_sorter.sorted;
        if !sorted.is_empty() {
            queue.write_buffer(&self.fish_instances, 0, bytemuck::cast_slice(sorted));
        }
    }

    /// Fish in the instance buffer this frame (all of them, seen or not).
    pub fn fish_count(&self) -> u32 {
        self.fish_ranges.all.end
    }
}
