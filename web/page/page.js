// The page around the canvas: the scene picker, the switches (as --set overrides of the scene
// file), the keyboard, the numbers, the link in the URL and the screenshot. All drawing is the
// C++ renderer's (web/page.cpp).
"use strict";

const canvas = document.getElementById("canvas");
const message = document.getElementById("message");
const numbers = document.getElementById("numbers");
const $ = (id) => document.getElementById(id);

// The URL's hash: scene=street&beta=0.9&doppler=off&...
function readHash() {
  const settings = {};
  for (const part of location.hash.replace(/^#/, "").split("&"))
    if (part) {
      const [key, value] = part.split("=");
      settings[decodeURIComponent(key)] = decodeURIComponent(value || "");
    }
  return settings;
}

createLightcone({ canvas }).then(async (lc) => {
  // The browser decodes every PNG and JPEG of the page's files, for the scenes' textures.
  const images = [];
  const walk = (dir) => {
    for (const name of lc.FS.readdir(dir)) {
      if (name === "." || name === "..") continue;
      const path = dir + "/" + name;
      if (lc.FS.isDir(lc.FS.stat(path).mode)) walk(path);
      else if (/\.(png|jpe?g)$/i.test(name)) images.push(path);
    }
  };
  walk("/scenes");
  walk("/assets");
  for (const path of images) {
    const bitmap = await createImageBitmap(new Blob([lc.FS.readFile(path)]),
      { premultiplyAlpha: "none", colorSpaceConversion: "none" });
    const scratch = new OffscreenCanvas(bitmap.width, bitmap.height).getContext("2d");
    scratch.drawImage(bitmap, 0, 0);
    const rgba = scratch.getImageData(0, 0, bitmap.width, bitmap.height).data;
    const pointer = lc._malloc(rgba.length);
    lc.HEAPU8.set(rgba, pointer);
    lc.ccall("lc_add_image", null, ["string", "number", "number", "number"],
      [path, bitmap.width, bitmap.height, pointer]);
    lc._free(pointer);
  }

  const started = JSON.parse(lc.ccall("lc_start", "string", [], []));
  if (started.error) { message.textContent = started.error; return; }
  for (const name of lc.FS.readdir("/scenes").filter((n) => n.endsWith(".json")).sort()) {
    const option = document.createElement("option");
    option.textContent = name.replace(/\.json$/, "");
    $("scene").appendChild(option);
  }

  const settings = Object.assign({ scene: "street" }, readHash());
  const overrides = () => {
    const sets = [];
    if (settings.relativity === "off") sets.push("render.relativity=false");
    if (settings.delay === "off") sets.push("render.light_delay=false");
    if (settings.doppler) sets.push(`render.doppler="${settings.doppler}"`);
    if (settings.searchlight) sets.push(`render.searchlight="${settings.searchlight}"`);
    if (settings.exposure !== undefined) sets.push(`render.exposure=${Number(settings.exposure)}`);
    return sets.join("\n");
  };
  const writeHash = () => {
    history.replaceState(null, "", "#" + Object.entries(settings)
      .map(([k, v]) => `${encodeURIComponent(k)}=${encodeURIComponent(v)}`).join("&"));
  };
  const load = () => {
    const result = JSON.parse(lc.ccall("lc_load", "string", ["string", "string"],
      [`/scenes/${settings.scene}.json`, overrides()]));
    message.textContent = result.error ? result.error : result.differences.join("\n");
    if (!result.error && settings.beta) lc.ccall("lc_set_speed", null, ["number"], [Number(settings.beta)]);
    writeHash();
  };
  $("scene").value = settings.scene;
  $("relativity").checked = settings.relativity !== "off";
  $("delay").checked = settings.delay !== "off";
  if (settings.doppler) $("doppler").value = settings.doppler;
  if (settings.searchlight) $("searchlight").value = settings.searchlight;
  if (settings.beta) $("beta").value = settings.beta;
  $("split").checked = settings.split === "on";
  lc.ccall("lc_set_split", null, ["number"], [settings.split === "on" ? 1 : 0]);
  $("scene").onchange = () => { settings.scene = $("scene").value; delete settings.beta; load(); };
  $("relativity").onchange = () => { settings.relativity = $("relativity").checked ? "on" : "off"; load(); };
  $("delay").onchange = () => { settings.delay = $("delay").checked ? "on" : "off"; load(); };
  $("doppler").onchange = () => { settings.doppler = $("doppler").value; load(); };
  $("searchlight").onchange = () => { settings.searchlight = $("searchlight").value; load(); };
  $("split").onchange = () => {
    settings.split = $("split").checked ? "on" : "off";
    lc.ccall("lc_set_split", null, ["number"], [$("split").checked ? 1 : 0]);
    writeHash();
  };
  $("beta").oninput = () => {
    settings.beta = $("beta").value;
    lc.ccall("lc_set_speed", null, ["number"], [Number(settings.beta)]);
    writeHash();
  };
  $("screenshot").onclick = () => canvas.toBlob((blob) => {
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download = `lightcone-${settings.scene}.png`;
    link.click();
  });
  // The native viewer's keys: W and S change the speed, Space stops, the arrows turn.
  const held = new Set();
  addEventListener("keydown", (e) => {
    if (e.key === "w") lc.ccall("lc_change_speed", null, ["number"], [1]);
    if (e.key === "s") lc.ccall("lc_change_speed", null, ["number"], [-1]);
    if (e.key === " ") lc.ccall("lc_set_speed", null, ["number"], [0]);
    held.add(e.key);
  });
  addEventListener("keyup", (e) => held.delete(e.key));
  load();

  let last = performance.now(), fps = 0;
  const frame = (now) => {
    const dt = Math.min(0.1, (now - last) / 1000);
    last = now;
    fps = fps ? 0.9 * fps + 0.1 / Math.max(dt, 1e-6) : 1 / Math.max(dt, 1e-6);
    const turn = 1.2 * dt;
    if (held.has("ArrowLeft")) lc.ccall("lc_turn", null, ["number", "number"], [turn, 0]);
    if (held.has("ArrowRight")) lc.ccall("lc_turn", null, ["number", "number"], [-turn, 0]);
    if (held.has("ArrowUp")) lc.ccall("lc_turn", null, ["number", "number"], [0, turn]);
    if (held.has("ArrowDown")) lc.ccall("lc_turn", null, ["number", "number"], [0, -turn]);
    const shown = JSON.parse(lc.ccall("lc_frame", "string", ["number", "number", "number"],
      [dt, canvas.width, canvas.height]));
    if (shown.error) message.textContent = shown.error;
    else numbers.textContent = `beta ${shown.beta.toFixed(3)}  gamma ${shown.gamma.toFixed(3)}  ` +
      `D ${shown.doppler[0].toFixed(2)} to ${shown.doppler[1].toFixed(2)}  ` +
      `tau ${shown.proper_time.toFixed(2)}  ${fps.toFixed(1)} fps`;
    document.body.dataset.frames = String(Number(document.body.dataset.frames || 0) + 1);
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
});
