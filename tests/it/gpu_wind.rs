//! The wind on the GPU equals the wind on the CPU: a compute pass samples `wind_velocity_at`
//! of the WESL module `bevy_windfall::wind` at 4096 points spread over the field, its heights
//! and ±6 s of wind time, in the four modes (plane and volume, frozen and evolving), with every
//! kind of local source, a wall and a room, a pulse and an eased wind late in a session; the
//! results are read back and compared with `WindField::velocity_at`. Two cases run on a device
//! with three storage buffers a stage, where the wind is read from a texture and a uniform
//! buffer (`GpuLayout::Texture`, as on WebGL2).
//!
//! Runs on any Vulkan, Metal or DX12 device, and on Mesa's software Vulkan (lavapipe) without a
//! window or a GPU: `WGPU_BACKEND=vulkan cargo test --features render --test it -- --include-ignored gpu_wind::`.

use std::sync::{Arc, Mutex};

use bevy::app::PluginsState;
use bevy::prelude::*;
use bevy::render::error_handler::{RenderErrorHandler, RenderErrorPolicy};
use bevy::render::extract_resource::{ExtractResource, ExtractResourcePlugin};
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::binding_types::storage_buffer_read_only_sized;
use bevy::render::render_resource::binding_types::storage_buffer_sized;
use bevy::render::render_resource::*;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderGraph};
use bevy::render::settings::{WgpuLimits, WgpuSettings};
use bevy::render::storage::{GpuShaderBuffer, ShaderBuffer};
use bevy::render::texture::GpuImage;
use bevy::render::{Render, RenderApp, RenderPlugin, RenderSystems};
use bevy::shader::ShaderDefVal;
use bevy::time::TimeUpdateStrategy;
use bevy::window::ExitCondition;
use bevy_windfall::prelude::*;
use bevy_windfall::render::{GpuLayout, WindGpuBuffers, WindGpuPlugin, WindGpuUploads};
use bevy_windfall::wind::{Pulse, WindShelter, WindSource};

const POINTS: usize = 4096;
const SHADER: &str = r"
import bevy_windfall::wind::wind_velocity_at;

@group(0) @binding(0) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> velocities: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&points) {
        return;
    }
    let p = points[i];
    velocities[i] = vec4<f32>(wind_velocity_at(p.xyz, p.w), 0.0);
}
";

/// The buffers of the test pass, shared with the render world.
#[derive(Resource, ExtractResource, Clone)]
#[extract_app(RenderApp)]
struct Probe {
    shader: Handle<Shader>,
    points: Handle<ShaderBuffer>,
    velocities: Handle<ShaderBuffer>,
    wind: WindGpuBuffers,
}

#[derive(Resource)]
struct ProbePipeline {
    layout: BindGroupLayoutDescriptor,
    pipeline: CachedComputePipelineId,
}

fn queue_pipeline(
    mut commands: Commands,
    probe: Res<Probe>,
    cache: Res<PipelineCache>,
    device: Res<RenderDevice>,
) {
    let mut entries = BindGroupLayoutEntries::with_indices(
        ShaderStages::COMPUTE,
        (
            (0, storage_buffer_read_only_sized(false, None)),
            (1, storage_buffer_sized(false, None)),
        ),
    )
    .to_vec();
    entries.extend(WindGpuBuffers::layout_entries(
        &device,
        ShaderStages::COMPUTE,
    ));
    let layout = BindGroupLayoutDescriptor::new("wind probe", &entries);
    let pipeline = cache.queue_compute_pipeline(ComputePipelineDescriptor {
        label: Some("wind probe".into()),
        layout: vec![layout.clone()],
        shader: probe.shader.clone(),
        shader_defs: vec![ShaderDefVal::UInt("WIND_BIND_GROUP".into(), 0)],
        ..default()
    });
    commands.insert_resource(ProbePipeline { layout, pipeline });
}

#[derive(Resource)]
struct ProbeBindGroup(BindGroup);

