// The page around the canvas: the scene picker and the user's own files, the switches (as
// --set overrides of the scene file), the keyboard, mouse, touch and gamepad, the numbers, the
// link in the URL and the screenshot. All drawing is the C++ renderer's (web/page.cpp).
"use strict";

const canvas = document.getElementById("canvas");
const $ = (id) => document.getElementById(id);

// The link: scene=street&beta=0.9&doppler=off&yaw=0.3&... (docs/web.md lists the keys).
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
  window.lightcone = lc;  // for the console, and for the page's tests
  const call = (name, ...args) => lc.ccall(name, "string", args.map((a) =>
    typeof a === "string" ? "string" : "number"), args);
  const run = (name, ...args) => lc.ccall(name, null, args.map(() => "number"), args);
  const say = (text) => { $("message").textContent = text; };

  // An image the scene asks for, decoded by the browser (8-bit RGBA) and handed to the page.
  const decodeImage = async (path) => {
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
  };

  const started = JSON.parse(call("lc_start"));
  if (started.error) { say(started.error); return; }
  const bundled = lc.FS.readdir("/scenes").filter((n) => n.endsWith(".json"))
    .map((n) => n.replace(/\.json$/, "")).sort();
  for (const name of bundled) {
    const option = document.createElement("option");
    option.textContent = option.value = name;
    $("scene").appendChild(option);
  }

  const settings = Object.assign({ scene: "street" }, readHash());
  let userScene = null;  // the file name of the user's scene in /user, once one has loaded
  // The camera as the link gives it: turned by yaw and pitch, boosted to beta, flown tau.
  let yaw = Number(settings.yaw || 0), pitch = Number(settings.pitch || 0);
  let tau = Number(settings.tau || 0);
  // The camera's proper time a second: the native viewer's default for the scene (near a black
  // hole its shortest free fall in 10 s, else 1).
  let timeScale = 1;

  const overrides = () => {
    const sets = [];
    if (settings.relativity === "off") sets.push("render.relativity=false");
    if (settings.delay === "off") sets.push("render.light_delay=false");
    if (settings.doppler) sets.push(`render.doppler="${settings.doppler}"`);
    if (settings.searchlight) sets.push(`render.searchlight="${settings.searchlight}"`);
    if (settings.exposure === "auto") sets.push('render.exposure="auto"');
    else if (settings.exposure !== undefined) sets.push(`render.exposure=${Number(settings.exposure)}`);
    if (settings.tonemap) sets.push(`render.tonemap="${settings.tonemap}"`);
    return sets.join("\n");
  };
  const writeHash = () => {
    settings.yaw = yaw.toFixed(4);
    settings.pitch = pitch.toFixed(4);
    settings.tau = tau.toFixed(3);
    history.replaceState(null, "", "#" + Object.entries(settings)
      .map(([k, v]) => `${encodeURIComponent(k)}=${encodeURIComponent(v)}`).join("&"));
  };
  // The probes: a click or tap on the picture asks what is seen there (locate --pixel's
  // answer, from the same C++), a second the ruler between the two; the link keeps their
  // points (probe=x,y;x,y) and the readouts are text in the page.
  let probePoints = [];
  const probed = [];  // locate --pixel's JSON of each, for the page's tests
  const showProbes = (lines) => {
    $("probes").textContent = lines.join("\n");
    for (const mark of document.querySelectorAll(".probe-mark")) mark.remove();
    probePoints.forEach(([x, y], k) => {
      const mark = document.createElement("div");
      mark.className = "probe-mark";
      mark.style.left = `${(x / canvas.width) * 100}%`;
      mark.style.top = `${(y / canvas.height) * 100}%`;
      mark.innerHTML = `<span>${k + 1}</span>`;
      $("view").appendChild(mark);
    });
    document.body.dataset.probes = JSON.stringify(probed);
  };
  const clearProbes = () => {
    run("lc_clear_probes");
    probePoints = [];
    probed.length = 0;
    delete settings.probe;
    showProbes([]);
  };
  const probe = (x, y) => {
    const result = JSON.parse(call("lc_probe", x, y));
    if (result.error) { say(result.error); return; }
    if (probePoints.length >= 2) { probePoints = []; probed.length = 0; }
    probePoints.push([x, y]);
    probed.push(result.probe);
    settings.probe = probePoints.map(([px, py]) => `${px},${py}`).join(";");
    showProbes(result.lines);
    writeHash();
  };

  // Reads the scene (bundled or the user's) with the switches. `keep`: a switch changed, so the
  // camera stays where it flew; else it starts at the scene's, moved as the link says when
  // `fromLink`. Returns whether it loaded; on failure the old scene stays.
  const load = async (keep, path, fromLink = true) => {
    path = path || (userScene && settings.scene === userScene ? userScene
      : `/scenes/${settings.scene}.json`);
    // The scene names its images one at a time, as the reader meets them undecoded.
    let result;
    const decoded = new Set();
    for (;;) {
      result = JSON.parse(call("lc_load", path, overrides(), keep ? 1 : 0));
      if (!result.images) break;
      const image = result.images[0];
      try {
        if (decoded.has(image)) throw new Error("decoded, yet asked for again");
        await decodeImage(image);
        decoded.add(image);
      } catch (e) {
        result = { error: `${image}: the browser cannot decode this image (${e.message})` };
        break;
      }
    }
    document.body.dataset.loads = String(Number(document.body.dataset.loads || 0) + 1);
    if (result.error) { say(result.error); return false; }
    say(result.differences.concat(result.warnings).join("\n"));
    timeScale = result.time_scale;
    document.body.dataset.timeScale = String(timeScale);
    if (!keep) {
      // A probe is of the picture it was made on: a new camera or scene starts without.
      const fromTheLink = fromLink ? settings.probe : undefined;
      clearProbes();
      if (fromTheLink) settings.probe = fromTheLink;
    }
    if (!keep && fromLink) {
      if (yaw || pitch) run("lc_turn", yaw, pitch);
      if (settings.beta !== undefined) run("lc_set_speed", Number(settings.beta));
      if (tau) run("lc_fly", tau);
    }
    $("beta").value = settings.beta !== undefined ? settings.beta : result.beta;
    writeHash();
    return true;
  };

  // The switches, from the link. A scene the link names that the page cannot open is said so
  // in the page (kept above what street's own load says), and street is shown instead.
  let unopened = null;
  if (!bundled.includes(settings.scene)) {
    unopened = `${settings.scene} is not among the page's scenes: drop its files on the page`;
    settings.scene = "street";
  }
  $("scene").value = settings.scene;
  $("relativity").checked = settings.relativity !== "off";
  $("delay").checked = settings.delay !== "off";
  if (settings.doppler) $("doppler").value = settings.doppler;
  if (settings.searchlight) $("searchlight").value = settings.searchlight;
  if (settings.tonemap) $("tonemap").value = settings.tonemap;
  const showExposure = () => {
    const mode = settings.exposure === undefined ? "scene"
      : settings.exposure === "auto" ? "auto" : "fixed";
    $("exposure-mode").value = mode;
    $("exposure").disabled = mode !== "fixed";
    if (mode === "fixed") $("exposure").value = settings.exposure;
    $("exposure-value").textContent = mode === "fixed" ? `${settings.exposure} EV` : "";
  };
  showExposure();
  $("split").checked = settings.split === "on";
  $("paused").checked = settings.paused === "on";
  run("lc_set_split", settings.split === "on" ? 1 : 0);

  $("scene").onchange = () => {
    settings.scene = $("scene").value;
    delete settings.beta;
    delete settings.probe;
    yaw = pitch = tau = 0;
    load(false);
  };
  const toggle = (id, key) => {
    $(id).onchange = () => { settings[key] = $(id).checked ? "on" : "off"; load(true); };
  };
  toggle("relativity", "relativity");
  toggle("delay", "delay");
  for (const id of ["doppler", "searchlight"])
    $(id).onchange = () => { settings[id] = $(id).value; load(true); };
  $("tonemap").onchange = () => {
    if ($("tonemap").value === "scene") delete settings.tonemap;
    else settings.tonemap = $("tonemap").value;
    load(true);
  };
  $("exposure-mode").onchange = () => {
    const mode = $("exposure-mode").value;
    if (mode === "scene") delete settings.exposure;
    else settings.exposure = mode === "auto" ? "auto" : $("exposure").value;
    showExposure();
    load(true);
  };
  $("exposure").oninput = () => { settings.exposure = $("exposure").value; showExposure(); load(true); };
  $("split").onchange = () => {
    settings.split = $("split").checked ? "on" : "off";
    run("lc_set_split", $("split").checked ? 1 : 0);
    writeHash();
  };
  $("paused").onchange = () => { settings.paused = $("paused").checked ? "on" : "off"; writeHash(); };
  $("beta").oninput = () => {
    settings.beta = $("beta").value;
    run("lc_set_speed", Number(settings.beta));
    writeHash();
  };
  $("screenshot").onclick = () => canvas.toBlob((blob) => {
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download = `lightcone-${settings.scene}.png`;
    link.click();
  });

  // The user's own scene: a JSON file and the meshes and images it names, dropped on the page
  // or chosen in the file dialog, into the page's folder /user (read as the CLI reads them).
  const openFiles = async (files) => {
    files = Array.from(files);
    const scene = files.find((f) => /\.json$/i.test(f.name));
    if (!scene) { say("drop a scene's .json file (with the meshes and images it names)"); return; }
    if (!lc.FS.analyzePath("/user").exists) lc.FS.mkdir("/user");
    lc.FS.chdir("/user");
    for (const file of files)
      lc.FS.writeFile(file.name, new Uint8Array(await file.arrayBuffer()));
    if (await load(false, scene.name, false)) {
      userScene = settings.scene = scene.name;
      delete settings.beta;
      if (![...$("scene").options].some((o) => o.value === scene.name)) {
        const option = document.createElement("option");
        option.value = option.textContent = scene.name;
        $("scene").appendChild(option);
      }
      $("scene").value = scene.name;
      yaw = pitch = tau = 0;
      writeHash();
    }
  };
  $("files").onchange = () => openFiles($("files").files);
  addEventListener("dragover", (e) => { e.preventDefault(); document.body.classList.add("dropping"); });
  addEventListener("dragleave", () => document.body.classList.remove("dropping"));
  addEventListener("drop", (e) => {
    e.preventDefault();
    document.body.classList.remove("dropping");
    openFiles(e.dataTransfer.files);
  });

  // The native viewer's keys: W and S change the speed, Space stops, the arrows turn, C splits.
  const held = new Set();
  addEventListener("keydown", (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
    if (e.key === "w") run("lc_change_speed", 1);
    if (e.key === "s") run("lc_change_speed", -1);
    if (e.key === " ") { run("lc_set_speed", 0); e.preventDefault(); }
    if (e.key === "c") $("split").click();
    if (e.key === "x") { clearProbes(); writeHash(); }
    if (e.key === "r") {
      // Back to the scene's camera, where and when it starts; the switches stay.
      delete settings.beta;
      yaw = pitch = tau = 0;
      load(false, undefined, false);
    }
    if (e.key.startsWith("Arrow")) e.preventDefault();
    held.add(e.key);
  });
  addEventListener("keyup", (e) => { held.delete(e.key); writeHash(); });
  // Turning: the keyboard's arrows, a drag on the picture (mouse or finger), the joystick's
  // and the gamepad's horizontal axes. Speed: the joystick's and gamepad's vertical axes.
  const turn = (dyaw, dpitch) => { yaw += dyaw; pitch += dpitch; run("lc_turn", dyaw, dpitch); };
  let drag = null, pressed = null;
  canvas.addEventListener("pointerdown", (e) => {
    drag = pressed = [e.clientX, e.clientY];
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    turn(-(e.clientX - drag[0]) * 0.004, -(e.clientY - drag[1]) * 0.004);
    drag = [e.clientX, e.clientY];
  });
  canvas.addEventListener("pointerup", (e) => {
    // A press that did not drag is a click (or tap): a probe of the pixel under it, at its
    // centre, in the canvas's own pixels.
    if (pressed && Math.hypot(e.clientX - pressed[0], e.clientY - pressed[1]) < 3) {
      const box = canvas.getBoundingClientRect();
      const x = Math.floor(((e.clientX - box.left) * canvas.width) / box.width) + 0.5;
      const y = Math.floor(((e.clientY - box.top) * canvas.height) / box.height) + 0.5;
      if (x >= 0 && x < canvas.width && y >= 0 && y < canvas.height) probe(x, y);
    }
    drag = pressed = null;
    writeHash();
  });
  const stick = { x: 0, y: 0, pointer: null };
  const joystick = $("joystick");
  if (matchMedia("(pointer: coarse)").matches) joystick.hidden = false;
  addEventListener("touchstart", () => { joystick.hidden = false; }, { once: true });
  const moveStick = (e) => {
    const box = joystick.getBoundingClientRect();
    let x = (e.clientX - box.left) / (box.width / 2) - 1, y = (e.clientY - box.top) / (box.height / 2) - 1;
    const r = Math.hypot(x, y);
    if (r > 1) { x /= r; y /= r; }
    stick.x = x; stick.y = y;
    $("knob").style.transform = `translate(${x * 40}px, ${y * 40}px)`;
  };
  joystick.addEventListener("pointerdown", (e) => { stick.pointer = e.pointerId; joystick.setPointerCapture(e.pointerId); moveStick(e); });
  joystick.addEventListener("pointermove", (e) => { if (e.pointerId === stick.pointer) moveStick(e); });
  joystick.addEventListener("pointerup", () => { stick.pointer = null; stick.x = stick.y = 0; $("knob").style.transform = ""; });
  let rapidity = 0;  // the axes' boost, collected until it makes a step of the native viewer's
  const steer = (x, y, dt) => {
    if (Math.abs(x) > 0.15) turn(-1.2 * x * dt, 0);
    if (Math.abs(y) > 0.15) rapidity -= y * dt;
    while (Math.abs(rapidity) >= 0.1) {
      run("lc_change_speed", Math.sign(rapidity));
      rapidity -= 0.1 * Math.sign(rapidity);
    }
  };

  if (!(await load(false))) {
    unopened = `${settings.scene} cannot be opened: ${$("message").textContent}`;
    settings.scene = $("scene").value = "street";
    await load(false);
  }
  if (unopened) {
    say([`${unopened}. Showing street instead.`, $("message").textContent].join("\n").trim());
  }

  let last = performance.now(), hashWritten = last;
  const times = [];  // the last frames' times, for the frame rate
  const frame = (now) => {
    const dt = Math.min(0.1, Math.max(0, (now - last) / 1000));
    last = now;
    times.push(now);
    if (times.length > 30) times.shift();
    const fps = times.length > 1 ? (times.length - 1) / ((now - times[0]) / 1000) : 0;
    const step = 1.2 * dt;
    if (held.has("ArrowLeft")) turn(step, 0);
    if (held.has("ArrowRight")) turn(-step, 0);
    if (held.has("ArrowUp")) turn(0, step);
    if (held.has("ArrowDown")) turn(0, -step);
    steer(stick.x, stick.y, dt);
    for (const pad of navigator.getGamepads ? navigator.getGamepads() : []) {
      if (!pad) continue;
      steer(pad.axes[0] || 0, pad.axes[3] !== undefined ? pad.axes[3] : pad.axes[1] || 0, dt);
      if (pad.axes.length > 3 && Math.abs(pad.axes[1]) > 0.15) turn(0, -1.2 * pad.axes[1] * dt);
      if (pad.buttons[0] && pad.buttons[0].pressed) run("lc_set_speed", 0);
    }
    const flown = $("paused").checked ? 0 : dt * timeScale;
    tau += flown;
    const shown = JSON.parse(call("lc_frame", flown, dt, canvas.width, canvas.height));
    if (shown.error) say(shown.error);
    else {
      $("numbers").textContent = `beta ${shown.beta_text}  gamma ${shown.gamma.toFixed(3)}  ` +
        `D ${shown.doppler[0].toFixed(2)} to ${shown.doppler[1].toFixed(2)}  ` +
        `tau ${shown.proper_time.toFixed(2)}  EV ${shown.exposure.toFixed(2)}  ${fps.toFixed(1)} fps`;
      $("numbers").dataset.beta = shown.beta;
      $("numbers").dataset.exposure = shown.exposure;
      $("numbers").dataset.properTime = shown.proper_time;
    }
    if (!document.body.dataset.firstFrame) {
      document.body.dataset.firstFrame = String(performance.now());
      // The link's probes, on the picture now drawn.
      const points = (settings.probe || "").split(";").filter((p) => p)
        .map((p) => p.split(",").map(Number));
      probePoints = [];
      for (const [x, y] of points) probe(x, y);
    }
    document.body.dataset.frames = String(Number(document.body.dataset.frames || 0) + 1);
    if (now - hashWritten > 1000) { hashWritten = now; writeHash(); }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
});
