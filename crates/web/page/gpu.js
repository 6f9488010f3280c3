// The wgpu ray caster's host side on WebGPU: the same bindings
// (tetray_gpu::GpuRaycaster), the same buffers, the same frame parameters
// (tetray_gpu::frame_params) and the same tiled dispatches.

// Storage buffers the kernel binds (params, tile, points x2, tets x2, bvh,
// tables, image, stats).
const STORAGE_BINDINGS = 10;
const TILE = 512;
const WORKGROUP = 8;
const STAT_COUNT = 10;
// Interval entries (vec4) per knot interval: the quantity is entries 2, 3.
const INTERVAL_ENTRIES = 4;
// Bytes per tetrahedron (tetray_scene::WalkTet: the XOR of its point
// indices and four neighbours).
const TET_BYTES = 20;

class PageError extends Error {}

async function openGpu() {
  if (!navigator.gpu) {
    throw new PageError("This browser has no WebGPU (navigator.gpu is missing). Open the page in a " +
      "browser with WebGPU: Chrome or Edge 113+, Safari 26+, or Firefox 141+ on Windows.");
  }
  const adapter = await navigator.gpu.requestAdapter({ powerPreference: "high-performance" });
  if (!adapter) throw new PageError("WebGPU is present but gave no adapter (is the GPU blocklisted?).");
  const limits = adapter.limits;
  if (limits.maxStorageBuffersPerShaderStage < STORAGE_BINDINGS) {
    throw new PageError(`the adapter binds ${limits.maxStorageBuffersPerShaderStage} storage buffers per ` +
      `shader stage; the ray caster needs ${STORAGE_BINDINGS}`);
  }
  const device = await adapter.requestDevice({
    requiredLimits: {
      maxStorageBuffersPerShaderStage: STORAGE_BINDINGS,
      maxStorageBufferBindingSize: limits.maxStorageBufferBindingSize,
      maxBufferSize: limits.maxBufferSize,
    },
  });
  const info = adapter.info || {};
  const name = [info.vendor, info.architecture, info.device, info.description]
    .filter((s) => s).join(" ") || "WebGPU adapter";
  return { adapter, device, name };
}

// `bytes` in up to two storage buffers of at most `limit` bytes, whole
// elements of `elementBytes` each (tetray_gpu's `chunked`): the buffers and
// the elements in the first.
function chunked(device, what, bytes, elementBytes, limit) {
  const elements = bytes.length / elementBytes;
  const perChunk = Math.floor(limit / elementBytes);
  if (elements > 2 * perChunk) {
    throw new PageError(`the ${what} take ${bytes.length} bytes; this adapter binds at most ${limit} ` +
      `bytes per buffer (maxStorageBufferBindingSize), two buffers: ${2 * limit} bytes`);
  }
  const first = Math.min(elements, perChunk);
  const split = first * elementBytes;
  return {
    buffers: [storage(device, what, bytes.subarray(0, split)), storage(device, what, bytes.subarray(split))],
    first,
  };
}

// A read-only storage buffer holding `bytes` (at least 16).
function storage(device, label, bytes, usage = GPUBufferUsage.STORAGE) {
  const size = Math.max(16, Math.ceil(bytes.length / 4) * 4);
  const buffer = device.createBuffer({ label, size, usage, mappedAtCreation: true });
  new Uint8Array(buffer.getMappedRange()).set(bytes);
  buffer.unmap();
  return buffer;
}

class Raycaster {
  constructor(gpu, wgsl, manifest, buffers) {
    const device = gpu.device;
    this.device = device;
    this.manifest = manifest;
    this.buffers = buffers;
    const limit = Math.min(device.limits.maxStorageBufferBindingSize, device.limits.maxBufferSize);
    const tets = chunked(device, "tetrahedra", buffers.tets, TET_BYTES, limit);
    const points = chunked(device, "points", buffers.points, 16, limit);
    if (buffers.bvh.length > device.limits.maxStorageBufferBindingSize) {
      throw new PageError(`the boundary BVH takes ${buffers.bvh.length} bytes; this adapter binds at most ` +
        `${device.limits.maxStorageBufferBindingSize} bytes per buffer`);
    }
    this.tets = tets;
    this.points = points;
    this.bvh = storage(device, "boundary bvh", buffers.bvh);
    this.tables = new Map();
    this.psi = new Map();
    const module = device.createShaderModule({ label: "raycast.wgsl", code: wgsl });
    this.module = module;
    const entry = (binding, type) => ({ binding, visibility: GPUShaderStage.COMPUTE, buffer: type });
    this.layout = device.createBindGroupLayout({
      label: "raycast bindings",
      entries: [
        entry(0, { type: "read-only-storage" }),
        entry(1, { type: "read-only-storage", hasDynamicOffset: true }),
        ...[2, 3, 4, 5, 6, 7].map((b) => entry(b, { type: "read-only-storage" })),
        { binding: 8, visibility: GPUShaderStage.COMPUTE, texture: { sampleType: "unfilterable-float" } },
        entry(9, { type: "storage" }),
        entry(10, { type: "storage" }),
      ],
    });
    this.pipeline = device.createComputePipeline({
      label: "raycast",
      layout: device.createPipelineLayout({ bindGroupLayouts: [this.layout] }),
      compute: { module, entryPoint: "main" },
    });
    this.params = device.createBuffer({
      label: "params", size: 192, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST,
    });
    this.stride = Math.max(device.limits.minStorageBufferOffsetAlignment, 16);
  }

