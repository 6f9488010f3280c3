// The scene's buffers: base64 text (in the page, or in scene.js next to
// it), inflated ("deflate-raw") and put back from their byte planes.

async function inflate(base64) {
  const packed = await (await fetch("data:application/octet-stream;base64," + base64)).blob();
  const stream = packed.stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// Byte planes (byte 0 of every word, then byte 1, ...) back to words.
function fromPlanes(planes) {
  const words = planes.length / 4;
  const out = new Uint8Array(planes.length);
  for (let plane = 0; plane < 4; plane++) {
    const from = plane * words;
    for (let w = 0; w < words; w++) out[4 * w + plane] = planes[from + w];
  }
  return out;
}

function bufferText(id) {
  const element = document.getElementById("tetray-buffer-" + id);
  if (element) return element.textContent.trim();
  if (window.tetrayBuffers && id in window.tetrayBuffers) return window.tetrayBuffers[id];
  throw new Error(`the page lacks its buffer "${id}" (a folder page needs its scene.js beside index.html)`);
}

// Every buffer of the manifest, by id, as bytes.
async function loadBuffers(manifest) {
  const ids = Object.keys(manifest.buffers);
  const bytes = await Promise.all(ids.map(async (id) => {
    const words = fromPlanes(await inflate(bufferText(id)));
    if (words.length !== manifest.buffers[id]) {
      throw new Error(`buffer "${id}" holds ${words.length} bytes, the manifest says ${manifest.buffers[id]}`);
    }
    return words;
  }));
  return Object.fromEntries(ids.map((id, i) => [id, bytes[i]]));
}