fn prepare_bind_group(
    mut commands: Commands,
    probe: Res<Probe>,
    pipeline: Res<ProbePipeline>,
    cache: Res<PipelineCache>,
    device: Res<RenderDevice>,
    buffers: Res<RenderAssets<GpuShaderBuffer>>,
    images: Res<RenderAssets<GpuImage>>,
) {
    let get = |h: &Handle<ShaderBuffer>| buffers.get(h).map(|b| b.buffer.as_entire_binding());
    let (Some(points), Some(velocities), Ok([nodes, params])) = (
        get(&probe.points),
        get(&probe.velocities),
        probe.wind.bindings(&images, &buffers),
    ) else {
        commands.remove_resource::<ProbeBindGroup>();
        return;
    };
    let mut entries = BindGroupEntries::with_indices(((0, points), (1, velocities))).to_vec();
    for (binding, resource) in [&nodes, &params] {
        entries.push(BindGroupEntry {
            binding: *binding,
            resource: resource.get_binding(),
        });
    }
    let group = device.create_bind_group(
        None,
        &cache.get_bind_group_layout(&pipeline.layout),
        &entries,
    );
    commands.insert_resource(ProbeBindGroup(group));
}

fn dispatch(
    mut context: RenderContext,
    cache: Res<PipelineCache>,
    pipeline: Res<ProbePipeline>,
    group: Option<Res<ProbeBindGroup>>,
) {
    let (Some(compute), Some(group)) = (cache.get_compute_pipeline(pipeline.pipeline), group)
    else {
        if let CachedPipelineState::Err(e) = cache.get_compute_pipeline_state(pipeline.pipeline) {
            panic!("the probe shader does not compile: {e}");
        }
        return;
    };
    let mut pass = context
        .command_encoder()
        .begin_compute_pass(&ComputePassDescriptor {
            label: Some("wind probe"),
            ..default()
        });
    pass.set_pipeline(compute);
    pass.set_bind_group(0, &group.0, &[]);
    pass.dispatch_workgroups(POINTS.div_ceil(64) as u32, 1, 1);
}

/// Readbacks that arrived, each tagged with the frame it was received in.
#[derive(Resource, Clone, Default)]
struct Received(Arc<Mutex<Vec<Arrival>>>);

/// The frame a readback arrived in, and the velocities it holds.
type Arrival = (u32, Vec<Vec4>);

#[derive(Resource, Default)]
struct Frame(u32);

/// A small, cheap, portable stream of numbers in [0, 1) for the sample points.
struct Points(u64);