  // Compile errors of the kernel, as text ("" when none).
  async compileErrors() {
    const info = await this.module.getCompilationInfo();
    return info.messages.filter((m) => m.type === "error")
      .map((m) => `raycast.wgsl ${m.lineNum}:${m.linePos}: ${m.message}`).join("\n");
  }

  // The tables of `spec` (an integrator of the manifest) with the opacity
  // scaled by `scale` where the method's scale is its attenuation.
  tablesFor(spec, method, scale) {
    const key = `${spec.tables}:${method.scale === "attenuation" ? scale : 1}`;
    let buffer = this.tables.get(key);
    if (!buffer) {
      const floats = new Float32Array(this.buffers[spec.tables].slice().buffer);
      if (method.scale === "attenuation" && scale !== 1) {
        const intervals = spec.knot_count + 1;
        for (let k = 0; k < intervals; k++) {
          for (const entry of [2, 3]) {
            const at = 4 * (INTERVAL_ENTRIES * k + entry);
            for (let c = 0; c < 3; c++) floats[at + c] = Math.fround(floats[at + c] * scale);
          }
        }
      }
      buffer = storage(this.device, "transfer function tables", new Uint8Array(floats.buffer));
      if (this.tables.size > 16) this.tables.clear();
      this.tables.set(key, buffer);
    }
    return buffer;
  }

  psiView(spec) {
    let view = this.psi.get(spec.psi);
    if (!view) {
      const size = spec.psi_size;
      const texture = this.device.createTexture({
        label: "psi table", size: [size, size], format: "r32float",
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
      });
      this.device.queue.writeTexture({ texture }, this.buffers[spec.psi], { bytesPerRow: 4 * size }, [size, size]);
      view = texture.createView();
      this.psi.set(spec.psi, view);
    }
    return view;
  }

  // WGSL Params (48 words) for the frame.
  writeParams(view, width, height, spec, method, scale) {
    const m = this.manifest;
    const words = new ArrayBuffer(192);
    const f = new Float32Array(words);
    const u = new Uint32Array(words);
    f.set(view.position, 0); u[3] = view.orthographic ? 1 : 0;
    f.set(view.right, 4); f[7] = view.pixel;
    f.set(view.up, 8); f[11] = view.halfWidth;
    f.set(view.direction, 12); f[15] = view.halfHeight;
    f.set(m.bounds[0], 16); u[19] = view.eyeInside ? 1 : 0;
    f.set(m.bounds[1], 20); f[23] = m.scene_abs_max;
    u[24] = width; u[25] = height; u[26] = m.max_steps; f[27] = 3 * (1 - m.early_termination);
    const preint = spec.preint;
    u[28] = spec.method; u[29] = spec.grey ? 1 : 0; u[30] = spec.split ? 1 : 0; u[31] = spec.knot_count;
    u[32] = spec.psi_size;
    f[33] = method.scale === "opacity" ? spec.inv_unit_distance * scale : spec.inv_unit_distance;
    f[34] = spec.riemann_step;
    u[35] = preint ? preint.size : 0; u[36] = preint ? preint.offset : 0;
    f[37] = preint ? preint.lo : 0; f[38] = preint ? preint.scale : 0;
    f[39] = preint ? (method.scale === "preintegrated" ? preint.length / scale : preint.length) : 1;
    u[40] = this.tets.first; u[41] = this.points.first;
    u[42] = m.prim_offset; u[43] = m.face_offset;
    u[44] = m.overlap_offset; u[45] = m.overlap_count;
    this.device.queue.writeBuffer(this.params, 0, words);
  }

