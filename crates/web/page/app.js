// The page: loads the scene, renders on demand, turns mouse and controls
// into the camera and integrator, shows the stats line, runs the
// benchmark, and exposes `window.tetray` (render and read back the float
// image, for tests and scripts).

const ui = {
  canvas: document.getElementById("view"),
  status: document.getElementById("status"),
  stats: document.getElementById("stats"),
  method: document.getElementById("method"),
  colormap: document.getElementById("colormap"),
  opacity: document.getElementById("opacity"),
  opacityValue: document.getElementById("opacity-value"),
  reset: document.getElementById("reset"),
  bench: document.getElementById("bench"),
};

function showError(message) {
  ui.status.textContent = message;
  ui.status.className = "error";
}

function base64Of(bytes) {
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) {
    text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  }
  return btoa(text);
}

// Premultiplied RGBA floats over the background, to 8 bits, drawn over
// the whole view (a preview frame of fewer pixels is scaled up).
function draw(pixels, width, height, background) {
  const scratch = draw.scratch || (draw.scratch = document.createElement("canvas"));
  scratch.width = width;
  scratch.height = height;
  const out = new ImageData(width, height);
  for (let i = 0; i < width * height; i++) {
    const a = pixels[4 * i + 3];
    for (let c = 0; c < 3; c++) {
      const v = pixels[4 * i + c] + (1 - a) * background[c];
      out.data[4 * i + c] = Math.round(Math.min(Math.max(v, 0), 1) * 255);
    }
    out.data[4 * i + 3] = 255;
  }
  scratch.getContext("2d").putImageData(out, 0, 0);
  const view = ui.canvas.getContext("2d");
  view.imageSmoothingEnabled = true;
  view.drawImage(scratch, 0, 0, ui.canvas.width, ui.canvas.height);
}

function statsLine(frame, adapter) {
  const c = frame.counters;
  const rate = frame.ms > 0 ? c.segments / (frame.ms / 1000) / 1e6 : 0;
  let line = `${frame.ms.toFixed(1)} ms per frame · ${rate.toFixed(2)} M segments/s · ` +
    `${c.segments} segments, ${c.rays_hit} of ${c.rays} rays hit · ${adapter}`;
  if (c.steps_bound_hits > 0) line += ` · ${c.steps_bound_hits} rays stopped at the step bound`;
  if (c.walk_failures > 0) line += ` · ${c.walk_failures} walk failures`;
  return line;
}

