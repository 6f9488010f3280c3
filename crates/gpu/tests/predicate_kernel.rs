//! The kernel's edge predicate, run on the GPU itself over adversarial
//! inputs (nearly collinear edges at every scale, exact zeros), against the
//! sign computed in f64, where products of f32 values are exact. A driver
//! that reorders or fuses float operations cannot change these signs.

mod support;

use wgpu::util::DeviceExt;

const KERNEL: &str = r#"
@group(0) @binding(0) var<storage, read> inputs: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> signs: array<i32>;

@compute @workgroup_size(64)
fn test_signs(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (gid.x >= arrayLength(&signs)) {
        return;
    }
    let v = inputs[gid.x];
    let a = vec3<f32>(v.x, v.y, 0.0);
    let b = vec3<f32>(v.z, v.w, 0.0);
    signs[gid.x] = det_sign(v.x, v.y, v.z, v.w, edge_value(a, b));
}
"#;

fn sign_f64(v: [f32; 4]) -> i32 {
    let d = f64::from(v[0]) * f64::from(v[3]) - f64::from(v[1]) * f64::from(v[2]);
    (d > 0.0) as i32 - (d < 0.0) as i32
}

/// Nearly collinear pairs at scales 2^-20 .. 2^20, nudged by a few ulp,
/// plus exact zeros and exact collinear multiples.
fn adversarial_inputs(n: usize) -> Vec<[f32; 4]> {
    let mut seed = 0x2545_f491_u32;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed
    };
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let scale = 2f32.powi((next() % 40) as i32 - 20);
        let ax = (next() as f32 / u32::MAX as f32 - 0.5) * scale;
        let ay = (next() as f32 / u32::MAX as f32 - 0.5) * scale;
        let k = [0.5f32, 1.0, 2.0, 3.0, -1.5][(next() % 5) as usize] * (1.0 + (next() % 3) as f32);
        let nudge =
            |x: f32, n: u32| f32::from_bits(x.to_bits().wrapping_add(n % 5).wrapping_sub(2));
        let (bx, by) = (nudge(ax * k, next()), nudge(ay * k, next()));
        out.push([ax, ay, bx, by]);
        out.push([ax, ay, ax * k, ay * k]);
    }
    out.push([0.0, 0.0, 1.0, 2.0]);
    out.push([1.0, 0.0, 0.0, 0.0]);
    out.truncate(n);
    out
}

#[test]
fn gpu_edge_signs_are_exact() {
    let Some((ctx, _)) = support::gpu() else {
        return;
    };
    let source = [tetray_gpu::shaders::PREDICATE, KERNEL].join("\n");
    let device = &ctx.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("predicate test"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("predicate test"),
        layout: None,
        module: &module,
        entry_point: Some("test_signs"),
        compilation_options: Default::default(),
        cache: None,
    });
    let inputs = adversarial_inputs(1 << 16);
    let input_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("inputs"),
        contents: bytemuck::cast_slice(&inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let bytes = (inputs.len() * 4) as u64;
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("signs"),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read"),
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups((inputs.len() as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &read, 0, bytes);
    ctx.queue.submit([encoder.finish()]);
    let slice = read.slice(..);
    slice.map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    let signs: Vec<i32> = bytemuck::cast_slice(&slice.get_mapped_range().expect("mapped")).to_vec();
    let mut wrong = 0;
    for (v, &s) in inputs.iter().zip(&signs) {
        let want = sign_f64(*v);
        if s != want {
            if wrong < 10 {
                eprintln!("{v:?}: gpu {s}, exact {want}");
            }
            wrong += 1;
        }
        // The twin agrees too.
        let value = v[0] * v[3] - v[1] * v[2];
        assert_eq!(
            tetray_gpu::twin::predicate::det_sign(v[0], v[1], v[2], v[3], value),
            want
        );
    }
    assert_eq!(wrong, 0, "{wrong} of {} GPU signs are wrong", inputs.len());
}