impl Points {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// An app that renders nothing, on a device whose limits choose `layout`.
fn headless_render_app(config: WindConfig, layout: GpuLayout) -> App {
    let mut settings = WgpuSettings::default();
    if layout == GpuLayout::Texture {
        // Three storage buffers a stage: fewer than the wind asks for.
        settings.constrained_limits = Some(WgpuLimits {
            max_storage_buffers_per_shader_stage: 3,
            ..WgpuLimits::default()
        });
    }
    let mut app = App::new();
    let plugins = DefaultPlugins
        .set(WindowPlugin {
            primary_window: None,
            exit_condition: ExitCondition::DontExit,
            ..default()
        })
        .set(RenderPlugin {
            synchronous_pipeline_compilation: true,
            render_creation: settings.into(),
            ..default()
        })
        // Bevy's GPU mesh preprocessing asks for five storage buffers a stage.
        .set(bevy::pbr::PbrPlugin {
            use_gpu_instance_buffer_builder: layout == GpuLayout::Storage,
            ..default()
        })
        .disable::<PipelinedRenderingPlugin>()
        // One global logger per process, and this test makes several apps.
        .disable::<bevy::log::LogPlugin>();
    let plugins = plugins.disable::<bevy::winit::WinitPlugin>();
    app.add_plugins(plugins)
        .add_plugins((WindPlugin::new(config), WindGpuPlugin))
        .add_plugins(ExtractResourcePlugin::<Probe>::default())
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    // Without the log: a wgpu error's whole text (the default handler logs its kind only).
    app.insert_resource(RenderErrorHandler(|error, _, _| {
        eprintln!("render error: {}", error.description);
        RenderErrorPolicy::StopRendering
    }));
    // The probe's pass, once its buffers exist (the test inserts `Probe` later).
    app.sub_app_mut(RenderApp)
        .add_systems(
            Render,
            (
                queue_pipeline.run_if(not(resource_exists::<ProbePipeline>)),
                prepare_bind_group,
            )
                .chain()
                .in_set(RenderSystems::PrepareBindGroups)
                .run_if(resource_exists::<Probe>),
        )
        .add_systems(
            RenderGraph,
            dispatch.run_if(resource_exists::<ProbePipeline>),
        );
    app
}

struct Case {
    name: &'static str,
    config: WindConfig,
    clock: f64,
    /// An easing in progress: (speed, direction, τ).
    ease: Option<(f32, Vec2, f32)>,
    /// Storage buffers, or a texture and a uniform buffer (WebGL2).
    layout: GpuLayout,
}

/// Runs one case; returns the largest |GPU − CPU| and the tolerance.
fn run(case: &Case) -> (f32, f32) {
    let mut app = headless_render_app(case.config.clone(), case.layout);
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    app.update();
    {
        let mut field = app.world_mut().resource_mut::<WindField>();
        field.set_clock(case.clock);
        if let Some((speed, direction, tau)) = case.ease {
            field.ease_to(speed, direction, tau).unwrap();
        }
    }
    // Every kind of source and shelter, turned and placed over the field.
    let turned = |yaw: f32, pitch: f32| Quat::from_rotation_y(yaw) * Quat::from_rotation_x(pitch);
    let world = app.world_mut();
    world.spawn((
        WindSource::sphere(9.0, Vec3::new(3.0, 1.0, -2.0)).with_pulse(0.4, 0.3),
        Transform::from_xyz(10.0, 4.0, 12.0),
    ));
    world.spawn((
        WindSource::fan(20.0, 0.5, 7.0),
        Transform::from_xyz(-12.0, 3.0, 0.0).with_rotation(turned(1.1, 0.2)),
    ));
    world.spawn((
        WindSource::vortex(12.0, 9.0).with_updraft(3.0),
        Transform::from_xyz(-8.0, 0.0, -14.0).with_rotation(turned(0.3, 0.25)),
    ));
    world.spawn((
        WindSource::blast(20.0, 150.0, 40.0),
        Transform::from_xyz(4.0, 1.0, -6.0),
    ));
    world.spawn((
        WindSource::gust(5.0, 60.0, 30.0, 80.0),
        Transform::from_xyz(-20.0, 0.0, 20.0).with_rotation(turned(-0.7, 0.0)),
    ));
    world.spawn((
        WindShelter::wall(Vec3::new(6.0, 3.0, 0.5)),
        Transform::from_xyz(0.0, 3.0, 18.0).with_rotation(turned(0.4, 0.0)),
    ));
    world.spawn((
        WindShelter::indoor(Vec3::new(4.0, 3.0, 4.0)),
        Transform::from_xyz(18.0, 3.0, -18.0),
    ));
    // A body moving low over the ground: 5 cm a step along a slant, and standing still from the
    // third step on its velocity is the mean of the last two steps (half its stride a step).
    let mover = world
        .spawn((
            WindMover {
                radius: 3.0,
                ..default()
            },
            Transform::from_xyz(6.0, 3.5, 4.0),
        ))
        .id();
    // The sources are placed in the next fixed step; then the clock stops, so every frame's
    // upload is the same state.
    app.update();
    app.world_mut()
        .get_mut::<Transform>(mover)
        .unwrap()
        .translation += Vec3::new(0.05, 0.01, -0.03);
    app.update();
    app.world_mut().resource_mut::<WindField>().paused = true;
    app.update();
    // No more fixed steps: the mover's flow (and every placement) stays as the CPU's copy has it.
    app.world_mut().resource_mut::<Time<Virtual>>().pause();
    let field = app.world().resource::<WindField>().clone();
    assert_eq!(field.source_count(), 5, "{}: blast or gust over", case.name);
    assert_eq!(field.mover_count(), 1, "{}: the mover moved", case.name);
    assert_eq!(field.shelter_count(), 2);
    let t0 = field.time_f64();

    // Points over the field (±32 m), from the ground to 30 m, ±6 s of wind time.
    let mut rng = Points(0x5EED);
    let mut points = Vec::with_capacity(POINTS);
    let mut times = Vec::with_capacity(POINTS);
    for _ in 0..POINTS {
        let p = Vec3::new(
            64.0 * rng.next() - 32.0,
            30.0 * rng.next() * rng.next(),
            64.0 * rng.next() - 32.0,
        );
        let t = (t0 + f64::from(12.0 * rng.next() - 6.0)) as f32;
        // What the GPU gets: seconds after the uploaded clock (exact in f32).
        let dt = (f64::from(t) - t0) as f32;
        points.push(p.extend(dt));
        times.push((p, t));
    }
    let world = app.world_mut();
    let shader = world
        .resource_mut::<Assets<Shader>>()
        .add(Shader::from_wesl(SHADER, "gpu_wind_probe.wesl"));
    let mut buffers = world.resource_mut::<Assets<ShaderBuffer>>();
    let points_buffer = buffers.add(ShaderBuffer::from(points));
    let mut out = ShaderBuffer::from(vec![Vec4::ZERO; POINTS]);
    out.buffer_usage |= BufferUsages::COPY_SRC;
    let velocities = buffers.add(out);
    let wind = world.resource::<WindGpuBuffers>().clone();
    assert_eq!(
        wind.layout, case.layout,
        "{}: the device's layout",
        case.name
    );
    world.insert_resource(Probe {
        shader,
        points: points_buffer,
        velocities: velocities.clone(),
        wind,
    });
    let received = Received::default();
    world.insert_resource(received.clone());
    world.init_resource::<Frame>();
    world.spawn(Readback::buffer(velocities)).observe(
        |event: On<ReadbackComplete>, frame: Res<Frame>, received: Res<Received>| {
            let data: Vec<Vec4> = event.to_shader_type();
            received.0.lock().unwrap().push((frame.0, data));
        },
    );
    // Frames until two readbacks of dispatches made after the paused state was uploaded.
    for frame in 1..=600 {
        app.world_mut().resource_mut::<Frame>().0 = frame;
        app.update();
        app.world()
            .resource::<RenderDevice>()
            .wgpu_device()
            .poll(PollType::Wait {
                submission_index: None,
                timeout: None,
            })
            .ok();
        let done = received
            .0
            .lock()
            .unwrap()
            .iter()
            .filter(|(f, v)| *f > 3 && v.iter().any(|w| *w != Vec4::ZERO))
            .count();
        if done >= 2 {
            break;
        }
    }
    let uploads = *app.world().resource::<WindGpuUploads>();
    assert_eq!(
        uploads.generation,
        field.generation(),
        "{}: nodes uploaded",
        case.name
    );
    assert_eq!(
        uploads.node_uploads, 1,
        "{}: the nodes go up once",
        case.name
    );
    let c = field.config();
    let vertical = match c.spatial {
        SpatialMode::Volume { vertical_nodes } => vertical_nodes,
        SpatialMode::Plane => 1,
    };
    let samples = match c.temporal {
        TemporalMode::Evolving { samples, .. } => samples,
        TemporalMode::Frozen => 1,
    };
    let nodes = c.grid[0] * c.grid[1] * vertical * samples;
    // A storage buffer holds 3 floats a node; a texture 4 a texel, in rows of up to 2048.
    let bytes = match case.layout {
        GpuLayout::Storage => 12 * nodes,
        GpuLayout::Texture => 16 * nodes,
    };
    assert_eq!(uploads.node_bytes, bytes, "{}", case.name);
    println!(
        "{}: {} B of nodes once, {} B of parameters a frame",
        case.name, uploads.node_bytes, uploads.param_bytes
    );
    let results = received.0.lock().unwrap();
    let (_, gpu) = results
        .iter()
        .rev()
        .find(|(_, v)| v.iter().any(|w| *w != Vec4::ZERO))
        .unwrap_or_else(|| panic!("{}: no readback arrived", case.name));
    assert_eq!(gpu.len(), POINTS);
    let sigma_u = field.sigma().x;
    let tolerance = 1e-3 * (field.config().reference_speed + 3.0 * sigma_u);
    let mut worst = 0.0f32;
    let mut sources_felt = 0;
    for ((p, t), g) in times.iter().zip(gpu.iter()) {
        let cpu = field.velocity_at(*p, *t);
        let error = (g.truncate() - cpu).length();
        if error > worst {
            worst = error;
        }
        assert!(
            error <= tolerance,
            "{}: at {p} t = {t}: GPU {} against CPU {cpu}",
            case.name,
            g.truncate()
        );
        if (cpu - field.global_velocity_at(*p, *t)).length() > 0.1 {
            sources_felt += 1;
        }
    }
    assert!(
        sources_felt > POINTS / 50,
        "{}: {sources_felt} points see a source",
        case.name
    );
    (worst, tolerance)
}

#[test]
#[ignore = "needs a GPU or Mesa's lavapipe (CI runs it): cargo test --test it -- --ignored gpu_wind::"]
fn the_gpu_samples_the_same_wind_as_the_cpu() {
    let plane = WindConfig {
        reference_speed: 6.0,
        grid: [32, 32],
        cell_size: 2.0,
        seed: 11,
        ..default()
    };
    let evolving = TemporalMode::Evolving {
        samples: 8,
        period: 10.0,
    };
    let volume = SpatialMode::Volume { vertical_nodes: 8 };
    let cases = [
        Case {
            name: "plane, frozen",
            config: plane.clone(),
            clock: 0.0,
            ease: None,
            layout: GpuLayout::Storage,
        },
        Case {
            name: "plane, evolving, pulsing, easing an hour in",
            config: WindConfig {
                temporal: evolving,
                direction: Vec2::new(1.0, 0.6),
                pulse: Pulse::new(0.3, 0.2),
                ..plane.clone()
            },
            clock: 3600.25,
            ease: Some((9.0, Vec2::new(-0.2, 1.0), 2.0)),
            layout: GpuLayout::Storage,
        },
        Case {
            name: "volume, frozen, ten minutes in",
            config: WindConfig {
                spatial: volume,
                ..plane.clone()
            },
            clock: 600.0,
            ease: Some((4.0, Vec2::new(0.0, -1.0), 1.0)),
            layout: GpuLayout::Storage,
        },
        Case {
            name: "volume, evolving",
            config: WindConfig {
                spatial: volume,
                temporal: evolving,
                beta: 2.5,
                ..plane.clone()
            },
            clock: 42.0,
            ease: None,
            layout: GpuLayout::Storage,
        },
        Case {
            name: "WebGL2 layout: plane, evolving, pulsing, easing an hour in",
            config: WindConfig {
                temporal: evolving,
                direction: Vec2::new(1.0, 0.6),
                pulse: Pulse::new(0.3, 0.2),
                grid: [48, 40],
                ..plane.clone()
            },
            clock: 3600.25,
            ease: Some((9.0, Vec2::new(-0.2, 1.0), 2.0)),
            layout: GpuLayout::Texture,
        },
        Case {
            name: "WebGL2 layout: volume, evolving",
            config: WindConfig {
                spatial: volume,
                temporal: evolving,
                beta: 2.5,
                ..plane.clone()
            },
            clock: 42.0,
            ease: None,
            layout: GpuLayout::Texture,
        },
    ];
    for case in &cases {
        let (worst, tolerance) = run(case);
        println!(
            "{}: max |GPU − CPU| = {worst:.2e} m/s (tolerance {tolerance:.2e})",
            case.name
        );
    }
}

/// Every triangle of a leaf cloud's mesh faces the way its normal points (+Y), for every preset's
/// outline and every shape without one: a double-sided material flips the normal of back faces,
/// so a reversed winding would light each leaf from the wrong side.
#[test]
fn cloud_leaves_face_their_normals() {
    use bevy::mesh::{Mesh, VertexAttributeValues};
    use bevy_windfall::freefall::{FallPreset, FallingObject, Shape};
    use bevy_windfall::render::LeafCloudLook;
    let plain = [
        Shape::Ellipse {
            major: 0.1,
            minor: 0.05,
            thickness: 3e-4,
        },
        Shape::Disk {
            diameter: 0.02,
            thickness: 1e-3,
        },
        Shape::Rectangle {
            length: 0.09,
            width: 0.06,
            thickness: 3e-4,
        },
    ]
    .map(|shape| FallingObject { shape, ..default() });
    for object in FallPreset::ALL.map(FallPreset::object).iter().chain(&plain) {
        let mesh = LeafCloudLook::default().mesh(object, 3);
        let Some(VertexAttributeValues::Float32x3(positions)) =
            mesh.attribute(Mesh::ATTRIBUTE_POSITION)
        else {
            panic!("positions");
        };
        let Some(VertexAttributeValues::Float32x3(normals)) =
            mesh.attribute(Mesh::ATTRIBUTE_NORMAL)
        else {
            panic!("normals");
        };
        let indices: Vec<usize> = mesh.indices().expect("indices").iter().collect();
        let what = (object.look, object.shape);
        assert!(indices.len() >= 3 * 4 * 3, "{what:?}");
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from_array(positions[i]));
            let face = (b - a).cross(c - a);
            let normal = Vec3::from_array(normals[t[0]]);
            assert!(face.dot(normal) > 0.0, "{what:?}: a triangle faces −normal");
        }
    }
}