async function main() {
  const manifest = JSON.parse(document.getElementById("tetray-manifest").textContent);
  const wgsl = document.getElementById("tetray-wgsl").textContent;
  document.title = `${manifest.name} · tetray`;
  ui.status.textContent = `${manifest.name}: ${manifest.tet_count} tetrahedra, ${manifest.field}; loading`;
  // Milliseconds from navigation to each stage of the start.
  const timings = { script: performance.now() };
  const gpu = await openGpu();
  timings.adapter = performance.now();
  const buffers = await loadBuffers(manifest);
  timings.buffers = performance.now();
  const caster = new Raycaster(gpu, wgsl, manifest, buffers);
  const errors = await caster.compileErrors();
  if (errors) throw new PageError(errors);
  timings.kernel = performance.now();
  gpu.device.lost.then((info) => showError(`the GPU device was lost: ${info.message || info.reason}`));

  const methods = new Map(manifest.methods.map((m) => [m.name, m]));
  const state = {
    camera: cameraCopy(manifest.camera),
    method: manifest.method,
    colormap: manifest.colormaps[0].name,
    scale: 1,
  };
  const size = () => [manifest.size[0], manifest.size[1]];
  const integratorOf = (colormap, method) => {
    const map = manifest.colormaps.find((c) => c.name === colormap);
    if (!map) throw new PageError(`no colour map "${colormap}"`);
    const spec = map.integrators[method];
    if (!spec) throw new PageError(`the ${method} integrator has no tables for colour map "${colormap}"`);
    if (!methods.has(method)) throw new PageError(`no GPU method "${method}"`);
    return [spec, methods.get(method)];
  };

  for (const m of manifest.methods) ui.method.add(new Option(m.name, m.name));
  for (const c of manifest.colormaps) ui.colormap.add(new Option(c.name, c.name));
  ui.method.value = state.method;
  const offer = () => {
    const map = manifest.colormaps.find((c) => c.name === state.colormap);
    for (const option of ui.method.options) option.disabled = !(option.value in map.integrators);
  };
  offer();

  // One frame at a time; a change during a frame renders once more after.
  // Each change shows a preview of a sixteenth of the pixels first (when
  // the view is large), then the full frame.
  const [fullWidth, fullHeight] = size();
  const preview = fullWidth * fullHeight >= 256 * 256 ? 4 : 1;
  let busy = false, again = false, firstFrame = null, shown;
  const firstShown = new Promise((resolve) => { shown = resolve; });
  async function redraw() {
    if (busy) { again = true; return; }
    busy = true;
    try {
      let factor = preview;
      for (;;) {
        again = false;
        const width = Math.max(1, Math.round(fullWidth / factor));
        const height = Math.max(1, Math.round(fullHeight / factor));
        const [spec, method] = integratorOf(state.colormap, state.method);
        const frame = await caster.render(state.camera, width, height, spec, method, state.scale);
        draw(frame.pixels, width, height, manifest.background);
        if (firstFrame === null) { firstFrame = performance.now(); shown(); }
        ui.stats.textContent = (factor > 1 ? `preview ${width}x${height}: ` : "") + statsLine(frame, gpu.name);
        if (again) { factor = preview; continue; }
        if (factor > 1) { factor = 1; continue; }
        break;
      }
      ui.status.textContent = `${manifest.name}: ${manifest.tet_count} tetrahedra, ${manifest.field} in ` +
        `[${manifest.range[0]}, ${manifest.range[1]}] · drag: orbit · shift/right drag: pan · wheel: dolly`;
      ui.status.className = "";
    } catch (e) {
      showError(String(e.message || e));
    } finally {
      busy = false;
    }
  }

  ui.method.onchange = () => { state.method = ui.method.value; redraw(); };
  ui.colormap.onchange = () => {
    state.colormap = ui.colormap.value;
    offer();
    if (!(state.method in manifest.colormaps.find((c) => c.name === state.colormap).integrators)) {
      state.method = manifest.method;
      ui.method.value = state.method;
    }
    redraw();
  };
  ui.opacity.oninput = () => {
    state.scale = Math.fround(Math.pow(10, Number(ui.opacity.value)));
    ui.opacityValue.textContent = `${state.scale.toPrecision(3)}x`;
    redraw();
  };
  ui.reset.onclick = () => { state.camera = cameraCopy(manifest.camera); redraw(); };

  let drag = null;
  ui.canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  ui.canvas.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button !== 0 || e.shiftKey };
    try { ui.canvas.setPointerCapture(e.pointerId); } catch (_) { /* a synthetic pointer */ }
  });
  ui.canvas.addEventListener("pointerup", () => { drag = null; });
  ui.canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const rect = ui.canvas.getBoundingClientRect();
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    try {
      if (drag.pan) cameraPan(state.camera, dx, dy, rect.height);
      else cameraOrbit(state.camera, dx, dy, rect.width, rect.height);
      redraw();
    } catch (err) { showError(String(err.message || err)); }
  });
  ui.canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    try { cameraDolly(state.camera, -Math.sign(e.deltaY)); redraw(); } catch (err) { showError(String(err.message || err)); }
  }, { passive: false });

  // The benchmark: `views` azimuths evenly round the start camera, `frames`
  // frames each; segments/s and frames/s over all of them.
  async function bench(frames, views) {
    const [width, height] = size();
    const [spec, method] = integratorOf(state.colormap, state.method);
    let ms = 0, segments = 0, count = 0;
    for (let v = 0; v < views; v++) {
      const camera = cameraCopy(manifest.camera);
      cameraAzimuth(camera, (360 * v) / views);
      for (let f = 0; f < frames; f++) {
        const frame = await caster.render(camera, width, height, spec, method, state.scale);
        ms += frame.ms; segments += frame.counters.segments; count++;
        if (f === frames - 1) draw(frame.pixels, width, height, manifest.background);
      }
    }
    const result = {
      adapter: gpu.name, method: state.method, width, height, frames: count,
      segments_per_second: segments / (ms / 1000), frames_per_second: count / (ms / 1000),
    };
    ui.stats.textContent = `bench: ${(result.segments_per_second / 1e6).toFixed(2)} M segments/s, ` +
      `${result.frames_per_second.toFixed(2)} frames/s (${count} frames of ${width}x${height}, ` +
      `${views} views, ${state.method}) · ${gpu.name}`;
    return result;
  }
  ui.bench.onclick = () => bench(manifest.bench ? manifest.bench.frames : 5, manifest.bench ? manifest.bench.views : 8)
    .catch((e) => showError(String(e.message || e)));

  window.tetray = {
    manifest,
    timings,
    adapter: gpu.name,
    // Renders one frame without showing it: `camera` (default: the page's
    // start, or with `current` the view, integrator, colour map and
    // opacity the controls have set), then `azimuth` and `elevation` as `tetray render` applies
    // them; the float image comes back as base64 of little-endian f32
    // RGBA, rows from the top.
    async render(options = {}) {
      // A camera in the file's coordinates, as `tetray render` takes it.
      const given = options.camera && {
        ...options.camera,
        position: sub3(options.camera.position, manifest.origin),
        focal_point: sub3(options.camera.focal_point, manifest.origin),
      };
      const camera = cameraCopy(given || (options.current ? state.camera : manifest.camera));
      if (given) {
        cameraBasis(camera);
        cameraAzimuth(camera, options.azimuth || 0);
        cameraElevation(camera, options.elevation || 0);
        cameraOrthogonalize(camera);
      }
      const width = options.width || manifest.size[0];
      const height = options.height || manifest.size[1];
      const now = options.current ? state : { colormap: manifest.colormaps[0].name, method: manifest.method, scale: 1 };
      const [spec, method] = integratorOf(options.colormap || now.colormap, options.method || now.method);
      const scale = options.opacity_scale || now.scale;
      const frame = await caster.render(camera, width, height, spec, method, scale);
      return { width, height, adapter: gpu.name, counters: frame.counters, ms: frame.ms,
        pixels: base64Of(new Uint8Array(frame.pixels.buffer)) };
    },
    bench,
  };
  // The page is ready once its first frame shows (a preview, when the
  // view is large); the full frame and the benchmark follow. Times are
  // from the page's start (navigation).
  const full = redraw();
  window.tetray.fullFrame = full.then(() => performance.now());
  if (manifest.bench) {
    window.tetray.benchDone = full.then(() => bench(manifest.bench.frames, manifest.bench.views))
      .then((result) => { window.tetray.benchResult = result; return result; });
  }
  await Promise.race([firstShown, full.then(() => {
    if (firstFrame === null) throw new PageError(ui.status.textContent);
  })]);
  window.tetray.firstFrameMs = firstFrame;
  timings.first_frame = firstFrame;
}

window.tetrayReady = main().then(
  () => ({ ok: true, adapter: window.tetray.adapter }),
  (e) => { showError(String(e.message || e)); return { ok: false, error: String(e.message || e) }; },
);