  // The image, counters and tiles of a frame size (the last two sizes
  // are kept: the preview's and the full frame's).
  target(width, height) {
    const key = `${width}x${height}`;
    this.targets = this.targets || new Map();
    const kept = this.targets.get(key);
    if (kept) return kept;
    const device = this.device;
    const image = device.createBuffer({ label: "image", size: width * height * 16,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const stats = device.createBuffer({ label: "stats", size: 4 * STAT_COUNT,
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST });
    const tiles = [];
    for (let y0 = 0; y0 < height; y0 += TILE) {
      for (let x0 = 0; x0 < width; x0 += TILE) {
        tiles.push([x0, y0, Math.min(TILE, width - x0), Math.min(TILE, height - y0)]);
      }
    }
    const tileBytes = new Uint8Array(tiles.length * this.stride);
    tiles.forEach((t, i) => tileBytes.set(new Uint8Array(new Uint32Array(t).buffer), i * this.stride));
    const target = { image, stats, tiles, tileBuffer: storage(device, "tiles", tileBytes) };
    if (this.targets.size >= 2) this.targets.clear();
    this.targets.set(key, target);
    return target;
  }

  // Renders a frame once the frames asked for before it are done (they
  // share the parameter buffer and the targets).
  render(camera, width, height, spec, method, scale) {
    const next = (this.last || Promise.resolve()).catch(() => {})
      .then(() => this.renderNow(camera, width, height, spec, method, scale));
    this.last = next;
    return next;
  }

  // Renders a frame; resolves to the premultiplied RGBA floats, the
  // counters and the milliseconds from submission to completion.
  async renderNow(camera, width, height, spec, method, scale) {
    const device = this.device;
    const target = this.target(width, height);
    const view = viewParams(camera, width, height, this.manifest.bounds);
    this.writeParams(view, width, height, spec, method, scale);
    const group = device.createBindGroup({
      label: "raycast",
      layout: this.layout,
      entries: [
        { binding: 0, resource: { buffer: this.params } },
        { binding: 1, resource: { buffer: target.tileBuffer, offset: 0, size: 16 } },
        { binding: 2, resource: { buffer: this.points.buffers[0] } },
        { binding: 3, resource: { buffer: this.points.buffers[1] } },
        { binding: 4, resource: { buffer: this.tets.buffers[0] } },
        { binding: 5, resource: { buffer: this.tets.buffers[1] } },
        { binding: 6, resource: { buffer: this.bvh } },
        { binding: 7, resource: { buffer: this.tablesFor(spec, method, scale) } },
        { binding: 8, resource: this.psiView(spec) },
        { binding: 9, resource: { buffer: target.image } },
        { binding: 10, resource: { buffer: target.stats } },
      ],
    });
    device.pushErrorScope("validation");
    const encoder = device.createCommandEncoder();
    encoder.clearBuffer(target.stats);
    const pass = encoder.beginComputePass({ label: "raycast" });
    pass.setPipeline(this.pipeline);
    target.tiles.forEach((t, i) => {
      pass.setBindGroup(0, group, [i * this.stride]);
      pass.dispatchWorkgroups(Math.ceil(t[2] / WORKGROUP), Math.ceil(t[3] / WORKGROUP), 1);
    });
    pass.end();
    const start = performance.now();
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    const ms = performance.now() - start;
    const imageRead = device.createBuffer({ size: width * height * 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    const statsRead = device.createBuffer({ size: 4 * STAT_COUNT, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    const copy = device.createCommandEncoder();
    copy.copyBufferToBuffer(target.image, 0, imageRead, 0, width * height * 16);
    copy.copyBufferToBuffer(target.stats, 0, statsRead, 0, 4 * STAT_COUNT);
    device.queue.submit([copy.finish()]);
    const error = await device.popErrorScope();
    if (error) throw new PageError("WebGPU: " + error.message);
    await Promise.all([imageRead.mapAsync(GPUMapMode.READ), statsRead.mapAsync(GPUMapMode.READ)]);
    const pixels = new Float32Array(imageRead.getMappedRange().slice(0));
    const c = new Uint32Array(statsRead.getMappedRange().slice(0));
    imageRead.destroy();
    statsRead.destroy();
    const wide = (lo, hi) => c[lo] + c[hi] * 4294967296;
    const counters = {
      rays: width * height, rays_hit: c[0], segments: wide(1, 2), steps: wide(3, 4),
      entries: c[5], steps_bound_hits: c[6], walk_failures: c[7],
    };
    return { pixels, counters, ms };
  }
}
